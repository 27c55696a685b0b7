//! Dice and shade: a piece diced into a grid at its dice rates, shaded through the
//! [`GridShader`], projected to raster space, back faces marked, border seams measured, and
//! (for displaced grids) checked against the `displacementbound`.
use crate::csg::NO_SOLID;
use crate::displacement_bound::{measure_overflow, Overflow};
use crate::flat_shading::{micropolygon_colours, micropolygon_means, micropolygon_of};
use crate::hider::{ns, Counters};
use crate::lens::Lens;
use crate::motion::GridMotion;
use crate::refine::Piece;
use crate::shader::GridShader;
use crate::still_grid::GridBands;
use glam::Vec3;
use illume_ri::Frame;
use std::ops::Range;
use std::sync::atomic::Ordering::Relaxed;
use std::sync::Arc;
use std::time::Instant;

/// A diced, shaded grid in raster space.
pub(crate) struct ShadedGrid {
    pub(crate) nu: usize,
    pub(crate) nv: usize,
    /// The rows of micropolygons still held: all of them when shaded, fewer once the buckets
    /// above have sampled the grid ([`ShadedGrid::trim_above`]). `pos`, `ci`, `oi` and
    /// `backface` hold only these rows (and their vertices); indices stay the whole grid's.
    held: Range<usize>,
    /// Raster x, y and camera z per vertex (of the held rows).
    pos: Vec<Vec3>,
    /// Colour and opacity per vertex (smooth shading) or per micropolygon (flat), of the held
    /// rows; one value when every vertex (micropolygon) has the same bits (an opaque surface's
    /// opacity): one fewer array per grid held between bands.
    ci: Vec<Vec3>,
    oi: Vec<Vec3>,
    /// Per-vertex AOV records ([`crate::AovLayout::stride`] floats each; empty without AOVs).
    pub(crate) aov: Vec<f32>,
    /// Per micropolygon (of the held rows): culled as a back face (Sides 1).
    backface: Vec<bool>,
    /// The primitive solid this grid bounds ([`NO_SOLID`] for none).
    pub(crate) solid: u32,
    /// Whether a micropolygon triangle wound counter-clockwise in raster space faces the eye
    /// (faces along the outward normal: an entering hit), given the grid's orientation.
    pub(crate) ccw_enters: bool,
    /// Outward reach (raster pixels) of each border segment, for the rows `j = 0`,
    /// `j = nv−1` and the columns `i = 0`, `i = nu−1`: see [`seam_reach`].
    pub(crate) seam: [Vec<f64>; 4],
    pub(crate) matte: bool,
    smooth: bool,
    /// Camera-space positions per motion key when the grid moves or depth of field is on
    /// (sampled by [`crate::motion`] instead of as a still grid).
    pub(crate) motion: Option<GridMotion>,
    /// Set when displacement moved the grid farther than its `displacementbound`.
    pub(crate) overflow: Option<Overflow>,
    /// Raster bounds of its rows and columns of micropolygons, for the still hider.
    pub(crate) bands: GridBands,
}

impl ShadedGrid {
    /// How far (raster pixels) the edges of micropolygon `(i, j)` reach outward, as
    /// `[bottom, right, top, left]`: a grid border's seam reach, 0 inside the grid.
    pub(crate) fn border_reach(&self, i: usize, j: usize) -> [f64; 4] {
        let bottom = if j == 0 { self.seam[0][i] } else { 0.0 };
        let top = if j + 2 == self.nv {
            self.seam[1][i]
        } else {
            0.0
        };
        let left = if i == 0 { self.seam[2][j] } else { 0.0 };
        let right = if i + 2 == self.nu {
            self.seam[3][j]
        } else {
            0.0
        };
        [bottom, right, top, left]
    }

    /// Raster x, y and camera z of grid vertex `k` (of a held row).
    #[inline]
    pub(crate) fn vertex(&self, k: usize) -> Vec3 {
        self.pos[k - self.held.start * self.nu]
    }

    /// Whether micropolygon `m` (of a held row) is culled as a back face.
    #[inline]
    pub(crate) fn backface(&self, m: usize) -> bool {
        self.backface[m - self.held.start * (self.nu - 1)]
    }

    /// Whether the held rows' vertices are all there (a shader may hand back fewer points
    /// than the grid has: such a grid is not sampled).
    pub(crate) fn complete(&self) -> bool {
        self.held.is_empty() || self.pos.len() >= (self.held.len() + 1) * self.nu
    }

    /// The colour and opacity of the triangle with grid vertices `idx` in the micropolygon
    /// whose first vertex is `first`, for [`TriangleShade::at`] to weigh at each hit.
    #[inline]
    pub(crate) fn triangle_shade(&self, idx: [usize; 3], first: usize) -> TriangleShade {
        if self.smooth {
            let base = self.held.start * self.nu;
            TriangleShade::Smooth(
                idx.map(|k| held_value(&self.ci, k, base)),
                idx.map(|k| held_value(&self.oi, k, base)),
            )
        } else {
            let m = micropolygon_of(first, self.nu);
            let base = self.held.start * (self.nu - 1);
            TriangleShade::Flat(held_value(&self.ci, m, base), held_value(&self.oi, m, base))
        }
    }

    /// Drops the rows of micropolygons no bucket still to come samples: those whose raster
    /// bound, grown by the grid's reach, ends above `y` (every later bucket's samples lie at
    /// or below `y`, so the sampler's own bound test would skip them there). Why: a grid that
    /// reaches the next bucket row is held until that row is done, and a frame twice as wide
    /// holds twice as many; most of such a grid lies in the row already rendered. Moving grids
    /// and grids with output variables are kept whole. The image is the same bits.
    pub(crate) fn trim_above(&mut self, y: f32) {
        if self.motion.is_some() || !self.aov.is_empty() || !self.complete() {
            return;
        }
        let keep = self.bands.rows_reaching(y, self.held.clone());
        if keep == self.held {
            return;
        }
        let nu = self.nu;
        let (old, new) = (self.held.start, keep.start);
        let verts = |v: &[Vec3]| match keep.is_empty() {
            true => Vec::new(),
            false => v[(new - old) * nu..(keep.end + 1 - old) * nu].to_vec(),
        };
        let mps = |v: &[Vec3]| v[(new - old) * (nu - 1)..(keep.end - old) * (nu - 1)].to_vec();
        let values = |v: &Vec<Vec3>| match (v.len(), self.smooth) {
            (1, _) => v.clone(),
            (_, true) => verts(v),
            (_, false) => mps(v),
        };
        self.ci = values(&self.ci);
        self.oi = values(&self.oi);
        self.pos = verts(&self.pos);
        self.backface = self.backface[(new - old) * (nu - 1)..(keep.end - old) * (nu - 1)].to_vec();
        self.bands.drop_rows_outside(keep.clone());
        self.held = keep;
    }

    /// Appends the AOV record at the hit to `store` (as [`TriangleShade::at`] weighs
    /// colour); `false` (nothing appended) when the grid has no records of that size.
    pub(crate) fn push_aov(
        &self,
        store: &mut Vec<f32>,
        stride: usize,
        idx: [usize; 3],
        w: [f64; 3],
        first: usize,
    ) -> bool {
        let records = if self.smooth {
            self.nu * self.nv
        } else {
            (self.nu - 1) * (self.nv - 1)
        };
        if stride == 0 || self.held != (0..self.nv - 1) || self.aov.len() != records * stride {
            return false;
        }
        let smooth = self.smooth.then(|| (idx, w.map(|x| x as f32)));
        let record = micropolygon_of(first, self.nu);
        crate::aov::push_record(store, &self.aov, stride, smooth, record);
        true
    }
}

/// One triangle's shading, fetched from its grid once per triangle rather than once per
/// sample hit: the lookups (a division for a flat micropolygon's index, a uniform-array test
/// per value) were 44 of a hit's ~160 instructions in `rib/sphere.rib` (1.5 M hits).
pub(crate) enum TriangleShade {
    /// Colour and opacity at the three vertices (smooth shading).
    Smooth([Vec3; 3], [Vec3; 3]),
    /// The micropolygon's constant colour and opacity (flat shading).
    Flat(Vec3, Vec3),
}

impl TriangleShade {
    /// Colour and opacity at barycentric weights `w` of the triangle's vertices.
    #[inline]
    pub(crate) fn at(&self, w: [f64; 3]) -> (Vec3, Vec3) {
        match self {
            TriangleShade::Smooth(c, o) => {
                let [a, b, cc] = w.map(|x| x as f32);
                (
                    c[0] * a + c[1] * b + c[2] * cc,
                    o[0] * a + o[1] * b + o[2] * cc,
                )
            }
            TriangleShade::Flat(c, o) => (*c, *o),
        }
    }
}

/// Value `k` (a whole-grid index) of held per-vertex or per-micropolygon values starting at
/// index `base`, or the one value of a uniform array.
#[inline]
fn held_value(v: &[Vec3], k: usize, base: usize) -> Vec3 {
    if v.len() == 1 {
        v[0]
    } else {
        v[k - base]
    }
}

/// `v` as one value when all its values have the same bits (see `ShadedGrid::oi`).
fn uniform_or_all(v: Vec<Vec3>) -> Vec<Vec3> {
    let bits = |c: &Vec3| c.to_array().map(f32::to_bits);
    match v.first() {
        Some(first) if v.len() > 1 && v.iter().all(|c| bits(c) == bits(first)) => vec![*first],
        _ => v,
    }
}

/// Floor of a border segment's outward reach: covers slivers thinner than the curvature
/// estimate resolves (a border diced with one segment has no estimate at all).
const SEAM_EPSILON: f64 = 1e-3;

/// How far (raster pixels) each segment of a grid-border polyline is pushed outward when
/// sampling, so seams between neighbouring grids overlap instead of cracking.
///
/// Why: neighbouring pieces are diced at their own rates, so a shared border is a T-junction:
/// the coarse grid's segment is a straight chord between two vertices on the curved border,
/// while the fine grid follows the curve. Where the curve bulges away from the coarse grid the
/// sliver between chord and curve belongs to neither grid (its width is the chord's sagitta
/// L²/8R, largest where the border curves tightly in raster space, e.g. the latitude circles
/// near a sphere's pole facing the camera). The coarse grid's own border tells the curvature:
/// vertex `k` lies `d_k` off the chord of its two neighbours, which for a uniformly curved
/// border is 4× the sagitta of one segment (counted only where the border bulges outward,
/// the side the sliver is on); reaching `d/2` (twice the sagitta) covers the
/// sliver, capped at a quarter of the segment's length. Only grid borders reach out, so
/// semi-transparent surfaces get no double coverage inside a grid, and a flat border (a
/// polygon's edge, a straight split line) reaches out only [`SEAM_EPSILON`].
fn seam_reach(pts: &[Vec3], inner: &[Vec3]) -> Vec<f64> {
    let n = pts.len();
    let p: Vec<glam::DVec3> = pts.iter().map(|q| q.as_dvec3()).collect();
    let dev: Vec<f64> = (0..n)
        .map(|k| {
            if k == 0 || k + 1 == n {
                return 0.0;
            }
            let (a, b, c) = (p[k - 1], p[k], p[k + 1]);
            let (dx, dy) = (c.x - a.x, c.y - a.y);
            let l = (dx * dx + dy * dy).sqrt();
            let side = |q: glam::DVec3| dx * (q.y - a.y) - dy * (q.x - a.x);
            // Only a border bulging away from the grid's interior (the parallel row or column
            // next to it) leaves a sliver on this side; a concave border overlaps its neighbour.
            let s = side(b);
            if s * side(inner[k].as_dvec3()) > 0.0 {
                return 0.0;
            }
            let d = (s / l).abs();
            if l > 0.0 && d.is_finite() {
                d
            } else {
                0.0
            }
        })
        .collect();
    (0..n.saturating_sub(1))
        .map(|k| {
            let inner = |i: usize| if n >= 3 { dev[i.clamp(1, n - 2)] } else { 0.0 };
            let len = (p[k + 1].truncate() - p[k].truncate()).length();
            let r = (0.5 * inner(k).max(inner(k + 1))).min(0.25 * len);
            if r.is_finite() {
                r.max(0.0) + SEAM_EPSILON
            } else {
                SEAM_EPSILON
            }
        })
        .collect()
}

pub(crate) fn dice_and_shade(
    frame: &Frame,
    shader: &dyn GridShader,
    piece: &Piece,
    counters: &Counters,
) -> Option<Arc<ShadedGrid>> {
    let t = Instant::now();
    let grid = piece.prim.get().dice(piece.nu, piece.nv);
    counters.dice_ns.fetch_add(ns(t), Relaxed);
    if grid.nu < 2 || grid.nv < 2 || grid.p.len() != grid.nu * grid.nv {
        return None;
    }
    let t = Instant::now();
    let a = &piece.attrs;
    // The orientation resolved against the primitive's handedness (see `normal_sign`).
    let flip = frame
        .primitives
        .get(piece.prim_index)
        .map_or(1.0, |fp| fp.normal_sign());
    let shaded = shader.shade_grid(&grid, a, flip, piece.prim_index);
    counters.shade_ns.fetch_add(ns(t), Relaxed);
    let cam = &frame.camera;
    // Displacement may have moved the points; sample where the shader left them.
    let pos: Vec<Vec3> = shaded
        .p
        .iter()
        .map(|p| match cam.raster_from_camera(p.as_dvec3()) {
            Some(q) => q.as_vec3(),
            None => Vec3::new(0.0, 0.0, f32::NAN),
        })
        .collect();
    let (nu, nv) = (grid.nu, grid.nv);
    let motion = grid_motion(frame, piece, &grid, &shaded.p);
    // Trimmed-away micropolygons are skipped exactly like back faces.
    let mut backface = if grid.hidden.len() == (nu - 1) * (nv - 1) {
        grid.hidden.clone()
    } else {
        vec![false; (nu - 1) * (nv - 1)]
    };
    // A solid's back faces are never culled: they are where a ray leaves it, which CSG needs
    // to know, and a difference shows the subtracted solid's far wall. The surface shaders
    // shade them with `faceforward(N, I)`, so that wall is lit as seen from inside.
    let solid = frame
        .primitives
        .get(piece.prim_index)
        .and_then(|fp| fp.solid)
        .unwrap_or(NO_SOLID);
    // Whether a solid's hit enters it is judged per triangle from its raster winding (see
    // `ccw_enters`), not from the vertex normals: those vanish at a sphere's poles, and the
    // winding is exactly what the sampler sees.
    if solid == NO_SOLID && a.sides == 1 {
        for j in 0..nv - 1 {
            for i in 0..nu - 1 {
                let k = j * nu + i;
                let view = if cam.is_perspective() {
                    grid.p[k]
                } else {
                    Vec3::Z
                };
                backface[j * (nu - 1) + i] |= (grid.ng[k] * flip).dot(view) > 0.0;
            }
        }
    }
    let row = |j: usize| pos[j * nu..(j + 1) * nu].to_vec();
    let col = |i: usize| (0..nv).map(|j| pos[j * nu + i]).collect::<Vec<_>>();
    let seam = [
        seam_reach(&row(0), &row(1)),
        seam_reach(&row(nv - 1), &row(nv - 2)),
        seam_reach(&col(0), &col(1)),
        seam_reach(&col(nu - 1), &col(nu - 2)),
    ];
    let overflow = a
        .displacement
        .is_some()
        .then(|| measure_overflow(&grid.p, &shaded.p, &pos, &seam, a.displacement_bound))
        .flatten();
    let smooth = a.smooth_shading;
    let (ci, oi, aov) = if smooth {
        (shaded.ci, shaded.oi, shaded.aov)
    } else {
        let stride = shaded.aov.len().checked_div(nu * nv).unwrap_or(0);
        (
            micropolygon_colours(&shaded.ci, nu, nv),
            micropolygon_colours(&shaded.oi, nu, nv),
            micropolygon_means(&shaded.aov, nu, nv, stride),
        )
    };
    counters.grids.fetch_add(1, Relaxed);
    counters
        .micropolygons
        .fetch_add(((nu - 1) * (nv - 1)) as u64, Relaxed);
    let bands = GridBands::new(&pos, nu, nv, &seam);
    Some(Arc::new(ShadedGrid {
        nu,
        nv,
        held: 0..nv - 1,
        ci: uniform_or_all(ci),
        oi: uniform_or_all(oi),
        bands,
        pos,
        aov,
        backface,
        solid,
        ccw_enters: flip > 0.0,
        seam,
        matte: a.matte,
        smooth,
        overflow,
        motion,
    }))
}

/// The camera-space positions of every motion key of a piece, diced at the first key's
/// `nu × nv` and displaced by the first key's displacement (shading runs once, at the first
/// key); one key when only depth of field is on; `None` for a still grid without a lens.
fn grid_motion(
    frame: &Frame,
    piece: &Piece,
    grid: &illume_geom::Grid,
    displaced: &[Vec3],
) -> Option<GridMotion> {
    let lens = Lens::new(frame.options.depth_of_field, &frame.camera).is_some();
    let times = frame.primitives[piece.prim_index]
        .motion
        .as_ref()
        .map(|m| m.times.iter().map(|&t| f64::from(t)).collect::<Vec<_>>());
    match times {
        Some(times) if !piece.later.is_empty() && times.len() == piece.later.len() + 1 => {
            let mut keys = vec![displaced.to_vec()];
            for k in &piece.later {
                let g = k.get().dice(grid.nu, grid.nv);
                if g.p.len() != grid.p.len() {
                    return None;
                }
                keys.push(
                    g.p.iter()
                        .zip(displaced.iter().zip(&grid.p))
                        .map(|(p, (d, p0))| *p + (*d - *p0))
                        .collect(),
                );
            }
            Some(GridMotion::new(times, keys))
        }
        _ if lens => Some(GridMotion::new(vec![0.0], vec![displaced.to_vec()])),
        _ => None,
    }
}
