//! `metal` (RI 3.2: `Cs * (Ka*ambient() + Ks*specular(Nf, V, roughness))`) and `roughmetal`,
//! `MaterialRoughMetal`, Listing 9.3:
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf) + Ks*specular(Nf, V, roughness))`.
//!
//! | name | type | metal | roughmetal |
//! |---|---|---|---|
//! | Ka | float | 1 | 1 |
//! | Kd | float | — | 0.1 (listing: Kd < 0.1 recommended; the chapter's shinymetal default) |
//! | Ks | float | 1 | 1 |
//! | roughness | float | 0.1 | 0.2 (listing: > 0.15) |
use super::{f, Components, SurfaceContext};
use crate::parameters::ParamValue;

pub(super) fn params(rough: bool) -> Vec<(&'static str, ParamValue)> {
    if rough {
        vec![
            ("Ka", f(1.0)),
            ("Kd", f(0.1)),
            ("Ks", f(1.0)),
            ("roughness", f(0.2)),
        ]
    } else {
        vec![("Ka", f(1.0)), ("Ks", f(1.0)), ("roughness", f(0.1))]
    }
}

/// The terms of [`shade`] apart (no diffuse term for `metal`).
pub(super) fn components(ctx: &SurfaceContext, rough: bool) -> Components {
    let g = ctx.grid;
    let [ka, kd, ks, r] = ctx.ka_kd_ks_roughness();
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        out.ambient[i] = g.cs[i] * (ka.at(i) * l.ambient(i));
        if rough {
            out.diffuse[i] = g.cs[i] * (kd.at(i) * l.diffuse(i, ctx.nf[i]));
        }
        out.specular[i] = g.cs[i]
            * (ks.at(i) * l.specular(i, ctx.nf[i], ctx.v[i], r.at(i), ctx.env.specular_model));
    }
    out
}
