#!/bin/sh
# Runs each cmocka binary from the repository root; prints one closing line
# "tests: N passed, N failed" and fails if any suite failed.
set -u
build=$1; shift
pass=0; fail=0; failed=""
for t in "$@"; do
    if "$t"; then pass=$((pass + 1)); else fail=$((fail + 1)); failed="$failed $t"; fi
done
[ -n "$failed" ] && echo "failed suites:$failed"
echo "suites: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
