#!/bin/sh
# outside.sh: scripts/ff run from outside the repository keeps a script's relative paths (gmshFile, results/) there;
# README's own scene runs there as pasted.
repo=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
fail() { echo "outside: $1"; exit 1; }

# a unit cube, mesh size h set from the command line
cat > "$tmp/cube.geo" <<'GEO'
SetFactory("OpenCASCADE");
DefineConstant[ h = 1 ];
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = h;
Physical Volume(1) = {1};
Physical Surface(1) = {1:6};
GEO
# older than any cache: the first run meshes, the second reuses
touch -t 200001010000 "$tmp/cube.geo"
# the user's script: writes the vertex count and the mesh path it got
cat > "$tmp/tiny.edp" <<'EDP'
include "ffc.idp"
string msh = gmshFile("cube.geo", "-setnumber h 0.5");
mesh3 Th = gmshload3(msh);
exec("mkdir -p results");
{ ofstream f("results/out.txt"); f << Th.nv << " " << msh << endl; }
EDP
touch "$tmp/start"

cd "$tmp" || exit 2
run() { sh "$repo/scripts/ff" tiny.edp >log 2>&1 || fail "tiny.edp exit $? ($(tail -1 log))"; }
run
[ -f results/out.txt ] || fail "no results/out.txt in the script's directory"
read -r nv msh < results/out.txt
[ "${nv:-0}" -gt 8 ] 2>/dev/null || fail "vertex count '$nv' in results/out.txt"
case "$msh" in .ffc-cache/cube-*.msh) ;; *) fail "mesh path '$msh' is not under .ffc-cache/" ;; esac
[ -f "$msh" ] || fail "no cached mesh $msh in the script's directory"

# the cache: reused while the .geo is older, meshed again once it is newer
# (a new mesh replaces the file, so its inode changes)
ino() { ls -i "$msh" | cut -d' ' -f1; }
i1=$(ino); run; i2=$(ino)
[ "$i1" = "$i2" ] || fail "cached mesh meshed again although the .geo is older"
touch cube.geo; run; i3=$(ino)
[ "$i2" != "$i3" ] || fail "cached mesh kept although the .geo is newer"

# two scripts meshing the same new cache file at once: each gmsh writes a
# file of its own (named by its shell's pid), renamed into place, so
# neither reads the other's half-written file nor loses its own
# (a finer mesh, so that gmsh takes long enough for the two to overlap)
sed 's/h 0.5/h 0.04/' tiny.edp > fine.edp
sh "$repo/scripts/ff" fine.edp >log1 2>&1 & p1=$!
sh "$repo/scripts/ff" fine.edp >log2 2>&1 & p2=$!
wait $p1 || fail "concurrent meshing, first script: exit $? ($(tail -1 log1))"
wait $p2 || fail "concurrent meshing, second script: exit $? ($(tail -1 log2))"
read -r nv msh < results/out.txt
[ -f "$msh" ] || fail "concurrent meshing left no $msh"
ls .ffc-cache | grep -q tmp && fail "concurrent meshing left a temporary file: $(ls .ffc-cache)"

# the scene of README "Your own scene", pasted into a file here: it runs
# with default settings and writes its JSON here
awk '/^## Your own scene/{f=1} f&&/^```$/&&c==1{exit} f&&c==1{print} f&&/^```$/{c=1}' "$repo/README.md" > my-scene.edp
[ "$(wc -l < my-scene.edp)" -le 40 ] || fail "README's scene has more than 40 lines"
sh "$repo/scripts/ff" my-scene.edp >log 2>&1 || fail "README's scene: exit $? ($(tail -1 log))"
grep -q '"converged": 1' results/my-scene.json 2>/dev/null || fail "README's scene wrote no converged results/my-scene.json"

# nothing written into the repository (results/ is git-ignored: look for
# the files themselves)
new=$(find "$repo" -path "$repo/.git" -prune -o \( -name out.txt -o -name my-scene.json -o -name .ffc-cache -o -name 'cube-*.msh' \) -newer "$tmp/start" -print)
[ -z "$new" ] || fail "written into the repository: $(echo $new)"
exit 0
