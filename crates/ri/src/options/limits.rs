//! `Option "limits"`: how much a scene may ask for before the renderer says no.
//!
//! A RIB is input like any other: `Format 100000 100000`, `PixelSamples 1000 1000`, a mesh that
//! claims 2³¹ vertices, `ShadingRate 1e-9` or an archive that reads itself would otherwise end
//! in an allocation failure, a stack overflow or a render that never finishes. Each limit below
//! is checked where the request is read, reported at its `file:line:col`, and the request is
//! clamped (the frame still renders, smaller or coarser) or skipped (the primitive, the nested
//! read), never left to the operating system. PRMan's own limits (`bucketsize`, `gridsize`,
//! `eyesplits`, `texturememory`) live on [`Options`](crate::Options) as before.
//!
//! | name | type | default | meaning |
//! |---|---|---|---|
//! | `resolution` | int | 65536 | largest `Format` width or height |
//! | `pixels` | int | 2²⁸ (16384²) | most pixels in one image (an RGBA float image of 4 GB) |
//! | `pixelsamples` | int | 64 | most `PixelSamples` per axis |
//! | `shadingrate` | float | 0.01 | smallest `ShadingRate` (100 shading points per pixel) |
//! | `vertices` | int | 2²⁶ | most vertices (or faces, curves, control points) of one primitive |
//! | `nesting` | int | 64 | deepest `ReadArchive` / `ObjectInstance` / procedural nesting (at most 256) |
//! | `memory` | MB | half the machine's RAM (4096 where unknown) | the frame's geometry estimate plus `texturememory` |
//!
//! The limits apply to the requests that follow the `Option`: set them before `Format`.

use crate::diagnostic::Diagnostics;
use illume_rib::{Request, Span};

/// The `Option "limits"` values this renderer adds (see the module table).
#[derive(Clone, Debug, PartialEq)]
pub struct Limits {
    pub resolution: u32,
    pub pixels: u64,
    pub pixel_samples: u32,
    pub min_shading_rate: f32,
    pub vertices: u64,
    pub nesting: u32,
    /// Bytes the frame's geometry (estimated by [`crate::options::request_bytes`]) and the
    /// texture cache (`texturememory`) may take together.
    pub memory: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            resolution: 65536,
            pixels: 1 << 28,
            pixel_samples: 64,
            min_shading_rate: 0.01,
            vertices: 1 << 26,
            nesting: 64,
            memory: default_memory(),
        }
    }
}

impl Limits {
    /// Sets limit `name` from an `Option "limits"` value; false when `name` is not one of ours
    /// (the caller handles PRMan's and reports the rest). A value that is not a positive
    /// number is an error and leaves the limit unchanged.
    pub(crate) fn set(
        &mut self,
        name: &str,
        value: &[f32],
        span: &Span,
        diagnostics: &mut Diagnostics,
    ) -> bool {
        let known = matches!(
            name,
            "resolution"
                | "pixels"
                | "pixelsamples"
                | "shadingrate"
                | "vertices"
                | "nesting"
                | "memory"
        );
        if !known {
            return false;
        }
        let Some(&v) = value.first().filter(|v| v.is_finite() && **v > 0.0) else {
            diagnostics.error(
                span,
                "Option",
                format!("\"limits\" \"{name}\": expected a positive number, found {value:?}"),
            );
            return true;
        };
        let count = v.min(u32::MAX as f32) as u32;
        match name {
            "resolution" => self.resolution = count.max(1),
            "pixels" => self.pixels = (v as f64).min(u64::MAX as f64) as u64,
            "pixelsamples" => self.pixel_samples = count.max(1),
            "shadingrate" => self.min_shading_rate = v,
            "vertices" => self.vertices = (v as f64).min(u64::MAX as f64) as u64,
            "memory" => self.memory = (f64::from(v) * MB as f64).min(u64::MAX as f64) as u64,
            // Each level is a few stack frames of the request loop: 256 stays far from the
            // main thread's 8 MB stack.
            _ => self.nesting = count.clamp(1, 256),
        }
        true
    }

    /// The largest image of `xres × yres`'s shape that both the `resolution` and the `pixels`
    /// limit allow (the same size when it is within them).
    pub fn fit_resolution(&self, xres: u32, yres: u32) -> (u32, u32) {
        let (x, y) = (f64::from(xres.max(1)), f64::from(yres.max(1)));
        let axis = f64::from(self.resolution) / x.max(y);
        let area = (self.pixels as f64 / (x * y)).sqrt();
        let scale = axis.min(area);
        if scale >= 1.0 {
            return (xres, yres);
        }
        let fit = |v: f64| ((v * scale).floor() as u32).max(1);
        (fit(x), fit(y))
    }
}

const MB: u64 = 1 << 20;

/// The default `memory` limit: half the physical memory (`MemTotal` of `/proc/meminfo`), or
/// 4 GB where that can not be read. Half, because the estimate counts what the RI state keeps
/// for the frame, not what the hider adds while rendering it (pieces, grids, the sample
/// buffer), and the point of the limit is that an error, not the kernel's OOM killer, ends a
/// scene that can not fit. A fixed value would be too small for a big machine's scenes or too
/// big for a small machine's RAM.
fn default_memory() -> u64 {
    let total_kb = std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| {
        let line = t.lines().find(|l| l.starts_with("MemTotal:"))?;
        line.split_whitespace().nth(1)?.parse::<u64>().ok()
    });
    total_kb.map_or(4096 * MB, |kb| kb * 1024 / 2)
}

/// How many vertices a geometry request asks for, from its counts (not its data, which may be
/// short): the largest of the vertex, face and control-point counts it declares, so a
/// `PointsPolygons` with a 2³¹ face count or a `PatchMesh` with `nu·nv` of 2³² is caught
/// before anything is allocated for it.
pub fn declared_vertices(req: &Request) -> u64 {
    let sum = |v: &[i32]| v.iter().map(|&n| n.max(0) as u64).sum::<u64>();
    let p_len = |params: &illume_rib::ParamList| {
        crate::paramlist::find(params, "P").map_or(0, |p| p.value.len() as u64 / 3)
    };
    use Request::*;
    match req {
        PointsPolygons { nverts, verts, .. } => sum(nverts).max(verts.len() as u64),
        PointsGeneralPolygons {
            nloops,
            nverts,
            verts,
            ..
        } => sum(nloops).max(sum(nverts)).max(verts.len() as u64),
        GeneralPolygon { nverts, .. } => sum(nverts),
        PatchMesh { nu, nv, .. } => (*nu).max(0) as u64 * (*nv).max(0) as u64,
        NuPatch { nu, nv, .. } => (*nu).max(0) as u64 * (*nv).max(0) as u64,
        Curves { nvertices, .. } => sum(nvertices),
        SubdivisionMesh {
            nvertices,
            vertices,
            ..
        } => sum(nvertices).max(vertices.len() as u64),
        Points { params } | Polygon { params } => p_len(params),
        _ => 0,
    }
}

/// Reports a primitive over the `vertices` limit (an error: the primitive is skipped).
pub(crate) fn check_vertices(
    limits: &Limits,
    req: &Request,
    span: &Span,
    diagnostics: &mut Diagnostics,
) -> bool {
    let n = declared_vertices(req);
    if n <= limits.vertices {
        return true;
    }
    diagnostics.error(
        span,
        req.name(),
        format!(
            "{n} vertices exceed Option \"limits\" \"vertices\" {} (primitive skipped)",
            limits.vertices
        ),
    );
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_keeps_small_images_and_shrinks_big_ones_to_both_limits() {
        let l = Limits::default();
        assert_eq!(l.fit_resolution(640, 480), (640, 480));
        // 100000² is over both limits; the pixel budget (16384²) is the tighter one.
        assert_eq!(l.fit_resolution(100_000, 100_000), (16384, 16384));
        // A long strip hits the per-axis limit first and keeps its 100:1 shape.
        let (x, y) = l.fit_resolution(1_000_000, 10_000);
        assert_eq!(x, 65536);
        assert_eq!(y, 655);
        assert!(u64::from(x) * u64::from(y) <= l.pixels);
    }

    #[test]
    fn declared_vertices_reads_counts_not_data() {
        let mesh = Request::PatchMesh {
            kind: "bilinear".into(),
            nu: 65536,
            uwrap: "nonperiodic".into(),
            nv: 65536,
            vwrap: "nonperiodic".into(),
            params: vec![],
        };
        assert_eq!(declared_vertices(&mesh), 1 << 32);
        let polys = Request::PointsPolygons {
            nverts: vec![3, i32::MAX],
            verts: vec![0, 1, 2],
            params: vec![],
        };
        assert_eq!(declared_vertices(&polys), 3 + i32::MAX as u64);
    }
}
