//! The back-end interface a session drives, and the in-process renderer (the RIB writer is in
//! `ribwriter.rs`).
use crate::errors::{RiError, RIE_BADFILE, RIE_ERROR};
use illume_ri::{Frame, Ri};
use illume_rib::{Param, Request};

/// What a session sends its requests to.
pub trait Backend {
    /// Sets up the session's `ri` state machine (texture maker) for this back end.
    fn configure(&self, ri: &mut Ri);
    /// `Option "rib" …`: settings of the RIB writer (format, compression); the session sends
    /// them nowhere else. Other back ends ignore them.
    fn rib_option(&mut self, _params: &[Param]) -> Vec<RiError> {
        Vec::new()
    }
    /// Whether requests end up as RIB (which can not hold a program's C functions).
    fn writes_rib(&self) -> bool {
        false
    }
    /// One request, as the program said it (before `ri` sees it).
    fn write(&mut self, req: &Request) -> Result<(), RiError>;
    /// A `#` comment (only the RIB writer keeps it).
    fn comment(&mut self, _text: &str) -> Result<(), RiError> {
        Ok(())
    }
    /// A frame the state machine finished (`WorldEnd`).
    fn frame(&mut self, frame: Frame) -> Vec<RiError>;
    /// `RiEnd`.
    fn finish(&mut self) -> Result<(), RiError>;
}

/// Renders frames as `render` does: same hider, same texture cache, displays written.
#[derive(Default)]
pub struct InProcess;

impl InProcess {
    pub fn new() -> InProcess {
        InProcess
    }
}

impl Backend for InProcess {
    fn configure(&self, ri: &mut Ri) {
        ri.set_texture_maker(illume_render::texture_maker(|request, warning| {
            eprintln!("illume: warning: {request}: {warning}")
        }));
    }

    fn write(&mut self, _req: &Request) -> Result<(), RiError> {
        Ok(())
    }

    fn frame(&mut self, frame: Frame) -> Vec<RiError> {
        render_frame(&frame)
    }

    fn finish(&mut self) -> Result<(), RiError> {
        Ok(())
    }
}

/// `render`'s per-frame work without the progress bar and statistics.
fn render_frame(frame: &Frame) -> Vec<RiError> {
    // `limits texturememory` is in kilobytes.
    let cache = illume_texture::TextureCache::new(frame.options.texture_memory as usize * 1024)
        .with_searchpath(frame.options.texture_path.clone());
    let settings = illume_render::RenderSettings {
        progress: None,
        textures: Some(&cache),
    };
    let rendered = illume_render::render(frame, &settings);
    let mut errors: Vec<RiError> = rendered.warnings.iter().map(RiError::from_ri).collect();
    for result in illume_render::write_displays(frame, &rendered) {
        if let Err(e) = result {
            errors.push(RiError::new(RIE_BADFILE, RIE_ERROR, e.to_string()));
        }
    }
    errors
}
