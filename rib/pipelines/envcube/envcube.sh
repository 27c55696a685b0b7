#!/bin/sh
# Cube-environment pipeline in three commands (chapter 9, section 9.2.2). Gives the same image as
# `render envcube_single.rib` (written to envcube_script.tif instead of envcube_single.tif).
# Binaries: $RENDER and $TXMAKE, default `render` and `txmake` on PATH.
set -e
cd "$(dirname "$0")"
RENDER=${RENDER:-render}
TXMAKE=${TXMAKE:-txmake}
"$RENDER" -q faces.rib &&
  "$TXMAKE" -envcube px.tif nx.tif py.tif ny.tif pz.tif nz.tif room.env &&
  "$RENDER" -q beauty.rib
