//! The fuzz targets' bodies, one function per target, shared by the cargo-fuzz binaries
//! (`fuzz_targets/*.rs`, nightly, libFuzzer) and the stable smoke pass (`tests/fuzz_smoke.rs`,
//! which includes this file with `#[path]` so `cargo test` runs every body without nightly).
//!
//! Each body takes arbitrary bytes and must return for any of them; a panic is a finding. The
//! modules refer to this root as `super::`, never `crate::`: in the smoke test the crate root
//! is the test, not this file.
pub mod images;
pub mod rib;
mod scratch;
pub mod sl;
pub mod texture;

pub use images::{read_exr, read_png, read_tiff, read_zfile};
pub use rib::{parse_rib, render_rib, render_rib_stats};
pub use scratch::{remove_scratch_files, scratch_file, scratch_path};
pub use sl::{sl_compile, sl_parse, sl_preprocess};
pub use texture::{read_texture, txmake};
