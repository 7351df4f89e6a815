#!/bin/sh
# same_answers.sh: case studies on one process and on N ranks of
# FreeFem++-mpi (sh scripts/ff -np N) give the same answers, to 1e-8
# relative (the runs differ only in the bulk factorization and who solves
# which compliance column: CHOLMOD, CHOLMOD on every rank or parallel
# MUMPS, all backward stable, and every Newton loop stops at a residual of
# 1e-10 or below of its force scale).
#   sh tests/mpi/same_answers.sh [N] [quick|full]
# quick: the coarse Hertz (augmented Lagrangian, node-to-surface, mortar)
# and the patch test; full: also the sliding block and Cattaneo-Mindlin.
cd "$(dirname "$0")/../.." || exit 2
np=${1:-2}
mode=${2:-quick}
dir=build/mpi-answers
mkdir -p "$dir"
fail=0
# the value of "key" in a case's JSON
val() { sed -n "s/^ *\"$2\": \([-0-9.eE+]*\),*\$/\1/p" "$1" | head -1; }
# a failed run's error lines (FreeFEM's, the ranks' and MPI's) and its end
why() { grep -n -i -m 12 "error\|ff: rank\|abort\|signal" "$1"; echo "    ..."; tail -8 "$1"; }
check() {   # check <name> <case> "<fields>" <options...>
    name=$1; case=$2; fields=$3; shift 3
    sh scripts/ff "scripts/$case.edp" "$@" -out "$dir/$name-1" > "$dir/$name-1.log" 2>&1 \
        || { echo "FAIL $name: one process (exit $?)"; why "$dir/$name-1.log"; fail=1; return; }
    sh scripts/ff -np "$np" "scripts/$case.edp" "$@" -out "$dir/$name-$np" > "$dir/$name-$np.log" 2>&1 \
        || { echo "FAIL $name: $np ranks (exit $?)"; why "$dir/$name-$np.log"; fail=1; return; }
    r=$(val "$dir/$name-$np.json" ranks)
    # the small-strain stiffness and the hyperelastic operator in C, whole
    # on every rank; FreeFEM's varf (-assembly varf) on P1, each rank its
    # part of the mesh
    case "$*" in
        *QUADRATIC*varf*|*varf*QUADRATIC*) ;;
        *varf*) grep -q '"bulk_assembly": "by rank"' "$dir/$name-$np.json" || { echo "FAIL $name: not assembled by rank"; fail=1; } ;;
        *) grep -q '"bulk_assembly": "in C"' "$dir/$name-$np.json" || { echo "FAIL $name: not assembled in C"; fail=1; } ;;
    esac
    [ "$r" = "$np" ] || { echo "FAIL $name: the JSON of $np ranks says ranks = $r"; fail=1; }
    for f in $fields; do
        a=$(val "$dir/$name-1.json" "$f"); b=$(val "$dir/$name-$np.json" "$f")
        if [ -z "$a" ] || [ -z "$b" ]; then echo "FAIL $name: no field $f"; fail=1; continue; fi
        awk -v a="$a" -v b="$b" 'function abs(x) { return x < 0 ? -x : x }
            BEGIN { m = abs(a) > abs(b) ? abs(a) : abs(b); exit !(abs(a - b) <= 1e-8 * m) }' \
            || { echo "FAIL $name: $f = $a (1 process), $b ($np ranks)"; fail=1; }
    done
}
# the contact evaluations of the condensed Newton shared out over the
# ranks (augmented Lagrangian, nodal multipliers): each rank its share of
# the links, counted in the JSON
shared() {   # shared <name>: some evaluations shared, on N ranks
    e=$(val "$dir/$1-$np.json" condensed_evaluations_shared)
    [ -n "$e" ] && [ "$e" -gt 0 ] || { echo "FAIL $1: no contact evaluation shared out over $np ranks ($e)"; fail=1; }
}
H="F F_contact a a_fit p_max p0_fit max_penetration"
check hertz-al hertz "$H" -hc 0.1 -vtk 0
shared hertz-al
# (node-to-surface: no penetration to compare, it is zero to round-off;
# the fitted a and p0 take the nodes of positive pressure, and the last
# node at the rim carries 1e-12 or 0 by round-off)
check hertz-nts hertz "F F_contact a p_max" -hc 0.1 -vtk 0 -method nts
check hertz-mortar hertz "$H" -hc 0.1 -vtk 0 -method mortar
# mortar on quadratic elements (6-node facets)
check hertz-mortar-p2 hertz "$H" -hc 0.1 -vtk 0 -method mortar -DQUADRATIC=1
# (a support of 384 contact dofs: the condensed Newton's dense LU shared
# over the ranks, ScaLAPACK)
check hertz-025 hertz "$H" -hc 0.025 -vtk 0
shared hertz-025
# the stiffness by FreeFEM's varf, each rank its part, summed (ffcRankSum)
check hertz-varf hertz "$H" -hc 0.1 -vtk 0 -assembly varf
# the bulk factorized by parallel MUMPS instead of CHOLMOD on every rank
check hertz-mumps hertz "$H" -hc 0.1 -vtk 0 -engine mumps
# the full-system path: K + Kc factorized at each Newton iteration
# (UMFPACK on one process, parallel MUMPS on N ranks), and finite
# deformation (the same path, the bulk tangent changing)
check hertz-full hertz "$H" -hc 0.1 -vtk 0 -solver UMFPACK
check hertz-finite hertz "$H" -hc 0.1 -vtk 0 -finite 1
check patch patch "contact_force contact_area err_p max_penetration"
# (mortar passes the patch test: err_p and the penetration are round-off.
# At the default tolerances, 1e-4, its answers carry the Uzawa loop's
# stopping error, about 2e-8 of p, which round-off moves: compared where
# both have converged, 1e-9, they agree to about 1e-11)
check patch-mortar patch "contact_force contact_area" -method mortar -h1 0.25 -h2 0.125 -ltol 1e-9 -pentol 1e-9
# a case's outputs in a folder under results/ that does not exist yet: each
# rank > 0 runs with its own, empty results/, and must make the folder
# there too (the JSON is rank 0's alone; hertz.edp also writes its p(r)
# table on every rank)
rm -rf results/mpi-answers
sh scripts/ff -np "$np" scripts/hertz.edp -hc 0.1 -vtk 0 -out results/mpi-answers/hertz > "$dir/results-folder.log" 2>&1 \
    || { echo "FAIL outputs into results/mpi-answers/: $np ranks (exit $?)"; why "$dir/results-folder.log"; fail=1; }
[ -s results/mpi-answers/hertz.json ] || { echo "FAIL no results/mpi-answers/hertz.json from $np ranks"; fail=1; }
rm -rf results/mpi-answers
if [ "$mode" = full ]; then
    check sliding-block sliding-block "N T_plateau T_reverse work work_steady"
    shared sliding-block
    check cattaneo cattaneo-mindlin "P level0_c level1_c level2_c level0_c_area level1_c_area level2_c_area level2_q_ratio_reached"
fi
[ "$fail" -eq 0 ] && echo "same answers on 1 and $np ranks ($mode)"
exit $fail
