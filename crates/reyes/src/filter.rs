//! The pixel reconstruction filters of RI Spec 3.2 §4.1.4 live with the other filter kernels
//! and their one name table in [`illume_core::filter`]; re-exported for the hider.
pub use illume_core::filter::{FilterKind, PixelFilter};
