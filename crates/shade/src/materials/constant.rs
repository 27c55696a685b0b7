//! RI 3.2 `constant`: `Oi = Os; Ci = Os * Cs`. No parameters.
use super::SurfaceContext;
use glam::Vec3;

pub(super) fn shade(ctx: &SurfaceContext) -> Vec<Vec3> {
    ctx.grid.cs.clone()
}
