# soft-ball.gp: force against indentation, finite deformation and small
# strain on the same mesh, with Hertz's curve.
set terminal pngcairo size 800,560
set output png
set datafile separator ','
set xlabel 'indentation d (ball radius 1)'
set ylabel 'contact force F'
set grid
set key top left
plot dat every ::1 using 1:2 with linespoints pt 7 ps 0.7 title 'finite deformation (Neo-Hookean)', \
     dat every ::1 using 1:3 with linespoints pt 5 ps 0.7 title 'small strain', \
     dat every ::1 using 1:4 with lines dt 2 lw 2 title 'Hertz'
