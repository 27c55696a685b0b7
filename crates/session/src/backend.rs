//! The two back ends a session drives: the in-process renderer and the RIB writer.
use crate::errors::{
    RiError, RIE_BADFILE, RIE_ERROR, RIE_SEVERE, RIE_SYSTEM, RIE_UNIMPLEMENT, RIE_WARNING,
};
use illume_ri::{Frame, Ri, Severity};
use illume_rib::Request;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// What a session sends its requests to.
pub trait Backend {
    /// Sets up the session's `ri` state machine (texture maker) for this back end.
    fn configure(&self, ri: &mut Ri);
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
    let mut errors: Vec<RiError> = rendered
        .warnings
        .iter()
        .map(|w| {
            let severity = match w.severity {
                Severity::Warning => RIE_WARNING,
                Severity::Error => RIE_ERROR,
            };
            RiError::new(RIE_UNIMPLEMENT, severity, w.to_string())
        })
        .collect();
    for result in illume_render::write_displays(frame, &rendered) {
        if let Err(e) = result {
            errors.push(RiError::new(RIE_BADFILE, RIE_ERROR, e.to_string()));
        }
    }
    errors
}

/// Canonical ASCII RIB, one request a line (`catrib`'s output for the same requests).
pub struct RibWriter {
    out: BufWriter<File>,
    path: PathBuf,
}

impl RibWriter {
    pub fn create(path: &Path) -> std::io::Result<RibWriter> {
        let mut out = BufWriter::new(File::create(path)?);
        writeln!(out, "##RenderMan RIB")?;
        Ok(RibWriter {
            out,
            path: path.to_path_buf(),
        })
    }

    fn io_error(&self, e: std::io::Error) -> RiError {
        RiError::new(
            RIE_SYSTEM,
            RIE_SEVERE,
            format!("{}: {e}", self.path.display()),
        )
    }
}

impl Backend for RibWriter {
    fn configure(&self, ri: &mut Ri) {
        // The RIB's reader makes the textures; the shadow state machine only validates.
        ri.set_texture_maker(Box::new(|_, _| Ok(())));
    }

    fn write(&mut self, req: &Request) -> Result<(), RiError> {
        illume_rib::write_ascii(req, &mut self.out).map_err(|e| self.io_error(e))
    }

    fn comment(&mut self, text: &str) -> Result<(), RiError> {
        for line in text.lines() {
            writeln!(self.out, "#{line}").map_err(|e| self.io_error(e))?;
        }
        Ok(())
    }

    fn frame(&mut self, _frame: Frame) -> Vec<RiError> {
        Vec::new()
    }

    fn finish(&mut self) -> Result<(), RiError> {
        self.out.flush().map_err(|e| self.io_error(e))
    }
}
