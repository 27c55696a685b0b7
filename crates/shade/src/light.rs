//! Light source instances and the per-grid light cache.
//!
//! A light shader runs once per grid (DESIGN.md “Shading”): [`LightCache::run`] evaluates every
//! light at every point and keeps `L`, `Cl`, `Ol`; every illuminance loop of the surface shader
//! (`diffuse()`, then `specular()`, …) reads the cache instead of re-running the light.
use crate::areaemitter::AreaEmitter;
use crate::error::ShadeError;
use crate::lights::{self, LightKind};
use crate::parameters::{ParamValue, ShaderParams};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::{DMat4, Vec3};
use illume_rib::Param;
use std::sync::Arc;

/// A bound light shader (`LightSource` / `AreaLightSource`).
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub(crate) name: String,
    pub(crate) kind: LightKind,
    pub(crate) params: ShaderParams,
    /// The light's "shader" space (the CTM at the `LightSource` request) as camera_from_shader.
    pub(crate) camera_from_shader: DMat4,
    /// Points sampled on an area light's geometry (`arealight`), camera space.
    pub(crate) area_samples: Vec<AreaSample>,
    /// `Attribute "light" "shadows" ["on"]`: visibility by shadow rays.
    pub(crate) raytraced: bool,
    /// Samples per shaded point on the emitter (`Attribute "light" "nsamples"`).
    pub(crate) samples: u32,
    /// An area light's geometry, sampled per shaded point.
    pub(crate) emitter: Option<Arc<AreaEmitter>>,
}

/// One point on an area light's geometry (Table 9.3: the light shader's `P` and `N`), in camera
/// space, with its share of the light (`weight`, the samples' weights summing to 1 for a light
/// whose `intensity` is its total).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaSample {
    pub p: Vec3,
    pub n: Vec3,
    pub weight: f32,
}

/// Binds light shader `name` with `params`. `camera_from_shader` is the CTM when the
/// `LightSource` request was read, composed with camera_from_world: `point "shader"` parameters
/// (`from`, `to`) and their defaults are transformed by it.
///
/// Every light also accepts the message-passing parameters `__category` (string),
/// `__nondiffuse`, `__nonspecular` (float), and keeps any other parameter it is given so that
/// surfaces can read it with `lightsource()` ([`Light::param`]).
///
/// Errors: [`ShadeError::UnknownShader`]; parameter problems come back as warnings.
pub fn light(
    name: &str,
    params: &[Param],
    camera_from_shader: DMat4,
) -> Result<(Light, Vec<String>), ShadeError> {
    let kind = LightKind::from_name(name).ok_or_else(|| ShadeError::UnknownShader {
        kind: "light",
        name: name.to_string(),
        known: LightKind::NAMES.join(", "),
    })?;
    let mut specs = kind.params();
    specs.push(("__category", ParamValue::String(String::new())));
    specs.push(("__nondiffuse", ParamValue::Float(0.0)));
    specs.push(("__nonspecular", ParamValue::Float(0.0)));
    let (params, warnings) = ShaderParams::bind(name, &specs, params, true);
    Ok((
        Light {
            name: name.to_string(),
            kind,
            params,
            camera_from_shader,
            area_samples: Vec::new(),
            raytraced: false,
            samples: 16,
            emitter: None,
        },
        warnings,
    ))
}

impl Light {
    /// Gives an `arealight` its geometry: each sample illuminates as Listing 9.18's
    /// `illuminate(P, N, PI/2)` and appears as its own light in illuminance loops, its `Cl`
    /// scaled by `weight`. Without samples an `arealight` is a point at its shader-space origin
    /// radiating in every direction. Ignored by the other lights.
    pub fn with_area_samples(mut self, samples: Vec<AreaSample>) -> Light {
        self.area_samples = samples;
        self
    }

    /// `Attribute "light" "shadows" ["on"]` (BMRT): the light's visibility is decided by
    /// shadow rays through [`crate::ShadingEnv::occlusion`] instead of shadow maps.
    pub fn with_raytraced_shadows(mut self, on: bool) -> Light {
        self.raytraced = on;
        self
    }

    /// Gives an `arealight` its geometry: every shaded point gets `samples` stratified points
    /// on it (a different jitter per point), each run as Listing 9.18's `illuminate(P, N, PI/2)`
    /// with `Cl` scaled by `1/samples` and its visibility decided by a shadow ray. Takes
    /// precedence over [`Light::with_area_samples`]. Ignored by the other lights.
    pub fn with_emitter(mut self, emitter: Arc<AreaEmitter>, samples: u32) -> Light {
        self.emitter = Some(emitter);
        self.samples = samples.max(1);
        self
    }

    /// Whether shading needs shadow rays for this light (the renderer builds its ray-tracing
    /// scene only when some light does).
    pub fn needs_rays(&self) -> bool {
        self.raytraced || self.emitter.is_some() || self.params.string("shadowname") == "raytrace"
    }

    /// The shader name as bound.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// True for lights with no direction (`ambientlight`): they feed `ambient()` and are skipped
    /// by illuminance loops.
    pub fn is_ambient(&self) -> bool {
        self.kind == LightKind::Ambient
    }

    /// `lightsource(name, result)`: the light's parameter `name`, if it has one.
    pub fn param(&self, name: &str) -> Option<&ParamValue> {
        self.params.get(name)
    }

    /// `__category`: comma-separated category list ("" when not given).
    pub fn category(&self) -> &str {
        self.params.string("__category")
    }

    /// `__nondiffuse` (0 unless given): Listing 9.10 scales the light's `diffuse()` share by
    /// `1 - __nondiffuse`.
    pub fn nondiffuse(&self) -> f32 {
        self.params.float("__nondiffuse")
    }

    /// `__nonspecular` (0 unless given).
    pub fn nonspecular(&self) -> f32 {
        self.params.float("__nonspecular")
    }

    /// A `point "shader"` parameter in camera space.
    pub(crate) fn point(&self, name: &str) -> Vec3 {
        self.camera_from_shader
            .transform_point3(self.params.vec3(name).as_dvec3())
            .as_vec3()
    }
}

/// One light evaluated over a grid.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSamples {
    /// No direction (feeds `ambient()` only).
    pub ambient: bool,
    /// `L` as the surface sees it: from the shaded point *toward* the light (not unit length:
    /// `from - P` for local lights, a unit vector for `solar` lights).
    pub l: Vec<Vec3>,
    /// `Cl`; zero where the light's `illuminate`/`solar` cone excludes the point.
    pub cl: Vec<Vec3>,
    /// `Ol` (1 for all built-in lights).
    pub ol: Vec<Vec3>,
    /// False where the light's cone excludes the point (its body did not run).
    pub lit: Vec<bool>,
    /// The light's `__shadow` output (PRMan's shadow lights): `shadow()`, the occluded
    /// fraction, per point; empty for a light that casts no shadows (no map, no rays).
    pub shadow: Vec<f32>,
}

impl LightSamples {
    pub(crate) fn new(n: usize, ambient: bool) -> LightSamples {
        LightSamples {
            ambient,
            l: vec![Vec3::ZERO; n],
            cl: vec![Vec3::ZERO; n],
            ol: vec![Vec3::ONE; n],
            lit: vec![false; n],
            shadow: Vec::new(),
        }
    }
}

/// Every light of the grid, run once (an area light appears once per geometry sample).
pub struct LightCache<'l> {
    pub lights: Vec<(&'l Light, LightSamples)>,
}

impl<'l> LightCache<'l> {
    /// Runs each light once over the grid's `P` (and `dPdu`/`dPdv` for shadow footprints).
    pub fn run(lights: &[&'l Light], grid: &ShadingGrid, env: &ShadingEnv) -> LightCache<'l> {
        LightCache {
            lights: lights
                .iter()
                .flat_map(|&light| {
                    lights::run(light, grid, env)
                        .into_iter()
                        .map(move |s| (light, s))
                })
                .collect(),
        }
    }

    /// The surface-side `__shadow` AOV at each of `n` points: the sum of every light's
    /// `__shadow` output (0 where no light casts a shadow), as a PRMan surface gathers it
    /// with `lightsource("__shadow", s)` in its illuminance loop.
    pub fn shadow(&self, n: usize) -> Vec<f32> {
        let mut sum = vec![0.0f32; n];
        for (_, s) in &self.lights {
            for (a, v) in sum.iter_mut().zip(&s.shadow) {
                *a += v;
            }
        }
        sum
    }
}
