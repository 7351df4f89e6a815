#!/bin/sh
# ensemble.sh: how much of an error is the mesh's draw. Runs Hertz (raw and
# fitted peak, nodal scatter) and Cattaneo-Mindlin (stick radius c_area) on
# n meshes of nearly the same size, h = h_c (1 + k / 80), k = 0 .. n-1 (up
# to +8.75% with n = 8: gmsh places every node anew), for each method, and
# writes (name: ensemble unless given)
#   results/<name>.csv   one row per run
#   results/<name>.txt   per case, method, h_c and quantity: min, median, max
#   results/<name>.png   the Hertz errors against h_c, the ensemble's range
#                        (with Hertz levels; a method not run leaves its
#                        curves out, gnuplot warns)
# and each run's files in results/<name>/. One core per run
# (OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = 1).
# Usage: sh scripts/ensemble.sh [n (8)] [methods ("al nts mortar")]
#            [Hertz levels ("0.05 0.025 0.0125")] [Cattaneo-Mindlin levels ("0.025")] [name]
#   ("" for no level of a case)
cd "$(dirname "$0")/.." || exit 2
n=${1:-8}
methods=${2-"al nts mortar"}
hlevels=${3-"0.05 0.025 0.0125"}
clevels=${4-"0.025"}
name=${5:-ensemble}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
dir=results/$name
mkdir -p "$dir"
csv=results/$name.csv
. scripts/json.sh
echo "case,method,level,h,converged,dofs,err_p,err_p0_fit,err_a_fit,p_bias,p_scatter,err_c_area_1,err_c_area_2,err_c_area_3,t_total" > "$csv"
# the mesh sizes of a level: L (1 + k / 80), k = 0 .. n-1
sizes() { awk -v L="$1" -v n="$n" 'BEGIN {for (k = 0; k < n; k++) printf "%.7g\n", L * (1 + k / 80)}'; }
for m in $methods; do
    for L in $hlevels; do
        for h in $(sizes "$L"); do
            out=$dir/hertz-$m-$h
            rm -f "$out.json"
            sh scripts/ff scripts/hertz.edp -hc "$h" -method "$m" -verbose 0 -vtk 0 -out "$out" > "$out.log" 2>&1
            j=$out.json
            echo "hertz,$m,$L,$h,$(val "$j" converged),$(val "$j" dofs),$(val "$j" err_p),$(val "$j" err_p0_fit),$(val "$j" err_a_fit),$(val "$j" p_bias),$(val "$j" p_scatter),,,,$(val "$j" time_total)" >> "$csv"
            echo "  hertz $m h_c $h: err_p $(val "$j" err_p), err_p0_fit $(val "$j" err_p0_fit)"
        done
    done
    for L in $clevels; do
        for h in $(sizes "$L"); do
            out=$dir/cm-$m-$h
            rm -f "$out.json"
            sh scripts/ff scripts/cattaneo-mindlin.edp -hc "$h" -method "$m" -out "$out" > "$out.log" 2>&1
            j=$out.json
            e="$(val "$j" level0_err_c_area),$(val "$j" level1_err_c_area),$(val "$j" level2_err_c_area)"   # (a level missing: empty)
            echo "cattaneo-mindlin,$m,$L,$h,$(last "$j" converged),$(val "$j" dofs),,,,,,$e,$(last "$j" time_total)" >> "$csv"
            echo "  cattaneo-mindlin $m h_c $h: err_c_area $e"
        done
    done
done

# min, median, max of each quantity per case, method and level (converged runs)
awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) name[i] = $i; next}
    $5 == 1 {key = $1 " " $2 " " $3
        if (!(key in seen)) {seen[key] = 1; order[++nk] = key}
        for (i = 7; i <= 14; i++) if ($i != "") {c = ++cnt[key, i]; v[key, i, c] = $i}}
    END {printf "%-17s %-7s %-7s %-14s %3s %9s %9s %9s\n", "case", "method", "h_c", "quantity", "n", "min", "median", "max"
        for (o = 1; o <= nk; o++) {key = order[o]
            for (i = 7; i <= 14; i++) {c = cnt[key, i]; if (!c) continue
                for (a = 1; a <= c; a++) w[a] = v[key, i, a]
                for (a = 2; a <= c; a++) {x = w[a]; b = a - 1; while (b >= 1 && w[b] > x) {w[b + 1] = w[b]; b--} w[b + 1] = x}
                med = c % 2 ? w[(c + 1) / 2] : (w[c / 2] + w[c / 2 + 1]) / 2
                split(key, kk, " ")
                printf "%-17s %-7s %-7s %-14s %3d %8.2f%% %8.2f%% %8.2f%%\n", kk[1], kk[2], kk[3], name[i], c, 100 * w[1], 100 * med, 100 * w[c]}}}' \
    "$csv" > "results/$name.txt"
cat "results/$name.txt"
# the Hertz errors against h_c: median with the ensemble's range, one file
# per method and quantity (the methods drawn side by side: h_c x 1.04^k)
rm -f "$dir"/hertz-*-err_p.dat "$dir"/hertz-*-err_p0_fit.dat
awk -v dir="$dir" '$1 == "hertz" && ($4 == "err_p" || $4 == "err_p0_fit") {gsub("%", "")
    f = dir "/hertz-" $2 "-" $4 ".dat"; print $3, $6, $7, $8 > f}' "results/$name.txt"
if ls "$dir"/hertz-*-err_p.dat > /dev/null 2>&1; then
gnuplot -e "dir = '$dir'; png = 'results/$name.png'" - <<'GP'
set terminal pngcairo size 860,540
set output png
set logscale xy
set grid
set key bottom left font ",9"
set xlabel 'h_c (the methods drawn side by side)'
set ylabel 'relative error (%): median, bar from min to max'
set title 'Hertz, linear elements: the errors over meshes of nearly each size'
set xrange [0.1:0.01]
set yrange [0.01:100]
ms = "al nts mortar"
plot for [i = 1:3] sprintf('%s/hertz-%s-err_p.dat', dir, word(ms, i)) using ($1 * 1.04**(i - 2)):3:2:4 \
         with yerrorlines lw 2 lc i pt 7 title word(ms, i) . ', largest nodal pressure', \
     for [i = 1:3] sprintf('%s/hertz-%s-err_p0_fit.dat', dir, word(ms, i)) using ($1 * 1.04**(i - 2)):3:2:4 \
         with yerrorlines lw 2 dt 2 lc i pt 5 title word(ms, i) . ', fitted peak'
GP
echo "wrote $csv, results/$name.txt, results/$name.png"
else
echo "wrote $csv, results/$name.txt (no Hertz level: no figure)"
fi
