# pgsim chart: edit and rerun 'gnuplot ortega93-vs-published.gp'
set title 'ortega93: simulated against published (fidelity faithful: cm200 formula, cm5 formula)'
set xlabel 'published'
set ylabel 'sim'
set grid
set key below left
set datafile separator "\t"
set logscale x
set xrange [0.2:1e+06]
set format x '%g'
set mxtics 10
set xtics (1, 10, 100, 1000, 10000, 100000, 1e+06)
set logscale y
set yrange [0.2:2e+06]
set format y '%g'
set mytics 10
set ytics (1, 10, 100, 1000, 10000, 100000, 1e+06)
set terminal pngcairo size 900,560 noenhanced font "sans,10"
set output 'ortega93-vs-published.png'
plot  'ortega93-vs-published.dat' index 0 using 1:2 with points pointtype 7 pointsize 1.2 title 'table=1', \
     'ortega93-vs-published.dat' index 1 using 1:2 with points pointtype 7 pointsize 1.2 title 'table=2', \
     'ortega93-vs-published.dat' index 2 using 1:2 with points pointtype 7 pointsize 1.2 title 'table=text', \
    x with lines dashtype 2 lc rgb "gray" title "y = x"
set terminal svg size 900,560 noenhanced font "sans,10"
set output 'ortega93-vs-published.svg'
plot  'ortega93-vs-published.dat' index 0 using 1:2 with points pointtype 7 pointsize 1.2 title 'table=1', \
     'ortega93-vs-published.dat' index 1 using 1:2 with points pointtype 7 pointsize 1.2 title 'table=2', \
     'ortega93-vs-published.dat' index 2 using 1:2 with points pointtype 7 pointsize 1.2 title 'table=text', \
    x with lines dashtype 2 lc rgb "gray" title "y = x"
set output
