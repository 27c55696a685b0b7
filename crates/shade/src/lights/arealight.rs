//! `arealight`, Listing 9.18: `illuminate(P, N, PI/2) { Cl = (intensity / (L.L)) * lightcolor; }`
//! where `P`, `N` are a point sampled on the light's geometry (Table 9.3). Each sample given with
//! [`crate::Light::with_area_samples`] is run as its own light with its `weight`; points behind a
//! sample (outside its `N, PI/2` cone) get nothing from it. Without samples the light is a point
//! at the shader-space origin radiating everywhere.
//!
//! With its geometry ([`crate::Light::with_emitter`], the hider's diced `AreaLightSource`
//! primitives) every shaded point gets its own `samples` stratified points on the surface
//! (uniform in area, jittered by a hash of the point, the sample and the frame), sample `k`
//! being the `k`-th light of the illuminance loops; each is shadowed by one shadow ray, so the
//! shadows are soft and their noise falls with the sample count.
//!
//! | name | type | default |
//! |---|---|---|
//! | intensity | float | 1 |
//! | lightcolor | color | 1 |
use super::inverse_square;
use crate::areaemitter::AreaEmitter;
use crate::light::{AreaSample, Light, LightSamples};
use crate::occlusion::{point_random, ray_origin, stratified};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::{DVec3, Vec3};

pub(super) fn run(light: &Light, grid: &ShadingGrid, env: &ShadingEnv) -> Vec<LightSamples> {
    let c = light.params.float("intensity") * light.params.vec3("lightcolor");
    if let Some(emitter) = light.emitter.as_deref().filter(|e| !e.is_empty()) {
        return (0..light.samples)
            .map(|k| run_emitter_sample(emitter, k, light.samples, c, grid, env))
            .collect();
    }
    if light.area_samples.is_empty() {
        let origin = light
            .camera_from_shader
            .transform_point3(DVec3::ZERO)
            .as_vec3();
        let sample = AreaSample {
            p: origin,
            n: Vec3::ZERO,
            weight: 1.0,
        };
        return vec![run_sample(&sample, c, grid)];
    }
    light
        .area_samples
        .iter()
        .map(|s| run_sample(s, c, grid))
        .collect()
}

fn run_sample(sample: &AreaSample, c: Vec3, grid: &ShadingGrid) -> LightSamples {
    let mut out = LightSamples::new(grid.len(), false);
    for i in 0..grid.len() {
        let l_light = grid.p[i] - sample.p;
        out.l[i] = -l_light;
        // illuminate(P, N, PI/2): only the outside of the geometry; a zero N radiates everywhere.
        if sample.n != Vec3::ZERO && l_light.dot(sample.n) < 0.0 {
            continue;
        }
        out.lit[i] = true;
        out.cl[i] = inverse_square(c * sample.weight, l_light);
    }
    out
}

/// Sample `k` of `n` on the emitter, a different point for every shaded point.
fn run_emitter_sample(
    emitter: &AreaEmitter,
    k: u32,
    n: u32,
    c: Vec3,
    grid: &ShadingGrid,
    env: &ShadingEnv,
) -> LightSamples {
    let mut out = LightSamples::new(grid.len(), false);
    let weight = 1.0 / n as f32;
    let stream = env.seed ^ 0x2c1b_3c6d;
    for i in 0..grid.len() {
        let (u1, u2) = stratified(k, n, point_random(grid.p[i], k, stream));
        let Some((p_light, n_light)) = emitter.sample(u1, u2) else {
            continue;
        };
        let sample = AreaSample {
            p: p_light,
            n: n_light,
            weight,
        };
        let l_light = grid.p[i] - sample.p;
        out.l[i] = -l_light;
        if sample.n != Vec3::ZERO && l_light.dot(sample.n) < 0.0 {
            continue;
        }
        out.lit[i] = true;
        if let Some(occlusion) = env.occlusion {
            let toward = -l_light.as_dvec3();
            let origin = ray_origin(grid, i, toward, env);
            // The emitter does not cast shadows itself; stop just short of its surface.
            if occlusion.occluded(origin, sample.p.as_dvec3() - origin, 1.0 - 1e-6) {
                continue;
            }
        }
        out.cl[i] = inverse_square(c * sample.weight, l_light);
    }
    out
}
