//! `thinplastic` through `MaterialThinPlastic`, Listing 9.4: backlighting through
//! `diffuse(-Nf)`:
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf) + Kt*diffuse(-Nf)) + Ks*specular(Nf, V, roughness)`.
//! The backlight `Kt*diffuse(-Nf)` is diffuse light through the sheet, so it belongs to `__diffuse`.
//!
//! | name | type | default (the listing's typical values) |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.8 |
//! | Kt | float | 0.2 |
//! | Ks | float | 0.5 |
//! | roughness | float | 0.1 |
use super::{f, Components, SurfaceContext};
use crate::parameters::ParamValue;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.8)),
        ("Kt", f(0.2)),
        ("Ks", f(0.5)),
        ("roughness", f(0.1)),
    ]
}

/// The listing's terms apart (front and back diffuse both in `__diffuse`).
pub(super) fn components(ctx: &SurfaceContext) -> Components {
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
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        let nf = ctx.nf[i];
        out.ambient[i] = g.cs[i] * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = g.cs[i] * (kd.at(i) * l.diffuse(i, nf) + kt.at(i) * l.diffuse(i, -nf));
        out.specular[i] = ks.at(i) * l.specular(i, nf, ctx.v[i], r.at(i), ctx.env.specular_model);
    }
    out
}
