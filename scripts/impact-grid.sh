#!/bin/sh
# impact-grid.sh: the bar impact on three mesh levels and three time steps,
# default settings otherwise (redistributed mass, trapezoidal rule), one
# core; a row per run, failed runs included:
#   results/impact-grid.csv
# Usage: sh scripts/impact-grid.sh [mass]   (mass: redistributed, the
# default, or consistent)
cd "$(dirname "$0")/.." || exit 2
mass=${1:-redistributed}
mkdir -p results/impact-grid
csv=results/impact-grid.csv
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
val() { sed -n "s/.*\"$2\": \([^,}]*\).*/\1/p" "$1" | head -1; }
echo "mass,h,dt,courant,dofs,converged,err_duration,err_p_mean,p_osc,p_peak,restitution,energy_drift,newton,uzawa,step_cuts,predictor_skipped,time_total" > "$csv"
for h in 0.1 0.05 0.025; do
    for dt in 0.004 0.002 0.001; do
        out=results/impact-grid/$mass-h$h-dt$dt
        rm -f "$out.json"
        sh scripts/ff scripts/bar-impact.edp -h "$h" -dt "$dt" -mass "$mass" -out "$out" > "$out.log" 2>&1
        j=$out.json
        if [ -f "$j" ]; then
            row="$mass,$h,$dt"
            for k in courant dofs converged err_duration err_p_mean p_osc p_peak restitution energy_drift \
                     newton_iterations uzawa_iterations step_cuts predictor_skipped time_total; do
                row="$row,$(val "$j" "$k")"
            done
        else
            row="$mass,$h,$dt,,,0,,,,,,,,,,,"
        fi
        echo "$row" >> "$csv"
        echo "$row"
    done
done
