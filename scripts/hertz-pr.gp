# hertz-pr.gp: contact pressure p(r) at the slave quadrature points against
# the Hertz profile p0 sqrt(1 - r^2/a^2) and the least-squares fit (the data
# file holds r^2 and p).
set terminal pngcairo size 800,560
set output png
set xlabel 'r'
set ylabel 'contact pressure'
set grid
set key top right
set samples 400
hz(r) = r < a ? p0 * sqrt(1 - (r / a)**2) : 0
fit_(r) = r < af ? pf * sqrt(1 - (r / af)**2) : 0
set xrange [0:1.6 * a]
set yrange [0:1.15 * p0]
plot dat using (sqrt($1)):2 with points pt 7 ps 0.5 title 'quadrature points', \
     hz(x) with lines lw 2 title 'Hertz (from computed F)', \
     fit_(x) with lines dt 2 lw 2 title 'fit p^2 = c0 + c1 r^2'
