//! `shinymetal`, Listing 9.8 (`MaterialShinyMetal`):
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf) + Ks*specular(Nf, V, roughness) + SampleEnvironment(P, R, Kr, blur, ENVPARAMS))`,
//! `R = reflect(normalize(I), Nf)`.
//!
//! The RI 3.2 shader of the same name takes its map as `texturename` and looks it up by the
//! world-space direction `R` (an infinitely distant environment); that is honoured when `envname`
//! is empty.
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0.1 |
//! | Ks | float | 1 |
//! | roughness | float | 0.2 |
//! | Kr | float | 0.8 |
//! | blur | float | 0 |
//! | envname | string | "" |
//! | envspace | string | "world" (`"NDC"`: flat reflection map, Listing 9.6) |
//! | envrad | float | 100 |
//! | texturename | string | "" (RI 3.2 name for a plain environment map) |
use super::environment::{environment_lookup, sample_environment, EnvParams};
use super::{envparams, f, s, Components, SurfaceContext};
use crate::geometric::reflect;
use crate::parameters::ParamValue;
use crate::texturelookup::TextureOptions;
use glam::Vec3;

pub(super) fn params() -> Vec<(&'static str, ParamValue)> {
    let mut p = vec![
        ("Ka", f(1.0)),
        ("Kd", f(0.1)),
        ("Ks", f(1.0)),
        ("roughness", f(0.2)),
        ("Kr", f(0.8)),
        ("blur", f(0.0)),
    ];
    p.extend(envparams());
    p.push(("texturename", s("")));
    p
}

/// The reflection term `SampleEnvironment(P, R, Kr, blur, ENVPARAMS)` (or the RI 3.2
/// shader's world-space `environment(texturename, R)`) per point, before `basecolor`.
fn environment_term(ctx: &SurfaceContext) -> Vec<Vec3> {
    let g = ctx.grid;
    let p = ctx.params;
    let n = g.len();
    let (kr, blur) = (p.float_on(g, "Kr"), p.float_on(g, "blur"));
    let refl: Vec<Vec3> = (0..n).map(|i| reflect(-ctx.v[i], ctx.nf[i])).collect();
    let kr_v: Vec<f32> = (0..n).map(|i| kr.at(i)).collect();
    let blur_v: Vec<f32> = (0..n).map(|i| blur.at(i)).collect();
    let envname = p.string("envname");
    let texturename = p.string("texturename");
    if envname.is_empty() && !texturename.is_empty() {
        world_environment(ctx, texturename, &refl, &kr_v, &blur_v)
    } else {
        let params = EnvParams {
            envname,
            envspace: p.string("envspace"),
            envrad: p.float("envrad"),
        };
        sample_environment(ctx.env, g, &refl, &kr_v, &blur_v, params)
    }
}

/// The terms of [`shade`] apart, each times `basecolor` (`Cs`).
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let g = ctx.grid;
    let p = ctx.params;
    let (ka, kd, ks, r) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "Ks"),
        p.float_on(g, "roughness"),
    );
    let env_term = environment_term(ctx);
    let l = ctx.lights;
    let mut out = Components::new(g.len());
    for (i, env) in env_term.into_iter().enumerate() {
        let nf = ctx.nf[i];
        out.ambient[i] = g.cs[i] * (ka.at(i) * l.ambient(i));
        out.diffuse[i] = g.cs[i] * (kd.at(i) * l.diffuse(i, nf));
        out.specular[i] =
            g.cs[i] * (ks.at(i) * l.specular(i, nf, ctx.v[i], r.at(i), ctx.env.specular_model));
        out.reflection[i] = g.cs[i] * env;
    }
    out
}

pub(super) fn shade(ctx: &SurfaceContext) -> Vec<Vec3> {
    let g = ctx.grid;
    let p = ctx.params;
    let n = g.len();
    let (ka, kd, ks, r) = (
        p.float_on(g, "Ka"),
        p.float_on(g, "Kd"),
        p.float_on(g, "Ks"),
        p.float_on(g, "roughness"),
    );
    let env_term = environment_term(ctx);
    let l = ctx.lights;
    (0..n)
        .map(|i| {
            let nf = ctx.nf[i];
            g.cs[i]
                * (ka.at(i) * l.ambient(i)
                    + kd.at(i) * l.diffuse(i, nf)
                    + ks.at(i) * l.specular(i, nf, ctx.v[i], r.at(i), ctx.env.specular_model)
                    + env_term[i])
        })
        .collect()
}

/// RI 3.2 shinymetal's `Kr * environment(texturename, R in "world")`.
fn world_environment(
    ctx: &SurfaceContext,
    name: &str,
    refl: &[Vec3],
    kr: &[f32],
    blur: &[f32],
) -> Vec<Vec3> {
    let dirs: Vec<Vec3> = refl
        .iter()
        .map(|&r| ctx.env.transform_vector("world", r).unwrap_or(r))
        .collect();
    (0..ctx.grid.len())
        .map(|i| {
            let d = ctx.grid.footprint(i).map(|k| dirs[k]);
            let opts = TextureOptions {
                blur: blur[i],
                ..TextureOptions::default()
            };
            kr[i] * environment_lookup(ctx.env, name, d, opts).0
        })
        .collect()
}
