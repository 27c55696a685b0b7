#!/bin/sh
# Rewrites every image in this directory from its closed form (see README.md here):
#   textures/make_textures.sh
# The generator is crates/imageio/examples/make_textures.rs; tests/textures.rs checks that the
# committed files are what it writes.
set -e
root="$(cd "$(dirname "$0")/.." && pwd)"
cargo run -q -p illume-imageio --example make_textures --manifest-path "$root/Cargo.toml" -- "$root/textures"
