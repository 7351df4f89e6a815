#!/bin/sh
# impact-grid.sh: an impact case on three mesh levels and three time
# steps, default settings otherwise (redistributed mass, trapezoidal rule),
# one core; a row per run, failed runs included:
#   bar      the bar impact                   -> results/impact-grid.csv
#   spheres  the head-on spheres impact       -> results/impact-grid-spheres.csv
#   oblique  the spheres at 45 deg, mu = 0.3  -> results/impact-grid-oblique.csv
# Usage: sh scripts/impact-grid.sh [bar | spheres | oblique] [mass]
#   (mass: redistributed, the default, or consistent)
cd "$(dirname "$0")/.." || exit 2
case=${1:-bar}
mass=${2:-redistributed}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
. scripts/json.sh
case $case in
bar)
    csv=results/impact-grid.csv script=scripts/bar-impact.edp hopt=-h extra=
    levels="0.1 0.05 0.025" steps="0.004 0.002 0.001"
    keys="courant dofs converged err_duration err_p_mean p_osc p_peak restitution energy_drift"
    head="mass,h,dt,courant,dofs,converged,err_duration,err_p_mean,p_osc,p_peak,restitution,energy_drift" ;;
spheres|oblique)
    csv=results/impact-grid-$case.csv script=scripts/spheres-impact.edp hopt=-hc extra=
    [ "$case" = oblique ] && extra="-vt 0.1"
    levels="0.04 0.02 0.01" steps="0.01 0.005 0.0025"
    keys="dofs converged err_duration err_F_peak err_duration_finite err_F_finite restitution energy_drift momentum_error"
    [ "$case" = oblique ] && keys="$keys impulse_t_over_mu_impulse_n dissipation"
    head="mass,hc,dt,$(echo $keys | tr ' ' ',')" ;;
*)
    echo "impact-grid.sh: case '$case' is not bar, spheres or oblique" >&2; exit 2 ;;
esac
keys="$keys newton_iterations uzawa_iterations step_cuts predictor_skipped time_total"
head="$head,newton,uzawa,step_cuts,predictor_skipped,time_total"
mkdir -p results/impact-grid
echo "$head" > "$csv"
for h in $levels; do
    for dt in $steps; do
        out=results/impact-grid/$case-$mass-h$h-dt$dt
        rm -f "$out.json"
        # shellcheck disable=SC2086
        sh scripts/ff $script $hopt "$h" -dt "$dt" -mass "$mass" $extra -out "$out" > "$out.log" 2>&1
        row="$mass,$h,$dt"
        for k in $keys; do
            v=
            [ -f "$out.json" ] && v=$(val "$out.json" "$k")
            [ "$k" = converged ] && [ -z "$v" ] && v=0
            row="$row,$v"
        done
        echo "$row" >> "$csv"
        echo "$row"
    done
done
