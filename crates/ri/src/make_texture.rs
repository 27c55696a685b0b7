//! `MakeTexture`, `MakeBump`, `MakeLatLongEnvironment`, `MakeCubeFaceEnvironment` and
//! `MakeShadow` (RI Spec 3.2 §8): handed to the texture builder the caller plugs in, so the RI
//! state does not depend on the texture crate.
use crate::options::Options;
use crate::state::Ri;
use illume_rib::{Request, Span};

/// Builds a texture for `MakeTexture`/`MakeShadow`/… (`illume-texture` plugs in here).
pub type TextureMaker = Box<dyn FnMut(&Request, &Options) -> Result<(), String>>;

impl Ri {
    pub(crate) fn make_texture(&mut self, req: &Request, span: &Span) {
        match self.texture_maker.as_mut() {
            Some(maker) => {
                if let Err(e) = maker(req, &self.options) {
                    self.diagnostics.error(span, req.name(), e);
                }
            }
            None => self.diagnostics.warn(
                span,
                req.name(),
                "texture making not supported yet (skipped)",
            ),
        }
    }
}
