#!/bin/sh
# docnames.sh: every name that README.md and scripts/REFERENCE.md document
# exists in the code.
# Checked (no FreeFEM needed):
#   - every plugin call written in backticks or in a code block, ffcName(,
#     and every backticked bare ffcName: registered by the plugin (plugin/*.cpp:
#     Global.Add, the ffcScene type, the reason constants) or defined in scripts/*.idp;
#   - the first column of README's tables, by the table's first header:
#       call              a plugin call (ffc...) or a scene-library function
#       function, global  a function or global defined in scripts/*.idp
#       setting           a driver setting (the table of plugin/ffc_settings.c)
#       option            a named option of a plugin call (plugin/*.cpp)
#       statistic         a name ffcStat accepts (plugin/ffc_scene*.c)
#       solver statistic  a name ffcSolverStat accepts (plugin/*.cpp)
#       field             a JSON field written by scripts/*.idp or scripts/*.edp
#       scene defines     a name scripts/scene.idp uses
#       case              a case study scripts/<name>.edp
#     (a cell's backticked names; of each, its first identifier:
#     `material(region, E, nu)` checks material). Other tables are not checked.
# Prints each missing name and a count; exits 1 if a name is missing, or if
# a kind of table above is absent from all the files together or nothing
# was checked (no vacuous pass).
#   sh tests/docnames.sh [file ...]   (default README.md scripts/REFERENCE.md)
here=$(pwd)
cd "$(dirname "$0")/.." || exit 2
[ $# -gt 0 ] || set -- README.md scripts/REFERENCE.md
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
names=""
for f in "$@"; do
    case "$f" in /*) p=$f ;; *) [ -f "$f" ] && p=$f || p="$here/$f" ;; esac
    [ -f "$p" ] || { echo "docnames: no file $f"; exit 2; }
    cat "$p" >> "$tmp/doc"
    echo >> "$tmp/doc"   # (a table at a file's end ends there)
    names="$names $(basename "$p")"
done
doc="$tmp/doc"

# ---- the names the code defines, one list per kind
# plugin calls: Global.Add("name", ...) and the type ffcScene
{ grep -ohE '(Global\.Add|zzzfff->Add)\("[A-Za-z0-9_]*"' plugin/*.cpp | sed 's/.*("//; s/"$//'
  grep -ohE '\{"ffc[A-Za-z0-9_]*", FFC_' plugin/*.cpp | sed 's/{"//; s/".*//'; } | sort -u > "$tmp/calls"
# named options of the plugin's calls: {"name", &typeid(...)}
grep -oh '{"[A-Za-z0-9_]*", *&typeid' plugin/*.cpp | sed 's/{"\([A-Za-z0-9_]*\)".*/\1/' | sort -u > "$tmp/options"
# the driver's settings: the table of plugin/ffc_settings.c, {"name", FFC_SET_...
grep -oh '{"[A-Za-z0-9_]*", FFC_SET_' plugin/*.c | sed 's/{"\([A-Za-z0-9_]*\)".*/\1/' | sort -u > "$tmp/settings"
# ffcStat's names: the statistics table of plugin/ffc_scene.c, {"name", 0|1, ...}
grep -oh '{"[A-Za-z0-9_]*", [01], ' plugin/ffc_scene*.c | sed 's/{"\([A-Za-z0-9_]*\)".*/\1/' | sort -u > "$tmp/stats"
# ffcSolverStat's names: if (k == "name")
grep -oh 'k == "[A-Za-z0-9_]*"' plugin/*.cpp | sed 's/k == "\(.*\)"/\1/' | sort -u > "$tmp/solverstats"
# JSON fields: jsonNum("key", ...), jsonStr("key", ...)
cat scripts/*.idp scripts/scene/*.idp scripts/*.edp | grep -oE 'json(Num|Str)\("[A-Za-z0-9_]*"' | sed 's/.*("\(.*\)"/\1/' | sort -u > "$tmp/fields"
# scene-library functions, macros and globals: the top-level lines of scripts/*.idp
awk '
/^[A-Za-z]/ {
    s = $0
    sub(/\/\/.*/, "", s)
    gsub(/"([^"\\]|\\.)*"/, "", s)                 # string literals
    if (s ~ /^func /) { sub(/\(.*/, "", s); n = split(s, w, " "); print w[n]; next }
    if (s ~ /^macro /) { split(s, w, " "); sub(/\(.*/, "", w[2]); print w[2]; next }
    if (s !~ /^(int|real|string|bool|matrix|ffcPh|varf|fespace)[^A-Za-z0-9_]/) next
    while (gsub(/\([^()]*\)/, "", s)) ;             # initializers f(...), nested
    while (gsub(/\[[^][]*\]/, "", s)) ;             # [int], [a, b], nested
    sub(/^[A-Za-z]+ +/, "", s)                      # the type
    n = split(s, w, ",")
    for (i = 1; i <= n; i++) {
        t = w[i]
        sub(/^[ \t]+/, "", t)
        if (match(t, /^[A-Za-z_][A-Za-z0-9_]*/)) print substr(t, 1, RLENGTH)
    }
}' scripts/*.idp scripts/scene/*.idp | sort -u > "$tmp/idp"
cat "$tmp/calls" "$tmp/idp" | sort -u > "$tmp/anycall"
for k in calls options settings stats solverstats fields idp; do
    [ -s "$tmp/$k" ] || { echo "docnames: found no $k in the code (has the code's layout changed?)"; exit 1; }
done

# ---- the names the document uses: "kind name" lines
awk '
function idents(cell, kind,    s, t) {     # each backticked name of a cell, its first identifier
    s = cell
    while (match(s, /`[^`]*`/)) {
        t = substr(s, RSTART + 1, RLENGTH - 2)
        s = substr(s, RSTART + RLENGTH)
        sub(/^[ \t]+/, "", t)
        if (kind == "case" && match(t, /^[A-Za-z0-9_-]+/)) print kind, substr(t, 1, RLENGTH)
        else if (match(t, /^[A-Za-z_][A-Za-z0-9_]*/)) print kind, substr(t, 1, RLENGTH)
    }
}
function calls(text,    s) {               # ffcName( anywhere in text
    s = text
    while (match(s, /ffc[A-Z][A-Za-z0-9_]*[ ]*\(/)) {
        t = substr(s, RSTART, RLENGTH)
        sub(/[ ]*\($/, "", t)
        print "anycall", t
        s = substr(s, RSTART + RLENGTH)
    }
}
/^```/ { code = !code; intable = 0; next }
code { calls($0); next }
{
    s = $0
    while (match(s, /`[^`]*`/)) {          # backticked plugin calls, bare ffc names
        t = substr(s, RSTART + 1, RLENGTH - 2)
        s = substr(s, RSTART + RLENGTH)
        calls(t)
        if (t ~ /^ffc[A-Z][A-Za-z0-9_]*$/) print "anycall", t
    }
}
/^\|/ {
    line = $0
    gsub(/\\\|/, "", line)                  # an escaped | inside a cell
    split(line, c, "|")
    cell = c[2]
    if (!intable) {                         # a header: the kind of the table
        intable = 1
        h = tolower(cell)
        gsub(/^[ \t]+|[ \t]+$/, "", h)
        kind = ""
        if (h == "call") kind = "call"
        else if (h == "function" || h == "global") kind = "idp"
        else if (h == "setting") kind = "setting"
        else if (h == "option") kind = "option"
        else if (h == "statistic") kind = "stat"
        else if (h == "solver statistic") kind = "solverstat"
        else if (h == "field") kind = "field"
        else if (h == "scene defines") kind = "scene"
        else if (h == "case") kind = "case"
        if (kind != "") print "table", kind
        next
    }
    if (cell ~ /^[ \t:-]*$/) next           # the separator row
    if (kind != "") idents(cell, kind)
    next
}
{ intable = 0 }
' "$doc" > "$tmp/used"

missing=0; checked=0
have() { grep -qx -- "$2" "$tmp/$1"; }
while read -r kind name; do
    case $kind in
        table) continue ;;
        anycall) have anycall "$name"; ok=$? ;;
        call) case $name in ffc*) have calls "$name" ;; *) have idp "$name" ;; esac; ok=$? ;;
        idp) have idp "$name"; ok=$? ;;
        setting) have settings "$name"; ok=$? ;;
        option) have options "$name"; ok=$? ;;
        stat) have stats "$name"; ok=$? ;;
        solverstat) have solverstats "$name"; ok=$? ;;
        field) have fields "$name"; ok=$? ;;
        scene) cat scripts/scene.idp scripts/scene/*.idp | grep -qw -- "$name"; ok=$? ;;
        case) [ -f "scripts/$name.edp" ]; ok=$? ;;
        *) continue ;;
    esac
    checked=$((checked + 1))
    if [ "$ok" -ne 0 ]; then
        missing=$((missing + 1))
        echo "docnames: $kind '$name' in$names is not in the code"
    fi
done < "$tmp/used"
for k in call idp setting option stat solverstat field scene case; do
    grep -qx "table $k" "$tmp/used" || { echo "docnames: no table of kind '$k' in$names"; missing=$((missing + 1)); }
done
[ "$checked" -ge 100 ] || { echo "docnames: only $checked names checked (expected 100 or more)"; missing=$((missing + 1)); }
distinct=$(grep -v '^table ' "$tmp/used" | sort -u | wc -l | tr -d ' ')
echo "docnames: $checked names checked ($distinct distinct), $missing missing"
[ "$missing" -eq 0 ]
