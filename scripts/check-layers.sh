#!/bin/sh
# Checks that includes point one way down the floors of sim/, and that
# files inside a workload folder follow one naming rule.  Floors:
#   app -> reproduce -> run -> workload -> machine, raster -> net, scene ->
#   output, core
# A file may include a header of its own folder or of a lower floor; an
# include of a higher floor, or of another folder on the same floor, is
# reported as FILE:LINE and fails.  Run by `make test`.
set -u
cd "$(dirname "$0")/.."
floor() {
    case $1 in
    core) echo 0 ;; output) echo 1 ;; net | scene) echo 2 ;;
    machine | raster) echo 3 ;; workload) echo 4 ;; run) echo 5 ;;
    reproduce) echo 6 ;; app) echo 7 ;; *) echo -1 ;;
    esac
}
bad=0
for f in $(find sim -name '*.[ch]' | LC_ALL=C sort); do
    from=$(echo "$f" | cut -d/ -f2)
    grep -n '^#include "sim/' "$f" | while IFS= read -r line; do
        to=$(echo "$line" | sed 's|^[0-9]*:#include "sim/\([a-z_]*\)/.*|\1|')
        [ "$to" = "$from" ] && continue
        fl=$(floor "$from"); tl=$(floor "$to")
        if [ "$fl" -lt 0 ] || [ "$tl" -lt 0 ] || [ "$tl" -ge "$fl" ]; then
            echo "$f:${line%%:*}: $from (floor $fl) includes $to (floor $tl)"
        fi
    done
done > /tmp/pgsim-layers.$$
# Processors and machines: proc.c must not include machine.h (one way).
grep -n '#include "sim/machine/machine.h"' sim/machine/proc.[ch] \
    | sed 's/$/: proc includes machine (proc is below machine)/' \
    >> /tmp/pgsim-layers.$$
# One naming rule inside workload folders: sim/workload/<family>/ holds
# <p>_workload.c (the WlOps table) and every other file is <p>_<concept>.
for d in sim/workload/*/; do
    w=$(ls "$d" | grep '_workload\.c$')
    if [ "$(echo "$w" | wc -w)" -ne 1 ]; then
        echo "$d: found '$w', expected one <prefix>_workload.c" >> /tmp/pgsim-layers.$$
        continue
    fi
    p=${w%_workload.c}
    ls "$d" | grep -v "^${p}_" | grep -v '^README' |
        sed "s|^|$d|; s|\$|: not named ${p}_<concept> (the folder's prefix)|" \
        >> /tmp/pgsim-layers.$$
done
if [ -s /tmp/pgsim-layers.$$ ]; then
    cat /tmp/pgsim-layers.$$
    bad=1
fi
rm -f /tmp/pgsim-layers.$$
n=$(find sim -name '*.[ch]' | wc -l)
if [ $bad -eq 0 ]; then echo "layers: $n files, includes point down, workload files named by prefix"; fi
exit $bad
