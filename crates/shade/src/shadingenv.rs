//! What shaders need from the rest of the renderer besides the grid: spaces, options, textures,
//! and a place to put warnings.
use crate::occlusion::Occlusion;
use crate::renderstate::RenderInfo;
use crate::texturelookup::TextureLookup;
use crate::tracing::RayTracer;
use glam::{DMat4, Vec3};
use std::collections::{HashMap, HashSet};
use std::sync::Mutex;

/// Which formula `specular()` uses (`Option "shading" "string specularmodel"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SpecularModel {
    /// Blinn-Phong `max(0, N·H)^(1/roughness)`: the RI Specification and Listing 9.10
    /// (`"blinn"`).
    Blinn,
    /// `max(0, N·H)^(8/roughness)`: the exponent PRMan, BMRT, Aqsis and 3Delight use. The
    /// default, because every RIB a user has was tuned on one of those renderers and the book's
    /// own figures were rendered with PRMan (`"prman"`).
    #[default]
    PrMan,
}

impl SpecularModel {
    /// Parses the option value: `"blinn"`/`"rispec"` or `"prman"`/`"bmrt"`/`"aqsis"`.
    pub fn from_option(value: &str) -> Option<SpecularModel> {
        match value.to_ascii_lowercase().as_str() {
            "blinn" | "blinnphong" | "rispec" | "spec" => Some(SpecularModel::Blinn),
            "prman" | "bmrt" | "aqsis" => Some(SpecularModel::PrMan),
            _ => None,
        }
    }

    /// The Blinn-Phong exponent for `roughness`.
    pub fn exponent(self, roughness: f32) -> f32 {
        match self {
            SpecularModel::Blinn => 1.0 / roughness,
            SpecularModel::PrMan => 8.0 / roughness,
        }
    }
}

/// Where in a shader's source a run-time problem arose: the statement being run.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SourceAt {
    pub file: String,
    pub line: u32,
    pub col: u32,
}

/// A message with the shader source position it is about, when there is one.
pub type Located = (Option<SourceAt>, String);

/// Where shading warnings go (missing maps, unknown spaces…). Implementations de-duplicate.
pub trait WarningSink: Send + Sync {
    fn warn(&self, message: &str);
    /// A shader that could not finish (a runaway loop stopped by a limit): the frame renders
    /// but is wrong, so `render` counts it as an error. Sinks without a separate list warn.
    fn error(&self, message: &str) {
        self.warn(message)
    }
    /// [`WarningSink::warn`] about a statement of a shader's source (SL run-time problems), so
    /// the report can name its `file:line:col`. Sinks that keep no positions just warn.
    fn warn_at(&self, at: Option<&SourceAt>, message: &str) {
        let _ = at;
        self.warn(message)
    }
    /// [`WarningSink::error`] about a statement of a shader's source.
    fn error_at(&self, at: Option<&SourceAt>, message: &str) {
        let _ = at;
        self.error(message)
    }
}

/// A [`WarningSink`] that keeps each distinct message once, in order of first occurrence.
#[derive(Debug, Default)]
pub struct WarnOnce {
    seen: Mutex<(HashSet<Located>, Vec<Located>)>,
    errors: Mutex<Vec<Located>>,
}

impl WarnOnce {
    pub fn new() -> WarnOnce {
        WarnOnce::default()
    }

    /// The distinct messages so far, first occurrence first.
    pub fn messages(&self) -> Vec<String> {
        self.located_messages().into_iter().map(|m| m.1).collect()
    }

    /// The distinct errors so far (see [`WarningSink::error`]), first occurrence first.
    pub fn errors(&self) -> Vec<String> {
        self.located_errors().into_iter().map(|m| m.1).collect()
    }

    /// [`WarnOnce::messages`] with the shader source position of each, where known.
    pub fn located_messages(&self) -> Vec<Located> {
        self.seen.lock().map(|g| g.1.clone()).unwrap_or_default()
    }

    /// [`WarnOnce::errors`] with the shader source position of each, where known.
    pub fn located_errors(&self) -> Vec<Located> {
        self.errors.lock().map(|g| g.clone()).unwrap_or_default()
    }
}

impl WarningSink for WarnOnce {
    fn warn(&self, message: &str) {
        self.warn_at(None, message)
    }

    fn error(&self, message: &str) {
        self.error_at(None, message)
    }

    fn warn_at(&self, at: Option<&SourceAt>, message: &str) {
        let m = (at.cloned(), message.to_string());
        if let Ok(mut g) = self.seen.lock() {
            if g.0.insert(m.clone()) {
                g.1.push(m);
            }
        }
    }

    fn error_at(&self, at: Option<&SourceAt>, message: &str) {
        let m = (at.cloned(), message.to_string());
        if let Ok(mut g) = self.errors.lock() {
            if !g.contains(&m) {
                g.push(m);
            }
        }
    }
}

/// The per-grid environment of a shader. Shading happens in camera ("current") space; every
/// matrix here maps *into* or *out of* camera space, in `f64` (DESIGN.md “Numbers and spaces”).
#[derive(Clone, Copy)]
pub struct ShadingEnv<'a> {
    pub camera_from_world: DMat4,
    /// `camera_from_object` of the primitive being shaded ("object" space).
    pub camera_from_object: DMat4,
    /// `camera_from_shader` of the surface/displacement shader ("shader" space: the CTM when the
    /// `Surface`/`Displacement` request was read).
    pub camera_from_shader: DMat4,
    /// Named coordinate systems (`CoordinateSystem`), each as `camera_from_X`.
    pub coordinate_systems: Option<&'a HashMap<String, DMat4>>,
    /// Projective maps from camera space (applied with the homogeneous divide).
    pub screen_from_camera: DMat4,
    pub ndc_from_camera: DMat4,
    pub raster_from_camera: DMat4,
    pub specular_model: SpecularModel,
    pub textures: Option<&'a dyn TextureLookup>,
    pub warnings: Option<&'a dyn WarningSink>,
    /// Shadow rays (ray-traced shadows, area lights); `None`: those lights are unshadowed.
    pub occlusion: Option<&'a dyn Occlusion>,
    /// How far shadow rays start off this grid's surface, camera-space units: the renderer's
    /// bound on the distance between its ray-tracing tessellation and the true surface
    /// (a rounding term is added per point, see `occlusion.rs`).
    pub ray_offset: f32,
    /// Rays from shaders (`trace`, `visibility`, `occlusion`, …); `None`: they see nothing.
    pub tracer: Option<&'a dyn RayTracer>,
    /// The frame primitive being shaded (for the tracer's ray offset).
    pub primitive: usize,
    /// How many `trace()` bounces led to this grid (0: the camera sees it).
    pub ray_depth: u32,
    /// Mixed into every per-point random number (the frame number), so frames differ.
    pub seed: u32,
    /// The camera's `Clipping` planes (camera-space z), for `depth()`.
    pub clipping: (f32, f32),
    /// The depth bias of SL `shadow()` calls that pass no `"bias"`: the frame's
    /// `Option "shadow" "bias"` (PRMan's; 0.225 by default as in PRMan and Aqsis).
    pub shadow_bias: f32,
    /// The frame's options and the primitive's attributes as `option()`/`attribute()` see
    /// them; `None`: every query answers "unknown".
    pub options: Option<&'a RenderInfo>,
    pub attributes: Option<&'a RenderInfo>,
}

impl<'a> ShadingEnv<'a> {
    /// An environment with every space equal to camera space, Blinn-Phong `specular()`, no
    /// textures and no warning sink. Set the public fields that the caller knows.
    pub fn new() -> ShadingEnv<'a> {
        ShadingEnv {
            camera_from_world: DMat4::IDENTITY,
            camera_from_object: DMat4::IDENTITY,
            camera_from_shader: DMat4::IDENTITY,
            coordinate_systems: None,
            screen_from_camera: DMat4::IDENTITY,
            ndc_from_camera: DMat4::IDENTITY,
            raster_from_camera: DMat4::IDENTITY,
            specular_model: SpecularModel::PrMan,
            textures: None,
            warnings: None,
            occlusion: None,
            ray_offset: 0.0,
            tracer: None,
            primitive: usize::MAX,
            ray_depth: 0,
            seed: 0,
            clipping: (f32::EPSILON, f32::INFINITY),
            shadow_bias: 0.225,
            options: None,
            attributes: None,
        }
    }

    /// Reports a warning to the sink, if any.
    pub fn warn(&self, message: &str) {
        if let Some(w) = self.warnings {
            w.warn(message);
        }
    }

    /// Reports an error (see [`WarningSink::error`]) to the sink, if any.
    pub fn error(&self, message: &str) {
        if let Some(w) = self.warnings {
            w.error(message);
        }
    }

    /// [`ShadingEnv::warn`] about a statement of a shader's source.
    pub fn warn_at(&self, at: Option<&SourceAt>, message: &str) {
        if let Some(w) = self.warnings {
            w.warn_at(at, message);
        }
    }

    /// [`ShadingEnv::error`] about a statement of a shader's source.
    pub fn error_at(&self, at: Option<&SourceAt>, message: &str) {
        if let Some(w) = self.warnings {
            w.error_at(at, message);
        }
    }

    /// `camera_from_X` for an affine named space: `current`, `camera`, `world`, `object`,
    /// `shader` or a `CoordinateSystem` name. Projective spaces (`screen`, `raster`, `NDC`) are
    /// handled by [`ShadingEnv::transform_point`]; `None` for an unknown name.
    pub fn camera_from(&self, space: &str) -> Option<DMat4> {
        match space {
            "current" | "camera" => Some(DMat4::IDENTITY),
            "world" => Some(self.camera_from_world),
            "object" => Some(self.camera_from_object),
            "shader" => Some(self.camera_from_shader),
            _ => self.coordinate_systems.and_then(|m| m.get(space)).copied(),
        }
    }

    /// `transform(space, P)`: a camera-space point into `space` (projective for `screen`,
    /// `raster`, `NDC`). `None` if the space is unknown.
    pub fn transform_point(&self, space: &str, p: Vec3) -> Option<Vec3> {
        let p = p.as_dvec3();
        let q = match space {
            "screen" => self.screen_from_camera.project_point3(p),
            "raster" => self.raster_from_camera.project_point3(p),
            "NDC" => self.ndc_from_camera.project_point3(p),
            _ => self.camera_from(space)?.inverse().transform_point3(p),
        };
        Some(q.as_vec3())
    }

    /// `vtransform(space, V)`: a camera-space direction into an affine `space`.
    pub fn transform_vector(&self, space: &str, v: Vec3) -> Option<Vec3> {
        let m = self.camera_from(space)?.inverse();
        Some(m.transform_vector3(v.as_dvec3()).as_vec3())
    }
}

impl Default for ShadingEnv<'_> {
    fn default() -> Self {
        ShadingEnv::new()
    }
}
