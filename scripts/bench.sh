#!/bin/sh
# make bench: benchmarks that print figures.  Timings belong here, never in
# unit tests.  Each section prints its own lines; figures end in a number.
set -u
build=${1:-build}
bin=$build/pgsim
section() { printf '\n== %s\n' "$*"; }

section "PHOLD, 1,024 LPs x 1 pending (target >= 10 M events/s)"
$bin bench phold --lps 1024 --pending-per-lp 1 --remote 0.25 \
    --lookahead 1us --events 20M
section "PHOLD, 16,384 LPs x 16 pending = 262,144 (target >= 3 M events/s)"
$bin bench phold --lps 16384 --pending-per-lp 16 --remote 0.25 \
    --lookahead 1us --events 10M

# Network fidelities on the iPSC/2 hypercube (sim/net, docs/net.md).  The
# network comes from models/ipsc2.yaml through the machine layer (2.8 MB/s
# per DCM channel, 350 us start-up and 700 us above 100 B, 10 us per hop);
# --nodes picks the partition; wall times are the best of 3 runs.  Each run
# prints its table; a summary of all of them follows.
net_out=$(mktemp)
net_rows=$(mktemp)
for n in 16 64 256; do
    for p in all-to-all pairwise random hotspot; do
        section "net: iPSC/2 $n nodes, $p, 10 KB (target at 256 all-to-all: flow well under 1 s wall)"
        $bin bench net --machine ipsc2 --nodes $n --pattern $p --bytes 10240 \
            --fidelity all --repeat 3 > "$net_out"
        cat "$net_out"
        awk -v n=$n -v p=$p '$1=="packet"||$1=="flow"||$1=="analytic" {
            print n, p, $1, $2, $3, $4, $5 }' "$net_out" >> "$net_rows"
    done
done
section "net: iPSC/2 summary, 10 KB messages (rel_err and speedup against packet level)"
awk 'BEGIN { printf "%5s %-10s %-9s %12s %9s %9s %8s\n", "nodes", "pattern",
             "fidelity", "sim_time_s", "rel_err", "wall_s", "speedup" }
     { printf "%5s %-10s %-9s %12s %9s %9s %8s\n", $1, $2, $3, $4, $5, $6, $7 }' \
    "$net_rows"
rm -f "$net_out" "$net_rows"

section "raster: 8 teapots (seed 003, 30,008 polygons), 640x640, modified scanline z-buffer"
$bin bench raster --scene teapots --count 8 --size 640 --frames 20
section "raster: 8 teapots, 640x640, full z-buffer"
$bin bench raster --scene teapots --count 8 --size 640 --frames 20 \
    --zbuffer full
section "raster: gyroid isosurface (grid 80, ~360K triangles), 1024x1024, scanline"
$bin bench raster --scene isosurface --grid 80 --size 1024 --frames 5
section "raster: gyroid isosurface, 1024x1024, full z-buffer"
$bin bench raster --scene isosurface --grid 80 --size 1024 --frames 5 \
    --zbuffer full
