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
