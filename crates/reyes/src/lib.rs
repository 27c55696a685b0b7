//! The bucketed REYES hider (Cook, Carpenter, Catmull 1987): bound → cull → eye-split → split
//! until diceable at the ShadingRate → dice → shade the grid → bust into micropolygons →
//! stratified jittered sampling → visible-point lists composited front to back → pixel filter
//! → exposure. Buckets run in parallel (rayon); results are identical for any thread count.
//!
//! Shading is asked for through [`GridShader`]; binding shaders, textures, traced rays, display
//! writing and the frame loop live in the driver (`illume-render`).
#![forbid(unsafe_code)]

mod aov;
mod bucket;
mod column_blocks;
mod csg;
mod csg_eye;
mod dice;
mod displacement_bound;
mod film;
pub mod filter;
mod flat_shading;
mod hider;
mod int_floor;
mod lazy_bands;
mod lens;
mod motion;
mod motion_setup;
mod raster_triangle;
mod refine;
mod row_sink;
mod sample_buffer;
pub mod sampling;
mod shader;
mod slice_window;
mod still_grid;
mod stratum_bound;
#[cfg(test)]
mod test_rng;
mod time_strata;
mod visible;
mod visible_lists;

pub use aov::{display_filter, AovChannel, AovLayout};
pub use column_blocks::{column_block_width, BLOCKS_ABOVE, BLOCK_WIDTH};
pub use film::PixelBlock;
pub use filter::PixelFilter;
pub use hider::Hider;
pub use row_sink::{FrameCollector, PixelRows, RowSink};
pub use shader::{GridShader, Shaded};

use illume_ri::Diagnostic;

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
    /// Shaded points whose colour came out NaN/Inf and was clamped (reported by `--stats`;
    /// counted by the shader, so the driver fills it in).
    pub nonfinite: u64,
    /// Arbitrary output variables: floats per visible point, the largest AOV store one
    /// bucket held (bytes), and the bytes of the finished AOV images.
    pub aov_stride: u64,
    pub aov_bucket_peak_bytes: u64,
    pub aov_image_bytes: u64,
    /// The most refine pieces (dice-ready or waiting for their band) and shaded grids the
    /// hider held at once: bounded by about one band of buckets, not by the frame.
    pub peak_live_pieces: u64,
    pub peak_live_grids: u64,
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
    /// The arbitrary output variables, filtered like the colour (not exposed): `aov.stride`
    /// floats per pixel, top row first, laid out as `aov.channels` say.
    pub aov_layout: AovLayout,
    pub aov: Vec<f32>,
    pub stats: Stats,
    pub warnings: Vec<Diagnostic>,
}
