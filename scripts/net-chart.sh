#!/bin/sh
# Error against speed of the network fidelities (docs/net.md): runs
# `pgsim bench net` on the iPSC/2 hypercube for 16, 64 and 256 nodes and
# every pattern, writes docs/net-speed-error.dat (one row per run and
# fidelity) and plots docs/net-speed-error.png with gnuplot.
# Usage: sh scripts/net-chart.sh [build-dir]
set -eu
build=${1:-build}
bin=${PGSIM_BIN:-$build/pgsim}
dat=docs/net-speed-error.dat
net="--machine ipsc2 --bandwidth 2.8 --startup 350 --per-hop 10"
echo "# nodes pattern fidelity sim_time_s rel_err wall_s speedup" > $dat
for n in 16 64 256; do
    for p in all-to-all shift pairwise random hotspot; do
        $bin bench net $net --nodes $n --pattern $p --bytes 10240 |
            awk -v n=$n -v p=$p '$1=="flow"||$1=="analytic"||$1=="packet" {
                print n, p, $1, $2, $3, $4, $5 }' >> $dat
    done
done
gnuplot <<GP
set terminal pngcairo size 900,600
set output 'docs/net-speed-error.png'
set title 'pgsim network fidelities on the iPSC/2 (10 KB messages)'
set xlabel 'speed-up over packet level (wall time)'
set ylabel '|relative error| of completion time vs packet level'
set logscale x
set key top left
set grid
plot '$dat' using (strcol(3) eq "flow" ? \$7 : 1/0):(abs(\$5)) with points pt 7 ps 1.5 title 'flow', \
     '$dat' using (strcol(3) eq "analytic" ? \$7 : 1/0):(abs(\$5)) with points pt 5 ps 1.5 title 'analytic'
GP
echo "wrote $dat and docs/net-speed-error.png"
