//! The renderer's integer hash lives in [`illume_core::hash`]; re-exported for the shading code
//! (occlusion and area-light sampling) and its callers.
pub use illume_core::hash::lowbias32;
