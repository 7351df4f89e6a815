#!/bin/sh
# bench_contact.sh: what a contact solve costs against its floor, one core.
# Each row runs one case study with -floor: the script times, after its
# solve and in the same process, the floor of its scene (the bulk
# stiffness assembled once by FreeFEM's varf, factorized once by CHOLMOD
# and solved once) and, where the scene assembles its stiffness in C
# (small strain, P1), the same floor with that assembly (floor_own_s).
# Writes results/bench-contact.csv
#   case,method,path,dofs,contact_dofs,wall_s,floor_s,ratio,factorizations,
#   newton,uzawa,active_set,step_cuts,peak_mb,err,floor_own_s,ratio_own
# (wall_s: the scene library's time from its start to the JSON, the
# case's main error: err_p0_fit for Hertz, the largest |c - c_analytic| /
# c_analytic for Cattaneo-Mindlin, err_plateau for the sliding block,
# err_deceleration for the sliding stop) and results/bench-contact.png.
#   sh tests/bench/bench_contact.sh [quick]   (quick: the coarser rows only)
cd "$(dirname "$0")/../.." || exit 2
mkdir -p results/bench
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=results/bench-contact.csv
echo "case,method,path,dofs,contact_dofs,wall_s,floor_s,ratio,factorizations,newton,uzawa,active_set,step_cuts,peak_mb,err,floor_own_s,ratio_own" > "$out"
num() { sed -n "s/^ *\"$2\": *\([-0-9.eE+]*\),*$/\1/p" "$1" | head -1; }
# row <name> <script> <method> [options]
row() {
    name=$1; script=$2; method=$3; shift 3
    j=results/bench/$name-$method
    log=$j.log
    /usr/bin/time -v sh scripts/ff "scripts/$script.edp" -method "$method" -floor 1 -out "$j" "$@" >"$log" 2>&1 \
        || { echo "bench-contact: $name $method failed (see $log)"; return 1; }
    f=$j.json
    solver=$(sed -n 's/^ *"linear_solver": *"\([^"]*\)".*/\1/p' "$f")
    loops=$(num "$f" condensed_loops)
    path=$solver; [ "${loops:-0}" != 0 ] && path=condensed
    [ "$method" = nts ] && path="$solver saddle"
    case $script in
        hertz) err=$(num "$f" err_p0_fit) ;;
        cattaneo-mindlin) err=$(awk -F'[:,]' '/level[0-9]_c"/{c=$2} /level[0-9]_c_analytic/{e=($2 - c) / $2; e = e < 0 ? -e : e; if (e > m) m = e} END {print m + 0}' "$f") ;;
        sliding-block) err=$(num "$f" err_plateau) ;;
        sliding-stop) err=$(num "$f" err_deceleration) ;;
    esac
    mb=$(sed -n 's/.*Maximum resident set size (kbytes): *\([0-9]*\).*/\1/p' "$log")
    wall=$(num "$f" time_total); floor=$(num "$f" floor_s); own=$(num "$f" floor_own_s)
    rown=; [ -n "$own" ] && rown=$(echo "$wall $own" | awk '{printf "%.2f", $1 / $2}')
    echo "$name,$method,$path,$(num "$f" dofs),$(num "$f" contact_dofs),$wall,$floor,$(echo "$wall $floor" | awk '{printf "%.2f", $1 / $2}'),$(num "$f" factorizations),$(num "$f" newton_iterations),$(num "$f" uzawa_iterations),$(num "$f" active_set_iterations),$(num "$f" step_cuts),$((mb / 1024)),$err,$own,$rown" | tee -a "$out"
}
for m in al nts; do
    row hertz-p1-hc0.05 hertz $m -hc 0.05 -vtk 0
    row hertz-p1-hc0.025 hertz $m -hc 0.025 -vtk 0
    [ "$1" = quick ] && continue
    [ $m = al ] && row hertz-p2-hc0.05 hertz $m -hc 0.05 -vtk 0 -DQUADRATIC=1   # (node-to-surface: linear facets only)
    row hertz-p1-hc0.0125 hertz $m -hc 0.0125 -vtk 0
    row cattaneo-hc0.025 cattaneo-mindlin $m -hc 0.025
    row sliding-block sliding-block $m
done
[ "$1" = quick ] || row sliding-stop sliding-stop al
gnuplot <<'GP'
set terminal pngcairo size 800,560
set output 'results/bench-contact.png'
set datafile separator ','
set logscale xy
set key top left
set grid
set xlabel 'dofs'
set ylabel 'seconds (one core)'
set title 'Contact solves against their floor (bulk assembly + one factorization and solve)'
plot 'results/bench-contact.csv' every ::1 using (strcol(2) eq "al" ? $4 : 1/0):6 with points pt 7 ps 1.3 title 'augmented Lagrangian', \
     '' every ::1 using (strcol(2) eq "nts" ? $4 : 1/0):6 with points pt 5 ps 1.3 title 'node-to-surface', \
     '' every ::1 using 4:7 with points pt 2 ps 1.5 lc rgb 'black' title 'floor'
GP
echo "wrote $out, results/bench-contact.png"
