#!/bin/sh
# Checks for the Debian packages pgsim needs and installs what is missing.
# As root it runs apt-get; otherwise it prints the exact command and fails.
# `deps.sh fuzz` checks what `make fuzz` needs instead (clang and its
# libFuzzer runtime); make test never needs clang.
set -u
PKGS="build-essential pkg-config libglib2.0-dev libyaml-dev libcmocka-dev \
libpng-dev libjson-glib-dev gnuplot-nox libopenmpi-dev openmpi-bin time"
[ "${1:-}" = fuzz ] && PKGS="clang libclang-rt-14-dev"
missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" ||
        missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "pgsim: missing Debian packages:$missing" >&2
if [ "$(id -u)" -eq 0 ]; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >&2 && apt-get install -y -qq $missing >&2 && exit 0
    echo "pgsim: apt-get failed" >&2
    exit 1
fi
echo "pgsim: run: sudo apt-get install -y$missing" >&2
exit 1
