//! The render driver around the REYES hider (`illume-reyes`): binds the frame's shaders
//! (built-in and `.sl`), lights, textures and ray-traced shadow geometry into the hider's
//! [`GridShader`](illume_reyes::GridShader); runs frames in file order; writes displays and
//! farm tiles. The hider knows grids and samples; everything that knows what a shader, a
//! texture file or an image format is lives here.
#![forbid(unsafe_code)]

pub mod aov;
mod aov_display;
pub mod display;
mod display_stream;
mod frame_loop;
mod imaging;
mod rayscene;
mod renderinfo;
mod shading;
mod slshaders;
mod tile;
mod trace;
mod volumes;

pub use display::{write_displays, DisplayError, WrittenDisplay};
pub use display_stream::DisplayStream;
pub use frame_loop::{render_frames_in_order, texture_maker};
pub use illume_reyes::{PixelFilter, Rendered, Stats};
pub use tile::{read_tile, write_tile, Tile};

use illume_reyes::Hider;
use illume_ri::{Diagnostic, Frame, Severity};
use shading::FrameShading;
use std::sync::atomic::Ordering::Relaxed;

/// Caller hooks for one render.
#[derive(Default)]
pub struct RenderSettings<'a> {
    /// Called after each bucket with (buckets done, bucket count).
    pub progress: Option<&'a (dyn Fn(usize, usize) + Sync)>,
    /// The texture system shaders look maps up in (`None`: every lookup is a missing map).
    pub textures: Option<&'a dyn illume_shade::TextureLookup>,
}

/// Renders one frame (uses the current rayon pool: `ThreadPool::install` to choose threads).
pub fn render(frame: &Frame, settings: &RenderSettings) -> Rendered {
    let (hider, shading) = prepare(frame, settings);
    let rendered = hider.render(&shading, settings.progress);
    finish(rendered, &shading)
}

/// [`render`] with every pixel filter evaluated exactly instead of through the film's
/// per-frame tables (issue 21 part 3): the reference the tables are tested against.
#[doc(hidden)]
pub fn render_with_exact_filter(frame: &Frame, settings: &RenderSettings) -> Rendered {
    let (mut hider, shading) = prepare(frame, settings);
    hider.use_exact_filter();
    let rendered = hider.render(&shading, settings.progress);
    finish(rendered, &shading)
}

/// Renders one frame straight into its displays (streaming output, issue 21): finished rows
/// go to the files while later buckets render, so memory does not grow with the frame (see
/// [`DisplayStream`] for the display kinds that still need a whole-frame buffer). The files
/// equal [`render`] then [`write_displays`], byte for byte. The [`Rendered`] returned carries
/// statistics and warnings; its pixel buffers are empty.
pub fn render_to_displays(
    frame: &Frame,
    settings: &RenderSettings,
) -> (Rendered, Vec<Result<WrittenDisplay, DisplayError>>) {
    let (hider, shading) = prepare(frame, settings);
    let mut displays = DisplayStream::new(frame, &shading.aov);
    let rendered = hider.render_to(&shading, settings.progress, &mut displays);
    (finish(rendered, &shading), displays.finish())
}

/// The hider with the frame's shading bound and the output variables it must carry.
fn prepare<'f>(frame: &'f Frame, settings: &RenderSettings<'f>) -> (Hider<'f>, FrameShading<'f>) {
    let mut hider = Hider::new(frame);
    let (mut shading, binding_warnings) = FrameShading::new(frame, settings.textures);
    hider.warnings.extend(binding_warnings);
    let (layout, aov_warnings) = aov::frame_layout(frame, &shading.sl.surface_outputs());
    hider.warnings.extend(aov_warnings);
    shading.aov = layout.clone();
    hider.set_aovs(layout);
    (hider, shading)
}

/// Adds what the shading stage counted and found to the hider's report.
fn finish(mut rendered: Rendered, shading: &FrameShading) -> Rendered {
    rendered.stats.nonfinite = shading.nonfinite.load(Relaxed);
    // Shading problems found while rendering (missing maps, unknown spaces), once each; then
    // shaders that could not finish (runaway loops), which are errors.
    // SL run-time problems carry the shader statement's file:line:col.
    let warnings = shading.warnings.located_messages().into_iter();
    let errors = shading.warnings.located_errors().into_iter();
    rendered.warnings.extend(
        (warnings.map(|m| (Severity::Warning, illume_ri::ErrorKind::MissingData, m)))
            .chain(errors.map(|m| (Severity::Error, illume_ri::ErrorKind::Limit, m)))
            .map(|(severity, kind, (at, message))| Diagnostic {
                severity,
                kind,
                span: at.map_or_else(illume_rib::Span::synthetic, |a| {
                    illume_rib::Span::new(a.file.into(), a.line, a.col, 0)
                }),
                request: None,
                message,
            }),
    );
    rendered
}
