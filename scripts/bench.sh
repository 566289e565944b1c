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
# parameters are those of models/ipsc2.yaml: 2.8 MB/s per DCM channel and
# 350 us start-up (Nugent 1988), 10 us per hop (assumption, see the model).
IPSC2_NET="--machine ipsc2 --bandwidth 2.8 --startup 350 --per-hop 10"
for n in 16 64 256; do
    for p in all-to-all pairwise random hotspot; do
        section "net: iPSC/2 $n nodes, $p, 10 KB (target at 256 all-to-all: flow well under 1 s wall)"
        $bin bench net $IPSC2_NET --nodes $n --pattern $p --bytes 10240 \
            --fidelity all
    done
done

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
