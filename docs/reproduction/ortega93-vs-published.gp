# pgsim chart: edit and rerun 'gnuplot ortega93-vs-published.gp'
set title 'ortega93: simulated against published (fidelity faithful: cm200 formula, cm5 formula)'
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
