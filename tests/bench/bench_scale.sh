#!/bin/sh
# bench_scale.sh: the linear engines against each other on the Hertz case
# (P1, small strain, frictionless) as the mesh grows: the factored path
# (CHOLMOD once, contact condensed), UMFPACK on K + Kc, and the iterative
# path (PETSc: GMRES with GAMG and the rigid-body modes) on one rank and
# on two; whole processes, one thread each, one run each. Writes
# results/bench-scale.csv
#   case,engine,ranks,threads,dofs,contact_dofs,wall_s,peak_mb_per_rank,newton,krylov_its,F,converged
#   sh tests/bench/bench_scale.sh [quick|full]   (quick: h_c 0.05 and 0.025;
#                                                  full: and 0.0125, 44k dofs)
cd "$(dirname "$0")/../.." || exit 2
. scripts/json.sh
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=results/bench-scale.csv
mkdir -p results
levels="0.05 0.025"
[ "$1" = full ] && levels="0.05 0.025 0.0125"
echo "case,engine,ranks,threads,dofs,contact_dofs,wall_s,peak_mb_per_rank,newton,krylov_its,F,converged" > "$out"
for hc in $levels; do
    for run in "factored auto 1" "UMFPACK UMFPACK 1" "iterative iterative 1" "iterative iterative 2"; do
        set -- $run
        o=results/bench-scale-$1-np$3-hc$hc
        np=; [ "$3" -gt 1 ] && np="-np $3"
        t0=$(date +%s.%N)
        sh scripts/ff $np scripts/hertz.edp -hc "$hc" -solver "$2" -out "$o" > "$o.log" 2>&1
        t1=$(date +%s.%N)
        wall=$(echo "$t1 - $t0" | bc)
        kry=$(val "$o.json" krylov_iterations)
        echo "hertz-hc$hc,$1,$3,1,$(val "$o.json" dofs),$(val "$o.json" contact_dofs),$wall,$(val "$o.json" peak_mb_per_rank),$(val "$o.json" newton_iterations),${kry:-0},$(val "$o.json" F),$(val "$o.json" converged)" | tee -a "$out"
    done
done
