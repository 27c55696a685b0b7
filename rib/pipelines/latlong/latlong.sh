#!/bin/sh
# Lat-long pipeline in two commands. Gives the same image as `render latlong_single.rib`
# (written to latlong_script.tif instead). sky.exr is committed; regenerate it with
#   cargo run -p illume-texture --example latlong_sky -- sky.exr
# Binaries: $RENDER and $TXMAKE, default `render` and `txmake` on PATH.
set -e
cd "$(dirname "$0")"
RENDER=${RENDER:-render}
TXMAKE=${TXMAKE:-txmake}
"$TXMAKE" -envlatl sky.exr sky.tx && "$RENDER" -q beauty.rib
