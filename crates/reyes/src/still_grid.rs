//! Sampling a still grid (one that neither moves nor is lens-blurred) in one bucket: each
//! micropolygon is split into two triangles whose samples are found inside their raster
//! bounds.
//!
//! A grid overlaps several buckets and is sampled once in each, so most of its micropolygons
//! miss any one bucket. Issue 21 part 3 found the still hider's cost there: bounding every
//! micropolygon per bucket, a `hypot` per sample on border edges, and `floorf` calls. So the
//! grid's rows and columns of micropolygons are bounded first (one pass over the vertices)
//! and only the micropolygons in a row and a column that reach the bucket are looked at; the
//! bound tests compare floats with the bucket's edges instead of flooring; and each triangle's
//! edge functions are set up once ([`TriangleEdges`]). Every test is conservative against the
//! exact per-sample test, which is unchanged, so the same samples are hit with the same
//! weights and depths as before, bit for bit.
use crate::dice::ShadedGrid;
use crate::int_floor::floor_to_i32;
use crate::raster_triangle::{split_quad, RasterTriangle, TriangleEdges};
use crate::sample_buffer::{Hit, SampleBuffer};
use std::cmp::Ordering::Less;
use std::ops::Range;

/// A raster box `[x0, x1, y0, y1]` (empty: `[∞, −∞, ∞, −∞]`).
type RasterBox = [f32; 4];

const EMPTY: RasterBox = [
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::INFINITY,
    f32::NEG_INFINITY,
];

/// `b` grown to hold `(x, y)`. `f32::min`/`max` skip a NaN coordinate, as the micropolygon
/// bound they stand in for does.
#[inline]
fn add(b: RasterBox, x: f32, y: f32) -> RasterBox {
    [b[0].min(x), b[1].max(x), b[2].min(y), b[3].max(y)]
}

#[inline]
fn union(a: RasterBox, b: RasterBox) -> RasterBox {
    [
        a[0].min(b[0]),
        a[1].max(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
    ]
}

/// The raster bounds of a grid's rows and columns of micropolygons, found once when the grid
/// is shaded and used by every bucket that samples it: a micropolygon's bound lies in both its
/// row's and its column's.
pub(crate) struct GridBands {
    /// Per row `j` of micropolygons (vertex rows `j` and `j + 1`), and per column `i`.
    rows: Vec<RasterBox>,
    cols: Vec<RasterBox>,
    /// The largest outward reach of any edge of the grid (raster pixels).
    grow: f32,
}

impl GridBands {
    /// The bands of an `nu × nv` grid of raster positions whose border segments reach out by
    /// `seam` (see [`ShadedGrid::seam`]).
    pub fn new(pos: &[glam::Vec3], nu: usize, nv: usize, seam: &[Vec<f64>; 4]) -> GridBands {
        let mut rows = vec![EMPTY; nv];
        let mut cols = vec![EMPTY; nu];
        if pos.len() >= nu * nv {
            for (j, row) in rows.iter_mut().enumerate() {
                for (i, col) in cols.iter_mut().enumerate() {
                    let p = pos[j * nu + i];
                    *row = add(*row, p.x, p.y);
                    *col = add(*col, p.x, p.y);
                }
            }
        }
        let pairs = |v: Vec<RasterBox>| v.windows(2).map(|w| union(w[0], w[1])).collect();
        GridBands {
            rows: pairs(rows),
            cols: pairs(cols),
            grow: seam.iter().flatten().copied().fold(0.0f64, f64::max) as f32,
        }
    }

    /// The rows of `held` from the first to the last whose bound, grown by the grid's reach,
    /// extends to raster `y` or below it (none: the empty range at `held`'s end): the rows a
    /// bucket whose samples lie at or below `y` may sample ([`SampleBuffer::box_may_reach`]
    /// fails for the others, whatever its columns). A NaN bound counts as reaching.
    pub fn rows_reaching(&self, y: f32, held: Range<usize>) -> Range<usize> {
        let reaches = |j: &usize| (self.rows[*j][3] + self.grow).partial_cmp(&y) != Some(Less);
        let first = held.clone().find(reaches);
        let last = held.clone().rev().find(reaches);
        match (first, last) {
            (Some(a), Some(b)) => a..b + 1,
            _ => held.end..held.end,
        }
    }

    /// Forgets the bounds of the rows outside `keep` (they are no longer held): the sampler
    /// then never looks at them.
    pub fn drop_rows_outside(&mut self, keep: Range<usize>) {
        for (j, row) in self.rows.iter_mut().enumerate() {
            if !keep.contains(&j) {
                *row = EMPTY;
            }
        }
    }
}

impl SampleBuffer {
    /// Samples every micropolygon of a still grid (piece `id`); returns the samples hit.
    pub fn sample_still_grid(&mut self, g: &ShadedGrid, id: usize) -> u64 {
        let (nu, nv) = (g.nu, g.nv);
        let bands = &g.bands;
        if nu < 2 || nv < 2 || !g.complete() || bands.rows.len() + 1 != nv {
            return 0;
        }
        let col_reaches: Vec<bool> = (bands.cols.iter())
            .map(|&c| self.box_may_reach(c, bands.grow))
            .collect();
        let mut hits = 0;
        for (j, &row) in bands.rows.iter().enumerate() {
            if !self.box_may_reach(row, bands.grow) {
                continue;
            }
            for (i, _) in col_reaches.iter().enumerate().filter(|c| *c.1) {
                hits += self.sample_still_micropolygon(g, id, i, j);
            }
        }
        hits
    }

    /// Samples micropolygon `(i, j)` of a still grid (piece `id`); returns the samples hit.
    fn sample_still_micropolygon(&mut self, g: &ShadedGrid, id: usize, i: usize, j: usize) -> u64 {
        let m = j * (g.nu - 1) + i;
        if g.backface(m) {
            return 0;
        }
        let a = j * g.nu + i;
        let quad = [a, a + 1, a + g.nu + 1, a + g.nu];
        let pos = quad.map(|k| g.vertex(k));
        if pos.iter().any(|p| p.z.is_nan()) {
            return 0;
        }
        let reach = g.border_reach(i, j);
        let grow = reach.iter().copied().fold(0.0f64, f64::max) as f32;
        let bound = pos.iter().fold(EMPTY, |b, p| add(b, p.x, p.y));
        if !self.box_may_reach(bound, grow) {
            return 0;
        }
        let order = ((id as u64) << 32) | m as u64;
        // The two triangles one after the other, not a loop over `split_quad`'s array (built
        // on the stack and spilled around for every micropolygon).
        let [(t0, r0), (t1, r1)] = split_quad(quad, reach);
        let mut one = |tri: [usize; 3], reach| {
            let v = tri.map(|k| g.vertex(k).as_dvec3());
            RasterTriangle::new(v, tri, reach).map_or(0, |t| self.sample_triangle(g, &t, a, order))
        };
        one(t0, r0) + one(t1, r1)
    }

    /// Whether a raster box grown by `grow` reaches a pixel of this bucket's sample region:
    /// `floor(x0 − grow) < sx0 + sw` and `floor(x1 + grow) ≥ sx0` (the same in y), compared
    /// as floats (exact: the region's edges are small integers). A box that fails holds no
    /// sample any triangle inside it could cover.
    #[inline]
    fn box_may_reach(&self, b: RasterBox, grow: f32) -> bool {
        let [sx0, sy0] = self.origin.map(|o| o as f32);
        let [sw, sh] = self.size.map(|s| s as f32);
        b[0] - grow < sx0 + sw && b[1] + grow >= sx0 && b[2] - grow < sy0 + sh && b[3] + grow >= sy0
    }

    /// Samples one still triangle (grid vertex `first` names its micropolygon): the samples
    /// of the pixels its bound, grown by its largest edge reach, touches.
    fn sample_triangle(
        &mut self,
        g: &ShadedGrid,
        t: &RasterTriangle,
        first: usize,
        order: u64,
    ) -> u64 {
        let [sx0, sy0] = self.origin.map(i64::from);
        let [sw, sh] = self.size.map(|s| s as i64);
        let grow = t.reach.iter().copied().fold(0.0f64, f64::max) as f32;
        let b =
            t.v.iter()
                .fold(EMPTY, |b, p| add(b, p.x as f32, p.y as f32));
        let pixel = |x: f32, o: i64| i64::from(floor_to_i32(x)) - o;
        let qx0 = pixel(b[0] - grow, sx0).max(0);
        let qx1 = pixel(b[1] + grow, sx0).min(sw - 1);
        let qy0 = pixel(b[2] - grow, sy0).max(0);
        let qy1 = pixel(b[3] + grow, sy0).min(sh - 1);
        if qx0 > qx1 || qy0 > qy1 {
            return 0;
        }
        let edges = TriangleEdges::new(t);
        let shade = g.triangle_shade(t.idx, first);
        let inv_z = t.v.map(|p| 1.0 / p.z);
        let [near, far] = self.near_far;
        let n_per = self.n_per;
        let mut hits = 0;
        for qy in qy0 as usize..=qy1 as usize {
            let row = qy * sw as usize;
            let samples = (row + qx0 as usize) * n_per..(row + qx1 as usize + 1) * n_per;
            // The samples covered, found without branches a run of 64 at a time (see
            // [`TriangleEdges::inside`]), then visited one set bit at a time.
            for start in samples.clone().step_by(64) {
                let run = start..samples.end.min(start + 64);
                let mut covered = 0u64;
                for (k, &(x, y)) in self.pos[run].iter().enumerate() {
                    covered |= u64::from(edges.inside(f64::from(x), f64::from(y))) << k;
                }
                while covered != 0 {
                    let s = start + covered.trailing_zeros() as usize;
                    covered &= covered - 1;
                    let (x, y) = (f64::from(self.pos[s].0), f64::from(self.pos[s].1));
                    let w = edges.weights(x, y);
                    // Depth is linear in screen space for ortho, its reciprocal for perspective.
                    let z = if self.perspective {
                        (1.0 / (w[0] * inv_z[0] + w[1] * inv_z[1] + w[2] * inv_z[2])) as f32
                    } else {
                        (w[0] * t.v[0].z + w[1] * t.v[1].z + w[2] * t.v[2].z) as f32
                    };
                    if z < near || z > far || z >= self.opaque_z[s] {
                        continue;
                    }
                    hits += 1;
                    let (idx, ccw) = (t.idx, t.ccw);
                    let hit = Hit {
                        idx,
                        w,
                        first,
                        z,
                        order,
                        ccw,
                    };
                    self.deposit(g, s, hit, &shade);
                }
            }
        }
        hits
    }
}
