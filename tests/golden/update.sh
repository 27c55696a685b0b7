#!/usr/bin/env bash
# Re-makes the golden references (tests/golden/*.png) from their scenes, after a deliberate
# change of what the renderer draws. Renders each scene listed in golden.toml with the dev
# build of `render` (the one CI builds; builds at other opt-levels can differ in a pixel or
# two, within the thresholds: golden.toml says by how much) in this folder (each scene's
# Display names its PNG), then runs the golden test.
# Review the new images before committing them, and say in the commit which changed and why.
#   tests/golden/update.sh            # all scenes
#   tests/golden/update.sh csg.rib    # only these
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
cd "$repo"
cargo build -q -p render
render="${CARGO_TARGET_DIR:-$repo/target}/debug/render"
if [ "$#" -gt 0 ]; then
  scenes=("$@")
else
  # Every `scene = "…"` of golden.toml, in file order.
  mapfile -t scenes < <(sed -n 's/^scene *= *"\(.*\)".*/\1/p' "$here/golden.toml")
fi
cd "$here"
for scene in "${scenes[@]}"; do
  "$render" -q "$scene"
done
ls -l "$here"/*.png
cd "$repo"
cargo test -q --test golden
