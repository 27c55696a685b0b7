//! `shinymetal`, Listing 9.8 (`MaterialShinyMetal`):
//! `basecolor * (Ka*ambient() + Kd*diffuse(Nf) + Ks*specular(Nf, V, roughness) + SampleEnvironment(P, R, Kr, blur, ENVPARAMS))`,
//! `R = reflect(normalize(I), Nf)`.
//!
//! The RI 3.2 shader of the same name takes its map as `texturename` and looks it up by the
//! world-space direction `R` (an infinitely distant environment); that is honoured when `envname`
//! is empty. A RIB `Surface "shinymetal"` means the RI 3.2 standard shader, so the defaults are
//! the standard's (RI 3.2 Appendix A: `Ka = 1, Ks = 1, Kr = 1, roughness = .1`, no diffuse term,
//! hence `Kd = 0`); the chapter's listing declares `Kd .1, roughness .2, Kr .8`, which a RIB
//! gives explicitly to get the book's look.
//!
//! | name | type | default |
//! |---|---|---|
//! | Ka | float | 1 |
//! | Kd | float | 0 |
//! | Ks | float | 1 |
//! | roughness | float | 0.1 |
//! | Kr | float | 1 |
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
        ("Kd", f(0.0)),
        ("Ks", f(1.0)),
        ("roughness", f(0.1)),
        ("Kr", f(1.0)),
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
    let [ka, kd, ks, r] = ctx.ka_kd_ks_roughness();
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
            let d = ctx.grid.centred_footprint(i, |k| dirs[k]);
            let opts = TextureOptions {
                blur: blur[i],
                ..TextureOptions::default()
            };
            kr[i] * environment_lookup(ctx.env, name, d, opts).0
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::{light, shade_surface, surface, ShadingEnv, ShadingGrid};
    use glam::{DMat4, Vec3};
    use illume_rib::{Param, Value};

    fn shade(params: &[(&str, f32)]) -> Vec<Vec3> {
        let params: Vec<Param> = params
            .iter()
            .map(|(n, v)| Param {
                name: n.to_string(),
                value: Value::Floats(vec![*v]),
            })
            .collect();
        let (s, w) = surface("shinymetal", &params).unwrap();
        assert!(w.is_empty(), "{w:?}");
        let (sun, _) = light("distantlight", &[], DMat4::IDENTITY).unwrap();
        let (amb, _) = light("ambientlight", &[], DMat4::IDENTITY).unwrap();
        let mut g = ShadingGrid::new(3, 1);
        for (k, p) in g.p.iter_mut().enumerate() {
            *p = Vec3::new(k as f32 - 1.0, 0.5, 5.0);
        }
        g.n = vec![Vec3::new(0.2, 0.1, -1.0); 3];
        g.set_incident_from_p(false);
        shade_surface(&s, &mut g, &[&sun, &amb], &ShadingEnv::new());
        g.ci
    }

    /// RI 3.2 Appendix A: `shinymetal(Ka = 1, Ks = 1, Kr = 1, roughness = .1)`, no diffuse.
    #[test]
    fn defaults_are_the_ri_standard_shaders() {
        let standard = [("Ka", 1.0), ("Kd", 0.0), ("Ks", 1.0), ("roughness", 0.1)];
        assert_eq!(shade(&[]), shade(&standard));
        let book = [("Kd", 0.1), ("roughness", 0.2)];
        assert_ne!(shade(&[]), shade(&book));
    }
}
