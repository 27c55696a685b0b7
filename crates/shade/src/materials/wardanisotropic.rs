//! `wardanisotropic`: brushed metal with `LocIllumWardAnisotropic`, Listing 9.12, as the
//! specular term of `MaterialRoughMetal` (§9.5.2 “Anisotropic Metal”):
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf) + Ks*LocIllumWardAnisotropic(Nf, V, xdir, xroughness, yroughness))`.
//!
//! `xdir` is a `vector` in "shader" space; when not given (zero) it is `normalize(dPdu)` as in
//! Figure 9.8. It is made tangent (its component along `Nf` removed) because the listing's `Y =
//! N × xdir` assumes a unit tangent.
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.1 |
//! | Ks | float | 1 |
//! | xroughness | float | 0.15 |
//! | yroughness | float | 0.5 |
//! | xdir | vector | normalize(dPdu) |
use super::{f, Components, SurfaceContext};
use crate::geometric::normalize_or_zero;
use crate::parameters::ParamValue;
use glam::Vec3;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.1)),
        ("Ks", f(1.0)),
        ("xroughness", f(0.15)),
        ("yroughness", f(0.5)),
        ("xdir", ParamValue::Point(Vec3::ZERO)),
    ]
}

/// A unit tangent: `x` without its `n` component, or any perpendicular of `n` if that vanishes.
pub(crate) fn tangent(n: Vec3, x: Vec3) -> Vec3 {
    let t = normalize_or_zero(x - n * n.dot(x));
    if t != Vec3::ZERO {
        t
    } else {
        normalize_or_zero(n.any_orthonormal_vector())
    }
}

/// `Cs·Ka·ambient`, `Cs·Kd·diffuse` and the anisotropic highlight (`__specular`) apart.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let p = ctx.params;
    let (ka, kd, ks, xr, yr) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "Ks"),
        p.float_on(g, "xroughness"),
        p.float_on(g, "yroughness"),
    );
    let xdir_param = p.vec3("xdir");
    let xdir_camera = (xdir_param != Vec3::ZERO).then(|| {
        ctx.env
            .camera_from_shader
            .transform_vector3(xdir_param.as_dvec3())
            .as_vec3()
    });
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        let nf = ctx.nf[i];
        let x = tangent(nf, xdir_camera.unwrap_or(g.dpdu[i]));
        out.ambient[i] = g.cs[i] * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = g.cs[i] * (kd.at(i) * l.diffuse(i, nf));
        out.specular[i] =
            g.cs[i] * (ks.at(i) * l.ward_anisotropic(i, nf, ctx.v[i], x, xr.at(i), yr.at(i)));
    }
    out
}
