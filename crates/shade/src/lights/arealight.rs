//! `arealight`, Listing 9.18: `illuminate(P, N, PI/2) { Cl = (intensity / (L.L)) * lightcolor; }`
//! where `P`, `N` are a point sampled on the light's geometry (Table 9.3). Each sample given with
//! [`crate::Light::with_area_samples`] is run as its own light with its `weight`; points behind a
//! sample (outside its `N, PI/2` cone) get nothing from it. Without samples the light is a point
//! at the shader-space origin radiating everywhere.
//!
//! | name | type | default |
//! |---|---|---|
//! | intensity | float | 1 |
//! | lightcolor | color | 1 |
use super::inverse_square;
use crate::light::{AreaSample, Light, LightSamples};
use crate::shadinggrid::ShadingGrid;
use glam::{DVec3, Vec3};

pub(super) fn run(light: &Light, grid: &ShadingGrid) -> Vec<LightSamples> {
    let c = light.params.float("intensity") * light.params.vec3("lightcolor");
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
