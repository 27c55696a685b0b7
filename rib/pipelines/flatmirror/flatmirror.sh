#!/bin/sh
# Flat-mirror pipeline in three commands (chapter 9, section 9.2.3). Gives the same image as
# `render flatmirror_single.rib` (written to flatmirror_script.tif instead).
# Binaries: $RENDER and $TXMAKE, default `render` and `txmake` on PATH.
set -e
cd "$(dirname "$0")"
RENDER=${RENDER:-render}
TXMAKE=${TXMAKE:-txmake}
"$RENDER" -q mirrored.rib &&
  "$TXMAKE" -mode clamp refl.tif refl.tx &&
  "$RENDER" -q beauty.rib
