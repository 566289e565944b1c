#!/bin/sh
# Runs each libFuzzer harness for SECONDS seconds, one after another:
#   sh scripts/fuzz.sh BUILD SECONDS NAME...
# Seeds: tests/fuzz/corpus/<name>/ (read only); new inputs go to
# BUILD/corpus/<name>/; crash, leak, timeout and OOM inputs to
# tests/fuzz/crashes/<name>/ (commit them with the fix: make test replays
# them).  Prints one line per harness with libFuzzer's execution count and
# fails if any harness found something.
set -u
build=$1; secs=$2; shift 2
status=0
for name in "$@"; do
    work="$build/corpus/$name"; crashes="tests/fuzz/crashes/$name"
    mkdir -p "$work" "$crashes"
    log="$build/fuzz_$name.log"
    "$build/fuzz/fuzz_$name" -max_total_time="$secs" -print_final_stats=1 \
        -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
        -artifact_prefix="$crashes/" "$work" "tests/fuzz/corpus/$name" \
        >"$log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    secs_run=$(sed -n 's/^stat::.*//; s/^Done \([0-9]*\) runs in \([0-9]*\) second.*/\2/p' "$log")
    echo "fuzz $name: ${execs:-?} executions in ${secs_run:-?} s, exit $rc (log: $log)"
    [ "$rc" -eq 0 ] || status=1
done
exit $status
