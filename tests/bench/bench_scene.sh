#!/bin/sh
# bench_scene.sh: README's own scene ("Your own scene": two blocks pressed,
# then sheared with friction) and variants a user would write, one core,
# one run each: what the frictional Newton costs and whether a step is cut.
# Writes results/bench-scene.csv
#   variant,change,newton,uzawa,step_cuts,epsT_raised,T_over_muN,wall_s
# (wall_s: the scene library's time from its start to the JSON).
#   sh tests/bench/bench_scene.sh [quick]   (quick: without the finer mesh)
cd "$(dirname "$0")/../.." || exit 2
repo=$(pwd)
mkdir -p results/bench
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=$repo/results/bench-scene.csv
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
awk '/^## Your own scene/{f=1} f&&/^```$/&&c==1{exit} f&&c==1{print} f&&/^```$/{c=1}' README.md > "$tmp/base.edp"
grep -q 'ffcAddPair(C, 25, 16, mu = 0.3)' "$tmp/base.edp" || { echo "bench-scene: README's scene not found"; exit 1; }
num() { sed -n "s/^ *\"$2\": *\([-0-9.eE+]*\),*$/\1/p" "$1" | head -1; }
echo "variant,change,newton,uzawa,step_cuts,epsT_raised,T_over_muN,wall_s" > "$out"
fail=0
# row <name> <mu> <change> [sed expressions...] (each variant's must change the scene)
row() {
    name=$1; mu=$2; change=$3; shift 3
    if [ $# -gt 0 ]; then
        sed "$@" "$tmp/base.edp" > "$tmp/$name.edp"
        cmp -s "$tmp/base.edp" "$tmp/$name.edp" && { echo "bench-scene: $name: the edit changed nothing in README's scene"; fail=1; return 1; }
    else cp "$tmp/base.edp" "$tmp/$name.edp"; fi
    f=$tmp/results/my-scene.json
    rm -f "$f"
    (cd "$tmp" && sh "$repo/scripts/ff" "$name.edp" > "$repo/results/bench/scene-$name.log" 2>&1) && [ -f "$f" ] \
        || { echo "bench-scene: $name failed (see results/bench/scene-$name.log)"; fail=1; return 1; }
    cp "$f" "results/bench/scene-$name.json"
    echo "$name,$change,$(num "$f" newton_iterations),$(num "$f" uzawa_iterations),$(num "$f" step_cuts),$(num "$f" tangential_penalty_raised),$(awk -v t="$(num "$f" T)" -v n="$(num "$f" N)" -v m="$mu" 'BEGIN {if (n * m != 0) printf "%.6f", t / (m * n)}'),$(num "$f" time_total)" | tee -a "$out"
}
row readme 0.3 "as in README"
row mu0.1 0.1 "mu = 0.1" -e 's/mu = 0.3)/mu = 0.1)/'
row mu0.6 0.6 "mu = 0.6" -e 's/mu = 0.3)/mu = 0.6)/'
row shear2x 0.3 "shear increments of 0.003" -e 's/0.0015 \* i/0.003 * i/'
row steps1 0.3 "1 step per solve" -e 's/^ffcSet(C, nsteps = 2);/ffcSet(C, nsteps = 1);/'
row steps4 0.3 "4 steps per solve" -e 's/^ffcSet(C, nsteps = 2);/ffcSet(C, nsteps = 4);/'
row p3 0.3 "pressure 3" -e 's/pB = 1,/pB = 3,/'
[ "$1" = quick ] || row fine 0.3 "mesh h 0.15 / 0.12" -e 's/h1 0.25 -setnumber h2 0.2", "h0.25-0.2"/h1 0.15 -setnumber h2 0.12", "h0.15-0.12"/'
exit $fail
