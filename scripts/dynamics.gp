# dynamics.gp: a dynamic scene's history (scene.idp writeDynamics): the
# energies and the contact force against time.
#   gnuplot -e "dat='x.dat'; png='x.png'" dynamics.gp
set terminal pngcairo size 900,700 font ",10"
set output png
set multiplot layout 2,1
set key outside right
set xlabel "t"
set ylabel "energy"
set grid
plot dat u 1:2 w l lw 2 t "kinetic", dat u 1:3 w l lw 2 t "elastic", \
     dat u 1:($2+$3+$6-$4) w l lw 2 dt 2 t "kin + el + dissipated - external work", \
     dat u 1:6 w l t "dissipated", dat u 1:5 w l dt 3 t "contact work"
set ylabel "contact force"
plot dat u 1:7 w lp pt 7 ps 0.4 t "Fx", dat u 1:8 w lp pt 7 ps 0.4 t "Fy", dat u 1:9 w lp pt 7 ps 0.4 t "Fz"
unset multiplot
