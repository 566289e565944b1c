# pgsim chart: edit and rerun 'gnuplot igehy98-vs-published.gp'
set title 'igehy98: simulated against published (fidelity faithful: origin2000 analytic)'
set xlabel 'published'
set ylabel 'sim'
set grid
set key top left
set datafile separator "\t"
set logscale x
set autoscale xfix
set offsets graph 0.02, graph 0.02, 0, 0
set logscale y
set autoscale yfix
set terminal pngcairo size 900,560 noenhanced font "sans,10"
set output 'igehy98-vs-published.png'
plot  'igehy98-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
    x with lines dashtype 2 lc rgb "gray" title "y = x"
set terminal svg size 900,560 noenhanced font "sans,10"
set output 'igehy98-vs-published.svg'
plot  'igehy98-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
    x with lines dashtype 2 lc rgb "gray" title "y = x"
set output
