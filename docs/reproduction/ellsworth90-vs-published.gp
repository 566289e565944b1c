# pgsim chart: edit and rerun 'gnuplot ellsworth90-vs-published.gp'
set title 'ellsworth90: simulated against published (fidelity faithful)'
set xlabel 'published'
set ylabel 'sim'
set grid
set key below left
set datafile separator "\t"
set logscale x
set xrange [1:5000]
set format x '%g'
set mxtics 10
set xtics (1, 10, 100, 1000)
set logscale y
set yrange [1:5000]
set format y '%g'
set mytics 10
set ytics (1, 10, 100, 1000)
set terminal pngcairo size 900,560 noenhanced font "sans,10"
set output 'ellsworth90-vs-published.png'
plot  'ellsworth90-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
     'ellsworth90-vs-published.dat' index 1 using 1:2:3:4 with yerrorbars title 'table=db', \
    x with lines dashtype 2 lc rgb "gray" title "y = x", \
    keyentry with yerrorbars lc rgb "black" title 'bars: min to max over the rows with that x (point: mean)'
set terminal svg size 900,560 noenhanced font "sans,10"
set output 'ellsworth90-vs-published.svg'
plot  'ellsworth90-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
     'ellsworth90-vs-published.dat' index 1 using 1:2:3:4 with yerrorbars title 'table=db', \
    x with lines dashtype 2 lc rgb "gray" title "y = x", \
    keyentry with yerrorbars lc rgb "black" title 'bars: min to max over the rows with that x (point: mean)'
set output
