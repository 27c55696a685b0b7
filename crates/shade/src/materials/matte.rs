//! `matte` (RI 3.2) through `MaterialMatte`, Listing 9.2:
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf))`.
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 1 |
use super::{f, Components, SurfaceContext};
use crate::parameters::ParamValue;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![("Ka", f(1.0)), ("Kd", f(1.0))]
}

/// `MaterialMatte`'s terms apart: `Cs·Ka·ambient` and `Cs·Kd·diffuse`.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let (ka, kd) = (ctx.params.float_on(g, "Ka"), ctx.params.float_on(g, "Kd"));
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        out.ambient[i] = g.cs[i] * (ka.at(i) * ctx.lights.ambient(i));
        out.diffuse[i] = g.cs[i] * (kd.at(i) * ctx.lights.diffuse(i, ctx.nf[i]));
    }
    out
}
