#!/bin/sh
# Rewrites the parameter tables of docs/models.md (between its two
# "pgsim models --markdown" marker lines) from models/*.yaml, with the
# built binary.  tests/app/cli/test_models_doc.c fails when they differ.
#   sh scripts/gen-models-doc.sh [build/pgsim]
set -eu
bin=${1:-build/pgsim}
doc=docs/models.md
begin='<!-- begin: made by `pgsim models --markdown` (scripts/gen-models-doc.sh); edit models/*.yaml, not this -->'
end='<!-- end: pgsim models --markdown -->'
grep -qxF "$begin" "$doc" && grep -qxF "$end" "$doc" ||
    { echo "gen-models-doc: $doc lacks the marker lines" >&2; exit 2; }
tables=$(mktemp)
"$bin" models --markdown models > "$tables"
tmp=$(mktemp)
awk -v b="$begin" -v e="$end" -v t="$tables" '
    $0 == b { print; while ((getline l < t) > 0) print l; skip = 1; next }
    $0 == e { skip = 0 }
    !skip' "$doc" > "$tmp"
mv "$tmp" "$doc"
rm -f "$tables"
