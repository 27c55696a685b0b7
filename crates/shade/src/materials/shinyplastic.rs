//! `shinyplastic`, Listing 9.9 (`MaterialShinyPlastic`), with the ERRATA's `fkt` argument:
//! `fresnel(IN, Nf, 1/ior, fkr, fkt, R, T); fkt = 1-fkr;`
//! `fkt * basecolor * (Ka*ambient() + Kd*diffuse(Nf)) + (Ks*fkr) * specular(Nf, V, roughness)
//!  + SampleEnvironment(P, R, fkr*Kr, blur, ENVPARAMS)`.
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.5 |
//! | Ks | float | 0.5 |
//! | roughness | float | 0.1 |
//! | Kr | float | 1 |
//! | blur | float | 0 |
//! | ior | float | 1.5 |
//! | envname | string | "" |
//! | envspace | string | "world" |
//! | envrad | float | 100 |
use super::environment::{sample_environment, EnvParams};
use super::{envparams, f, Components, SurfaceContext};
use crate::geometric::fresnel;
use crate::parameters::ParamValue;
use glam::Vec3;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    let mut p = vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.5)),
        ("Ks", f(0.5)),
        ("roughness", f(0.1)),
        ("Kr", f(1.0)),
        ("blur", f(0.0)),
        ("ior", f(1.5)),
    ];
    p.extend(envparams());
    p
}

/// The Fresnel reflectance per point and the reflection term `SampleEnvironment(P, R,
/// Kr·Kr_fresnel, blur, ENVPARAMS)`.
fn fresnel_and_environment(ctx: &SurfaceContext) -> (Vec<f32>, Vec<Vec3>) {
    let g = ctx.grid;
    let p = ctx.params;
    let n = g.len();
    let (kr, blur, ior) = (
        p.float_on(g, "Kr"),
        p.float_on(g, "blur"),
        p.float_on(g, "ior"),
    );
    let fr: Vec<_> = (0..n)
        .map(|i| fresnel(-ctx.v[i], ctx.nf[i], 1.0 / ior.at(i)))
        .collect();
    let refl: Vec<Vec3> = fr.iter().map(|f| f.r).collect();
    let kr_v: Vec<f32> = (0..n).map(|i| fr[i].kr * kr.at(i)).collect();
    let blur_v: Vec<f32> = (0..n).map(|i| blur.at(i)).collect();
    let params = EnvParams {
        envname: p.string("envname"),
        envspace: p.string("envspace"),
        envrad: p.float("envrad"),
    };
    let env_term = sample_environment(ctx.env, g, &refl, &kr_v, &blur_v, params);
    (fr.iter().map(|f| f.kr).collect(), env_term)
}

/// The terms of [`shade`] apart.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let [ka, kd, ks, r] = ctx.ka_kd_ks_roughness();
    let (fr, env_term) = fresnel_and_environment(ctx);
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for i in 0..g.len() {
        let nf = ctx.nf[i];
        let fkt = 1.0 - fr[i];
        out.ambient[i] = fkt * g.cs[i] * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = fkt * g.cs[i] * (kd.at(i) * l.diffuse(i, nf));
        out.specular[i] =
            (ks.at(i) * fr[i]) * l.specular(i, nf, ctx.v[i], r.at(i), ctx.env.specular_model);
        out.reflection[i] = env_term[i];
    }
    out
}
