#!/bin/sh
# bench_mpi.sh: strong scaling of a case on 1 and N ranks (one core per
# rank: OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1), the runs one after the
# other in the same invocation. Writes results/bench-mpi.csv
#   case,options,ranks,dofs,contact_dofs,wall_s,solve_s,factor_s,backsolve_s,speedup,newton,
#   factor_mb_per_rank,peak_mb_per_rank,F
# (wall_s: the scene library's time from its start to the JSON; speedup:
# the 1-rank wall over this row's; factor_s: the bulk factorizations'
# wall time inside solve_s (small strain); backsolve_s: the single
# back-solves' (small strain, inside solve_s); factor_mb_per_rank: MUMPS's
# factorization memory on the largest rank; peak_mb_per_rank: the largest
# rank's peak resident memory).
#   sh tests/bench/bench_mpi.sh [quick|full|large] [N]   (quick: h_c 0.025 and 0.0125
#   (CHOLMOD on every rank, and parallel MUMPS; and 0.0125 in one process
#   with N threads, its speedup against the 1-rank row), and finite deformation at
#   0.025; full: also finite deformation at 0.0125
#   and small strain at h_c 0.008, about 150k dofs; large: that row alone)
# First, what N processes at once get from this machine against one
# (build/bench_pair: a dense product and a streamed update; the ceiling of
# any N-rank speedup of work of either kind) into
# results/bench-mpi-machine.txt.
cd "$(dirname "$0")/../.." || exit 2
mode=${1:-quick}; np=${2:-2}
mkdir -p results/bench
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=results/bench-mpi.csv
echo "case,options,ranks,dofs,contact_dofs,wall_s,solve_s,factor_s,backsolve_s,speedup,newton,factor_mb_per_rank,peak_mb_per_rank,F" > "$out"
build/bench_pair "$np" | tee results/bench-mpi-machine.txt || exit 1
num() { sed -n "s/^ *\"$2\": *\([-0-9.eE+]*\),*$/\1/p" "$1" | head -1; }
# each row: the run of median wall time among REPS (3) runs (a run on
# several ranks is not reproducible to the last bit: MUMPS's parallel sums
# change from run to run, and so may the number of Newton iterations)
reps=${REPS:-3}
# measure <tag> <ranks> <threads> <case> <options...>: REPS runs of the
# case on that many ranks, each with that many BLAS / OpenMP threads; the
# row of the median one (its speedup against w1, the wall of the row that
# set it: pair's 1-rank row)
measure() {
    tag=$1 r=$2 t=$3 case=$4; shift 4
    j=results/bench/mpi-$case-$(echo "$*" | tr -c 'a-z0-9.\n' '_')-$tag
    for k in $(seq "$reps"); do
        OPENBLAS_NUM_THREADS=$t OMP_NUM_THREADS=$t sh scripts/ff -np "$r" "scripts/$case.edp" "$@" -vtk 0 -out "$j-$k" > "$j.log" 2>&1 \
            || { echo "bench-mpi: $case $* on $r ranks of $t threads failed (see $j.log)"; return 1; }
        echo "$(num "$j-$k.json" time_total) $k"
    done | sort -g | awk -v m=$(( (reps + 1) / 2 )) 'NR == m {print $2}' > "$j.median"
    f=$j-$(cat "$j.median").json; w=$(num "$f" time_total); [ -z "$w1" ] && w1=$w
    opts="$*"; [ "$t" -gt 1 ] && opts="$opts ($t threads)"
    echo "$case,$opts,$r,$(num "$f" dofs),$(num "$f" contact_dofs),$w,$(num "$f" time_solve),$(num "$f" time_factor),$(num "$f" time_backsolves),$(echo "$w1 $w" | awk '{printf "%.2f", $1 / $2}'),$(num "$f" newton_iterations),$(num "$f" factor_mb_per_rank),$(num "$f" peak_mb_per_rank),$(num "$f" F)" | tee -a "$out"
}
pair() {   # pair <case> <options...>: on 1 and N ranks of one thread
    w1=
    for r in 1 "$np"; do measure "$r" "$r" 1 "$@"; done
}
# one process with N threads, against which ranks must pay on one machine
# (after a pair: its speedup against that pair's 1-rank row)
threads() { measure "t$np" 1 "$np" "$@"; }
if [ "$mode" = large ]; then pair hertz -hc 0.008; exit 0; fi
pair hertz -hc 0.025
pair hertz -hc 0.0125
threads hertz -hc 0.0125
# the same on parallel MUMPS instead of CHOLMOD on every rank
pair hertz -hc 0.0125 -engine mumps
# the full-system path: finite deformation, K(u) + Kc factorized at every
# Newton iteration (UMFPACK / parallel MUMPS)
pair hertz -hc 0.025 -finite 1
[ "$mode" = full ] && pair hertz -hc 0.0125 -finite 1 && pair hertz -hc 0.008
exit 0
