#!/bin/sh
# bench_search.sh: contact-search benchmark; medians of 3 runs per size into
# results/bench-search.csv (facets,points,build_s,query_s,brute_s,peak_mb)
# and a log-log plot results/bench-search.png.
cd "$(dirname "$0")/../.." || exit 2
mkdir -p results
out=results/bench-search.csv
echo "facets,points,build_s,query_s,brute_s,peak_mb" > "$out"
med() { sort -g | sed -n 2p; }
for n in 10000 20000 100000 200000 1000000 2000000; do
    runs=$(for r in 1 2 3; do ./build/bench_search "$n" 200000 2>/dev/null || exit 1; done)
    [ -n "$runs" ] || { echo "bench_search failed at $n"; exit 1; }
    f=$(echo "$runs" | head -1 | cut -d, -f1)
    p=$(echo "$runs" | head -1 | cut -d, -f2)
    b=$(echo "$runs" | cut -d, -f3 | med)
    q=$(echo "$runs" | cut -d, -f4 | med)
    bf=$(echo "$runs" | cut -d, -f5 | med)
    m=$(echo "$runs" | cut -d, -f6 | med)
    echo "$f,$p,$b,$q,$bf,$m" | tee -a "$out"
done
gnuplot <<'GP'
set terminal pngcairo size 800,560
set output 'results/bench-search.png'
set datafile separator ','
set logscale xy
set key bottom right
set grid
set xlabel 'master facets (= slave points)'
set ylabel 'seconds (one core)'
set title 'Contact search: tree build and query vs brute force'
plot 'results/bench-search.csv' every ::1 using 1:3 with linespoints title 'tree build', \
     '' every ::1 using 1:4 with linespoints title 'query, all points', \
     '' every ::1 using 1:($3+$4) with linespoints title 'build + query', \
     '' every ::1 using 1:5 with linespoints title 'brute force (sampled, scaled)', \
     x/1e6*2 with lines dt 2 title 'linear: 2 s at 1e6'
GP
echo "wrote $out and results/bench-search.png"
