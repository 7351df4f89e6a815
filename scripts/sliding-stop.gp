# sliding-stop.gp: the block's mean velocity against time, with the
# analytic deceleration v0 - (mu N / m) t, and the friction force.
set terminal pngcairo size 800,560
set output png
set xlabel 'time t'
set ylabel 'mean velocity of the block'
set y2label 'friction force on the block F_x'
set y2tics
set ytics nomirror
set grid
set key top right
plot dat using 1:2 with points pt 7 ps 0.7 title 'computed v_{cm}', \
     dat using 1:3 with lines lw 2 dt 2 title 'v_0 - (mu N / m) t', \
     dat using 1:5 axes x1y2 with lines lw 1 title 'F_x'
