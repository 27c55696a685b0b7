//! What sampling a moving grid's micropolygons needs that no bucket changes, set up once per
//! grid by the first bucket that samples it: each micropolygon's raster box and depths over
//! every key, its time strata (`time_strata.rs`; fewer for one that moves rigidly) and its
//! strata's paths (`stratum_bound.rs`).
use crate::dice::ShadedGrid;
use crate::motion::GridMotion;
use crate::sample_buffer::SampleBuffer;
use crate::stratum_bound::{
    cut_corners, moves_rigidly, strata_paths, stratum_bound, StratumBound, StratumPath,
};
use crate::time_strata::{stratum_count, stratum_cuts, time_slack};
use glam::DVec3;

/// What sampling a moving micropolygon needs that no bucket changes: its raster box and
/// depth range over every key, its time strata and their padding, and where its strata's
/// paths are in [`GridSetup`] (none when it is not `chorded`).
pub(crate) struct MicropolygonSetup {
    pub(crate) key_box: [f64; 4],
    pub(crate) z: [f64; 2],
    pub(crate) strata: usize,
    /// `MovingMicropolygon::pad`.
    pub(crate) pad: f64,
    pub(crate) paths: u32,
    /// Whether its strata are bounded between their cuts (moving), not by its key box.
    pub(crate) chorded: bool,
}

/// [`MicropolygonSetup`] per micropolygon (`None`: back-facing, or a position that does not
/// project, so it is never sampled); every micropolygon's strata's paths ([`strata_paths`])
/// in one vector; the cuts per stratum count. The corners at the cuts are projected again
/// by each bucket, for only the strata it reaches: keeping them would triple the memory.
pub(crate) struct GridSetup {
    pub(crate) mps: Vec<Option<MicropolygonSetup>>,
    pub(crate) paths: Vec<StratumPath>,
    pub(crate) cuts: Vec<Vec<f64>>,
}

impl GridSetup {
    /// Stratum `k`'s bound of micropolygon `s` (of vertices `quad`); `ends` holds its corners
    /// at the stratum's cuts when a previous stratum computed them. `None` when a corner does
    /// not project (never, once `strata_paths` projected them).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn bound(
        &self,
        m: &GridMotion,
        quad: &[usize; 4],
        s: &MicropolygonSetup,
        k: usize,
        shutter: [f64; 2],
        persp: bool,
        project: &impl Fn(DVec3) -> Option<DVec3>,
        ends: &mut Option<(usize, [DVec3; 4])>,
    ) -> Option<StratumBound> {
        if !s.chorded {
            return Some(StratumBound {
                path: s.key_box,
                t0: shutter[0],
                v: [0.0; 2],
                still: s.key_box,
                chord: None,
            });
        }
        let cuts = &self.cuts[s.strata];
        let start = match *ends {
            Some((c, v)) if c == k => v,
            _ => cut_corners(m, quad, cuts[k], project)?,
        };
        let end = cut_corners(m, quad, cuts[k + 1], project)?;
        *ends = Some((k + 1, end));
        let p = self.paths[s.paths as usize + k];
        Some(stratum_bound(
            p,
            &start,
            &end,
            [cuts[k], cuts[k + 1]],
            persp,
        ))
    }

    /// Stratum `k`'s path box of micropolygon `s`.
    pub(crate) fn path(&self, s: &MicropolygonSetup, k: usize) -> [f64; 4] {
        if !s.chorded {
            s.key_box
        } else {
            self.paths[s.paths as usize + k].path
        }
    }
}

/// A bound on how far (raster pixels, either axis) a vertex of a micropolygon with raster box
/// `[x0, x1, y0, y1]` and depths `[z0, z1]` over every key moves in `dt` of time. Between keys
/// a raster coordinate `α·X/Z + β` of a point moving linearly in camera space has the
/// derivative `(x₁ − x₀)·Z₀Z₁/Z(t)²` per unit of the key span, at most the key box's extent
/// times `z1/z0` (perspective) over the shortest key span. Infinite when keys share a time.
fn drift(
    m: &GridMotion,
    [x0, x1, y0, y1]: [f64; 4],
    [z0, z1]: [f64; 2],
    persp: bool,
    dt: f64,
) -> f64 {
    let span = m
        .times
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::MAX, f64::min);
    if span <= 0.0 {
        return f64::INFINITY;
    }
    let depth = if persp { z1 / z0 } else { 1.0 };
    (x1 - x0).max(y1 - y0) * depth / span * dt
}

/// How far (raster pixels, x and y) micropolygon `quad` moves over the keys beyond its own size
/// at the first key, given its raster box `[x0, x1, y0, y1]` over every key.
fn sweep(
    m: &GridMotion,
    quad: &[usize; 4],
    [x0, x1, y0, y1]: [f64; 4],
    project: &impl Fn(DVec3) -> Option<DVec3>,
) -> [f64; 2] {
    let mut v = [DVec3::ZERO; 4];
    let mut len = 0;
    for &k in quad {
        if let Some(q) = project(m.keys[0][k].as_dvec3()) {
            v[len] = q;
            len += 1;
        }
    }
    let v = &v[..len];
    let extent = |g: fn(&DVec3) -> f64| {
        let xs = v.iter().map(g);
        xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min)
    };
    [
        ((x1 - x0) - extent(|q| q.x)).max(0.0),
        ((y1 - y0) - extent(|q| q.y)).max(0.0),
    ]
}

/// Every micropolygon's [`MicropolygonSetup`]: its raster box and depths over every key, its
/// time strata (`time_strata.rs`), its corners at their cuts and their paths, as no bucket
/// changes them.
pub(crate) fn grid_setup(
    g: &ShadedGrid,
    m: &GridMotion,
    project: &impl Fn(DVec3) -> Option<DVec3>,
    persp: bool,
    lens: bool,
    out: &SampleBuffer,
) -> GridSetup {
    let mut setup = GridSetup {
        mps: Vec::with_capacity((g.nu - 1) * (g.nv - 1)),
        paths: Vec::new(),
        cuts: Vec::new(),
    };
    let mut paths = Vec::new();
    for j in 0..g.nv - 1 {
        for i in 0..g.nu - 1 {
            let s = micropolygon_setup(
                g,
                m,
                [i, j],
                project,
                [persp, lens],
                out,
                &mut setup.cuts,
                &mut paths,
            );
            setup.mps.push(s.map(|mut s| {
                s.paths = setup.paths.len() as u32;
                if s.chorded {
                    setup.paths.extend_from_slice(&paths);
                }
                s
            }));
        }
    }
    setup.paths.shrink_to_fit();
    setup
}

/// Micropolygon `(i, j)`'s [`MicropolygonSetup`], its strata's paths left in `paths` when it
/// has more than one stratum; `None` when it is never sampled.
#[allow(clippy::too_many_arguments)]
fn micropolygon_setup(
    g: &ShadedGrid,
    m: &GridMotion,
    [i, j]: [usize; 2],
    project: &impl Fn(DVec3) -> Option<DVec3>,
    [persp, lens]: [bool; 2],
    out: &SampleBuffer,
    cuts: &mut Vec<Vec<f64>>,
    paths: &mut Vec<StratumPath>,
) -> Option<MicropolygonSetup> {
    let nu = g.nu;
    if g.backface(j * (nu - 1) + i) {
        return None;
    }
    let a = j * nu + i;
    let quad = [a, a + 1, a + nu + 1, a + nu];
    // Raster box over every key, depth range for the circle of confusion.
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let (mut z0, mut z1) = (f64::MAX, f64::MIN);
    for key in &m.keys {
        for &v in &quad {
            let q = project(key[v].as_dvec3()).filter(|q| q.is_finite())?;
            (x0, x1, y0, y1) = (x0.min(q.x), x1.max(q.x), y0.min(q.y), y1.max(q.y));
            (z0, z1) = (z0.min(q.z), z1.max(q.z));
        }
    }
    let key_box = [x0, x1, y0, y1];
    let n = out.n_per;
    let shutter = out.shutter.map(f64::from);
    let (mut strata, mut rigid) = (1, false);
    if m.keys.len() > 1 && shutter[1] > shutter[0] {
        let [sx, sy] = sweep(m, &quad, key_box, project);
        // Not through a lens: there a stratum's box grows by the whole circle of confusion,
        // and longer strata cost more (measured on `rib/motion.rib`).
        let spanned = (!lens)
            .then(|| rigid_strata(m, &quad, [sx, sy], shutter, n, cuts, project, persp))
            .flatten();
        rigid = spanned.is_some();
        strata = spanned.unwrap_or_else(|| stratum_count(sx.max(sy), n));
    }
    // A sample time may round past its stratum's cuts by `time_slack`: the boxes grow by the
    // motion over that time (a tiny fraction of a pixel), or are not cut when it is unbounded.
    let drift = drift(m, key_box, [z0, z1], persp, time_slack(shutter));
    if drift.is_nan() || drift >= 0.25 {
        (strata, rigid) = (1, false);
    }
    let chorded = strata > 1 || rigid;
    let mut pad = 0.0;
    if chorded {
        pad = drift;
        strata_paths(
            m,
            &quad,
            cached_cuts(cuts, strata, n, shutter),
            project,
            paths,
        )?;
    }
    Some(MicropolygonSetup {
        key_box,
        z: [z0, z1],
        strata,
        pad,
        paths: 0,
        chorded,
    })
}

/// The cuts of `strata` time strata of `n` samples per pixel over `shutter`, computed once
/// per count for a grid.
fn cached_cuts(cuts: &mut Vec<Vec<f64>>, strata: usize, n: usize, shutter: [f64; 2]) -> &[f64] {
    if cuts.len() <= strata {
        cuts.resize(strata + 1, Vec::new());
    }
    if cuts[strata].is_empty() {
        cuts[strata] = stratum_cuts(strata, n, shutter);
    }
    &cuts[strata]
}

/// Pixels of sweep per time stratum for a micropolygon that [`moves_rigidly`], counted as the
/// geometric mean of its x and y sweeps (one stratum per pixel of the longer one otherwise,
/// `time_strata::stratum_count`). Moved back by its velocity, such a micropolygon stays
/// within its own size over a stratum of any length, and the sampler visits only the time
/// slices that can reach each pixel (`slice_window.rs`), so a longer stratum costs no more
/// candidates, only the pixels of its path box that its path misses: none for a move along
/// an axis, which gets one stratum (`rib/bench/camera_blur.rib` at 320×240: one stratum
/// instead of one per 8 pixels of its 47-pixel sweep, 9% fewer instructions), and about
/// `sx·sy/strata` for a diagonal one. `rib/bench/transform_blur.rib`'s bent path of
/// translations is rigid between its keys: 4 strata instead of 16, 4% fewer instructions.
const RIGID_SWEEP_PER_STRATUM: f64 = 8.0;

/// How many time strata micropolygon `quad`, sweeping `[sx, sy]` pixels, is bounded over when
/// it [`moves_rigidly`] between its motion keys inside the shutter: per key span, one per
/// [`RIGID_SWEEP_PER_STRATUM`] pixels of the geometric mean of its sweeps (shared evenly by the
/// spans), when those strata's cuts fall on every key inside the shutter (a stratum with a key
/// inside has no chord). `None` when it does not move rigidly or the cuts miss a key.
#[allow(clippy::too_many_arguments)]
fn rigid_strata(
    m: &GridMotion,
    quad: &[usize; 4],
    [sx, sy]: [f64; 2],
    [open, close]: [f64; 2],
    n: usize,
    cuts: &mut Vec<Vec<f64>>,
    project: &impl Fn(DVec3) -> Option<DVec3>,
    persp: bool,
) -> Option<usize> {
    let inner = || m.times.iter().copied().filter(|&t| t > open && t < close);
    let spans = inner().count() + 1;
    let per_span = (sx * sy).sqrt() / spans as f64 / RIGID_SWEEP_PER_STRATUM;
    let strata = spans * stratum_count(per_span, n);
    if strata > n {
        return None;
    }
    let c = cached_cuts(cuts, strata, n, [open, close]);
    if !inner().all(|t| c.contains(&t)) {
        return None;
    }
    let mut start = open;
    for end in inner().chain([close]) {
        if !moves_rigidly(m, quad, [start, end], project, persp) {
            return None;
        }
        start = end;
    }
    Some(strata)
}
