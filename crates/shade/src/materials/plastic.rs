//! `plastic` and `paintedplastic` (RI 3.2) through `MaterialPlastic`, Listing 9.1, with the RI
//! shaders' `specularcolor`:
//! `Ct * (Ka*ambient() + Kd*diffuse(Nf)) + specularcolor * Ks*specular(Nf, V, roughness)`,
//! `Ct = Cs` (plastic) or `Cs * texture(texturename)` (paintedplastic, when named).
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.5 |
//! | Ks | float | 0.5 |
//! | roughness | float | 0.1 |
//! | specularcolor | color | 1 |
//! | texturename | string | "" (paintedplastic) |
use super::environment::texture_colors;
use super::{c, f, s, Components, SurfaceContext};
use crate::parameters::ParamValue;
use glam::Vec3;

pub(super) fn params(painted: bool) -> Vec<(&'static str, ParamValue)> {
    let mut p = vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.5)),
        ("Ks", f(0.5)),
        ("roughness", f(0.1)),
        ("specularcolor", c(1.0)),
    ];
    if painted {
        p.push(("texturename", s("")));
    }
    p
}

/// The terms of [`shade`] apart (`Ct·Ka·ambient`, `Ct·Kd·diffuse`, `specularcolor·Ks·specular`).
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let p = ctx.params;
    let [ka, kd, ks, rough] = ctx.ka_kd_ks_roughness();
    let spec = p.vec3_on(g, "specularcolor");
    let name = p.string("texturename");
    let tex = (!name.is_empty()).then(|| texture_colors(ctx.env, g, name, 3, 0.0));
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        let ct = match &tex {
            Some(t) => g.cs[i] * Vec3::new(t[i][0], t[i][1], t[i][2]),
            None => g.cs[i],
        };
        out.ambient[i] = ct * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = ct * (kd.at(i) * l.diffuse(i, ctx.nf[i]));
        out.specular[i] = spec.at(i)
            * ks.at(i)
            * l.specular(i, ctx.nf[i], ctx.v[i], rough.at(i), ctx.env.specular_model);
    }
    out
}
