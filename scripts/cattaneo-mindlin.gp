# cattaneo-mindlin.gp: tangential traction along the loading direction
# against Mindlin's profile.  Called with files (one .dat per level),
# ratios (Q / (mu P) reached), a, p0, mu, png.
set terminal pngcairo size 900,600
set output png
set xlabel "x (along the load)"
set ylabel "tangential traction q_x"
set key top right
set grid
qa(x) = abs(x) < a ? mu * p0 * sqrt(1 - x * x / (a * a)) : 0
qc(x, c) = abs(x) < c ? (c / a) * mu * p0 * sqrt(1 - x * x / (c * c)) : 0
c(r) = a * (1 - r) ** (1. / 3)
set samples 800
plot for [i=1:words(files)] word(files, i) using 1:3 with points pt 7 ps 0.6 lc i title sprintf("FE, Q/(mu P) = %.2f", word(ratios, i) + 0), \
     for [i=1:words(files)] qa(x) - qc(x, c(word(ratios, i) + 0)) with lines lw 2 lc i notitle, \
     qa(x) with lines dt 2 lc rgb "black" title "mu p (full slip)"
