//! Shading Language shaders of a frame: every `Surface`, `Displacement` and `LightSource` name
//! is looked up as `name.sl` on the shader searchpath (then the requesting RIB file's
//! directory) through `illume_slvm::library`; a file found there wins over the built-in shader
//! of the same name. Files compile once per run (cached by path and mtime); a file that does
//! not compile warns once with its `file:line:col` diagnostics and the built-in (or
//! `defaultsurface`) is used instead.
use glam::DMat4;
use illume_ri::{Attributes, Diagnostic, Frame, Severity, Shader};
use illume_shade::{Light, LightSamples, ShadingEnv, ShadingGrid};
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
}

/// An SL light's parameters by name after it ran on a grid (what `lightsource()` reads).
pub(crate) type LightParams = Vec<(String, Value)>;

#[derive(Default)]
pub(crate) struct SlShaders {
    surfaces: HashMap<usize, Arc<SlInstance>>,
    displacements: HashMap<usize, Arc<SlInstance>>,
    /// Index-aligned with `Frame::lights`.
    lights: Vec<Option<SlLight>>,
}

fn warning(shader: &Shader, request: &str, message: String) -> Diagnostic {
    Diagnostic {
        severity: Severity::Warning,
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
            diags.extend(warnings.into_iter().map(|w| warning(shader, request, w)));
            Some(inst)
        }
        Err(e) => {
            if reported.insert(e.clone()) {
                diags.push(warning(
                    shader,
                    request,
                    format!(
                        "shader \"{}\" does not compile; using the built-in:\n{e}",
                        shader.name
                    ),
                ));
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
            .map(|l| {
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
                Some(SlLight {
                    shader,
                    proxy,
                    camera_from_shader: s.camera_from_shader,
                })
            })
            .collect();
        sl
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
        indices
            .iter()
            .filter_map(|&i| self.lights.get(i).and_then(Option::as_ref))
            .map(|l| {
                let mut lenv = *env;
                lenv.camera_from_shader = l.camera_from_shader;
                let (samples, outputs) = l.shader.run_light_with(grid, &lenv, messages.clone());
                (&l.proxy, samples, outputs)
            })
            .collect()
    }
}
