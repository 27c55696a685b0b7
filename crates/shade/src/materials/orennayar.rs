//! `orennayar`: `basecolor * (Ka*ambient() + Kd*LocIllumOrenNayar(Nf, V, roughness))`, the rough
//! diffuse model of Listing 9.11 (σ = `roughness` in radians; σ = 0 is exactly `matte`).
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 1 |
//! | roughness | float | 0.5 (Figure 9.7's left teapot) |
use super::{f, SurfaceContext};
use crate::parameters::ParamValue;
use glam::Vec3;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![("Ka", f(1.0)), ("Kd", f(1.0)), ("roughness", f(0.5))]
}

pub(super) fn shade(ctx: &SurfaceContext) -> Vec<Vec3> {
    let g = ctx.grid;
    let p = ctx.params;
    let (ka, kd, r) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "roughness"),
    );
    let l = ctx.lights;
    (0..g.len())
        .map(|i| {
            g.cs[i]
                * (ka.at(i) * l.ambient(i)
                    + kd.at(i) * l.oren_nayar(i, ctx.nf[i], ctx.v[i], r.at(i)))
        })
        .collect()
}
