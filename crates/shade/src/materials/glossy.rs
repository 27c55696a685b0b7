//! `glossy`: plastic with `LocIllumGlossy` (Listing 9.13) in place of `specular()`, as Figure 9.9
//! compares: `Cs * (Ka*ambient() + Kd*diffuse(Nf)) + specularcolor * Ks*LocIllumGlossy(Nf, V, roughness, sharpness)`.
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.5 |
//! | Ks | float | 1 |
//! | roughness | float | 0.1 (Figure 9.9) |
//! | sharpness | float | 0.5 (Figure 9.9) |
//! | specularcolor | color | 1 |
use super::{c, f, Components, SurfaceContext};
use crate::parameters::ParamValue;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.5)),
        ("Ks", f(1.0)),
        ("roughness", f(0.1)),
        ("sharpness", f(0.5)),
        ("specularcolor", c(1.0)),
    ]
}

/// `Cs·Ka·ambient`, `Cs·Kd·diffuse` and the glossy highlight (`__specular`) apart.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let p = ctx.params;
    let (ka, kd, ks, r, sh) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "Ks"),
        p.float_on(g, "roughness"),
        p.float_on(g, "sharpness"),
    );
    let spec = p.vec3_on(g, "specularcolor");
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        let nf = ctx.nf[i];
        out.ambient[i] = g.cs[i] * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = g.cs[i] * (kd.at(i) * l.diffuse(i, nf));
        out.specular[i] = spec.at(i) * ks.at(i) * l.glossy(i, nf, ctx.v[i], r.at(i), sh.at(i));
    }
    out
}
