//! Volume shaders of a frame (RI 3.2 §9): the `Atmosphere` of a primitive runs on each of its
//! grids right after the surface shader, on the `Ci`/`Oi` the surface left, before the hider
//! composites; points where no surface is hit are never shaded, so the background stays as the
//! hider leaves it (RI 3.2: atmospheres apply to surfaces only). A `.sl` volume shader on the
//! searchpath wins over the built-in `fog`/`depthcue`/`null` of the same name.
//!
//! SL volume shaders get the grid's lights and a [`Relight`] hook ([`GridRelight`]), so the
//! book's smoke pattern (ray-march toward `E` calling `illuminance(Pmarch)` and `shadow()`)
//! sees every light at every step.
//!
//! `Interior`/`Exterior` apply to rays that `trace()` follows (`trace/volume.rs` calls
//! [`FrameVolumes::volume_along`] with a one-point grid per ray segment).
use crate::slshaders::{bind_sl, shader_warning, SlShaders};
use illume_ri::{Attributes, Diagnostic, Frame, Shader};
use illume_shade::{Light, LightCache, LightSamples, ShadingEnv, ShadingGrid, Volume};
use illume_sl::types::ShaderKind;
use illume_slvm::{Lights, Messages, Relight, SlInstance, Value};
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// A bound volume shader: SL (found on the searchpath) or built-in.
#[derive(Clone)]
pub(crate) enum BoundVolume {
    Sl(Arc<SlInstance>),
    Builtin(Arc<Volume>),
}

/// Which volume of the attributes.
#[derive(Clone, Copy)]
pub(crate) enum VolumeSlot {
    Atmosphere,
    Interior,
    Exterior,
}

impl VolumeSlot {
    fn shader(self, attrs: &Attributes) -> Option<&Arc<Shader>> {
        match self {
            VolumeSlot::Atmosphere => attrs.atmosphere.as_ref(),
            VolumeSlot::Interior => attrs.interior.as_ref(),
            VolumeSlot::Exterior => attrs.exterior.as_ref(),
        }
    }

    fn request(self) -> &'static str {
        match self {
            VolumeSlot::Atmosphere => "Atmosphere",
            VolumeSlot::Interior => "Interior",
            VolumeSlot::Exterior => "Exterior",
        }
    }
}

/// Every volume shader the frame's primitives name, keyed by the address of the shared
/// `Arc<Shader>`; a name that is neither a `.sl` nor a built-in warns once and is skipped.
#[derive(Default)]
pub(crate) struct FrameVolumes {
    bound: HashMap<usize, BoundVolume>,
}

impl FrameVolumes {
    pub fn bind(frame: &Frame, diags: &mut Vec<Diagnostic>) -> FrameVolumes {
        let mut v = FrameVolumes::default();
        let mut tried = HashSet::new();
        let mut reported = HashSet::new();
        for prim in &frame.primitives {
            for slot in [
                VolumeSlot::Atmosphere,
                VolumeSlot::Interior,
                VolumeSlot::Exterior,
            ] {
                let Some(s) = slot.shader(&prim.attributes) else {
                    continue;
                };
                let key = Arc::as_ptr(s) as usize;
                if !tried.insert(key) {
                    continue;
                }
                let request = slot.request();
                if s.name != "null" {
                    if let Some(i) =
                        bind_sl(frame, s, ShaderKind::Volume, request, &mut reported, diags)
                    {
                        v.bound.insert(key, BoundVolume::Sl(Arc::new(i)));
                        continue;
                    }
                }
                match illume_shade::volume(&s.name, &s.params) {
                    Ok((b, warnings)) => {
                        diags.extend(warnings.into_iter().map(|w| shader_warning(s, request, w)));
                        v.bound.insert(key, BoundVolume::Builtin(Arc::new(b)));
                    }
                    Err(e) => diags.push(shader_warning(s, request, format!("{e}; ignored"))),
                }
            }
        }
        v
    }

    /// The bound shader of `slot` for these attributes, with its "shader" space.
    pub fn get<'s, 'a>(
        &'s self,
        attrs: &'a Attributes,
        slot: VolumeSlot,
    ) -> Option<(&'s BoundVolume, &'a Shader)> {
        let s = slot.shader(attrs)?;
        Some((self.bound.get(&(Arc::as_ptr(s) as usize))?, s))
    }

    /// What the surface's `atmosphere()` reads: an SL atmosphere's parameter values on `grid`.
    pub fn atmosphere_messages(
        &self,
        attrs: &Attributes,
        grid: &ShadingGrid,
        env: &ShadingEnv,
    ) -> Vec<(String, Value)> {
        match self.get(attrs, VolumeSlot::Atmosphere) {
            Some((BoundVolume::Sl(i), s)) => {
                let mut venv = *env;
                venv.camera_from_shader = s.camera_from_shader;
                i.parameter_values(grid, &venv)
            }
            _ => Vec::new(),
        }
    }

    /// Runs the volume shader in `slot` of `attrs` over `grid` (its `Ci`/`Oi` in place);
    /// returns the count of non-finite results repaired. Nothing happens without one.
    ///
    /// For `Atmosphere` the grid is the shaded surface grid and `eye` is `None` (`E` is the
    /// camera origin). For `Interior`/`Exterior` on a traced ray the grid is one point: `p`
    /// where the ray segment ends, `i = p − origin` (the volume's `I`, whose length is the
    /// distance through the volume), `ci`/`oi` the colour and opacity arriving there, and
    /// `eye` the ray's origin (`E`); the attenuated values come back in `ci`/`oi`.
    #[allow(clippy::too_many_arguments)]
    pub fn volume_along(
        &self,
        attrs: &Attributes,
        slot: VolumeSlot,
        grid: &mut ShadingGrid,
        env: &ShadingEnv,
        lights: &Lights,
        relight: Option<&dyn Relight>,
        eye: Option<glam::Vec3>,
    ) -> usize {
        let Some((bound, s)) = self.get(attrs, slot) else {
            return 0;
        };
        let mut venv = *env;
        venv.camera_from_shader = s.camera_from_shader;
        match bound {
            BoundVolume::Builtin(v) => {
                illume_shade::run_volume(v, grid, &venv);
                0
            }
            BoundVolume::Sl(i) => {
                i.shade_volume(grid, lights, relight, &venv, Messages::default(), eye)
                    .nonfinite
            }
        }
    }
}

/// The lights of one grid re-run at other points (a volume shader's `illuminance(Pmarch)`):
/// the built-in lights through [`LightCache`], then the SL lights, the order of the grid's
/// [`Lights`] view.
pub(crate) struct GridRelight<'s> {
    pub builtin: &'s [&'s Light],
    pub sl: &'s SlShaders,
    pub indices: &'s [usize],
    pub env: &'s ShadingEnv<'s>,
    pub messages: &'s Messages,
}

impl Relight for GridRelight<'_> {
    fn relight(&self, p: &[glam::Vec3]) -> Vec<LightSamples> {
        let mut g = ShadingGrid::new(p.len(), 1);
        g.p = p.to_vec();
        // A point in a volume has no surface: no normal to push shadow rays along.
        g.ng = vec![glam::Vec3::ZERO; p.len()];
        g.n = g.ng.clone();
        g.set_incident_from_p(false);
        let cache = LightCache::run(self.builtin, &g, self.env);
        let sl = self
            .sl
            .run_lights(self.indices, &g, self.env, self.messages);
        cache
            .lights
            .into_iter()
            .map(|(_, s)| s)
            .chain(sl.into_iter().map(|(_, s, _)| s))
            .collect()
    }
}
