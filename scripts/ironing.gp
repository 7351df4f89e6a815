# ironing.gp: the die's reaction forces against its prescribed displacement
# (pressing, then sliding), as in Puso and Laursen's figure; the Coulomb
# line mu Fz for comparison.
set terminal pngcairo size 900,600
set output png
set datafile separator ','
set xlabel 'prescribed die displacement (press |u_z|, then press depth + slide u_x)'
set ylabel 'reaction force on the die'
set grid
set key top left
path(x, z) = -z + x
plot dat every ::1 using (path($2, $3)):5 with linespoints pt 7 ps 0.5 title 'F_z', \
     dat every ::1 using (path($2, $3)):4 with linespoints pt 5 ps 0.5 title 'F_x', \
     dat every ::1 using (path($2, $3)):(mu * $5) with lines dt 2 title 'mu F_z'
