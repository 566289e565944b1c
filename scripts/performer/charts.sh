#!/bin/sh
# The charts of docs/workloads.md, sections "performer" and "PN
# triangles": per-stage frame times of configs/performer-town.yaml, the
# stress-feedback LOD over time at a low and a high gain, and the PN
# geometry-compression sweeps.  Run from the repository root after
# `make`; writes docs/performer-*.png, docs/pn-*.png and the sweeps'
# tables docs/pn-*.csv.
set -eu
B=${PGSIM:-build/pgsim}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

"$B" run configs/performer-town.yaml -q --set "workload.frame_log=$T/town.csv" >/dev/null
"$B" plot "$T/town_stages.csv" --x=frame --y=ms --series=stage \
    --title="performer-town: time per stage and between swaps (30 Hz, 3 processes, DRAW locked)" \
    -o "$T/performer-stages.png"

for g in 0.5 8; do
    "$B" run configs/performer-town.yaml -q --set workload.stress.gain=$g \
        --set "workload.frame_log=$T/g$g.csv" >/dev/null
done
{
    echo "frame,gain,stress,mean_lod"
    for g in 0.5 8; do
        awk -F, -v g=$g 'NR > 1 && $1 < 120 { print $1 "," g "," $10 "," $11 }' "$T/g$g.csv"
    done
} >"$T/stress.csv"
"$B" plot "$T/stress.csv" --x=frame --y=stress --series=gain \
    --title="Stress-feedback LOD: stress CULL used, per frame (gain 0.5 settles, 8 oscillates)" \
    -o "$T/performer-stress.png"
"$B" plot "$T/stress.csv" --x=frame --y=mean_lod --series=gain \
    --title="Mean LOD child chosen per frame (0 finest, 3 none)" \
    -o "$T/performer-lod.png"

cp "$T"/performer-*.png docs/

for v in onyx onyx-fastpipe pp5; do
    "$B" sweep "configs/sweep-pn-$v.yaml" --out="$T/pn-$v" -j 2 >/dev/null
    cp "$T/pn-$v"/pn-$v-*.png docs/
    cp "$T/pn-$v/results.csv" "docs/pn-$v.csv"
done
