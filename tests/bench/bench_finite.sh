#!/bin/sh
# bench_finite.sh: finite deformation's cost, one core, one run each: the
# soft ball at three mesh levels (10 steps to d = 0.3) and, with MODE=full,
# the ironing's default run (friction). Writes results/bench-finite.csv
#   case,h_c,dofs,F,newton,newton_per_step,uzawa,steps,factorizations,krylov,time_s,time_total_s
# (time_s: the load steps; time_total_s: the process from its start, mesh
# and set-up included, without the soft ball's small-strain reference).
#   sh tests/bench/bench_finite.sh [full]
cd "$(dirname "$0")/../.." || exit 2
. scripts/json.sh
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=results/bench-finite.csv
mkdir -p results
echo "case,h_c,dofs,F,newton,newton_per_step,uzawa,steps,factorizations,krylov,time_s,time_total_s" > "$out"
sh scripts/ff scripts/soft-ball.edp -levels 3 -hc 0.1 -out results/bench-soft-ball > results/bench-soft-ball.log 2>&1 \
    || { echo "bench-finite: the soft ball failed (results/bench-soft-ball.log)"; exit 1; }
# one line per level of results/bench-soft-ball.json
awk -F', ' '/"h_c"/ {
    for (i = 1; i <= NF; i++) { split($i, kv, ": "); k = kv[1]; x = kv[2]; gsub(/[{}" ]/, "", k); gsub(/[{}, ]/, "", x); v[k] = x }
    print "soft-ball," v["h_c"] "," v["dofs"] "," v["F"] "," v["newton_iterations"] "," v["newton_per_step"] "," v["uzawa_iterations"] "," v["steps"] "," v["factorizations"] "," v["krylov_iterations"] "," v["time"] "," v["time_total"]
}' results/bench-soft-ball.json | tee -a "$out"
if [ "$1" = full ]; then
    sh scripts/ff scripts/ironing.edp -out results/bench-ironing > results/bench-ironing.log 2>&1 \
        || { echo "bench-finite: the ironing failed (results/bench-ironing.log)"; exit 1; }
    f=$(ls results/bench-ironing-hs*.json | head -1)
    echo "ironing,$(val $f h_s),$(val $f dofs),$(val $f Fz_mean),$(val $f newton_iterations),,$(val $f uzawa_iterations),,$(val $f full_factorizations),$(val $f full_krylov_iterations),$(val $f time),$(val $f time_total)" | tee -a "$out"
fi
