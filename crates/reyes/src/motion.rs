//! Motion blur and depth of field in the hider: a grid whose vertices move over the shutter
//! (motion keys diced at one `nu × nv`, linearly interpolated) or shift with the lens position.
//!
//! Shading happened once, at the first key (PRMan's default: shading at shutter open); only
//! positions move. The shutter is cut into time strata, about one per pixel of a
//! micropolygon's motion and at most one per pixel sample (`time_strata.rs`; far fewer for
//! one that moves rigidly, `motion_setup.rs`); the
//! micropolygon is bounded over each stratum's times (a vertex moving linearly in camera
//! space moves along a straight line in raster space, so its positions at the stratum's ends
//! and at the keys between hold its path) and grown by the circle of confusion over its depth
//! range. Only that stratum's samples in the pixels of that box are tested, each against the
//! micropolygon moved to the sample's own time and lens position, with the same edge rules as
//! a still micropolygon. So a fast micropolygon costs about one test per pixel it sweeps plus
//! what it would cost still, instead of every sample of its whole path.
//!
//! A micropolygon the lens blurs by half a pixel or more is bounded per lens cell instead
//! (`sample_lens_cells`): every pixel has one sample per cell of the lens grid
//! (`sampling::lens_strata`), so per cell only the pixels its path reaches through that cell
//! (a `1/√n` share of the circle of confusion per axis) are visited; whichever of the two
//! visits fewer pixels is used (`lens_cells_pay`).
use crate::dice::ShadedGrid;
use crate::int_floor::floor_f64_to_i32;
use crate::lens::Lens;
use crate::motion_setup::{grid_setup, GridSetup, MicropolygonSetup};
use crate::sample_buffer::{split_quad, Hit, RasterTriangle, SampleBuffer};
use crate::slice_window::SliceWindow;
use crate::stratum_bound::{LazyHull, StratumBound};
use crate::time_strata::stratum_samples;
use glam::{DVec3, Vec3};
use illume_ri::motion::segment;
use illume_ri::Camera;
use std::sync::OnceLock;

/// The camera-space positions of a grid at each motion key (one key: depth of field only).
pub(crate) struct GridMotion {
    pub times: Vec<f64>,
    pub keys: Vec<Vec<Vec3>>,
    /// Its micropolygons' bucket-independent bounds, set up by the first bucket that samples
    /// it and shared by the others (a blurred grid spans many buckets).
    setup: OnceLock<GridSetup>,
}

impl GridMotion {
    pub fn new(times: Vec<f64>, keys: Vec<Vec<Vec3>>) -> GridMotion {
        GridMotion {
            times,
            keys,
            setup: OnceLock::new(),
        }
    }

    pub(crate) fn at(&self, v: usize, (k, w): (usize, f64)) -> DVec3 {
        let a = self.keys[k][v].as_dvec3();
        if w == 0.0 || self.keys.len() == 1 {
            return a;
        }
        let b = self.keys[k + 1][v].as_dvec3();
        a + (b - a) * w
    }
}

/// Samples every micropolygon of a moving or lens-blurred grid; returns the samples hit.
pub(crate) fn sample_moving_grid(
    g: &ShadedGrid,
    m: &GridMotion,
    id: usize,
    cam: &Camera,
    lens: Option<&Lens>,
    out: &mut SampleBuffer,
) -> u64 {
    let persp = cam.is_perspective();
    let project = |p: DVec3| -> Option<DVec3> {
        if persp && p.z <= 0.0 {
            return None;
        }
        cam.raster_from_camera(p)
    };
    let setup = m
        .setup
        .get_or_init(|| grid_setup(g, m, &project, persp, lens.is_some(), out));
    let mut hits = 0;
    let (mut bounds, mut slices) = (Vec::new(), Vec::new());
    for j in 0..g.nv - 1 {
        for i in 0..g.nu - 1 {
            let k = j * (g.nu - 1) + i;
            let Some(s) = &setup.mps[k] else { continue };
            let mp = [i, j];
            hits += sample_moving_micropolygon(
                g,
                m,
                id,
                mp,
                setup,
                s,
                &project,
                persp,
                lens,
                out,
                &mut bounds,
                &mut slices,
            );
        }
    }
    hits
}

/// Samples micropolygon `(i, j)` of a moving grid, set up as `s`: over each time stratum of
/// the shutter (`time_strata.rs`) whose path reaches the buffer, the samples of that stratum
/// inside the micropolygon's box over the stratum's times (grown by its circle of
/// confusion); returns the samples hit. `bounds` and `slices` are scratch.
#[allow(clippy::too_many_arguments)]
fn sample_moving_micropolygon(
    g: &ShadedGrid,
    m: &GridMotion,
    id: usize,
    [i, j]: [usize; 2],
    setup: &GridSetup,
    s: &MicropolygonSetup,
    project: &impl Fn(DVec3) -> Option<DVec3>,
    persp: bool,
    lens: Option<&Lens>,
    out: &mut SampleBuffer,
    bounds: &mut Vec<StratumBound>,
    slices: &mut Vec<[i32; 2]>,
) -> u64 {
    let nu = g.nu;
    let mp = j * (nu - 1) + i;
    let a = j * nu + i;
    let quad = [a, a + 1, a + nu + 1, a + nu];
    let [z0, z1] = s.z;
    let mut mp = MovingMicropolygon {
        g,
        m,
        quad,
        reach: g.border_reach(i, j),
        order: ((id as u64) << 32) | mp as u64,
        z: s.z,
        persp,
        lens,
        lens_cells: lens.is_some_and(|l| {
            let (gx, gy) = l.blur_radius(z0, z1);
            gx.max(gy) >= LENS_CELL_BLUR
        }),
        pad: 0.0,
        fixed: None,
    };
    // Most micropolygons of a grid that several buckets share miss this one (checked before
    // projecting a lens-blurred still one's corners, which its pixels do not need).
    if mp.pixels(s.key_box, out).is_none() {
        return 0;
    }
    if m.keys.len() == 1 {
        let (mut v, mut k) = ([DVec3::ZERO; 4], [0.0; 4]);
        for ((q, f), &i) in v.iter_mut().zip(&mut k).zip(&quad) {
            let Some(p) = project(m.keys[0][i].as_dvec3()) else {
                return 0;
            };
            *q = p;
            *f = lens.map_or(0.0, |l| l.factor(p.z));
        }
        mp.fixed = Some((v, k));
    }
    mp.pad = s.pad;
    let n = out.n_per;
    let shutter = out.shutter.map(f64::from);
    let mut hits = 0;
    if let Some(lens) = lens {
        bounds.clear();
        let mut ends = None;
        for k in 0..s.strata {
            let Some(b) = setup.bound(m, &quad, s, k, shutter, persp, project, &mut ends) else {
                return 0;
            };
            bounds.push(b);
        }
        if mp.lens_cells && lens_cells_pay(&mp, bounds, n) {
            return mp
                .sample_lens_cells(lens, bounds, project, out)
                .unwrap_or(0);
        }
        for (k, &b) in bounds.iter().enumerate() {
            match mp.sample_stratum(b, stratum_samples(k, s.strata, n), project, out, slices) {
                Some(h) => hits += h,
                None => return hits,
            }
        }
        return hits;
    }
    // Without a lens only the strata whose paths reach the buffer are bounded further (a
    // stratum that reaches none tests no sample).
    let mut ends = None;
    for k in 0..s.strata {
        let run = stratum_samples(k, s.strata, n);
        if run.is_empty() || mp.pixels(setup.path(s, k), out).is_none() {
            continue;
        }
        let Some(b) = setup.bound(m, &quad, s, k, shutter, persp, project, &mut ends) else {
            return hits;
        };
        match mp.sample_stratum(b, run, project, out, slices) {
            Some(h) => hits += h,
            None => return hits,
        }
    }
    hits
}

/// The lens blur (raster radius) from which a micropolygon is bounded per lens cell: below
/// it, the cells' boxes would all be about the micropolygon's own, and one box per time
/// stratum costs less.
const LENS_CELL_BLUR: f64 = 0.5;

/// The box of a micropolygon's paths over every stratum.
fn union_path(bounds: &[StratumBound]) -> [f64; 4] {
    bounds.iter().fold(
        [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ],
        |a, b| {
            let p = b.path;
            [
                a[0].min(p[0]),
                a[1].max(p[1]),
                a[2].min(p[2]),
                a[3].max(p[3]),
            ]
        },
    )
}

/// Whether bounding a lens-blurred micropolygon per lens cell (its whole path, a cell's share
/// of the blur) visits fewer samples than per time stratum (a stratum's path, the whole
/// blur): the first wins unless it moves much farther than it blurs.
fn lens_cells_pay(mp: &MovingMicropolygon, bounds: &[StratumBound], n: usize) -> bool {
    let Some(lens) = mp.lens else { return false };
    let [z0, z1] = mp.z;
    let (gx, gy) = lens.blur_radius(z0, z1);
    let cell = 2.0 / (n as f64).sqrt();
    let area = |b: [f64; 4], gx: f64, gy: f64| {
        (b[1] - b[0] + 2.0 * gx + 1.0) * (b[3] - b[2] + 2.0 * gy + 1.0)
    };
    let by_cell = n as f64 * area(union_path(bounds), gx * cell, gy * cell);
    let per_stratum = n as f64 / bounds.len() as f64;
    let by_time: f64 = bounds
        .iter()
        .map(|b| area(b.path, gx, gy) * per_stratum)
        .sum();
    by_cell < by_time
}

/// The buffer's pixels `[x0, x1, y0, y1]` (inclusive, relative to its origin) that the
/// raster box `b` reaches; `None` when it reaches none. In `i64`: a box far off screen (a
/// huge circle of confusion) saturates `as i32`, and the origin subtracted from `i32::MIN`
/// overflowed (found by the render_rib fuzzer).
fn buffer_pixels(b: [f64; 4], out: &SampleBuffer) -> Option<[i32; 4]> {
    let [ox, oy] = out.origin.map(i64::from);
    let [sw, sh] = out.size.map(|s| s as i64);
    let pixel = |v: f64| i64::from(floor_f64_to_i32(v));
    let qx0 = (pixel(b[0]) - ox).max(0);
    let qx1 = (pixel(b[1]) - ox).min(sw - 1);
    let qy0 = (pixel(b[2]) - oy).max(0);
    let qy1 = (pixel(b[3]) - oy).min(sh - 1);
    // Within the buffer, so each fits an `i32`.
    (qx0 <= qx1 && qy0 <= qy1).then(|| [qx0, qx1, qy0, qy1].map(|q| q as i32))
}

/// The shortest run of time slices a stratum's pixels are narrowed to (`SliceWindow`) for:
/// a run of one sample per pixel (a stratum per pixel of motion over 16 samples) has nothing
/// to skip, and setting up the windows cost `rib/bench/transform_blur.rib` 5%.
const SLICE_WINDOW_MIN: usize = 4;

/// One moving micropolygon and what testing a sample against it needs.
struct MovingMicropolygon<'a> {
    g: &'a ShadedGrid,
    m: &'a GridMotion,
    /// Its grid vertices, counter-clockwise in (u, v).
    quad: [usize; 4],
    /// Outward reach of its `[bottom, right, top, left]` edges (grid borders only).
    reach: [f64; 4],
    order: u64,
    /// Camera depth range over every key.
    z: [f64; 2],
    persp: bool,
    lens: Option<&'a Lens>,
    /// Whether the lens blurs it enough (half a pixel) to bound it per lens cell.
    lens_cells: bool,
    /// Extra growth of a stratum's box for the rounding of sample times (pixels).
    pad: f64,
    /// Its raster corners and their lens factors when it does not move (one key: only a lens
    /// blurs it), computed once instead of per sample.
    fixed: Option<([DVec3; 4], [f64; 4])>,
}

/// How many candidate samples [`MovingMicropolygon::sample_stratum`] gathers before testing them.
const CANDIDATES: usize = 64;

impl MovingMicropolygon<'_> {
    /// The buffer's pixels `[x0, x1, y0, y1]` (inclusive, relative to its origin) that the
    /// raster box `b` reaches, grown by the edge reach, the circle of confusion and `pad`;
    /// `None` when it reaches none.
    fn pixels(&self, b: [f64; 4], out: &SampleBuffer) -> Option<[i32; 4]> {
        let grow = self.reach.iter().copied().fold(0.0, f64::max) + self.pad;
        let [z0, z1] = self.z;
        let (gx, gy) = self.lens.map_or((0.0, 0.0), |l| l.blur_radius(z0, z1));
        let (gx, gy) = (grow + gx, grow + gy);
        buffer_pixels([b[0] - gx, b[1] + gx, b[2] - gy, b[3] + gy], out)
    }

    /// Tests the samples at time-ordered positions `run` of every pixel the stratum's path
    /// box (the pinhole path over those samples' times) reaches, grown by the edge reach and
    /// the circle of confusion, of only the time slices that can reach the micropolygon there
    /// (`SliceWindow`, for a run of `SLICE_WINDOW_MIN` or more); a sample is first moved back
    /// along the stratum's mean velocity and compared with its `still` box, then with its
    /// still hull (`LazyHull`). `None` when a position fails to project (the micropolygon is
    /// dropped, as when a key does not project).
    fn sample_stratum(
        &self,
        sb: StratumBound,
        run: std::ops::Range<usize>,
        project: &impl Fn(DVec3) -> Option<DVec3>,
        out: &mut SampleBuffer,
        slices: &mut Vec<[i32; 2]>,
    ) -> Option<u64> {
        if run.is_empty() {
            return Some(0);
        }
        let Some([qx0, qx1, qy0, qy1]) = self.pixels(sb.path, out) else {
            return Some(0);
        };
        let [z0, z1] = self.z;
        let sw = out.size[0];
        // `pad` holds the motion over a sample time's rounding (`time_slack`); moving back
        // along `v` over that extra time at most doubles it.
        let pad = self.reach.iter().copied().fold(0.0, f64::max) + 3.0 * self.pad + 1e-6;
        let b = sb.still;
        // Without a lens, the candidates in the still box's corners are dropped before the
        // full test (a lens offset would shift each sample by its own amount). Not for a
        // grid border micropolygon: an edge that reaches out widens its triangle's wedge at an
        // acute corner by more than the reach (`Chord::still_hull`).
        let mut hull = LazyHull::new(
            match (self.lens, &sb.chord) {
                (None, Some(c)) if self.reach == [0.0; 4] => Some(c),
                _ => None,
            },
            pad,
        );
        let mut hits = 0;
        // The candidates that pass the still box, gathered without a branch per sample (which
        // way a sample goes follows no pattern a predictor learns) and tested in their order.
        let mut candidates = [0u32; CANDIDATES];
        let mut n = 0;
        // Only the time slices of each pixel whose samples can pass the still box once moved
        // back (`SliceWindow`): for a long stratum (a rigid move along an axis has one) the
        // slices of a pixel the micropolygon passes over early or late are skipped.
        let (r0, r1) = (run.start as i32, run.end as i32);
        let narrow = run.len() >= SLICE_WINDOW_MIN && sb.chord.is_some();
        let cols = (qx1 - qx0 + 1) as usize;
        slices.clear();
        if narrow {
            let (gx, gy) = self.lens.map_or((0.0, 0.0), |l| l.blur_radius(z0, z1));
            let (shutter, per_pixel) = (out.shutter.map(f64::from), out.n_per);
            let window = |axis: usize, lo: f64, hi: f64| {
                SliceWindow::new(sb.t0, sb.v[axis], [lo, hi], shutter, per_pixel)
            };
            let wx = window(0, b[0] - gx - pad, b[1] + gx + pad);
            let wy = window(1, b[2] - gy - pad, b[3] + gy + pad);
            let [ox, oy] = out.origin;
            slices.extend((qx0..=qx1).map(|qx| wx.slices(qx + ox, r0, r1)));
            slices.extend((qy0..=qy1).map(|qy| wy.slices(qy + oy, r0, r1)));
        }
        for qy in qy0..=qy1 {
            let row = cols + (qy - qy0) as usize;
            for qx in qx0..=qx1 {
                let (fa, fb) = if narrow {
                    let ([xa, xb], [ya, yb]) = (slices[(qx - qx0) as usize], slices[row]);
                    let fa = xa.max(ya);
                    (fa as usize, xb.min(yb).max(fa) as usize)
                } else {
                    (run.start, run.end)
                };
                let base = (qy as usize * sw + qx as usize) * out.n_per;
                for p in base + fa..base + fb {
                    let ts = out.timed[p];
                    let (x, y) = sb.moved_back(ts.x, ts.y, ts.t);
                    // The still box shifted by this sample's lens offset over the
                    // micropolygon's depth range: most candidates end here.
                    let (ex, ey) = match self.lens {
                        Some(lens) => lens.offset_range(z0, z1, ts.lens),
                        None => ([0.0; 2], [0.0; 2]),
                    };
                    let outside = (x < b[0] + ex[0] - pad)
                        | (x > b[1] + ex[1] + pad)
                        | (y < b[2] + ey[0] - pad)
                        | (y > b[3] + ey[1] + pad);
                    candidates[n] = p as u32;
                    n += usize::from(!outside);
                    if n == CANDIDATES {
                        hits += self.sample_in_hull(&candidates, &sb, &mut hull, project, out)?;
                        n = 0;
                    }
                }
            }
        }
        hits += self.sample_in_hull(&candidates[..n], &sb, &mut hull, project, out)?;
        Some(hits)
    }

    /// [`Self::sample_candidates`] for the samples `candidates` of stratum `sb` that its
    /// `hull` holds once moved back (all of them without one), picked without a branch.
    fn sample_in_hull(
        &self,
        candidates: &[u32],
        sb: &StratumBound,
        hull: &mut LazyHull,
        project: &impl Fn(DVec3) -> Option<DVec3>,
        out: &mut SampleBuffer,
    ) -> Option<u64> {
        let Some(hull) = hull.for_candidates(candidates.len()) else {
            let all = candidates.iter().map(|&p| (p, sb));
            return self.sample_candidates(all, project, out);
        };
        let mut kept = [0u32; CANDIDATES];
        let mut n = 0;
        for &p in candidates {
            let ts = out.timed[p as usize];
            let (x, y) = sb.moved_back(ts.x, ts.y, ts.t);
            kept[n] = p;
            n += usize::from(hull.holds(x, y));
        }
        let kept = kept[..n].iter().map(|&p| (p, sb));
        self.sample_candidates(kept, project, out)
    }

    /// [`Self::sample_at`] for each time-ordered sample `p` of `candidates` with its time
    /// stratum's bound, in order.
    fn sample_candidates<'b>(
        &self,
        candidates: impl Iterator<Item = (u32, &'b StratumBound)>,
        project: &impl Fn(DVec3) -> Option<DVec3>,
        out: &mut SampleBuffer,
    ) -> Option<u64> {
        let mut hits = 0;
        for (p, sb) in candidates {
            let ts = out.timed[p as usize];
            hits += self.sample_at(&ts, sb, project, out)?;
        }
        Some(hits)
    }

    /// Every sample through a lens that blurs, one lens index `j` at a time: in every pixel
    /// one sample, whose lens position lies in one lens cell (`sampling::lens_strata`) and
    /// whose time is anywhere in the shutter. Such a sample sees the micropolygon only inside
    /// its box over the shutter (`path`, the union of the strata's) shifted by the cell's lens
    /// offsets over the micropolygon's depths; only the pixels of that box are visited, and a
    /// sample is then checked against its own time stratum's bound. A cell is `1/n` of the
    /// lens, so the box is the micropolygon's own size (plus its motion) and about
    /// `2·CoC/√n` instead of `2·CoC`: about `n·(size + 2·CoC/√n)²` samples tested instead of
    /// `n·(size + 2·CoC)²`.
    fn sample_lens_cells(
        &self,
        lens: &Lens,
        bounds: &[StratumBound],
        project: &impl Fn(DVec3) -> Option<DVec3>,
        out: &mut SampleBuffer,
    ) -> Option<u64> {
        let n = out.n_per;
        let strata = bounds.len();
        let [z0, z1] = self.z;
        let sw = out.size[0];
        let pad = self.reach.iter().copied().fold(0.0, f64::max) + 3.0 * self.pad + 1e-6;
        let path = union_path(bounds);
        let (k0, k1) = (lens.factor(z0), lens.factor(z1));
        let mut hits = 0;
        // Candidates (sample, stratum) gathered without a branch, as in `sample_stratum`.
        let mut candidates = [(0u32, 0u32); CANDIDATES];
        let mut m = 0;
        for j in 0..n {
            let o = lens.offset_box(z0, z1, lens.stratum_bound(j));
            let bx = [
                path[0] + o[0] - pad,
                path[1] + o[1] + pad,
                path[2] + o[2] - pad,
                path[3] + o[3] + pad,
            ];
            let Some([qx0, qx1, qy0, qy1]) = buffer_pixels(bx, out) else {
                continue;
            };
            for qy in qy0..=qy1 {
                for qx in qx0..=qx1 {
                    let base = (qy as usize * sw + qx as usize) * n;
                    let f = out.timed[base + j].by_lens as usize;
                    let p = base + f.min(n - 1);
                    let ts = out.timed[p];
                    let k = (f * strata / n).min(strata - 1);
                    let sb = &bounds[k];
                    let b = sb.still;
                    let (x, y) = sb.moved_back(ts.x, ts.y, ts.t);
                    // `Lens::offset_range` with the depth range's factors computed once.
                    let ((ax, ay), (cx, cy)) =
                        (lens.offset_by(k0, ts.lens), lens.offset_by(k1, ts.lens));
                    let outside = (x < b[0] + ax.min(cx) - pad)
                        | (x > b[1] + ax.max(cx) + pad)
                        | (y < b[2] + ay.min(cy) - pad)
                        | (y > b[3] + ay.max(cy) + pad);
                    candidates[m] = (p as u32, k as u32);
                    m += usize::from(!outside);
                    if m == CANDIDATES {
                        let all = candidates.iter().map(|&(p, k)| (p, &bounds[k as usize]));
                        hits += self.sample_candidates(all, project, out)?;
                        m = 0;
                    }
                }
            }
        }
        let rest = candidates[..m]
            .iter()
            .map(|&(p, k)| (p, &bounds[k as usize]));
        hits += self.sample_candidates(rest, project, out)?;
        Some(hits)
    }

    /// Tests one sample against the micropolygon moved to the sample's time and lens
    /// position, with the same edge rules as a still micropolygon; deposits its hits.
    fn sample_at(
        &self,
        ts: &crate::time_strata::TimedSample,
        sb: &StratumBound,
        project: &impl Fn(DVec3) -> Option<DVec3>,
        out: &mut SampleBuffer,
    ) -> Option<u64> {
        if let (Some(lens), Some((mut v, k))) = (self.lens, self.fixed) {
            for (q, k) in v.iter_mut().zip(k) {
                let (dx, dy) = lens.offset_by(k, ts.lens);
                q.x += dx;
                q.y += dy;
            }
            return Some(self.sample_corners(v, ts, out));
        }
        let mut v = match (&sb.chord, self.fixed) {
            (_, Some((v, _))) => v,
            (Some(c), None) => c.corners(f64::from(ts.t), sb.t0)?,
            (None, None) => {
                let seg = segment(&self.m.times, f64::from(ts.t));
                let mut v = [DVec3::ZERO; 4];
                for (vk, &k) in v.iter_mut().zip(&self.quad) {
                    *vk = project(self.m.at(k, seg))?;
                }
                v
            }
        };
        if let Some(lens) = self.lens {
            for q in &mut v {
                let (dx, dy) = lens.offset(q.z, ts.lens);
                q.x += dx;
                q.y += dy;
            }
        }
        Some(self.sample_corners(v, ts, out))
    }

    /// Tests sample `ts` against the micropolygon with raster corners `v` (moved to the
    /// sample's time and lens position); deposits its hits.
    ///
    /// The two triangles of [`split_quad`] one after the other, each with its corner indices
    /// known to the compiler: looping over `split_quad`'s array made every call build it on the
    /// stack and spill around it (about 115 instructions before the first test, a fifth of a
    /// candidate sample's cost on `rib/bench/camera_blur.rib`).
    fn sample_corners(
        &self,
        v: [DVec3; 4],
        ts: &crate::time_strata::TimedSample,
        out: &mut SampleBuffer,
    ) -> u64 {
        let [(first, first_reach), (second, second_reach)] = split_quad([0, 1, 2, 3], self.reach);
        self.sample_triangle(v, first, first_reach, ts, out)
            + self.sample_triangle(v, second, second_reach, ts, out)
    }

    /// [`Self::sample_corners`] for the triangle of corners `tri` with edge reach `reach`.
    #[inline(always)]
    fn sample_triangle(
        &self,
        v: [DVec3; 4],
        tri: [usize; 3],
        reach: [f64; 3],
        ts: &crate::time_strata::TimedSample,
        out: &mut SampleBuffer,
    ) -> u64 {
        let (x, y) = (f64::from(ts.x), f64::from(ts.y));
        let s = ts.s as usize;
        let Some(t) = RasterTriangle::new(tri.map(|k| v[k]), tri, reach) else {
            return 0;
        };
        let Some(w) = t.covers(x, y) else {
            return 0;
        };
        // Divided per sample (this triangle exists for one sample only);
        // a still triangle multiplies by reciprocals it computes once.
        let vd = t.v;
        let z = if self.persp {
            (1.0 / (w[0] / vd[0].z + w[1] / vd[1].z + w[2] / vd[2].z)) as f32
        } else {
            (w[0] * vd[0].z + w[1] * vd[1].z + w[2] * vd[2].z) as f32
        };
        let [near, far] = out.near_far;
        if z < near || z > far || z >= out.opaque_z[s] {
            return 0;
        }
        let (idx, ccw) = (t.idx.map(|k| self.quad[k]), t.ccw);
        let hit = Hit {
            idx,
            w,
            first: self.quad[0],
            z,
            order: self.order,
            ccw,
        };
        out.deposit(self.g, s, hit, &self.g.triangle_shade(idx, self.quad[0]));
        1
    }
}
