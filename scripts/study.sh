#!/bin/sh
# study.sh: what accuracy costs in time, on the Hertz case. Sweeps one knob
# at a time from the default (P1, h_c = 0.05, automatic penalty, Uzawa
# tolerance 1e-4 h_c, quadrature degree 4, the factored linear path), runs
# each setting `reps` times (the median wall time is kept), and writes
#   results/study.csv              one row per setting, failed runs included
#   results/study-pareto.png       error against wall time, Pareto front
#   results/study-eps.png          iterations against the penalty factor
#   results/study-time.png         where the time goes at each mesh level
# Runs longer than 30 s are timed once (column reps).  Knob "method": the
# node-to-surface Lagrange-multiplier method (-method nts) and the mortar
# method (-method mortar) at each mesh level.
# Knob "solver": UMFPACK on K + Kc at every Newton iteration instead of the
# default factored path (the stiffness factorized once, each Newton system
# solved on the contact dofs), at h_c = 0.025, 0.0125 and P2 h_c = 0.05.
# Friction: the sliding block and Cattaneo-Mindlin with node-to-surface and, for the
# augmented Lagrangian, with both linear paths (auto: the factored one;
# UMFPACK: one factorization per Newton system):
#   results/study-friction.csv     one row per run (error, iterations, time split)
#   results/study-friction.png     wall time of both paths and of node-to-surface
# Usage: sh scripts/study.sh [quick | plots | friction]   (plots: redraw from
# results/study.csv; friction: only the friction cases, then all plots)
cd "$(dirname "$0")/.." || exit 2
mode=${1:-full}
. scripts/json.sh   # val, last, tval: the JSON's fields
mkdir -p results/study
csv=results/study.csv
reps=3
[ "$mode" = quick ] && reps=1

if [ "$mode" != plots ] && [ "$mode" != friction ]; then
# reference: the finest quadratic solution of the same finite bodies
refjson=results/study/reference.json
if [ ! -f "$refjson" ] || [ "$mode" != quick ]; then
    [ "$mode" = quick ] && refargs="-hc 0.1 -DQUADRATIC=1" || refargs="-hc 0.05 -DQUADRATIC=1"
    sh scripts/ff scripts/hertz.edp $refargs -verbose 0 -vtk 0 -out results/study/reference > /dev/null 2>&1
fi
F_ref=$(val "$refjson" F); p0_ref=$(val "$refjson" p0_fit); a_ref=$(val "$refjson" a_fit)

echo "knob,label,order,h_c,eps_factor,pentol,qdeg,converged,dofs,F,a,a_fit,p_max,p0_fit,a_hertz,p0_hertz,err_a,err_a_fit,err_p,err_p0_fit,err_F_ref,err_p0_ref,err_a_ref,max_penetration,newton,uzawa,factorizations,t_total,t_search,t_contact,t_bulk,t_solve,peak_mb,reps,method,solver" > "$csv"

run() {   # run <knob> <label> <args...>
    knob=$1; label=$2; shift 2
    out=results/study/$label
    times=""
    n=0
    for r in $(seq 1 $reps); do
        /usr/bin/time -f "%M" -o "$out.mem" sh scripts/ff scripts/hertz.edp "$@" -verbose 0 -vtk 0 -out "$out" \
            > "$out.log" 2>&1
        t=$(val "$out.json" time_total)
        times="$times $t"
        n=$((n + 1))
        awk -v t="$t" 'BEGIN {exit !(t > 30)}' && break
    done
    j=$out.json
    tmed=$(echo $times | tr ' ' '\n' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
    conv=$(val "$j" converged)
    order=1; case "$*" in *QUADRATIC*) order=2 ;; esac
    hc=$(echo "$@" | sed -n 's/.*-hc \([^ ]*\).*/\1/p'); hc=${hc:-0.05}
    ef=$(echo "$@" | sed -n 's/.*-epsfactor \([^ ]*\).*/\1/p'); ef=${ef:-1}
    pt=$(echo "$@" | sed -n 's/.*-pentol \([^ ]*\).*/\1/p'); pt=${pt:-1e-4}
    q=$(echo "$@" | sed -n 's/.*-q \([^ ]*\).*/\1/p'); q=${q:-4}
    mem=$(tail -1 "$out.mem" 2>/dev/null | awk '{printf "%.1f", $1 / 1024}')
    method=al; case "$*" in *"-method nts"*) method=nts ;; *"-method mortar"*) method=mortar ;; esac
    solver=$(val "$j" linear_solver | tr -d '"'); solver=${solver:-?}
    if [ "$conv" = 1 ]; then
        F=$(val $j F); p0f=$(val $j p0_fit); af=$(val $j a_fit)
        eref=$(awk -v a="$F" -v b="$F_ref" 'BEGIN {printf "%.6g", (a - b) / b < 0 ? (b - a) / b : (a - b) / b}')
        epref=$(awk -v a="$p0f" -v b="$p0_ref" 'BEGIN {d = (a - b) / b; printf "%.6g", d < 0 ? -d : d}')
        earef=$(awk -v a="$af" -v b="$a_ref" 'BEGIN {d = (a - b) / b; printf "%.6g", d < 0 ? -d : d}')
        echo "$knob,$label,$order,$hc,$ef,$pt,$q,1,$(val $j dofs),$F,$(val $j a),$af,$(val $j p_max),$p0f,$(val $j a_hertz),$(val $j p0_hertz),$(val $j err_a),$(val $j err_a_fit),$(val $j err_p),$(val $j err_p0_fit),$eref,$epref,$earef,$(val $j max_penetration),$(val $j newton_iterations),$(val $j uzawa_iterations),$(val $j factorizations),$tmed,$(tval $j search),$(tval $j contact),$(tval $j bulk),$(tval $j solve),$mem,$n,$method,$solver" >> "$csv"
    else
        echo "$knob,$label,$order,$hc,$ef,$pt,$q,0,,,,,,,,,,,,,,,,,$(val $j newton_iterations),$(val $j uzawa_iterations),,$tmed,,,,,$mem,$n,$method,$solver" >> "$csv"
    fi
    echo "  $label: converged=$conv wall=$tmed s"
}

if [ "$mode" = quick ]; then
    for h in 0.1 0.05; do run mesh "p1-hc$h" -hc $h; done
    run mesh p2-hc0.1 -hc 0.1 -DQUADRATIC=1
    for f in 0.01 1 100; do run eps "eps$f" -hc 0.05 -epsfactor $f; done
    run uzawa penalty-only -hc 0.05 -pentol 1e30 -ltol 1e30
    for t in 1e-2 1e-6; do run uzawa "pentol$t" -hc 0.05 -pentol $t -ltol $t; done
    for q in 1 6; do run quad "q$q" -hc 0.05 -q $q; done
    for h in 0.1 0.05; do run method "nts-hc$h" -hc $h -method nts; done
    for h in 0.1 0.05; do run method "mortar-hc$h" -hc $h -method mortar; done
else
    for h in 0.1 0.05 0.025 0.0125; do run mesh "p1-hc$h" -hc $h; done
    for h in 0.1 0.05; do run mesh "p2-hc$h" -hc $h -DQUADRATIC=1; done
    for f in 0.01 0.1 1 10 100 1000; do run eps "eps$f" -hc 0.05 -epsfactor $f; done
    run uzawa penalty-only -hc 0.05 -pentol 1e30 -ltol 1e30
    for t in 1e-2 1e-4 1e-6 1e-8; do run uzawa "pentol$t" -hc 0.05 -pentol $t -ltol $t; done
    for q in 1 2 4 5 6; do run quad "q$q" -hc 0.05 -q $q; done
    run combined p1-hc0.025-q2 -hc 0.025 -q 2
    run combined p2-hc0.05-q2 -hc 0.05 -q 2 -DQUADRATIC=1
    for h in 0.1 0.05 0.025 0.0125; do run method "nts-hc$h" -hc $h -method nts; done
    for h in 0.1 0.05 0.025 0.0125; do run method "mortar-hc$h" -hc $h -method mortar; done
    for h in 0.05 0.025; do run method "mortar-p2-hc$h" -hc $h -method mortar -DQUADRATIC=1; done
    run solver solver-UMFPACK -hc 0.025 -solver UMFPACK
    run solver solver-UMFPACK-hc0.0125 -hc 0.0125 -solver UMFPACK
    run solver solver-UMFPACK-p2 -hc 0.05 -DQUADRATIC=1 -solver UMFPACK
fi
fi

if [ "$mode" != plots ]; then
# friction: both solver paths on the sliding block and Cattaneo-Mindlin, and
# the sliding block's knobs (increments per ramp, tangential penalty)
fcsv=results/study-friction.csv
echo "case,label,h,solver,converged,error_name,error,newton,uzawa,factorizations,contact_dofs,t_total,t_search,t_contact,t_bulk,t_solve,reps,peak_mb,method,active_set,args" > "$fcsv"
frun() {   # frun <case> <label> <h> <error field (max over the file)> <args...>
    case_=$1; label=$2; h=$3; ef=$4; shift 4
    out=results/study/$label
    times=""; n=0; rc=0
    for r in $(seq 1 $reps); do
        /usr/bin/time -f "%M" -o "$out.mem" sh scripts/ff scripts/$case_.edp "$@" -out "$out" > "$out.log" 2>&1; rc=$?
        t=$(val "$out.json" time_total); times="$times $t"; n=$((n + 1))
        awk -v t="$t" 'BEGIN {exit !(t > 30)}' && break
    done
    j=$out.json
    tmed=$(echo $times | tr ' ' '\n' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
    err=$(sed -n "s/.*\"$ef\": \([^,}]*\).*/\1/p" "$j" | sort -g | tail -1)
    solver=$(val "$j" linear_solver | tr -d '"')
    echo "$case_,$label,$h,$solver,$([ $rc = 0 ] && echo 1 || echo 0),$ef,$err,$(last $j newton_iterations),$(last $j uzawa_iterations),$(val $j factorizations),$(val $j contact_dofs),$tmed,$(tval $j search),$(tval $j contact),$(tval $j bulk),$(tval $j solve),$n,$(tail -1 "$out.mem" | awk '{printf "%.1f", $1 / 1024}'),$(val $j method | tr -d '"'),$(val $j active_set_iterations),$*" >> "$fcsv"
    echo "  $label: wall=$tmed s"
}
# node-to-surface (exact constraints, UMFPACK on the saddle-point system)
frun sliding-block "sb-nts" 0.15 err_plateau -method nts
frun cattaneo-mindlin "cm-hc0.1-nts" 0.1 "level[0-9]_err_c_over_h" -hc 0.1 -method nts
[ "$mode" = quick ] || frun cattaneo-mindlin "cm-hc0.05-nts" 0.05 "level[0-9]_err_c_over_h" -hc 0.05 -method nts
# mortar (segment-to-segment, dual multipliers)
frun sliding-block "sb-mortar" 0.15 err_plateau -method mortar
frun cattaneo-mindlin "cm-hc0.1-mortar" 0.1 "level[0-9]_err_c_over_h" -hc 0.1 -method mortar
[ "$mode" = quick ] || frun cattaneo-mindlin "cm-hc0.05-mortar" 0.05 "level[0-9]_err_c_over_h" -hc 0.05 -method mortar
for sv in auto UMFPACK; do
    frun sliding-block "sb-$sv" 0.15 err_plateau -solver $sv
    frun cattaneo-mindlin "cm-hc0.1-$sv" 0.1 "level[0-9]_err_c_over_h" -hc 0.1 -solver $sv
    [ "$mode" = quick ] || frun cattaneo-mindlin "cm-hc0.05-$sv" 0.05 "level[0-9]_err_c_over_h" -hc 0.05 -solver $sv
done
if [ "$mode" != quick ]; then
    for n in 8 32; do frun sliding-block "sb-n$n" 0.15 err_plateau -n $n; done
    # the tangential penalty, absolute (the automatic one is epsN = 5.49e5)
    for e in 5.49e4 5.49e6; do frun sliding-block "sb-epst$e" 0.15 err_plateau -epst $e; done
fi
fi

# Pareto front of (wall time, error on p_max) over converged runs
awk -F, 'NR > 1 && $8 == 1 {print $28, $19, $2}' "$csv" | sort -g | \
    awk 'BEGIN {best = 1e300; OFS = ","} {if ($2 < best) {best = $2; print $1, $2, $3}}' > results/study-pareto.dat
# time split of the mesh levels, in % of the wall time
awk -F, 'NR > 1 && $1 == "mesh" && $8 == 1 {t = $28; o = t - $29 - $30 - $31 - $32; if (o < 0) o = 0;
    printf "%s(%.3g) %g %g %g %g %g %g\n", $2, t, t, 100*$32/t, 100*$31/t, 100*$30/t, 100*$29/t, 100*o/t}' "$csv" \
    > results/study-mesh.dat
gnuplot <<'GP'
set datafile separator ','
set terminal pngcairo size 860,560
set output 'results/study-pareto.png'
set logscale xy
set grid
set key top right
set xlabel 'wall time (s, median)'
set ylabel 'relative error of the raw peak pressure against Hertz'
set title 'Hertz: error against time (P1 circles, P2 squares; Pareto front in red)'
plot 'results/study.csv' every ::1 using ($8 == 1 && $3 == 1 ? $28 : 1/0):19 with points pt 7 ps 1.2 title 'P1', \
     '' every ::1 using ($8 == 1 && $3 == 2 ? $28 : 1/0):19 with points pt 5 ps 1.2 title 'P2', \
     '' every ::1 using ($8 == 1 ? $28 : 1/0):19:2 with labels font ',7' offset 0,0.8 notitle, \
     'results/study-pareto.dat' using 1:2 with steps lw 2 lc rgb 'red' title 'Pareto front'
set output 'results/study-eps.png'
set logscale x
unset logscale y
set xlabel 'penalty factor (x automatic)'
set ylabel 'iterations'
set title 'Hertz h_c = 0.05: iterations against the penalty'
plot 'results/study.csv' every ::1 using (strcol(1) eq 'eps' && $8 == 1 ? $5 : 1/0):25 with linespoints pt 7 title 'Newton', \
     '' every ::1 using (strcol(1) eq 'eps' && $8 == 1 ? $5 : 1/0):26 with linespoints pt 5 title 'Uzawa', \
     '' every ::1 using (strcol(1) eq 'eps' && $8 == 1 ? $5 : 1/0):27 with linespoints pt 9 title 'factorizations'
set output 'results/study-time.png'
unset logscale
set datafile separator ' '
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set key outside right
set yrange [0:100]
set xlabel 'mesh level (wall time in s)'
set ylabel 'share of the wall time (%)'
set title 'Hertz: where the time goes'
set xtics rotate by -20
plot 'results/study-mesh.dat' using 3:xtic(1) title 'linear solves', '' using 4 title 'bulk assembly', \
     '' using 5 title 'contact assembly', '' using 6 title 'search', '' using 7 title 'other (script, output)'
GP
# friction: wall time of the two solver paths per case
awk -F, 'NR > 1 && $2 ~ /-(auto|UMFPACK|nts)$/ {k = $2; m = $2; sub(/-(auto|UMFPACK|nts)$/, "", k); sub(/.*-/, "", m);
    t[k, m] = $12; if (!(k in seen)) {seen[k] = 1; order[++n] = k}}
    END {for (i = 1; i <= n; i++) {o = order[i]; print o, t[o, "UMFPACK"], t[o, "auto"], ((o, "nts") in t) ? t[o, "nts"] : "NaN"}}' results/study-friction.csv \
    > results/study-friction.dat
gnuplot <<'GP'
set terminal pngcairo size 760,480
set output 'results/study-friction.png'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set logscale y
set grid y
set ylabel 'wall time (s, median)'
set title 'Friction cases: wall time of the two solver paths and of node-to-surface'
set key top left
set yrange [1:*]
plot 'results/study-friction.dat' using 2:xtic(1) title 'AL, UMFPACK per Newton iteration', '' using 3 title 'AL factored (CHOLMOD once)', \
     '' using 4 title 'node-to-surface (UMFPACK, saddle point)'
GP
echo "wrote $csv, results/study-pareto.png, results/study-eps.png, results/study-time.png, results/study-friction.csv, results/study-friction.png"
