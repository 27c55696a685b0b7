#!/usr/bin/env bash
# Installs the RI C binding under PREFIX: include/ri.h, lib/libillume.a, lib/libillume.so
# (the static library's objects linked whole, exporting only the RI symbols; ri.map) and
# lib/pkgconfig/illume.pc. Build first: cargo build --release -p libillume.
# Usage: crates/libillume/install.sh PREFIX     then: cc prog.c $(pkg-config --cflags --libs illume)
set -euo pipefail
prefix="${1:?usage: install.sh PREFIX}"
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
lib="${CARGO_TARGET_DIR:-$root/target}/${PROFILE:-release}/libillume.a"
[ -f "$lib" ] || { echo "install.sh: $lib missing: cargo build --release -p libillume" >&2; exit 2; }
mkdir -p "$prefix/include" "$prefix/lib/pkgconfig"
cp "$root/include/ri.h" "$prefix/include/"
cp "$lib" "$prefix/lib/"
cc -shared -o "$prefix/lib/libillume.so" -Wl,--whole-archive "$lib" -Wl,--no-whole-archive \
  -Wl,--version-script="$here/ri.map" -lm
version="$(sed -n 's/^version = "\(.*\)"/\1/p' "$root/Cargo.toml" | head -1)"
sed -e "s|@PREFIX@|$prefix|" -e "s|@VERSION@|$version|" "$here/illume.pc.in" \
  > "$prefix/lib/pkgconfig/illume.pc"
echo "installed under $prefix (PKG_CONFIG_PATH=$prefix/lib/pkgconfig)"
