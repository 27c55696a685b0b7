//! Reflections from maps (chapter 9 §9.2): `raysphere` and `Environment()` (Listing 9.5),
//! `ReflMap()` (Listing 9.6) and `SampleEnvironment()` (Listing 9.7).
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use crate::texturelookup::TextureOptions;
use glam::Vec3;

/// Intersections of a ray with a sphere at the origin: `count` of 0, 1 or 2, `t0 ≤ t1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaySphere {
    pub count: u32,
    pub t0: f32,
    pub t1: f32,
}

/// `raysphere(E, I, r, eps, t0, t1)`, Listing 9.5: hits of the ray `E + I t` (`I` unit) with the
/// sphere of radius `r`, ignoring hits closer than `eps`. Solved in `f64` (the discriminant
/// `b² - 4c` cancels for rays grazing the sphere).
pub fn raysphere(e: Vec3, i: Vec3, r: f32, eps: f32) -> RaySphere {
    let (e, i, r, eps) = (e.as_dvec3(), i.as_dvec3(), r as f64, eps as f64);
    let b = 2.0 * e.dot(i);
    let c = e.dot(e) - r * r;
    let discrim = b * b - 4.0 * c;
    let (mut t0, mut t1, count);
    if discrim > 0.0 {
        let d = discrim.sqrt();
        t0 = (-d - b) / 2.0;
        t1 = 0.0;
        if t0 > eps {
            t1 = (d - b) / 2.0;
            count = 2;
        } else {
            t0 = (d - b) / 2.0;
            count = if t0 > eps { 1 } else { 0 };
        }
    } else if discrim == 0.0 {
        t0 = -b / 2.0;
        t1 = 0.0;
        count = if t0 > eps { 1 } else { 0 };
    } else {
        t0 = 0.0;
        t1 = 0.0;
        count = 0;
    }
    RaySphere {
        count,
        t0: t0 as f32,
        t1: t1 as f32,
    }
}

/// The environment parameters of Listing 9.7 (`DECLARE_ENVPARAMS`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EnvParams<'s> {
    pub envname: &'s str,
    pub envspace: &'s str,
    pub envrad: f32,
}

/// `SampleEnvironment(P, R, Kr, blur, ENVPARAMS)` over the whole grid, Listing 9.7: `Kr` times
/// `ReflMap` (`envspace == "NDC"`) or `Environment`; zero when `envname` is empty. `r` holds one
/// reflection direction per grid point (camera space) so that each lookup's footprint spans its
/// neighbours' directions.
pub(crate) fn sample_environment(
    env: &ShadingEnv,
    grid: &ShadingGrid,
    r: &[Vec3],
    kr: &[f32],
    blur: &[f32],
    params: EnvParams,
) -> Vec<Vec3> {
    let n = grid.len();
    if params.envname.is_empty() {
        return vec![Vec3::ZERO; n];
    }
    let colors = if params.envspace == "NDC" {
        reflmap(env, grid, params.envname, blur)
    } else {
        environment(env, grid, params, r, blur)
    };
    colors
        .into_iter()
        .zip(kr)
        .map(|((c, _alpha), &k)| k * c)
        .collect()
}

/// `ReflMap(reflname, P, blur, alpha)`, Listing 9.6: a texture indexed by the NDC position of
/// `P` (flat mirrors rendered from the mirrored camera). Returns `(colour, alpha)` per point;
/// alpha is channel 3 with fill 1.
pub(crate) fn reflmap(
    env: &ShadingEnv,
    grid: &ShadingGrid,
    reflname: &str,
    blur: &[f32],
) -> Vec<(Vec3, f32)> {
    let ndc: Vec<[f32; 2]> = grid
        .p
        .iter()
        .map(|&p| {
            let q = env.transform_point("NDC", p).unwrap_or(Vec3::ZERO);
            [q.x, q.y]
        })
        .collect();
    (0..grid.len())
        .map(|i| {
            let st = grid
                .centred_footprint(i, |k| glam::Vec2::from(ndc[k]))
                .map(|c| c.to_array());
            let opts = TextureOptions {
                blur: blur[i],
                ..TextureOptions::default()
            };
            lookup(env, reflname, |t| {
                let alpha = t.texture(reflname, 3, 1, st, &TextureOptions { fill: 1.0, ..opts })?;
                let c = t.texture(reflname, 0, 3, st, &opts)?;
                Some((Vec3::new(c[0], c[1], c[2]), alpha[0]))
            })
        })
        .collect()
}

/// `Environment(envname, envspace, envrad, P, R, blur, alpha)`, Listing 9.5: traces `(P, R)`
/// against a sphere of radius `envrad` in `envspace` and looks up the hit point's direction.
pub(crate) fn environment(
    env: &ShadingEnv,
    grid: &ShadingGrid,
    params: EnvParams,
    r: &[Vec3],
    blur: &[f32],
) -> Vec<(Vec3, f32)> {
    let space_ok = env.camera_from(params.envspace).is_some();
    if !space_ok {
        env.warn(&format!(
            "environment map `{}`: unknown space `{}`; treated as \"world\"",
            params.envname, params.envspace
        ));
    }
    let space = if space_ok { params.envspace } else { "world" };
    let envrad = params.envrad;
    let r2 = envrad * envrad;
    let dirs: Vec<Vec3> = (0..grid.len())
        .map(|i| {
            let mut psp = env.transform_point(space, grid.p[i]).unwrap_or(grid.p[i]);
            let rsp = crate::geometric::normalize_or_zero(
                env.transform_vector(space, r[i]).unwrap_or(r[i]),
            );
            if psp.length_squared() > r2 {
                psp = envrad * crate::geometric::normalize_or_zero(psp);
            }
            let hit = raysphere(psp, rsp, envrad, 1.0e-4);
            if hit.count > 0 {
                psp + hit.t0 * rsp
            } else {
                rsp
            }
        })
        .collect();
    (0..grid.len())
        .map(|i| {
            let d = grid.centred_footprint(i, |k| dirs[k]);
            let opts = TextureOptions {
                blur: blur[i],
                ..TextureOptions::default()
            };
            environment_lookup(env, params.envname, d, opts)
        })
        .collect()
}

/// One `environment()` pair of lookups: colour (channels 0–2) and alpha (`envname[3]`, fill 1).
pub(crate) fn environment_lookup(
    env: &ShadingEnv,
    name: &str,
    dirs: [Vec3; 4],
    opts: TextureOptions,
) -> (Vec3, f32) {
    lookup(env, name, |t| {
        let alpha = t.environment(name, 3, 1, dirs, &TextureOptions { fill: 1.0, ..opts })?;
        let c = t.environment(name, 0, 3, dirs, &opts)?;
        Some((Vec3::new(c[0], c[1], c[2]), alpha[0]))
    })
}

/// Runs a lookup; a missing texture system or map warns once and gives black, alpha 0.
fn lookup(
    env: &ShadingEnv,
    name: &str,
    f: impl FnOnce(&dyn crate::texturelookup::TextureLookup) -> Option<(Vec3, f32)>,
) -> (Vec3, f32) {
    let Some(t) = env.textures else {
        env.warn(&format!("map `{name}`: no texture system; black"));
        return (Vec3::ZERO, 0.0);
    };
    match f(t) {
        Some((c, a)) if c.is_finite() && a.is_finite() => (c, a),
        Some(_) => (Vec3::ZERO, 0.0),
        None => {
            env.warn(&format!("map `{name}` not found; black"));
            (Vec3::ZERO, 0.0)
        }
    }
}

/// `texture(name, s, t)` colour over each point's footprint (paintedplastic, bumpy); a missing map
/// warns once and reads as `missing`.
pub(crate) fn texture_colors(
    env: &ShadingEnv,
    grid: &ShadingGrid,
    name: &str,
    nchannels: usize,
    missing: f32,
) -> Vec<[f32; 4]> {
    let Some(t) = env.textures else {
        env.warn(&format!("texture `{name}`: no texture system; black"));
        return vec![[missing; 4]; grid.len()];
    };
    let mut warned = false;
    (0..grid.len())
        .map(|i| {
            let st = grid
                .centred_footprint(i, |k| glam::Vec2::new(grid.s[k], grid.t[k]))
                .map(|c| c.to_array());
            match t.texture(name, 0, nchannels, st, &TextureOptions::default()) {
                Some(c) if c.iter().all(|x| x.is_finite()) => c,
                Some(_) => [0.0; 4],
                None => {
                    if !warned {
                        env.warn(&format!("texture `{name}` not found; black"));
                        warned = true;
                    }
                    [missing; 4]
                }
            }
        })
        .collect()
}
