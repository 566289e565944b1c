#!/bin/sh
# Regenerates sim/scene/teapot_data.c from data/teapot.txt (Newell's
# patches).  Run from the repo root after editing the data file;
# tests/scene/test_teapot.c checks that the two agree.
set -eu
in=${1:-data/teapot.txt}
out=${2:-sim/scene/teapot_data.c}
awk '
BEGIN {
    print "/* teapot_data.c -- GENERATED from data/teapot.txt by"
    print " * scripts/gen-teapot-data.sh; do not edit.  Newell'"'"'s Utah teapot"
    print " * (1975, public domain): 32 bicubic Bezier patches over 306 control"
    print " * points, z up.  See data/teapot.txt for provenance."
    print " */"
    print "#include \"sim/scene/teapot.h\""
    print ""
}
/^#/ || NF == 0 { next }
$1 == "patches" { mode = "p"; print "const uint16_t scene_teapot_patches[32][16] = {"; next }
$1 == "points" {
    print "};"; print ""
    mode = "v"; print "const double scene_teapot_points[306][3] = {"; next
}
mode == "p" {
    line = "    {"
    for (i = 1; i <= 16; i++) line = line $i (i < 16 ? ", " : "},")
    print line
}
mode == "v" { printf "    {%s, %s, %s},\n", $1, $2, $3 }
END { print "};" }
' "$in" > "$out"
