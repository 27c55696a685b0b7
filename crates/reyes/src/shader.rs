//! The one question the hider asks of the shading system: "shade this diced grid". The hider
//! knows grids, attributes and samples; what a shader is (built-in, compiled `.sl`, lights,
//! textures, traced rays) is the driver's business (`illume-render`), so this crate does not
//! depend on the shading, texture or ray-tracing crates.
use crate::film::PixelBlock;
use glam::Vec3;
use illume_geom::Grid;
use illume_ri::Attributes;

/// A shaded grid's per-vertex results, index-aligned with the diced [`Grid`].
#[derive(Clone, Debug, Default)]
pub struct Shaded {
    /// Camera-space positions after displacement (the diced positions when there is none).
    pub p: Vec<Vec3>,
    /// Output colour `Ci` (premultiplied by `Oi`, as the shader left it).
    pub ci: Vec<Vec3>,
    /// Output opacity `Oi`.
    pub oi: Vec<Vec3>,
    /// The arbitrary output variables the hider was asked for ([`crate::AovLayout`]), one
    /// record of `stride` floats per vertex; empty when no display names an AOV.
    pub aov: Vec<f32>,
}

/// Shades diced grids for the hider. Called from many buckets at once, each grid once.
pub trait GridShader: Sync {
    /// Displaces and shades one grid of frame primitive `prim` (an index into
    /// `Frame::primitives`). `flip` (±1) orients the geometric normals as the attributes'
    /// `Orientation` says (camera space is left-handed, so `dPdu×dPdv` is flipped for "rh").
    fn shade_grid(&self, grid: &Grid, attrs: &Attributes, flip: f32, prim: usize) -> Shaded;

    /// Runs the frame's imager (RI Spec 3.2 `RiImager`) on one bucket's developed pixels:
    /// after the pixel filter, before exposure and quantization. Pixels are premultiplied RGBA
    /// at full-frame positions (`block.rect`), so the result does not depend on which thread
    /// or in what order buckets finish. The default runs no imager.
    fn image(&self, block: &mut PixelBlock) {
        let _ = block;
    }
}
