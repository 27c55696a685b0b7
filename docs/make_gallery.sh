#!/usr/bin/env bash
# Regenerates the README gallery: renders every scene in rib/ch9/ with a release build of
# `render` and converts each image it writes to a small PNG in docs/gallery/.
#
# Usage (from anywhere inside the repository):  docs/make_gallery.sh
# Needs: cargo, and oiiotool (OpenImageIO) to convert TIFF to PNG.
# RENDER=/path/to/render uses that binary instead of building one.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
gallery="$root/docs/gallery"
mkdir -p "$gallery"

command -v oiiotool >/dev/null || { echo "make_gallery: oiiotool (OpenImageIO) is needed to write PNGs" >&2; exit 1; }

if [ -n "${RENDER:-}" ]; then
  render="$(realpath "$RENDER")"   # absolute: each scene renders in its own directory
else
  echo "make_gallery: building render (release)"
  cargo build --release --quiet -p render --manifest-path "$root/Cargo.toml"
  target_dir="$(cargo metadata --format-version 1 --no-deps --manifest-path "$root/Cargo.toml" \
    | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')"
  render="$target_dir/release/render"
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

made=()
failed=()
for rib in "$root"/rib/ch9/*.rib; do
  name="$(basename "$rib" .rib)"
  # Each scene writes its TIFF(s) relative to the current directory; render in its own dir so
  # we know which files came from which scene.
  dir="$work/$name"
  mkdir -p "$dir"
  start=$(date +%s.%N)
  if ! (cd "$dir" && "$render" -q "$rib"); then
    echo "make_gallery: render failed on $rib" >&2
    failed+=("$name")
    continue
  fi
  secs=$(echo "$(date +%s.%N) - $start" | bc)
  shopt -s nullglob
  tifs=("$dir"/*.tif "$dir"/*.tiff)
  shopt -u nullglob
  if [ ${#tifs[@]} -eq 0 ]; then
    echo "make_gallery: $rib wrote no TIFF" >&2
    failed+=("$name")
    continue
  fi
  for tif in "${tifs[@]}"; do
    png="$gallery/$(basename "${tif%.*}").png"
    # Drop alpha (the gallery shows the images over the page, not composited) and write 8 bits.
    # No metadata (render time stamps, software name), so regenerating unchanged images gives
    # byte-identical PNGs and no spurious diffs.
    oiiotool --nosoftwareattrib "$tif" --ch R,G,B -d uint8 --eraseattrib ".*" -o "$png"
    made+=("$(printf '%-40s %6d bytes  (%s, %.1f s)' "${png#"$root"/}" "$(stat -c %s "$png")" "$name.rib" "$secs")")
  done
done

echo "make_gallery: made ${#made[@]} image(s):"
for line in "${made[@]}"; do echo "  $line"; done
if [ ${#failed[@]} -gt 0 ]; then
  echo "make_gallery: FAILED: ${failed[*]}" >&2
  exit 1
fi
