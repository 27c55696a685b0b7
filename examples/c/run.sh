#!/usr/bin/env bash
# Builds the C examples against libillume and checks that each renders bit-identically
# in-process (RiBegin(RI_NULL)) and through the RIB it writes under ILLUME_RIBOUT, rendered
# by `render`; then installs the library (crates/libillume/install.sh: libillume.so, illume.pc)
# under the output dir, checks the .so exports only the RI binding (`nm -D`), builds one example
# against the .so through pkg-config and checks it renders the same bits as the static build,
# as does its capture in gzip-compressed binary RIB rendered by `render`.
# Needs: cargo build --release -p libillume -p render (or PROFILE=debug).
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

# The shared library: installed, exporting only Ri*/RI_* symbols, same bits as the static link.
prefix="$out/prefix"
"$root/crates/libillume/install.sh" "$prefix" >/dev/null
so="$prefix/lib/libillume.so"
stray=$(nm -D --defined-only "$so" | awk '{print $3}' | grep -v -e '^Ri' -e '^RI_' || true)
if [ -n "$stray" ]; then
  echo "examples/c: libillume.so exports non-RI symbols: $(echo "$stray" | head -5 | tr '\n' ' ')" >&2
  status=1
fi
symbols="$(nm -D --defined-only "$so")"
grep -q ' T RiSphere$' <<<"$symbols" \
  || { echo "examples/c: libillume.so does not export RiSphere" >&2; status=1; }
if command -v pkg-config >/dev/null 2>&1; then
  flags="$(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs illume)"
else
  flags="-I$prefix/include -L$prefix/lib -lillume -lm"
fi
name=quadrics
mkdir -p "$out/$name/shared"
# shellcheck disable=SC2086 # $flags is a word list from pkg-config
cc -Wall -Wextra -Werror -o "$out/$name/$name-shared" "$root/examples/c/$name.c" $flags
# ldd's output is taken whole first: `ldd | grep -q` under pipefail fails at random when grep
# exits on its first match and ldd then dies of SIGPIPE.
libs="$(LD_LIBRARY_PATH="$prefix/lib" ldd "$out/$name/$name-shared")"
case "$libs" in
  *"$so"*) ;;
  *) echo "examples/c: $name-shared is not linked against $so" >&2; status=1 ;;
esac
(cd "$out/$name/shared" && LD_LIBRARY_PATH="$prefix/lib" "../$name-shared")
# And its capture as gzip-compressed binary RIB renders the same bits through `render`.
mkdir -p "$out/$name/binary"
(cd "$out/$name/binary" && ILLUME_RIBOUT="$name.rib.gz" ILLUME_RIBFORMAT=binary \
  LD_LIBRARY_PATH="$prefix/lib" "../$name-shared" && "$render" -q "$name.rib.gz")
for img in $(cd "$out/$name/direct" && ls *.tif); do
  for via in shared binary; do
    if cmp -s "$out/$name/direct/$img" "$out/$name/$via/$img"; then
      echo "examples/c: $name: $img via $via == in-process via libillume.a (bit-identical)"
    else
      echo "examples/c: $name: $img differs between $via and in-process via libillume.a" >&2
      status=1
    fi
  done
done
exit $status
