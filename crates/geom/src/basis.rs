//! The spline bases live in [`illume_core::basis`] (one home for the matrices the RIB `Basis`
//! request, patches, curves and SL `spline()` share); re-exported so `illume_geom::basis` paths
//! keep working.
pub use illume_core::basis::*;
