#!/bin/sh
# Error against speed of the network fidelities (docs/net.md): runs
# `pgsim bench net` on the iPSC/2 (models/ipsc2.yaml, through the machine
# layer) for 16, 64 and 256 nodes and every pattern, 10 KB messages, best
# wall time of 3 runs; writes docs/net-speed-error.dat (one row per run and
# fidelity) and plots docs/net-speed-error.png with gnuplot.
# Usage: sh scripts/net-chart.sh [build-dir]
set -eu
build=${1:-build}
bin=${PGSIM_BIN:-$build/pgsim}
dat=docs/net-speed-error.dat
{
    echo "# pgsim bench net --machine ipsc2 --bytes 10240 --repeat 3 ($(date -u +%Y-%m-%d))"
    echo "# nodes pattern fidelity sim_time_s rel_err wall_s speedup"
} > $dat
for n in 16 64 256; do
    for p in all-to-all shift xor pairwise random hotspot; do
        $bin bench net --machine ipsc2 --nodes $n --pattern $p --bytes 10240 \
            --repeat 3 |
            awk -v n=$n -v p=$p '$1=="flow"||$1=="analytic"||$1=="packet" {
                print n, p, $1, $2, $3, $4, $5 }' >> $dat
    done
done
# |error| on a log scale: exact agreement (0) is drawn at the floor.
gnuplot <<GP
set terminal pngcairo size 1000,650 font 'Sans,11'
set output 'docs/net-speed-error.png'
set title "pgsim network fidelities on the iPSC/2 (models/ipsc2.yaml), 10 KB messages\n|error| of the completion time against packet level (circuit switching); 0 is drawn at 0.01 %"
set xlabel 'speed-up over packet level (wall time, best of 3)'
set ylabel '|relative error| (%)'
set logscale xy
set yrange [0.005:2000]
set format y '%g'
set grid
set key outside right top box
clampe(e) = abs(e) * 100 < 0.01 ? 0.01 : abs(e) * 100
is(f, n) = strcol(3) eq f && \$1 == n
# 256-node points with an error are named (random below, others above)
lab(side) = \$1 == 256 && strcol(3) ne "packet" && abs(\$5) > 0 && \
            (strcol(2) eq "random" ? -1 : 1) == side
set label 1 'shift, xor, pairwise: error 0 (contention-free)' at graph 0.02, first 0.016 font 'Sans,9'
plot '$dat' using (is("flow", 16) ? \$7 : 1/0):(clampe(\$5)) with points pt 6 ps 1.6 lc rgb '#1f77b4' title 'flow, 16 nodes', \
     '$dat' using (is("flow", 64) ? \$7 : 1/0):(clampe(\$5)) with points pt 8 ps 1.6 lc rgb '#1f77b4' title 'flow, 64', \
     '$dat' using (is("flow", 256) ? \$7 : 1/0):(clampe(\$5)) with points pt 5 ps 1.6 lc rgb '#1f77b4' title 'flow, 256', \
     '$dat' using (is("analytic", 16) ? \$7 : 1/0):(clampe(\$5)) with points pt 6 ps 1.6 lc rgb '#d62728' title 'analytic, 16', \
     '$dat' using (is("analytic", 64) ? \$7 : 1/0):(clampe(\$5)) with points pt 8 ps 1.6 lc rgb '#d62728' title 'analytic, 64', \
     '$dat' using (is("analytic", 256) ? \$7 : 1/0):(clampe(\$5)) with points pt 5 ps 1.6 lc rgb '#d62728' title 'analytic, 256', \
     '$dat' using (lab(1) ? \$7 : 1/0):(clampe(\$5)):2 with labels offset 0,1 font 'Sans,9' notitle, \
     '$dat' using (lab(-1) ? \$7 : 1/0):(clampe(\$5)):2 with labels offset 0,-1 font 'Sans,9' notitle
GP
echo "wrote $dat and docs/net-speed-error.png"
