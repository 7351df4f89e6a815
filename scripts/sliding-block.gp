# sliding-block.gp: tangential reaction on the block's top face against the
# imposed displacement, with the Coulomb limits +-mu N.
set terminal pngcairo size 800,560
set output png
set xlabel 'imposed tangential displacement d'
set ylabel 'tangential reaction T'
set grid
set key bottom right
plot dat using 1:2 with linespoints pt 7 ps 0.6 title 'computed', \
     muN with lines dt 2 lw 2 title 'mu N', -muN with lines dt 2 lw 2 title '-mu N'
