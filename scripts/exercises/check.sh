#!/bin/sh
# check.sh: the exercises' checker. Reads what an exercise's run wrote
# (results/exercise-<k>.json: per quantity the computed value, the value
# theory expects, the run's tolerance and why, the prediction's tolerance
# and why) and the student's predictions (name=value), and prints for each
# quantity the computed value next to the expected one with two verdicts:
# the run (computed against theory) and the prediction (against theory).
#   sh scripts/exercises/check.sh results/exercise-1.json a=0.176 p0=61.6
# Exit status: 0 all right (quantities not predicted are only shown),
# 3 a prediction is wrong, 4 the run is wrong, 2 bad input.
# Predictions are checked first: each names a quantity of the exercise,
# once, with a number.
#   sh scripts/exercises/check.sh --names "a p0" a=0.176    only that (run.sh)
predictions() {   # predictions "<names>" name=value ...: the valid ones, or exit 2
    names=$1; shift; preds=""
    for a in "$@"; do
        case "$a" in
            *=*) ;;
            *) echo "check.sh: '$a' is not a prediction (name=value)"; exit 2 ;;
        esac
        name=${a%%=*}; value=${a#*=}
        case " $names " in *" $name "*) ;; *) echo "check.sh: no quantity \"$name\" to predict; the quantities are: $names"; exit 2 ;; esac
        case " $preds " in *" $name="*) echo "check.sh: '$name' predicted twice"; exit 2 ;; esac
        case "$value" in ''|*[!0-9eE.+-]*) echo "check.sh: prediction '$a': '$value' is not a number"; exit 2 ;; esac
        preds="$preds $a"
    done
}
[ -n "$1" ] || { echo "usage: check.sh <exercise json> [name=value ...]"; exit 2; }
if [ "$1" = --names ]; then
    names=$2; shift 2
    predictions "$names" "$@"
    exit 0
fi
json=$1
[ -f "$json" ] || { echo "check.sh: no results file '$json' (the run did not finish)"; exit 2; }
shift
predictions "$(sed -n 's/^ *"quantities": "\(.*\)",$/\1/p' "$json")" "$@"
awk -v preds="$preds" '
function num(s) { return s + 0 }
function absf(x) { return x < 0 ? -x : x }
function fmt(x) { return sprintf("%.6g", x) }
{
    line = $0
    if (match(line, /^ *"[^"]*": /)) {
        key = substr(line, RSTART, RLENGTH); sub(/^ *"/, "", key); sub(/": $/, "", key)
        val = substr(line, RSTART + RLENGTH); sub(/,$/, "", val)
        if (val ~ /^"/) { sub(/^"/, "", val); sub(/"$/, "", val) }
        f[key] = val
    }
}
END {
    n = split(preds, pl, " ")
    for (i = 1; i <= n; i++) { split(pl[i], kv, "="); p[kv[1]] = kv[2]; given[kv[1]] = 1 }
    nq = split(f["quantities"], q, " ")
    printf "Exercise %s: %s\n", f["exercise"], f["title"]
    printf "  settings: %s\n", f["settings"]
    if (f["converged"] != "1") printf "  the run did not converge: %s\n", f["reason"]
    runbad = 0; predbad = 0; npred = 0
    for (i = 1; i <= nq; i++) {
        k = q[i]
        c = num(f[k]); e = num(f[k "_expected"]); t = num(f[k "_tol"]); pt = num(f[k "_ptol"])
        printf "\n  %s: %s\n", k, f[k "_what"]
        if (f[k] == "null") { printf "    computed   (none: the run failed)\n"; runbad = 1; continue }
        d = absf(c - e)
        ok = d <= t
        printf "    computed   %-14s expected %-14s |diff| %s %s %s\n", fmt(c), fmt(e), fmt(d), ok ? "<=" : ">", fmt(t)
        printf "    run:        %s (%s)\n", ok ? "right" : "WRONG", f[k "_why"]
        if (!ok) runbad = 1
        if (k in given) {
            npred++
            v = num(p[k]); dp = absf(v - e)
            pok = dp <= pt
            printf "    predicted  %-14s expected %-14s |diff| %s %s %s\n", fmt(v), fmt(e), fmt(dp), pok ? "<=" : ">", fmt(pt)
            printf "    prediction: %s (%s)\n", pok ? "right" : "WRONG", f[k "_pwhy"]
            if (!pok) predbad = 1
        } else printf "    prediction: none (predict it: add %s=<value> to ARGS)\n", k
    }
    printf "\n"
    if (runbad) { print "Verdict: the run is WRONG (see above)"; exit 4 }
    if (predbad) { print "Verdict: a prediction is WRONG (see above)"; exit 3 }
    if (npred == nq) print "Verdict: every prediction right, the run right"
    else printf "Verdict: the run right; %d of %d quantities predicted, all right\n", npred, nq
}' "$json"
