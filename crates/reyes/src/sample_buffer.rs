//! A bucket's samples and the visible points they collect: one buffer for still and moving
//! (motion-blurred, lens-blurred) micropolygons, so both deposit hits the same way and the
//! compositing and film stages see one layout.
//!
//! The samples cover every pixel whose samples reach the bucket's pixel centres through the
//! pixel filter, pixel by pixel (rows first), `n_per` samples per pixel; a sample's position
//! (and time and lens position, when something blurs) is a hash of its pixel, index and frame
//! only, so neighbouring buckets agree on the samples they share.
use crate::csg::NO_SOLID;
use crate::dice::ShadedGrid;
use crate::film::SampleRegion;
use crate::sampling::{sample_position, sample_time_lens};
use crate::time_strata::{push_time_ordered, TimedSample};
use crate::visible::{VisiblePoint, NO_AOV};
use glam::DVec3;

/// How a bucket's samples are placed.
pub(crate) struct SampleSetup {
    /// `PixelSamples` per pixel (x, y).
    pub spp: [u32; 2],
    pub frame: i32,
    pub jitter: bool,
    /// Whether times and lens positions are needed (something moves or a lens blurs).
    pub blur: bool,
    pub shutter: [f32; 2],
    /// Camera clipping planes.
    pub near_far: [f32; 2],
    pub perspective: bool,
    /// Floats per visible point's AOV record (0: no AOVs).
    pub aov_stride: usize,
    /// The primitive solids that contain the eye (see `csg_eye`): where each sample's CSG
    /// state starts.
    pub eye_in_solids: Vec<u32>,
}

pub(crate) struct SampleBuffer {
    /// First pixel (x, y) and size in pixels of the sample region; samples per pixel.
    pub origin: [i32; 2],
    pub size: [usize; 2],
    pub n_per: usize,
    /// Raster position per sample.
    pub pos: Vec<(f32, f32)>,
    /// Every sample with its time and lens position, pixel by pixel as in `pos` but each
    /// pixel's samples in time order, so a time stratum is a run per pixel (`time_strata.rs`);
    /// empty when nothing blurs.
    pub timed: Vec<TimedSample>,
    /// Visible points per sample, unsorted.
    pub lists: Vec<Vec<VisiblePoint>>,
    /// Per sample, the depth of the nearest opaque visible point (nothing behind it shows).
    pub opaque_z: Vec<f32>,
    pub near_far: [f32; 2],
    pub shutter: [f32; 2],
    perspective: bool,
    /// AOV records of the visible points (`aov_stride` floats each), indexed by their tag.
    pub aov_store: Vec<f32>,
    pub aov_stride: usize,
}

/// One sample hit of a micropolygon, ready to become a [`VisiblePoint`].
pub(crate) struct Hit {
    /// Grid vertices of the hit triangle and the barycentric weights of the sample in it.
    pub idx: [usize; 3],
    pub w: [f64; 3],
    /// The micropolygon's first vertex (names its constant colour when shading is flat).
    pub first: usize,
    pub z: f32,
    /// Piece index (high 32 bits) and micropolygon index: the tie-break order at equal depth.
    pub order: u64,
    /// Whether the triangle was wound counter-clockwise at the sample (CSG entering test).
    pub ccw: bool,
}

impl SampleBuffer {
    /// The samples reaching the pixels `[px0, px1, py0, py1]` through a filter of radius
    /// `(rx, ry)`.
    pub fn new([px0, px1, py0, py1]: [u32; 4], (rx, ry): (f32, f32), set: &SampleSetup) -> Self {
        let sx0 = (px0 as f32 + 0.5 - rx).floor() as i32;
        let sx1 = (px1 as f32 - 0.5 + rx).floor() as i32 + 1;
        let sy0 = (py0 as f32 + 0.5 - ry).floor() as i32;
        let sy1 = (py1 as f32 - 0.5 + ry).floor() as i32 + 1;
        let (sw, sh) = ((sx1 - sx0) as usize, (sy1 - sy0) as usize);
        let spp = set.spp;
        let n_per = (spp[0] * spp[1]) as usize;
        let mut pos = Vec::with_capacity(sw * sh * n_per);
        for py in sy0..sy1 {
            for px in sx0..sx1 {
                for j in 0..spp[1] {
                    for i in 0..spp[0] {
                        pos.push(sample_position(px, py, i, j, spp, set.frame, set.jitter));
                    }
                }
            }
        }
        let mut timed = Vec::new();
        if set.blur {
            timed.reserve(pos.len());
            let mut time_lens = Vec::with_capacity(n_per);
            for py in sy0..sy1 {
                for px in sx0..sx1 {
                    let (frame, jitter) = (set.frame, set.jitter);
                    time_lens.clear();
                    sample_time_lens(px, py, spp, frame, jitter, set.shutter, &mut time_lens);
                    let first = timed.len();
                    push_time_ordered(&pos[first..first + n_per], &time_lens, first, &mut timed);
                }
            }
        }
        SampleBuffer {
            origin: [sx0, sy0],
            size: [sw, sh],
            n_per,
            lists: vec![Vec::new(); pos.len()],
            opaque_z: vec![f32::INFINITY; pos.len()],
            pos,
            timed,
            near_far: set.near_far,
            shutter: set.shutter,
            perspective: set.perspective,
            aov_store: Vec::new(),
            aov_stride: set.aov_stride,
        }
    }

    /// The samples as the film sees them.
    pub fn region(&self) -> SampleRegion<'_> {
        SampleRegion {
            origin: self.origin,
            size: self.size,
            per_pixel: self.n_per,
            pos: &self.pos,
        }
    }

    /// The farthest depth at which some sample still sees through: a piece starting behind it
    /// is hidden in the whole bucket.
    pub fn max_opaque_z(&self) -> f32 {
        self.opaque_z.iter().copied().fold(0.0f32, f32::max)
    }

    /// Samples every micropolygon of a still grid (piece `id`); returns the samples hit.
    pub fn sample_still_grid(&mut self, g: &ShadedGrid, id: usize) -> u64 {
        let mut hits = 0;
        for j in 0..g.nv - 1 {
            for i in 0..g.nu - 1 {
                let m = j * (g.nu - 1) + i;
                if g.backface[m] {
                    continue;
                }
                let a = j * g.nu + i;
                let quad = [a, a + 1, a + g.nu + 1, a + g.nu];
                if quad.iter().any(|&k| g.pos[k].z.is_nan()) {
                    continue;
                }
                let order = ((id as u64) << 32) | m as u64;
                for (tri, reach) in split_quad(quad, g.border_reach(i, j)) {
                    let v = tri.map(|k| g.pos[k].as_dvec3());
                    if let Some(t) = RasterTriangle::new(v, tri, reach) {
                        hits += self.sample_triangle(g, &t, a, order);
                    }
                }
            }
        }
        hits
    }

    /// Samples one still triangle (grid vertex `first` names its micropolygon).
    fn sample_triangle(
        &mut self,
        g: &ShadedGrid,
        t: &RasterTriangle,
        first: usize,
        order: u64,
    ) -> u64 {
        let [sx0, sy0] = self.origin;
        let [sw, sh] = self.size;
        let v = t.v.map(|p| p.as_vec3());
        let grow = t.reach.iter().copied().fold(0.0f64, f64::max) as f32;
        let xmin = v.iter().map(|p| p.x).fold(f32::INFINITY, f32::min) - grow;
        let xmax = v.iter().map(|p| p.x).fold(f32::NEG_INFINITY, f32::max) + grow;
        let ymin = v.iter().map(|p| p.y).fold(f32::INFINITY, f32::min) - grow;
        let ymax = v.iter().map(|p| p.y).fold(f32::NEG_INFINITY, f32::max) + grow;
        let qx0 = (xmin.floor() as i32 - sx0).max(0);
        let qx1 = (xmax.floor() as i32 - sx0).min(sw as i32 - 1);
        let qy0 = (ymin.floor() as i32 - sy0).max(0);
        let qy1 = (ymax.floor() as i32 - sy0).min(sh as i32 - 1);
        if qx0 > qx1 || qy0 > qy1 {
            return 0;
        }
        let inv_z = t.v.map(|p| 1.0 / p.z);
        let [near, far] = self.near_far;
        let mut hits = 0;
        for qy in qy0..=qy1 {
            for qx in qx0..=qx1 {
                let base = (qy as usize * sw + qx as usize) * self.n_per;
                for s in base..base + self.n_per {
                    let (x, y) = (f64::from(self.pos[s].0), f64::from(self.pos[s].1));
                    let Some(w) = t.covers(x, y) else {
                        continue;
                    };
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
                    self.deposit(
                        g,
                        s,
                        Hit {
                            idx,
                            w,
                            first,
                            z,
                            order,
                            ccw,
                        },
                    );
                }
            }
        }
        hits
    }

    /// Records one sample hit of a micropolygon (still or moving) in sample `s`: colour and
    /// opacity interpolated at the hit's barycentric weights (or the micropolygon's first
    /// vertex when shading is flat).
    pub fn deposit(&mut self, g: &ShadedGrid, s: usize, hit: Hit) {
        let (c, o) = g.shaded_at(hit.idx, hit.w, hit.first);
        let stride = self.aov_stride;
        let mut aov = NO_AOV;
        if let Some(k) = self.aov_store.len().checked_div(stride) {
            let k = k.min(NO_AOV as usize) as u32;
            if k < NO_AOV && g.push_aov(&mut self.aov_store, stride, hit.idx, hit.w, hit.first) {
                aov = k;
            }
        }
        self.lists[s].push(VisiblePoint {
            z: hit.z,
            order: hit.order,
            c,
            o,
            tag: VisiblePoint::tag(g.matte, hit.ccw == g.ccw_enters, aov),
        });
        // A solid's surface may yet be carved away, so it hides nothing behind it.
        if o.min_element() >= 1.0 && g.solid == NO_SOLID {
            self.opaque_z[s] = hit.z;
        }
    }
}

/// The two triangles (v0 v1 v2 and v0 v2 v3) a micropolygon quad is sampled as, with the
/// outward reach of each triangle edge, from the quad's `[bottom, right, top, left]` reach
/// (the diagonal never reaches out).
pub(crate) fn split_quad<T: Copy>(q: [T; 4], reach: [f64; 4]) -> [([T; 3], [f64; 3]); 2] {
    let [bottom, right, top, left] = reach;
    [
        ([q[0], q[1], q[2]], [bottom, right, 0.0]),
        ([q[0], q[2], q[3]], [0.0, top, left]),
    ]
}

/// A micropolygon triangle in raster space, wound counter-clockwise, with its edge rules.
pub(crate) struct RasterTriangle {
    /// Raster x, y and camera z per vertex, counter-clockwise.
    pub v: [DVec3; 3],
    /// The grid vertices in the same order.
    pub idx: [usize; 3],
    /// Outward reach of the edges v0→v1, v1→v2, v2→v0 (see the hider's `seam_reach`).
    pub reach: [f64; 3],
    /// Twice the triangle's area (positive).
    area: f64,
    /// Whether it was given wound counter-clockwise.
    pub ccw: bool,
}

impl RasterTriangle {
    /// `None` for a degenerate (zero or non-finite area) triangle. `reach` belongs to the edges
    /// as given: v0→v1, v1→v2, v2→v0.
    pub fn new(mut v: [DVec3; 3], mut idx: [usize; 3], mut reach: [f64; 3]) -> Option<Self> {
        let mut ar = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
        if ar == 0.0 || !ar.is_finite() {
            return None;
        }
        let ccw = ar > 0.0;
        if ar < 0.0 {
            v.swap(1, 2);
            idx.swap(1, 2);
            // Edges v0→v1, v1→v2, v2→v0 are now the old v2→v0, v1→v2 (reversed), v0→v1.
            reach = [reach[2], reach[1], reach[0]];
            ar = -ar;
        }
        Some(RasterTriangle {
            v,
            idx,
            reach,
            area: ar,
            ccw,
        })
    }

    /// The barycentric weights of raster point `(x, y)` when the triangle covers it.
    #[inline]
    pub fn covers(&self, x: f64, y: f64) -> Option<[f64; 3]> {
        let (v, r) = (&self.v, &self.reach);
        if !(edge(v[0], v[1], r[0], x, y)
            && edge(v[1], v[2], r[1], x, y)
            && edge(v[2], v[0], r[2], x, y))
        {
            return None;
        }
        let w0 = ((v[2].x - v[1].x) * (y - v[1].y) - (v[2].y - v[1].y) * (x - v[1].x)) / self.area;
        let w1 = ((v[0].x - v[2].x) * (y - v[2].y) - (v[0].y - v[2].y) * (x - v[2].x)) / self.area;
        Some([w0, w1, 1.0 - w0 - w1])
    }
}

/// Edge test with a top-left tie rule so a sample on a shared edge counts once; a grid border
/// edge instead accepts samples up to `r` pixels outside it.
#[inline]
fn edge(a: DVec3, b: DVec3, r: f64, x: f64, y: f64) -> bool {
    let e = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
    if r > 0.0 {
        return e > -r * (b.x - a.x).hypot(b.y - a.y);
    }
    e > 0.0 || (e == 0.0 && (b.y < a.y || (b.y == a.y && b.x > a.x)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sample_on_an_edge_shared_by_two_triangles_counts_once() {
        // A unit square split along its diagonal, both windings; samples on a lattice that
        // puts many points exactly on the diagonal and on the square's edges.
        let p = |x: f64, y: f64| DVec3::new(x, y, 1.0);
        let quad = [p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0), p(0.0, 4.0)];
        for q in [quad, [quad[0], quad[3], quad[2], quad[1]]] {
            let tris: Vec<RasterTriangle> = split_quad([0, 1, 2, 3], [0.0; 4])
                .into_iter()
                .filter_map(|(t, r)| RasterTriangle::new(t.map(|k| q[k]), t, r))
                .collect();
            assert_eq!(tris.len(), 2);
            for j in 0..=16 {
                for i in 0..=16 {
                    let (x, y) = (f64::from(i) * 0.25, f64::from(j) * 0.25);
                    let n = tris.iter().filter(|t| t.covers(x, y).is_some()).count();
                    let inside = x > 0.0 && x < 4.0 && y > 0.0 && y < 4.0;
                    if inside {
                        assert_eq!(n, 1, "sample ({x}, {y}) covered {n} times");
                    } else {
                        assert!(n <= 1, "border sample ({x}, {y}) covered {n} times");
                    }
                }
            }
        }
    }

    #[test]
    fn barycentric_weights_reproduce_the_sample_position() {
        let v = [
            DVec3::new(0.3, 0.1, 2.0),
            DVec3::new(7.9, 1.7, 3.0),
            DVec3::new(2.2, 6.4, 5.0),
        ];
        // Given clockwise, so the constructor reorders it.
        let t = RasterTriangle::new([v[0], v[2], v[1]], [0, 2, 1], [0.0; 3]).unwrap();
        assert!(!t.ccw);
        let w = t.covers(3.0, 2.5).expect("inside");
        let x: f64 = (0..3).map(|k| w[k] * v[t.idx[k]].x).sum();
        let y: f64 = (0..3).map(|k| w[k] * v[t.idx[k]].y).sum();
        assert!(
            (x - 3.0).abs() < 1e-12 && (y - 2.5).abs() < 1e-12,
            "({x}, {y})"
        );
        assert!(t.covers(9.0, 9.0).is_none());
    }

    #[test]
    fn a_border_edge_reaches_out_by_its_reach() {
        let p = |x: f64, y: f64| DVec3::new(x, y, 1.0);
        // Edge v0→v1 along y = 0, interior above: a sample 0.1 below counts only with reach.
        let v = [p(0.0, 0.0), p(4.0, 0.0), p(0.0, 4.0)];
        let exact = RasterTriangle::new(v, [0, 1, 2], [0.0; 3]).unwrap();
        let reaching = RasterTriangle::new(v, [0, 1, 2], [0.2, 0.0, 0.0]).unwrap();
        assert!(exact.covers(1.0, -0.1).is_none());
        assert!(reaching.covers(1.0, -0.1).is_some());
        assert!(reaching.covers(1.0, -0.3).is_none());
    }
}
