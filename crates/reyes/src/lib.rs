//! The bucketed REYES hider (Cook, Carpenter, Catmull 1987): bound → cull → eye-split → split
//! until diceable at the ShadingRate → dice → shade the grid → bust into micropolygons →
//! stratified jittered sampling → visible-point lists composited front to back → pixel filter
//! → exposure. Buckets run in parallel (rayon); results are identical for any thread count.
#![forbid(unsafe_code)]

mod csg;
pub mod display;
pub mod filter;
mod frame_loop;
mod hider;
mod lens;
mod motion;
mod rayscene;
mod refine;
mod renderinfo;
pub mod sampling;
mod shading;
mod slshaders;
mod tile;

pub use display::{write_displays, DisplayError, WrittenDisplay};
pub use filter::PixelFilter;
pub use frame_loop::{render_frames_in_order, texture_maker};
pub use tile::{read_tile, write_tile, Tile};

use illume_ri::{Diagnostic, Frame};

/// Caller hooks for one render.
#[derive(Default)]
pub struct RenderSettings<'a> {
    /// Called after each bucket with (buckets done, bucket count).
    pub progress: Option<&'a (dyn Fn(usize, usize) + Sync)>,
    /// The texture system shaders look maps up in (`None`: every lookup is a missing map).
    pub textures: Option<&'a dyn illume_shade::TextureLookup>,
}

/// Counts and per-stage times (CPU seconds summed over threads, except `split_seconds`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    pub primitives: u64,
    pub pieces: u64,
    pub grids: u64,
    pub micropolygons: u64,
    pub samples: u64,
    pub culled_pieces: u64,
    pub occluded_grids: u64,
    pub split_seconds: f64,
    pub dice_seconds: f64,
    pub shade_seconds: f64,
    pub sample_seconds: f64,
    pub filter_seconds: f64,
    /// Shaded points whose colour came out NaN/Inf and was clamped (reported by `--stats`).
    pub nonfinite: u64,
}

/// The filtered, exposed float image of the crop window, plus per-pixel depth.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// Position of the crop window in the full frame.
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
    /// Premultiplied RGBA, top row first.
    pub rgba: Vec<f32>,
    /// Camera-space depth per pixel after `depthfilter`; `f32::MAX` where nothing was hit.
    pub z: Vec<f32>,
    pub stats: Stats,
    pub warnings: Vec<Diagnostic>,
}

/// Renders one frame (uses the current rayon pool: `ThreadPool::install` to choose threads).
pub fn render(frame: &Frame, settings: &RenderSettings) -> Rendered {
    hider::render(frame, settings)
}
