#!/bin/sh
# Shadow-map pipeline in three commands (chapter 9, section 9.6.3). Gives the same image as
# `render shadow_single.rib` (written to shadow_script.tif instead of shadow_single.tif).
# Binaries: $RENDER and $TXMAKE, default `render` and `txmake` on PATH.
set -e
cd "$(dirname "$0")"
RENDER=${RENDER:-render}
TXMAKE=${TXMAKE:-txmake}
"$RENDER" -q depth.rib && "$TXMAKE" -shadow depth.z shadow.sm && "$RENDER" -q beauty.rib
