#!/bin/sh
# make coverage: line and branch coverage of the test suites with gcov
# (GCC's own).  Builds the library and tests with --coverage into
# build-cov/, runs every suite from the repository root, then prints
#   - one line per folder of sim/: lines and branches executed;
#   - every public (non-static) function of the model folders (core, net,
#     machine, raster, scene, workload) that no test executes.
# Fails (exit 1) when such a function exists, so the list stays empty.
# The suites run from a scratch root whose build/ is $B (the rest are links
# to the tree), so the tests that run build/pgsim run the instrumented one.
set -u
export LC_ALL=C
B=${1:-build-cov}
MODEL="core net machine raster scene workload"
find "$B" -name '*.gcda' -delete 2>/dev/null
run=$(mktemp -d)
for f in *; do
    [ "$f" = build ] || ln -s "$PWD/$f" "$run/$f"
done
ln -s "$PWD/$B" "$run/build"
for t in $(cd "$B" && find tests -type f -perm -u+x | sort); do
    (cd "$run" && "build/$t" > /dev/null 2>&1) ||
        echo "coverage: suite fails: $t" >&2
done
rm -rf "$run"
out=$(mktemp)
for d in $(find sim -name '*.c' -exec dirname {} \; | sort -u); do
    (gcov -n -b -c -f -o "$B/obj/$d" $(ls "$d"/*.c) 2>/dev/null) |
        sed "s|^|$d\t|"
done > "$out"

echo "coverage by folder (gcov; lines and branches executed by make test's suites)"
awk -F'\t' '
function folder(d,    p) { split(d, p, "/"); return p[2] }
$2 ~ /^Function / { mode = "fn"; next }
$2 ~ /^File / { mode = ($2 ~ /\.c.$/) ? "file" : "hdr"; next }
mode == "file" && $2 ~ /^Lines executed:/ {
    split($2, a, /[:% ]+/); f = folder($1)
    lt[f] += a[5]; lx[f] += a[3] * a[5] / 100 }
mode == "file" && $2 ~ /^Taken at least once:/ {
    split($2, a, /[:% ]+/); f = folder($1)
    bt[f] += a[7]; bx[f] += a[5] * a[7] / 100 }
END {
    printf "%-10s %8s %8s %7s %9s %9s %7s\n", "folder", "lines", "run",
        "%", "branches", "taken", "%"
    n = split("core net machine raster scene workload reproduce output app", F, " ")
    for (i = 1; i <= n; i++) {
        f = F[i]; if (!(f in lt)) continue
        printf "%-10s %8d %8d %6.1f%% %9d %9d %6.1f%%\n", f, lt[f], lx[f] + 0.5,
            100 * lx[f] / lt[f], bt[f], bx[f] + 0.5,
            bt[f] ? 100 * bx[f] / bt[f] : 100
    }
}' "$out"

# Public functions never entered: gcov's per-function "Lines executed:0.00%"
# intersected with the objects' global text symbols.
nm_syms=$(mktemp)
for f in $MODEL; do
    find "$B/obj/sim/$f" -name '*.o' -exec nm -g --defined-only {} + 2>/dev/null
done | awk '$2 == "T" { print $3 }' | sort -u > "$nm_syms"
unrun=$(awk -F'\t' -v model="$MODEL" '
BEGIN { split(model, M, " "); for (i in M) ism["sim/" M[i]] = 1 }
$2 ~ /^Function / { fn = $2; sub(/^Function ./, "", fn); sub(/.$/, "", fn)
                    d = $1; next }
fn != "" && $2 ~ /^Lines executed:/ {
    split(d, p, "/"); top = p[1] "/" p[2]
    if ((top in ism) && $2 ~ /:0\.00%/) print fn "\t" d
    fn = "" }' "$out" | sort -u | join -t "$(printf '\t')" - "$nm_syms")
echo
if [ -n "$unrun" ]; then
    echo "public functions of the model folders that no test executes:"
    echo "$unrun" | awk -F'\t' '{ printf "  %s  (%s)\n", $1, $2 }'
    rm -f "$out" "$nm_syms"
    exit 1
fi
echo "every public function of the model folders is executed by a test"
rm -f "$out" "$nm_syms"
