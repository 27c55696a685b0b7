#!/bin/sh
# Texture pipeline with txmake: the same textures and images as `render texture_single.rib`
# (written to card_script.tif and texture_script.tif instead). Run from anywhere; the source
# images are the repository's textures/ (textures/make_textures.sh rewrites them).
# Binaries: $RENDER and $TXMAKE, default `render` and `txmake` on PATH.
set -e
cd "$(dirname "$0")"
RENDER=${RENDER:-render}
TXMAKE=${TXMAKE:-txmake}
src=../../../textures
for name in checker brick bump; do
  "$TXMAKE" -mode periodic -filter gaussian -filterwidth 2 "$src/$name.tif" "$name.tx"
done
"$TXMAKE" -envlatl -filter gaussian -filterwidth 2 "$src/sky.exr" sky.tx
"$RENDER" -q card.rib beauty.rib
