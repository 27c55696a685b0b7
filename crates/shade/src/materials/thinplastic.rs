//! `thinplastic` through `MaterialThinPlastic`, Listing 9.4: backlighting through
//! `diffuse(-Nf)`:
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf) + Kt*diffuse(-Nf)) + Ks*specular(Nf, V, roughness)`.
//!
//! | name | type | default (the listing's typical values) |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.8 |
//! | Kt | float | 0.2 |
//! | Ks | float | 0.5 |
//! | roughness | float | 0.1 |
use super::{f, SurfaceContext};
use crate::parameters::ParamValue;
use glam::Vec3;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.8)),
        ("Kt", f(0.2)),
        ("Ks", f(0.5)),
        ("roughness", f(0.1)),
    ]
}

pub(super) fn shade(ctx: &SurfaceContext) -> Vec<Vec3> {
    let g = ctx.grid;
    let p = ctx.params;
    let (ka, kd, kt, ks, r) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "Kt"),
        p.float_on(g, "Ks"),
        p.float_on(g, "roughness"),
    );
    let l = ctx.lights;
    (0..g.len())
        .map(|i| {
            let nf = ctx.nf[i];
            g.cs[i]
                * (ka.at(i) * l.ambient(i)
                    + kd.at(i) * l.diffuse(i, nf)
                    + kt.at(i) * l.diffuse(i, -nf))
                + ks.at(i) * l.specular(i, nf, ctx.v[i], r.at(i), ctx.env.specular_model)
        })
        .collect()
}
