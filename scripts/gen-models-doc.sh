#!/bin/sh
# Rewrites the parameter tables of docs/models.md (between its two
# "pgsim models --markdown" marker lines) from models/*.yaml, and its
# pairings table (between the "pgsim models --pairings" lines: every
# workload config on every model, configs/pairings/pairings.yaml), with
# the built binary.  tests/app/cli/test_models_doc.c and
# test_pairings.c fail when they differ.
#   sh scripts/gen-models-doc.sh [build/pgsim]
set -eu
bin=${1:-build/pgsim}
doc=docs/models.md
# splice BEGIN END ARGS...: the lines between the marker lines BEGIN and
# END of the doc become the output of pgsim ARGS.
splice() {
    b=$1 e=$2
    shift 2
    grep -qxF "$b" "$doc" && grep -qxF "$e" "$doc" ||
        { echo "gen-models-doc: $doc lacks the marker lines $b" >&2; exit 2; }
    tables=$(mktemp)
    "$bin" "$@" > "$tables"
    tmp=$(mktemp)
    awk -v b="$b" -v e="$e" -v t="$tables" '
        $0 == b { print; while ((getline l < t) > 0) print l; skip = 1; next }
        $0 == e { skip = 0 }
        !skip' "$doc" > "$tmp"
    mv "$tmp" "$doc"
    rm -f "$tables"
}
splice '<!-- begin: made by `pgsim models --markdown` (scripts/gen-models-doc.sh); edit models/*.yaml, not this -->' \
    '<!-- end: pgsim models --markdown -->' models --markdown models
splice '<!-- begin: made by `pgsim models --pairings configs/pairings/pairings.yaml` (scripts/gen-models-doc.sh); edit the list and models/*.yaml, not this -->' \
    '<!-- end: pgsim models --pairings -->' \
    models --pairings configs/pairings/pairings.yaml
