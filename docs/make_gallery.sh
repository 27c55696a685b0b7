#!/usr/bin/env bash
# Regenerates the README gallery: renders every scene in rib/ch9/, rib/geometry.rib, rib/blobby.rib,
# rib/csg.rib, rib/displacement.rib, rib/motion.rib,
# rib/bmrt/arealight.rib and the single-RIB form of every pipeline in rib/pipelines/ with a
# release build of `render`, and converts the images they write to small 8-bit PNGs in
# docs/gallery/ (with the `to_png` example of illume-imageio, so no outside image tool is
# needed).
#
# Usage (from anywhere inside the repository):  docs/make_gallery.sh
# Needs: cargo. RENDER=/path/to/render uses that binary instead of building one.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
gallery="$root/docs/gallery"
mkdir -p "$gallery"

echo "make_gallery: building render and to_png (release)"
# Two builds: with --example, cargo would build only that target of every named package.
cargo build --release --quiet -p render --manifest-path "$root/Cargo.toml"
cargo build --release --quiet -p illume-imageio --example to_png --manifest-path "$root/Cargo.toml"
target_dir="$(cargo metadata --format-version 1 --no-deps --manifest-path "$root/Cargo.toml" \
  | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')"
to_png="$target_dir/release/examples/to_png"
if [ -n "${RENDER:-}" ]; then
  render="$(realpath "$RENDER")"   # absolute: each scene renders in its own directory
else
  render="$target_dir/release/render"
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

made=()
failed=()

# render_in DIR RIB NAME: renders RIB with DIR as the working directory; prints the seconds.
render_in() {
  local dir="$1" rib="$2" name="$3" start
  start=$(date +%s.%N)
  if ! (cd "$dir" && "$render" -q "$rib"); then
    echo "make_gallery: render failed on $rib" >&2
    failed+=("$name")
    return 1
  fi
  secs=$(echo "$(date +%s.%N) - $start" | bc)
}

# convert TIF PNG_NAME SOURCE: one gallery PNG.
convert() {
  local png="$gallery/$2"
  "$to_png" "$1" "$png"
  made+=("$(printf '%-44s %6d bytes  (%s, %.1f s)' "${png#"$root"/}" "$(stat -c %s "$png")" "$3" "$secs")")
}

# Chapter 9 figures: every TIFF each scene writes.
for rib in "$root"/rib/ch9/*.rib; do
  name="$(basename "$rib" .rib)"
  # Each scene writes its TIFF(s) relative to the current directory; render in its own dir so
  # we know which files came from which scene.
  dir="$work/$name"
  mkdir -p "$dir"
  render_in "$dir" "$rib" "$name" || continue
  shopt -s nullglob
  tifs=("$dir"/*.tif "$dir"/*.tiff)
  shopt -u nullglob
  if [ ${#tifs[@]} -eq 0 ]; then
    echo "make_gallery: $rib wrote no TIFF" >&2
    failed+=("$name")
    continue
  fi
  for tif in "${tifs[@]}"; do
    convert "$tif" "$(basename "${tif%.*}").png" "$name.rib"
  done
done

# Other example scenes: the issue-10 geometry, Blobby, CSG, displacement, the BMRT area light,
# motion blur and depth of field.
for rib in "$root"/rib/geometry.rib "$root"/rib/blobby.rib "$root"/rib/csg.rib \
  "$root"/rib/displacement.rib "$root"/rib/bmrt/arealight.rib "$root"/rib/motion.rib; do
  name="$(basename "$rib" .rib)"
  dir="$work/$name"
  mkdir -p "$dir"
  render_in "$dir" "$rib" "$name" || continue
  convert "$dir/$name.tif" "$name.png" "${rib#"$root"/}"
done

# Pipelines: each runs in a copy of its directory (they read inputs such as sky.exr from the
# working directory, and texture/ reads textures/); the images shown, as
# pipeline:file.tif:gallery-name.png.
pipeline_images=(
  shadow:shadow_single.tif:pipeline_shadow.png
  envcube:px.tif:pipeline_envcube_px.png
  envcube:nx.tif:pipeline_envcube_nx.png
  envcube:py.tif:pipeline_envcube_py.png
  envcube:ny.tif:pipeline_envcube_ny.png
  envcube:pz.tif:pipeline_envcube_pz.png
  envcube:nz.tif:pipeline_envcube_nz.png
  envcube:envcube_single.tif:pipeline_envcube.png
  envcube:fig9_6_envcube_single.tif:fig9_6_shiny_envmap.png
  flatmirror:refl.tif:pipeline_flatmirror_mirrored.png
  flatmirror:flatmirror_single.tif:pipeline_flatmirror.png
  latlong:sky.exr:pipeline_latlong_sky.png
  latlong:latlong_single.tif:pipeline_latlong.png
  texture:texture_single.tif:pipeline_texture.png
  texture:card_single.tif:pipeline_texture_card.png
)
for p in "$root"/rib/pipelines/*/; do
  name="$(basename "$p")"
  # Only workflows with a single-RIB form (rib/pipelines/farm/ is the Slurm test scene).
  [ -f "$p${name}_single.rib" ] || continue
  # The repository's layout, so a pipeline can read the source images as ../../../textures/.
  dir="$work/pipeline-$name/rib/pipelines/$name"
  mkdir -p "$dir"
  cp "$p"* "$dir"/
  cp -r "$root/textures" "$work/pipeline-$name/"
  render_in "$dir" "${name}_single.rib" "$name" || continue
  for entry in "${pipeline_images[@]}"; do
    IFS=: read -r pipeline tif png <<<"$entry"
    [ "$pipeline" = "$name" ] || continue
    if [ -f "$dir/$tif" ]; then
      convert "$dir/$tif" "$png" "rib/pipelines/$name/${name}_single.rib"
    else
      echo "make_gallery: $name wrote no $tif" >&2
      failed+=("$name:$tif")
    fi
  done
done

echo "make_gallery: made ${#made[@]} image(s):"
for line in "${made[@]}"; do echo "  $line"; done
if [ ${#failed[@]} -gt 0 ]; then
  echo "make_gallery: FAILED: ${failed[*]}" >&2
  exit 1
fi
