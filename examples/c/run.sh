#!/usr/bin/env bash
# Builds the C examples against libillume and checks that each renders bit-identically
# in-process (RiBegin(RI_NULL)) and through the RIB it writes under ILLUME_RIBOUT, rendered
# by `render`. Needs: cargo build --release -p libillume -p render (or PROFILE=debug).
# Usage: examples/c/run.sh [outdir]   (default: a temporary directory, removed afterwards)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
lib="${CARGO_TARGET_DIR:-$root/target}/${PROFILE:-release}"
render="$lib/render"
for f in "$lib/libillume.a" "$render"; do
  [ -e "$f" ] || { echo "examples/c: $f missing: cargo build --release -p libillume -p render" >&2; exit 2; }
done
out="${1:-}"
if [ -z "$out" ]; then
  out="$(mktemp -d)"
  trap 'rm -rf "$out"' EXIT
fi
status=0
for src in "$root"/examples/c/*.c; do
  name="$(basename "$src" .c)"
  mkdir -p "$out/$name/direct" "$out/$name/rib"
  cc -Wall -Wextra -Werror -o "$out/$name/$name" "$src" -I"$root/include" -L"$lib" -lillume -lm
  (cd "$out/$name/direct" && "../$name")
  (cd "$out/$name/rib" && ILLUME_RIBOUT="$name.rib" "../$name" && "$render" -q "$name.rib")
  images=$(cd "$out/$name/direct" && ls *.tif)
  [ -n "$images" ] || { echo "examples/c: $name wrote no image" >&2; status=1; }
  for img in $images; do
    if cmp -s "$out/$name/direct/$img" "$out/$name/rib/$img"; then
      echo "examples/c: $name: $img in-process == RIB via render (bit-identical)"
    else
      echo "examples/c: $name: $img differs between in-process and RIB via render" >&2
      status=1
    fi
  done
done
exit $status
