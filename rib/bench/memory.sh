#!/bin/sh
# Peak memory and time against image size (issue 21): renders spotlight.rib at 1x, 2x, 4x and
# 8x its Format (640x480 .. 5120x3840) under /usr/bin/time -v and prints one line per size.
#   rib/bench/memory.sh [RENDER_COMMAND] [SCALES]
# RENDER_COMMAND defaults to the release `render`; the peer: rib/bench/memory.sh
# ../shared/tools/aqsis-render. Each render runs in a scratch directory (its TIFF lands there).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
render=${1:-$here/../../target/release/render}
scales=${2:-1 2 4 8}
case $render in /*) ;; */*) render=$(pwd)/$render ;; esac
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
printf '%-10s %10s %10s %10s\n' format wall_s cpu_s peak_MB
for s in $scales; do
    w=$((640 * s)); h=$((480 * s))
    sed "s/^Format 640 480 1/Format $w $h 1/" "$here/spotlight.rib" > "$scratch/spotlight.rib"
    (cd "$scratch" && /usr/bin/time -v $render spotlight.rib > /dev/null 2> time.txt) ||
        { cat "$scratch/time.txt" >&2; exit 1; }
    awk -v f="${w}x${h}" -F': ' '
        /Elapsed \(wall clock\)/ { n = split($2, t, ":"); wall = (n == 3) ? t[1] * 3600 + t[2] * 60 + t[3] : t[1] * 60 + t[2] }
        /User time/ { cpu += $2 } /System time/ { cpu += $2 }
        /Maximum resident/ { rss = $2 / 1024 }
        END { printf "%-10s %10.2f %10.2f %10.1f\n", f, wall, cpu, rss }' "$scratch/time.txt"
done
