# pgsim chart: edit and rerun 'gnuplot kurc96-vs-published.gp'
set title 'kurc96: simulated against published (fidelity faithful: ipsc2 packet)'
set xlabel 'published'
set ylabel 'sim'
set grid
set key below left
set datafile separator "\t"
set logscale x
set xrange [200:200000]
set format x '%g'
set mxtics 10
set xtics (1000, 10000, 100000)
set logscale y
set yrange [200:200000]
set format y '%g'
set mytics 10
set ytics (1000, 10000, 100000)
set terminal pngcairo size 900,560 noenhanced font "sans,10"
set output 'kurc96-vs-published.png'
plot  'kurc96-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
     'kurc96-vs-published.dat' index 1 using 1:2:3:4 with yerrorbars title 'table=2', \
    x with lines dashtype 2 lc rgb "gray" title "y = x", \
    keyentry with yerrorbars lc rgb "black" title 'bars: min to max over the rows with that x (point: mean)'
set terminal svg size 900,560 noenhanced font "sans,10"
set output 'kurc96-vs-published.svg'
plot  'kurc96-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
     'kurc96-vs-published.dat' index 1 using 1:2:3:4 with yerrorbars title 'table=2', \
    x with lines dashtype 2 lc rgb "gray" title "y = x", \
    keyentry with yerrorbars lc rgb "black" title 'bars: min to max over the rows with that x (point: mean)'
set output
