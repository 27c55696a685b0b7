//! The bucket loop: pieces overlapping each bucket, nearest first; shared grids diced and
//! shaded once (by whichever bucket needs them first); micropolygons sampled into visible-point
//! lists; lists composited front to back; pixel filter; exposure.
use crate::csg::{SolidResolver, NO_SOLID};
use crate::film::{Composited, Film, PixelBlock};
use crate::lens::Lens;
use crate::motion::{sample_moving_grid, GridMotion};
use crate::refine::{Piece, PrimRef, RefineCounts, Refiner};
use crate::sample_buffer::{SampleBuffer, SampleSetup};
use crate::shader::GridShader;
use crate::{Rendered, Stats};
use glam::Vec3;
use illume_ri::{Diagnostic, Frame, Severity};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering::Relaxed};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// A diced, shaded grid in raster space.
pub(crate) struct ShadedGrid {
    pub(crate) nu: usize,
    pub(crate) nv: usize,
    /// Raster x, y and camera z per vertex.
    pub(crate) pos: Vec<Vec3>,
    ci: Vec<Vec3>,
    oi: Vec<Vec3>,
    /// Per micropolygon: culled as a back face (Sides 1).
    pub(crate) backface: Vec<bool>,
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
    /// (sampled by [`crate::motion`] instead of [`sample_triangle`]).
    motion: Option<GridMotion>,
    /// Set when displacement moved the grid farther than its `displacementbound`.
    overflow: Option<Overflow>,
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

    /// Colour and opacity at barycentric weights `w` of grid vertices `idx`, or at the
    /// micropolygon's `first` vertex when shading is flat.
    pub(crate) fn shaded_at(&self, idx: [usize; 3], w: [f64; 3], first: usize) -> (Vec3, Vec3) {
        if self.smooth {
            let [a, b, cc] = w.map(|x| x as f32);
            (
                self.ci[idx[0]] * a + self.ci[idx[1]] * b + self.ci[idx[2]] * cc,
                self.oi[idx[0]] * a + self.oi[idx[1]] * b + self.oi[idx[2]] * cc,
            )
        } else {
            (self.ci[first], self.oi[first])
        }
    }
}

/// Where a displaced grid really is, when displacement moved it farther than the piece's
/// `displacementbound` said (so the piece may have been bucketed too tightly).
#[derive(Clone, Copy, Debug)]
struct Overflow {
    /// Raster x0 x1 y0 y1 of the displaced vertices, grown by the seams' reach.
    raster: [f32; 4],
    /// Nearest camera depth of the displaced vertices.
    zmin: f32,
    /// Largest distance (camera space) a vertex moved.
    displacement: f32,
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

/// A piece's grid, shared by the buckets it overlaps: diced and shaded by the first bucket
/// that needs it, dropped when the last one is done (DESIGN.md, "Parallelism and memory").
struct GridSlot {
    grid: Mutex<Option<Option<Arc<ShadedGrid>>>>,
    /// Buckets that still have to visit this piece.
    remaining: AtomicUsize,
    /// The grid's [`Overflow`], kept after the grid is freed for the re-bucketing pass.
    overflow: OnceLock<Overflow>,
    /// Whether some bucket diced and shaded the piece (not all culled it as occluded).
    shaded: AtomicBool,
}

impl GridSlot {
    fn new(remaining: usize) -> GridSlot {
        GridSlot {
            grid: Mutex::new(None),
            remaining: AtomicUsize::new(remaining),
            overflow: OnceLock::new(),
            shaded: AtomicBool::new(false),
        }
    }

    fn get(&self, make: impl FnOnce() -> Option<Arc<ShadedGrid>>) -> Option<Arc<ShadedGrid>> {
        let mut g = self.grid.lock().unwrap_or_else(|e| e.into_inner());
        let g = g.get_or_insert_with(make).clone();
        self.shaded.store(true, Relaxed);
        if let Some(o) = g.as_ref().and_then(|g| g.overflow) {
            let _ = self.overflow.set(o);
        }
        g
    }

    /// One overlapping bucket is done; the last one frees the grid.
    fn release(&self) {
        if self.remaining.fetch_sub(1, Relaxed) == 1 {
            *self.grid.lock().unwrap_or_else(|e| e.into_inner()) = None;
        }
    }
}

#[derive(Clone, Copy)]
pub(crate) struct VisiblePoint {
    pub(crate) z: f32,
    pub(crate) order: u64,
    pub(crate) c: Vec3,
    pub(crate) o: Vec3,
    pub(crate) matte: bool,
    /// For CSG (see `csg.rs`): an entering hit. The primitive solid is found through the
    /// piece index in `order`, which keeps the point at 40 bytes, as without CSG.
    pub(crate) entering: bool,
}

const _: () = assert!(std::mem::size_of::<VisiblePoint>() <= 40);

#[derive(Default)]
struct Counters {
    grids: AtomicU64,
    micropolygons: AtomicU64,
    samples: AtomicU64,
    occluded: AtomicU64,
    dice_ns: AtomicU64,
    shade_ns: AtomicU64,
    sample_ns: AtomicU64,
    filter_ns: AtomicU64,
}

fn ns(t: Instant) -> u64 {
    t.elapsed().as_nanos() as u64
}

/// One frame's hider: built from the frame by the refine stage (bound, cull, eye-split, split:
/// [`Hider::new`]), then run over the buckets with a shader ([`Hider::render`]).
pub struct Hider<'f> {
    frame: &'f Frame,
    refiner: Refiner<'f>,
    pieces: Vec<Piece<'f>>,
    film: Film,
    /// Filter reach (pixels) around each piece's raster bound.
    margin: f32,
    culled: u64,
    split_ns: u64,
    /// Problems found so far, in the order they arose. A driver appends its own (e.g. shader
    /// binding) here before [`Hider::render`], which adds the rest and hands them all back.
    pub warnings: Vec<Diagnostic>,
}

impl<'f> Hider<'f> {
    /// The refine stage: every primitive of the frame bound, culled against the crop region
    /// (grown by the filter's reach), split across the eye plane and split until diceable.
    pub fn new(frame: &'f Frame) -> Hider<'f> {
        let opts = &frame.options;
        let cam = &frame.camera;
        let film = Film::new(opts);
        let (rx, ry) = film.filter.radius();
        let [cx0, cx1, cy0, cy1] = cam.crop;
        let margin = rx.max(ry) + 1.0;
        let region = [
            cx0 as f32 - margin,
            cx1 as f32 + margin,
            cy0 as f32 - margin,
            cy1 as f32 + margin,
        ];
        let mut warnings = Vec::new();
        let lens = Lens::new(opts.depth_of_field, cam);
        if opts.depth_of_field.is_some() && !cam.is_perspective() {
            warnings.push(Diagnostic {
                severity: Severity::Warning,
                span: illume_rib::Span::synthetic(),
                request: Some("DepthOfField".to_string()),
                message: "depth of field needs a perspective camera (ignored)".to_string(),
            });
        }
        let [open, close] = opts.shutter;
        let t0 = Instant::now();
        let refiner = Refiner {
            camera: cam,
            region,
            eye_splits: opts.eye_splits,
            grid_size: opts.grid_size.max(1) as usize,
            lens,
        };
        let per_prim: Vec<(Vec<Piece>, RefineCounts)> = frame
            .primitives
            .par_iter()
            .map(|fp| {
                let mut out = Vec::new();
                let mut counts = RefineCounts::default();
                // A moving primitive keeps its keys unless the shutter is closed at (or before)
                // its first key, where it is exactly its first key.
                let later = match &fp.motion {
                    Some(m) if close > open || m.times.first().is_some_and(|&t| open > t) => m
                        .later
                        .iter()
                        .map(|k| PrimRef::Borrowed(k.as_ref()))
                        .collect(),
                    _ => Vec::new(),
                };
                refiner.refine(
                    PrimRef::Borrowed(fp.primitive.as_ref()),
                    later,
                    &fp.attributes,
                    0,
                    0,
                    &mut out,
                    &mut counts,
                );
                (out, counts)
            })
            .collect();
        let mut pieces: Vec<Piece> = Vec::new();
        let mut culled = 0;
        for (index, ((ps, counts), fp)) in per_prim.into_iter().zip(&frame.primitives).enumerate() {
            culled += counts.culled;
            if counts.eye_dropped > 0 {
                warnings.push(Diagnostic {
                    severity: Severity::Warning,
                    span: fp.span.clone(),
                    request: None,
                    message: format!(
                        "{} piece(s) still crossed the eye plane after {} eye splits (or split too deep) and were dropped",
                        counts.eye_dropped, opts.eye_splits
                    ),
                });
            }
            pieces.extend(ps.into_iter().map(|mut p| {
                p.prim_index = index;
                p
            }));
        }
        let split_ns = ns(t0);
        Hider {
            frame,
            refiner,
            pieces,
            film,
            margin,
            culled,
            split_ns,
            warnings,
        }
    }

    /// The bucket stage (see [`render`]).
    pub fn render(
        self,
        shader: &dyn GridShader,
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    ) -> Rendered {
        render(self, shader, progress)
    }
}

/// The bucket stage: every bucket's pieces diced, shaded by `shader`, sampled, composited and
/// filtered; `progress` is called after each bucket with (buckets done, bucket count).
pub(crate) fn render(
    hider: Hider,
    shader: &dyn GridShader,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Rendered {
    let Hider {
        frame,
        refiner,
        mut pieces,
        film,
        margin,
        culled,
        split_ns,
        mut warnings,
    } = hider;
    let opts = &frame.options;
    let cam = &frame.camera;
    let [cx0, cx1, cy0, cy1] = cam.crop;
    let (width, height) = (cx1 - cx0, cy1 - cy0);
    let lens = refiner.lens;

    // Buckets over the crop region; each lists the pieces whose padded bound overlaps it.
    let [bw, bh] = opts.bucket_size.map(|b| b.max(1));
    let nbx = width.div_ceil(bw).max(1) as usize;
    let nby = height.div_ceil(bh).max(1) as usize;
    let layout = BucketLayout {
        origin: [cx0 as f32, cy0 as f32],
        size: [bw as f32, bh as f32],
        count: [nbx, nby],
        margin,
    };
    let mut lists = layout.lists(&pieces);
    let counters = Counters::default();
    let done = AtomicUsize::new(0);
    let total = AtomicUsize::new(nbx * nby);
    let setup = SampleSetup {
        spp: opts.pixel_samples,
        frame: frame.number.unwrap_or(0),
        jitter: opts.jitter,
        // Times and lens positions, only when something in the frame moves or a lens blurs.
        blur: lens.is_some() || pieces.iter().any(|p| !p.later.is_empty()),
        shutter: opts.shutter,
        near_far: [cam.near as f32, cam.far as f32],
        perspective: cam.is_perspective(),
    };

    // Render every bucket; then, if a displaced grid turned out larger than its
    // displacementbound, grow its piece to the measured bound, re-list the buckets and render
    // again exactly the buckets whose lists changed, until no new grid overflows. Each pass
    // shades a deterministic set of grids, so the image does not depend on the thread count,
    // and it equals the image a large enough bound gives (the same pieces, diced the same).
    let mut buckets: Vec<PixelBlock> = vec![Default::default(); nbx * nby];
    let mut todo: Vec<usize> = (0..nbx * nby).collect();
    let mut overflows: Vec<Option<Overflow>> = vec![None; pieces.len()];
    let mut rerendered = 0usize;
    let mut shaded = vec![false; pieces.len()];
    let mut padded_by: Vec<f32> = pieces.iter().map(|p| p.attrs.displacement_bound).collect();
    while !todo.is_empty() {
        let mut overlaps = vec![0usize; pieces.len()];
        for &b in &todo {
            for &id in &lists[b] {
                overlaps[id] += 1;
            }
        }
        let grids: Vec<GridSlot> = overlaps.into_iter().map(GridSlot::new).collect();
        let out: Vec<PixelBlock> = todo
            .par_iter()
            .map(|&b| {
                let (bx, by) = ((b % nbx) as u32, (b / nbx) as u32);
                let px0 = cx0 + bx * bw;
                let py0 = cy0 + by * bh;
                let px1 = (px0 + bw).min(cx1);
                let py1 = (py0 + bh).min(cy1);
                let out = render_bucket(
                    frame,
                    shader,
                    &pieces,
                    &grids,
                    &lists[b],
                    [px0, px1, py0, py1],
                    &film,
                    &setup,
                    lens.as_ref(),
                    &counters,
                );
                let n = done.fetch_add(1, Relaxed) + 1;
                if let Some(p) = progress {
                    p(n, total.load(Relaxed));
                }
                out
            })
            .collect();
        for (&b, o) in todo.iter().zip(out) {
            buckets[b] = o;
        }
        let mut grown = false;
        // Pieces now nearer than their old bound said: a bucket may have culled them as
        // occluded, so every bucket listing one renders again.
        let mut nearer = vec![false; pieces.len()];
        for (id, slot) in grids.iter().enumerate() {
            if let (None, Some(o)) = (overflows[id], slot.overflow.get()) {
                nearer[id] = o.zmin < pieces[id].zmin;
                let p = &mut pieces[id];
                p.raster = [
                    p.raster[0].min(o.raster[0]),
                    p.raster[1].max(o.raster[1]),
                    p.raster[2].min(o.raster[2]),
                    p.raster[3].max(o.raster[3]),
                ];
                p.zmin = p.zmin.min(o.zmin);
                overflows[id] = Some(*o);
                grown = true;
            }
        }
        // A piece no bucket shaded (all culled it as occluded, by its undisplaced depth) is
        // not measured: pad it by the most its primitive's measured grids moved, so the
        // next pass shades it where it may now show (and measures it, if it moves farther).
        for (id, slot) in grids.iter().enumerate() {
            shaded[id] |= slot.shaded.load(Relaxed);
        }
        let mut moved = vec![0.0f32; frame.primitives.len()];
        for (p, o) in pieces.iter().zip(&overflows) {
            if let Some(o) = o {
                moved[p.prim_index] = moved[p.prim_index].max(o.displacement);
            }
        }
        for (id, p) in pieces.iter_mut().enumerate() {
            let m = moved[p.prim_index];
            if shaded[id] || m <= padded_by[id] {
                continue;
            }
            let b = p.prim.get().bound().padded(m);
            let r = refiner.raster_bound(&b);
            p.raster = [
                p.raster[0].min(r[0]),
                p.raster[1].max(r[1]),
                p.raster[2].min(r[2]),
                p.raster[3].max(r[3]),
            ];
            nearer[id] |= b.min.z < p.zmin;
            p.zmin = p.zmin.min(b.min.z);
            padded_by[id] = m;
            grown = true;
        }
        if !grown {
            break;
        }
        let relisted = layout.lists(&pieces);
        todo = (0..nbx * nby)
            .filter(|&b| relisted[b] != lists[b] || relisted[b].iter().any(|&id| nearer[id]))
            .collect();
        lists = relisted;
        rerendered += todo.len();
        total.fetch_add(todo.len(), Relaxed);
    }
    warnings.extend(overflow_warnings(frame, &pieces, &overflows, rerendered));

    let (rgba, z) = film.print(cam.crop, buckets);
    let stats = Stats {
        primitives: frame.primitives.len() as u64,
        pieces: pieces.len() as u64,
        grids: counters.grids.load(Relaxed),
        micropolygons: counters.micropolygons.load(Relaxed),
        samples: counters.samples.load(Relaxed),
        culled_pieces: culled,
        occluded_grids: counters.occluded.load(Relaxed),
        split_seconds: split_ns as f64 * 1e-9,
        dice_seconds: counters.dice_ns.load(Relaxed) as f64 * 1e-9,
        shade_seconds: counters.shade_ns.load(Relaxed) as f64 * 1e-9,
        sample_seconds: counters.sample_ns.load(Relaxed) as f64 * 1e-9,
        filter_seconds: counters.filter_ns.load(Relaxed) as f64 * 1e-9,
        // The hider does not see shaded values: the driver counts them.
        nonfinite: 0,
    };
    Rendered {
        x0: cx0,
        y0: cy0,
        width,
        height,
        rgba,
        z,
        stats,
        warnings,
    }
}

/// The bucket grid over the crop region.
struct BucketLayout {
    origin: [f32; 2],
    size: [f32; 2],
    count: [usize; 2],
    /// Filter reach (pixels) added around each piece's raster bound.
    margin: f32,
}

impl BucketLayout {
    /// Per bucket, the pieces whose padded raster bound overlaps it, nearest first.
    fn lists(&self, pieces: &[Piece]) -> Vec<Vec<usize>> {
        let [nbx, nby] = self.count;
        let [ox, oy] = self.origin;
        let [bw, bh] = self.size;
        let m = self.margin;
        let mut lists: Vec<Vec<usize>> = vec![Vec::new(); nbx * nby];
        for (id, p) in pieces.iter().enumerate() {
            let bx0 = ((p.raster[0] - m - ox) / bw).floor().max(0.0) as usize;
            let bx1 = ((p.raster[1] + m - ox) / bw).floor();
            let by0 = ((p.raster[2] - m - oy) / bh).floor().max(0.0) as usize;
            let by1 = ((p.raster[3] + m - oy) / bh).floor();
            if bx1 < 0.0 || by1 < 0.0 {
                continue;
            }
            for by in by0..=(by1 as usize).min(nby - 1) {
                for bx in bx0..=(bx1 as usize).min(nbx - 1) {
                    lists[by * nbx + bx].push(id);
                }
            }
        }
        for l in &mut lists {
            l.sort_by(|&a, &b| pieces[a].zmin.total_cmp(&pieces[b].zmin).then(a.cmp(&b)));
        }
        lists
    }
}

/// One warning per primitive whose displaced grids left their `displacementbound`, at the
/// primitive's request, with the bound given and the largest displacement measured.
fn overflow_warnings(
    frame: &Frame,
    pieces: &[Piece],
    overflows: &[Option<Overflow>],
    rerendered: usize,
) -> Vec<Diagnostic> {
    let mut worst: Vec<Option<f32>> = vec![None; frame.primitives.len()];
    for (p, o) in pieces.iter().zip(overflows) {
        if let (Some(o), Some(w)) = (o, worst.get_mut(p.prim_index)) {
            *w = Some(w.map_or(o.displacement, |w| w.max(o.displacement)));
        }
    }
    worst
        .iter()
        .zip(&frame.primitives)
        .filter_map(|(w, fp)| {
            let w = (*w)?;
            Some(Diagnostic {
                severity: Severity::Warning,
                span: fp.span.clone(),
                request: None,
                message: format!(
                    "displacement moved the surface {w:.4} (camera space) but its \"displacementbound\" \"sphere\" is {:.4} there; rendered correctly by re-rendering {rerendered} bucket(s) with the measured bound (raise the bound to avoid the cost)",
                    fp.attributes.displacement_bound
                ),
            })
        })
        .collect()
}

fn dice_and_shade(
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
    // Camera space is left-handed, so dPdu×dPdv is the left-handed normal: flip for "rh".
    let flip = if a.orientation_rh { -1.0 } else { 1.0 };
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
    counters.grids.fetch_add(1, Relaxed);
    counters
        .micropolygons
        .fetch_add(((nu - 1) * (nv - 1)) as u64, Relaxed);
    Some(Arc::new(ShadedGrid {
        nu,
        nv,
        pos,
        ci: shaded.ci,
        oi: shaded.oi,
        backface,
        solid,
        ccw_enters: flip > 0.0,
        seam,
        matte: a.matte,
        smooth: a.smooth_shading,
        overflow,
        motion,
    }))
}

/// The grid's [`Overflow`] if some vertex moved (diced `before` → displaced `after`, camera
/// space) farther than `bound`: then the displaced grid may lie outside the piece's padded
/// bound. The tolerance absorbs f32 rounding of `P + a·N` for a displacement exactly at the
/// bound.
fn measure_overflow(
    before: &[Vec3],
    after: &[Vec3],
    pos: &[Vec3],
    seam: &[Vec<f64>; 4],
    bound: f32,
) -> Option<Overflow> {
    let mut moved = 0.0f32;
    let mut scale = 0.0f32;
    for (b, a) in before.iter().zip(after) {
        let d = (*a - *b).length();
        if d.is_finite() {
            moved = moved.max(d);
        }
        scale = scale.max(b.abs().max_element());
    }
    if moved <= bound * (1.0 + 1e-4) + 1e-6 * scale {
        return None;
    }
    let reach = seam.iter().flatten().copied().fold(0.0f64, f64::max) as f32;
    let mut raster = [
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    let mut zmin = f32::INFINITY;
    for q in pos.iter().filter(|q| q.is_finite()) {
        raster = [
            raster[0].min(q.x - reach),
            raster[1].max(q.x + reach),
            raster[2].min(q.y - reach),
            raster[3].max(q.y + reach),
        ];
        zmin = zmin.min(q.z);
    }
    Some(Overflow {
        raster,
        zmin,
        displacement: moved,
    })
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
            Some(GridMotion { times, keys })
        }
        _ if lens => Some(GridMotion {
            times: vec![0.0],
            keys: vec![displaced.to_vec()],
        }),
        _ => None,
    }
}

#[allow(clippy::too_many_arguments)]
fn render_bucket(
    frame: &Frame,
    shader: &dyn GridShader,
    pieces: &[Piece],
    grids: &[GridSlot],
    list: &[usize],
    rect: [u32; 4],
    film: &Film,
    setup: &SampleSetup,
    lens: Option<&Lens>,
    counters: &Counters,
) -> PixelBlock {
    let mut buf = SampleBuffer::new(rect, film.filter.radius(), setup);
    let t_sample = Instant::now();
    let mut shade_elapsed = 0u64;
    for &id in list {
        let piece = &pieces[id];
        if piece.zmin > buf.max_opaque_z() {
            counters.occluded.fetch_add(1, Relaxed);
            continue;
        }
        let t = Instant::now();
        let grid = grids[id].get(|| dice_and_shade(frame, shader, piece, counters));
        shade_elapsed += ns(t);
        let Some(g) = grid.as_deref() else { continue };
        let hits = match &g.motion {
            Some(m) if setup.blur => sample_moving_grid(g, m, id, &frame.camera, lens, &mut buf),
            _ => buf.sample_still_grid(g, id),
        };
        counters.samples.fetch_add(hits, Relaxed);
    }
    counters
        .sample_ns
        .fetch_add(ns(t_sample).saturating_sub(shade_elapsed), Relaxed);
    for &id in list {
        grids[id].release();
    }
    // Composite each sample front to back, then filter into pixels.
    let t = Instant::now();
    let solids = SolidResolver::new(&frame.solids);
    let composited: Vec<Composited> = buf
        .lists
        .iter_mut()
        .zip(&buf.opaque_z)
        .map(|(l, oz)| {
            l.sort_by(|a, b| a.z.total_cmp(&b.z).then(a.order.cmp(&b.order)));
            if let Some(s) = &solids {
                // Only opaque surfaces outside solids set `opaque_z` and cut lists short.
                s.resolve(l, oz.is_infinite(), |vp| {
                    let prim = pieces[(vp.order >> 32) as usize].prim_index;
                    let solid = frame.primitives.get(prim).and_then(|fp| fp.solid);
                    (solid.unwrap_or(NO_SOLID), vp.entering)
                });
            }
            let mut c = Vec3::ZERO;
            let mut t = Vec3::ONE;
            let mut alpha = 0.0f32;
            let mut ta = 1.0f32;
            for vp in l.iter() {
                let om = (vp.o.x + vp.o.y + vp.o.z) / 3.0;
                if !vp.matte {
                    c += t * vp.c;
                    alpha += ta * om;
                }
                t *= Vec3::ONE - vp.o;
                ta *= 1.0 - om;
                if t.max_element() <= 0.0 {
                    break;
                }
            }
            let z1 = l.first().map_or(f32::MAX, |v| v.z);
            let z2 = l.get(1).map_or(z1, |v| v.z);
            Composited {
                rgba: [c.x, c.y, c.z, alpha],
                z: z1,
                z_mid: 0.5 * (z1 + z2),
            }
        })
        .collect();
    let block = film.develop(rect, &buf.region(), &composited);
    counters.filter_ns.fetch_add(ns(t), Relaxed);
    block
}
