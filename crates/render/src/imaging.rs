//! The frame's imager (RI Spec 3.2 `RiImager`): bound once per frame, run by the hider on each
//! bucket's filtered pixels ([`GridShader::image`](illume_reyes::GridShader::image)), so it
//! sees pre-exposure, pre-quantization premultiplied colour and coverage. A `name.sl` imager on
//! the shader searchpath wins over the built-ins (`background`, `clamptoalpha`); an unknown
//! name warns once at the `Imager` request and no imager runs.
use crate::slshaders;
use illume_reyes::PixelBlock;
use illume_ri::{Diagnostic, Frame, Severity};
use illume_shade::ShadingEnv;
use illume_sl::types::ShaderKind;
use illume_slvm::SlInstance;
use std::collections::HashSet;

/// Which imager runs.
enum Kind {
    Builtin(illume_shade::Imager),
    Sl(SlInstance),
}

/// A bound imager and the frame size its raster positions are measured in.
pub(crate) struct FrameImager {
    kind: Kind,
    resolution: [u32; 2],
}

impl FrameImager {
    /// Binds the frame's `Imager`, if any; problems go to `diags` with the request's span.
    pub fn bind(frame: &Frame, diags: &mut Vec<Diagnostic>) -> Option<FrameImager> {
        let shader = frame.options.imager.as_ref()?;
        let mut reported = HashSet::new();
        let sl = slshaders::bind_sl(
            frame,
            shader,
            ShaderKind::Imager,
            "Imager",
            &mut reported,
            diags,
        );
        let kind = match sl {
            Some(inst) => Kind::Sl(inst),
            None => match illume_shade::imager(&shader.name, &shader.params) {
                Ok((imager, warnings)) => {
                    diags.extend(warnings.into_iter().map(|w| warning(shader, w)));
                    Kind::Builtin(imager)
                }
                Err(e) => {
                    diags.push(warning(shader, format!("{e}; no imager runs")));
                    return None;
                }
            },
        };
        let o = &frame.options;
        Some(FrameImager {
            kind,
            resolution: [o.xres, o.yres],
        })
    }

    /// Runs the imager on one bucket's pixels in place; returns how many came out non-finite
    /// (and were repaired).
    pub fn run(&self, block: &mut PixelBlock, env: &ShadingEnv) -> usize {
        match &self.kind {
            Kind::Builtin(imager) => {
                imager.apply(&mut block.rgba);
                0
            }
            Kind::Sl(inst) => {
                let grid = illume_slvm::imager_grid(block.rect, self.resolution);
                inst.run_imager(&grid, &mut block.rgba, env).nonfinite
            }
        }
    }
}

fn warning(shader: &illume_ri::Shader, message: String) -> Diagnostic {
    Diagnostic {
        severity: Severity::Warning,
        kind: illume_ri::ErrorKind::Unimplemented,
        span: shader.span.clone(),
        request: Some("Imager".to_string()),
        message,
    }
}
