//! RI 3.2 `defaultsurface`, the fallback for unknown surfaces: a headlight,
//! `Ci = Os * Cs * (Ka + Kd * cos²(I, N))`.
//!
//! | name | type | default |
//! |---|---|---|
//! | Kd | float | 0.8 |
//! | Ka | float | 0.2 |
use super::{f, SurfaceContext};
use crate::parameters::ParamValue;
use glam::Vec3;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![("Kd", f(0.8)), ("Ka", f(0.2))]
}

pub(super) fn shade(ctx: &SurfaceContext) -> Vec<Vec3> {
    let g = ctx.grid;
    let (kd, ka) = (ctx.params.float_on(g, "Kd"), ctx.params.float_on(g, "Ka"));
    (0..g.len())
        .map(|i| {
            let (ii, nn) = (g.i[i].as_dvec3(), g.n[i].as_dvec3());
            let denom = ii.length_squared() * nn.length_squared();
            let d = if denom > 0.0 {
                (ii.dot(nn).powi(2) / denom).min(1.0) as f32
            } else {
                0.0
            };
            g.cs[i] * (ka.at(i) + kd.at(i) * d)
        })
        .collect()
}
