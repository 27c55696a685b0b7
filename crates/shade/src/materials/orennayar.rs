//! `orennayar`: `basecolor * (Ka*ambient() + Kd*LocIllumOrenNayar(Nf, V, roughness))`, the rough
//! diffuse model of Listing 9.11 (σ = `roughness` in radians; σ = 0 is exactly `matte`).
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 1 |
//! | roughness | float | 0.5 (Figure 9.7's left teapot) |
use super::{f, Components, SurfaceContext};
use crate::parameters::ParamValue;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![("Ka", f(1.0)), ("Kd", f(1.0)), ("roughness", f(0.5))]
}

/// `Cs·Ka·ambient` and the Oren–Nayar term (`__diffuse`) apart.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let p = ctx.params;
    let (ka, kd, r) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "roughness"),
    );
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        out.ambient[i] = g.cs[i] * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = g.cs[i] * (kd.at(i) * l.oren_nayar(i, ctx.nf[i], ctx.v[i], r.at(i)));
    }
    out
}
