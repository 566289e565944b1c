# pgsim chart: edit and rerun 'gnuplot igehy98-vs-published.gp'
set title 'igehy98: simulated against published (fidelity faithful: origin2000 analytic)'
set xlabel 'published'
set ylabel 'sim'
set grid
set key below left
set datafile separator "\t"
set logscale x
set xrange [0.5:100]
set format x '%g'
set mxtics 10
set xtics (1, 10, 100)
set logscale y
set yrange [0.5:100]
set format y '%g'
set mytics 10
set ytics (1, 10, 100)
set terminal pngcairo size 900,560 noenhanced font "sans,10"
set output 'igehy98-vs-published.png'
plot  'igehy98-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
    x with lines dashtype 2 lc rgb "gray" title "y = x", \
    keyentry with yerrorbars lc rgb "black" title 'bars: min to max over the rows with that x (point: mean)'
set terminal svg size 900,560 noenhanced font "sans,10"
set output 'igehy98-vs-published.svg'
plot  'igehy98-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
    x with lines dashtype 2 lc rgb "gray" title "y = x", \
    keyentry with yerrorbars lc rgb "black" title 'bars: min to max over the rows with that x (point: mean)'
set output
