//! Shading Language shaders of a frame: every `Surface`, `Displacement` and `LightSource` name
//! is looked up as `name.sl` on the shader searchpath (then the requesting RIB file's
//! directory) through `illume_slvm::library`; a file found there wins over the built-in shader
//! of the same name. Files compile once per run (cached by path and mtime); a file that does
//! not compile warns once with its `file:line:col` diagnostics and the built-in (or
//! `defaultsurface`) is used instead.
use glam::DMat4;
use glam::Vec3;
use illume_ri::{Attributes, Diagnostic, Frame, Severity, Shader};
use illume_shade::{AreaEmitter, Light, LightSamples, ShadingEnv, ShadingGrid};
use illume_sl::types::ShaderKind;
use illume_slvm::library::ShaderLibrary;
use illume_slvm::{SlInstance, Value};
use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

/// An SL light and the built-in stand-in that carries its RIB parameters (`__category`,
/// `__nondiffuse`, …) for the illuminance loops of built-in surfaces.
pub(crate) struct SlLight {
    pub shader: SlInstance,
    pub proxy: Light,
    pub camera_from_shader: DMat4,
    /// An `AreaLightSource`'s geometry and samples per shaded point (`Attribute "light"
    /// "nsamples"`): the shader runs once per sample with `P`, `N` on the geometry.
    pub emitter: Option<(Arc<AreaEmitter>, u32)>,
}

/// The random stream of area-light samples: the built-in `arealight`'s, so an SL area light
/// samples the very points the built-in does.
const AREA_STREAM: u32 = 0x2c1b_3c6d;

/// An SL light's parameters by name after it ran on a grid (what `lightsource()` reads).
pub(crate) type LightParams = Vec<(String, Value)>;

#[derive(Default)]
pub(crate) struct SlShaders {
    surfaces: HashMap<usize, Arc<SlInstance>>,
    displacements: HashMap<usize, Arc<SlInstance>>,
    /// Index-aligned with `Frame::lights`.
    lights: Vec<Option<SlLight>>,
}

/// A warning about `shader` at its request (binding problems, fallbacks to a built-in): the
/// one form the surface, displacement, light and volume bindings all report in.
pub(crate) fn shader_warning(shader: &Shader, request: &str, message: String) -> Diagnostic {
    Diagnostic {
        severity: Severity::Warning,
        kind: illume_ri::ErrorKind::Unimplemented,
        span: shader.span.clone(),
        request: Some(request.to_string()),
        message,
    }
}

/// Binds `shader` as an SL shader of `kind` if its `.sl` is on the searchpath and compiles.
pub(crate) fn bind_sl(
    frame: &Frame,
    shader: &Shader,
    kind: ShaderKind,
    request: &str,
    reported: &mut HashSet<String>,
    diags: &mut Vec<Diagnostic>,
) -> Option<SlInstance> {
    let dir = Path::new(&*shader.span.file).parent();
    let found =
        ShaderLibrary::global().load(&shader.name, kind, &frame.options.shader_path, dir)?;
    match found {
        Ok(compiled) => {
            let (inst, warnings) =
                SlInstance::bind(compiled, &shader.params, shader.camera_from_shader);
            diags.extend(
                warnings
                    .into_iter()
                    .map(|w| shader_warning(shader, request, w)),
            );
            Some(inst)
        }
        Err(e) => {
            if reported.insert(e.clone()) {
                diags.push(Diagnostic {
                    kind: illume_ri::ErrorKind::NoShader,
                    ..shader_warning(
                        shader,
                        request,
                        format!(
                            "shader \"{}\" does not compile; using the built-in:\n{e}",
                            shader.name
                        ),
                    )
                });
            }
            None
        }
    }
}

impl SlShaders {
    pub fn bind(frame: &Frame, diags: &mut Vec<Diagnostic>) -> SlShaders {
        let mut sl = SlShaders::default();
        let mut reported = HashSet::new();
        // Each distinct request is looked up once, found or not (no file-system access per
        // primitive).
        let mut tried: HashSet<(u8, usize)> = HashSet::new();
        for prim in &frame.primitives {
            let a = &prim.attributes;
            if let Some(s) = a.surface.as_ref() {
                let key = Arc::as_ptr(s) as usize;
                if s.name != "null" && tried.insert((0, key)) {
                    if let Some(i) = bind_sl(
                        frame,
                        s,
                        ShaderKind::Surface,
                        "Surface",
                        &mut reported,
                        diags,
                    ) {
                        sl.surfaces.insert(key, Arc::new(i));
                    }
                }
            }
            if let Some(s) = a.displacement.as_ref() {
                let key = Arc::as_ptr(s) as usize;
                if tried.insert((1, key)) {
                    if let Some(i) = bind_sl(
                        frame,
                        s,
                        ShaderKind::Displacement,
                        "Displacement",
                        &mut reported,
                        diags,
                    ) {
                        sl.displacements.insert(key, Arc::new(i));
                    }
                }
            }
        }
        sl.lights = frame
            .lights
            .iter()
            .enumerate()
            .map(|(index, l)| {
                let s = &l.shader;
                let shader = bind_sl(
                    frame,
                    s,
                    ShaderKind::Light,
                    "LightSource",
                    &mut reported,
                    diags,
                )?;
                // The stand-in keeps every RIB parameter (lights keep unknown ones).
                let proxy = illume_shade::light("pointlight", &s.params, s.camera_from_shader)
                    .map(|(l, _)| l)
                    .ok()?;
                let emitter = l
                    .area
                    .then(|| crate::rayscene::emitter(frame, index))
                    .filter(|e| !e.is_empty())
                    .map(|e| (Arc::new(e), l.samples.max(1)));
                Some(SlLight {
                    shader,
                    proxy,
                    camera_from_shader: s.camera_from_shader,
                    emitter,
                })
            })
            .collect();
        sl
    }

    /// The float and triple `output` parameters of every SL surface of the frame (name,
    /// floats, colour), sorted by name: the variables a display may name besides the globals.
    pub fn surface_outputs(&self) -> crate::aov::SlOutputs {
        let mut out: crate::aov::SlOutputs = self
            .surfaces
            .values()
            .flat_map(|s| s.output_parameters())
            .collect();
        out.sort();
        out.dedup_by(|a, b| a.0 == b.0);
        out
    }

    pub fn has_surface(&self, shader: &Arc<Shader>) -> bool {
        self.surfaces.contains_key(&(Arc::as_ptr(shader) as usize))
    }

    pub fn has_displacement(&self, shader: &Arc<Shader>) -> bool {
        self.displacements
            .contains_key(&(Arc::as_ptr(shader) as usize))
    }

    pub fn has_light(&self, index: usize) -> bool {
        self.lights.get(index).is_some_and(Option::is_some)
    }

    pub fn surface(&self, attrs: &Attributes) -> Option<&Arc<SlInstance>> {
        let s = attrs.surface.as_ref()?;
        self.surfaces.get(&(Arc::as_ptr(s) as usize))
    }

    pub fn displacement(&self, attrs: &Attributes) -> Option<&Arc<SlInstance>> {
        let s = attrs.displacement.as_ref()?;
        self.displacements.get(&(Arc::as_ptr(s) as usize))
    }

    /// Runs the SL lights among `indices` over `grid`: (stand-in, samples, parameters after
    /// the run) to append to the grid's light cache; the parameters answer `lightsource()`.
    pub fn run_lights<'s>(
        &'s self,
        indices: &[usize],
        grid: &ShadingGrid,
        env: &ShadingEnv,
        messages: &illume_slvm::Messages,
    ) -> Vec<(&'s Light, LightSamples, LightParams)> {
        let mut out = Vec::new();
        for l in indices
            .iter()
            .filter_map(|&i| self.lights.get(i).and_then(Option::as_ref))
        {
            let mut lenv = *env;
            lenv.camera_from_shader = l.camera_from_shader;
            match &l.emitter {
                Some((emitter, n)) => {
                    for k in 0..*n {
                        let (samples, outputs) =
                            area_sample(l, emitter, k, *n, grid, &lenv, messages);
                        out.push((&l.proxy, samples, outputs));
                    }
                }
                None => {
                    let (samples, outputs) = l.shader.run_light_with(grid, &lenv, messages.clone());
                    out.push((&l.proxy, samples, outputs));
                }
            }
        }
        out
    }
}

/// Sample `k` of `n` of an SL area light: every shaded point gets its own stratified point on
/// the geometry (the built-in `arealight`'s numbers), the shader runs with `P`, `N` there, and
/// its `Cl` carries `1/n` of the light. A point without a sample gets nothing.
fn area_sample(
    l: &SlLight,
    emitter: &AreaEmitter,
    k: u32,
    n: u32,
    grid: &ShadingGrid,
    env: &ShadingEnv,
    messages: &illume_slvm::Messages,
) -> (LightSamples, LightParams) {
    let stream = env.seed ^ AREA_STREAM;
    let points: Vec<Option<(Vec3, Vec3)>> = grid
        .p
        .iter()
        .map(|&p| {
            let (u1, u2) = illume_shade::stratified_sample(p, k, n, stream);
            emitter.sample(u1, u2)
        })
        .collect();
    let position = points
        .iter()
        .map(|s| s.map_or(Vec3::ZERO, |s| s.0))
        .collect();
    let normal = points
        .iter()
        .map(|s| s.map_or(Vec3::ZERO, |s| s.1))
        .collect();
    let (mut samples, outputs) =
        l.shader
            .run_area_light_sample(grid, env, messages.clone(), position, normal);
    let weight = 1.0 / n as f32;
    for (i, s) in points.iter().enumerate() {
        if s.is_none() {
            samples.lit[i] = false;
            samples.cl[i] = Vec3::ZERO;
        } else {
            samples.cl[i] *= weight;
        }
    }
    (samples, outputs)
}
