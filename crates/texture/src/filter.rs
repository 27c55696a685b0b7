//! Reconstruction/decimation filters named as `txmake -filter` and `MakeTexture` name them:
//! the kernels and the one name table shared with `PixelFilter` live in
//! [`illume_core::filter`]; re-exported for the texture builders.
pub use illume_core::filter::{filter_names_list, FilterKind, FILTER_NAMES};
