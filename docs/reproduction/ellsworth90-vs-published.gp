# pgsim chart: edit and rerun 'gnuplot ellsworth90-vs-published.gp'
set title 'ellsworth90: simulated against published (fidelity faithful)'
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
set output 'ellsworth90-vs-published.png'
plot  'ellsworth90-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
     'ellsworth90-vs-published.dat' index 1 using 1:2:3:4 with yerrorbars title 'table=db', \
    x with lines dashtype 2 lc rgb "gray" title "y = x"
set terminal svg size 900,560 noenhanced font "sans,10"
set output 'ellsworth90-vs-published.svg'
plot  'ellsworth90-vs-published.dat' index 0 using 1:2:3:4 with yerrorbars title 'table=1', \
     'ellsworth90-vs-published.dat' index 1 using 1:2:3:4 with yerrorbars title 'table=db', \
    x with lines dashtype 2 lc rgb "gray" title "y = x"
set output
