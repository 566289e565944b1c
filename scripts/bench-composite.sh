# Sourced by scripts/bench.sh (uses its bin, section, goal and field):
# the image fidelity ladder of sort-last compositing (issue 35, points 2
# and 4; sim/workload/pixelmerge/pm_rung.h, docs/workloads.md).
# Rungs: each one's error against real pixels (compositing time, bytes)
# and its speed-up, on block-decomposition footprints.  Scale: 32,768
# processes compositing a 64-megapixel image at the counts rung, wall
# seconds and peak RSS beside the goals (60 s, 4 GB).
# PGSIM_BENCH_COMPOSITE_MACHINE picks the scale run's machine (default:
# bgp-intrepid when the model exists, else the iPSC/2's hypercube).
comp_rows=$(mktemp)
for s in binary_swap radix_k direct_send; do
    for o in none rect rect_rle; do
        section "composite: rungs, 256 processes, 1024 x 1024, iPSC/2, $s, $o"
        out=$($bin bench composite --machine ipsc2 --procs 256 --size 1024 \
            --scheme $s --opt $o --repeat 2)
        echo "$out"
        echo "$out" | awk -v s=$s -v o=$o '$1 == "runs" || $1 == "counts" {
            print s, o, $1, $6, $7, $9 }' >> "$comp_rows"
    done
done
section "composite: rung errors against real pixels (256 processes, 1024 x 1024)"
awk 'BEGIN { printf "%-12s %-9s %-7s %9s %9s %8s\n", "scheme", "opt", "rung",
             "err_time", "err_bytes", "speedup" }
     { printf "%-12s %-9s %-7s %9s %9s %8s\n", $1, $2, $3, $4, $5, $6 }' \
    "$comp_rows"
worst() { # rung column: the largest |relative error| in percent
    awk -v r=$1 -v c=$2 '$3 == r { e = $c < 0 ? -$c : $c; if (e > w) w = e }
        END { printf "%.2f", 100 * w }' "$comp_rows"
}
goal "composite: runs rung, worst |error| in time vs pixels" "$(worst runs 4)" "<=" 0 %
goal "composite: counts rung, worst |error| in time vs pixels" "$(worst counts 4)" "<=" 30 %
goal "composite: counts rung, worst |error| in bytes vs pixels" "$(worst counts 5)" "<=" 30 %
rm -f "$comp_rows"

cm=${PGSIM_BENCH_COMPOSITE_MACHINE:-}
if [ -z "$cm" ]; then
    if [ -f models/bgp-intrepid.yaml ]; then cm=bgp-intrepid; else cm=ipsc2; fi
fi
# A model without compositing costs (pack, compare of node kind "node")
# gets them from its clock: the Blue Gene/P's PowerPC 450 at 850 MHz
# (models/bgp-intrepid.yaml), assumed 4 cycles to pack a pixel record
# (load, store, index, loop branch) and 6 to composite one (two loads, a
# compare, a branch, a store, the loop), single issue: 4.7 ns and 7.1 ns.
# Not fitted to any compositing measurement.
cm_sets=""
if [ "$cm" = bgp-intrepid ]; then
    cm_sets="--set machine.nodes.node.costs.pack=4.7ns --set machine.nodes.node.costs.compare=7.1ns"
fi
comp_t=$(mktemp)
for s in radix_k binary_swap; do
    section "composite: 32,768 processes, 8192 x 8192 (64 MP), counts rung, $cm, $s, rect_rle"
    /usr/bin/time -f '%e %M' -o "$comp_t" $bin bench composite --machine $cm \
        $cm_sets --procs 32768 --size 8192 --rung counts --scheme $s \
        --opt rect_rle
    w=$(awk '{ printf "%.2f", $1 }' "$comp_t")
    rss=$(awk '{ printf "%.1f", $2 / 1024 }' "$comp_t")
    echo "wall_s (process): $w"
    echo "peak_rss_mb (process): $rss"
    goal "composite: 32,768 procs 64 MP $s ($cm), wall" "$w" "<=" 60 s
    goal "composite: 32,768 procs 64 MP $s ($cm), peak RSS" "$rss" "<=" 4096 MB
done
rm -f "$comp_t"
