//! RI 3.2 `defaultsurface`, the fallback for unknown surfaces: a headlight,
//! `Ci = Os * Cs * (Ka + Kd * cos²(I, N))`. Components: `Cs·Ka` is `__ambient`, the headlight
//! `Cs·Kd·cos²` is `__diffuse`.
//!
//! | name | type | default |
//! |---|---|---|
//! | Kd | float | 0.8 |
//! | Ka | float | 0.2 |
use super::{f, Components, SurfaceContext};
use crate::parameters::ParamValue;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![("Kd", f(0.8)), ("Ka", f(0.2))]
}

/// `Cs·Ka` (ambient) and `Cs·Kd·cos²(I, N)` (diffuse) apart.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let (kd, ka) = (ctx.params.float_on(g, "Kd"), ctx.params.float_on(g, "Ka"));
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        let (ii, nn) = (g.i[i].as_dvec3(), g.n[i].as_dvec3());
        let denom = ii.length_squared() * nn.length_squared();
        let d = if denom > 0.0 {
            (ii.dot(nn).powi(2) / denom).min(1.0) as f32
        } else {
            0.0
        };
        out.ambient[i] = g.cs[i] * ka.at(i);
        out.diffuse[i] = g.cs[i] * (kd.at(i) * d);
    }
    out
}
