//! Depth of field: the thin lens of `DepthOfField fstop focallength focaldistance` (RI Spec 3.2
//! §4.1.3; Potmesil and Chakravarty 1981, as PRMan models it).
//!
//! The pinhole ray of screen point `s` meets the focal plane `z = zf` at `F = (s·zf/d, zf)`
//! (`d` the perspective scale). Through the lens point `L = (lx, ly, 0)` the ray `L + u(F − L)`
//! passes the camera-space point `P` when `u = z/zf`, so `P` is seen at
//! `s = d·x/z + d·lx·(1/zf − 1/z)`: every point moves on screen by the lens offset times
//! `d·(1/zf − 1/z)`, zero on the focal plane. The hider shifts each micropolygon vertex by that
//! amount for the sample's lens position instead of tracing rays.
use crate::sampling::{lens_cell, lens_strata};
use illume_ri::Camera;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::sync::Arc;

/// The lens of one frame, in raster units.
#[derive(Clone, Debug)]
pub(crate) struct Lens {
    /// Lens radius `focallength / (2·fstop)`, camera-space units.
    pub radius: f64,
    pub focal_distance: f64,
    /// Raster pixels per screen unit times the perspective scale, for x and y (y flips).
    scale: [f64; 2],
    /// Per lens index `j` of a pixel's samples, a box `[x0, x1, y0, y1]` on the unit disk
    /// holding the lens positions of those samples in every pixel (`sampling::lens_strata`);
    /// empty until [`Lens::with_strata`].
    strata: Arc<[[f64; 4]]>,
}

impl Lens {
    /// The frame's lens; `None` without `DepthOfField` (a pinhole) or for an orthographic
    /// camera, whose rays are parallel (the caller warns).
    pub fn new(dof: Option<[f32; 3]>, cam: &Camera) -> Option<Lens> {
        let [fstop, focal_length, focal_distance] = dof?;
        let d = cam.perspective_scale?;
        let [l, r, b, t] = cam.screen_window;
        let radius = f64::from(focal_length) / (2.0 * f64::from(fstop));
        (radius > 0.0 && radius.is_finite()).then(|| Lens {
            radius,
            focal_distance: f64::from(focal_distance),
            scale: [
                d * f64::from(cam.xres) / (r - l),
                -d * f64::from(cam.yres) / (t - b),
            ],
            strata: Arc::new([]),
        })
    }

    /// The lens with the disk box of each lens index's cell, for `samples` per pixel
    /// in frame `frame` (the pairing [`lens_strata`] makes).
    pub fn with_strata(mut self, samples: [u32; 2], frame: i32) -> Lens {
        let samples = samples.map(|s| s.max(1));
        self.strata = lens_strata(samples, frame)
            .into_iter()
            .map(|l| cell_disk_bound(lens_cell(l, samples)))
            .collect();
        self
    }

    /// The disk box of the lens positions of time stratum `f` (the whole disk when unknown).
    #[inline]
    pub fn stratum_bound(&self, f: usize) -> [f64; 4] {
        self.strata.get(f).copied().unwrap_or([
            -1.0 - DISK_PAD,
            1.0 + DISK_PAD,
            -1.0 - DISK_PAD,
            1.0 + DISK_PAD,
        ])
    }

    /// Raster box `[x0, x1, y0, y1]` of the offset of points with depths in `[z0, z1]` seen
    /// through lens positions in the disk box `[u0, u1, v0, v1]`: the offset is `k(z)·l`
    /// scaled, with `k` increasing in `z`, so both factors' ranges are spanned by their ends
    /// and the product's by the four products of ends.
    #[inline]
    pub fn offset_box(&self, z0: f64, z1: f64, [u0, u1, v0, v1]: [f64; 4]) -> [f64; 4] {
        let k0 = self.radius * (1.0 / self.focal_distance - 1.0 / z0);
        let k1 = self.radius * (1.0 / self.focal_distance - 1.0 / z1);
        let span = |a: f64, b: f64, s: f64| {
            let p = [k0 * a, k0 * b, k1 * a, k1 * b].map(|x| x * s);
            let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        };
        let (x0, x1) = span(u0, u1, self.scale[0]);
        let (y0, y1) = span(v0, v1, self.scale[1]);
        [x0, x1, y0, y1]
    }

    /// The diameter (raster pixels, the smaller axis) of the smallest circle of confusion of
    /// points with depths in `[z0, z1]`: zero when the range holds the focal plane.
    pub fn min_blur_diameter(&self, z0: f64, z1: f64) -> f64 {
        let zf = self.focal_distance;
        if z0.is_nan() || z0 <= 0.0 || (z0 <= zf && zf <= z1) {
            return 0.0;
        }
        let k = [z0, z1]
            .map(|z| (1.0 / zf - 1.0 / z).abs())
            .into_iter()
            .fold(f64::INFINITY, f64::min)
            * self.radius;
        2.0 * k * self.scale[0].abs().min(self.scale[1].abs())
    }

    /// Raster offset of a point at depth `z` seen through lens position `(lu, lv)` (unit disk).
    #[inline]
    pub fn offset(&self, z: f64, l: (f32, f32)) -> (f64, f64) {
        self.offset_by(self.factor(z), l)
    }

    /// The lens factor `k(z) = R·(1/zf − 1/z)` of depth `z`: [`Lens::offset`] is `k·l` scaled,
    /// so a point whose depth does not change computes it once.
    #[inline]
    pub fn factor(&self, z: f64) -> f64 {
        self.radius * (1.0 / self.focal_distance - 1.0 / z)
    }

    /// [`Lens::offset`] of a point with lens factor `k` (the same bits).
    #[inline]
    pub fn offset_by(&self, k: f64, (lu, lv): (f32, f32)) -> (f64, f64) {
        (
            k * f64::from(lu) * self.scale[0],
            k * f64::from(lv) * self.scale[1],
        )
    }

    /// Range of the raster offset (x and y) of points with depths in `[z0, z1]` seen through
    /// lens position `l`: the offset is `k(z)·l` scaled, `k(z) = R·(1/zf − 1/z)` increasing in
    /// `z`, so its range is spanned by the two ends.
    #[inline]
    pub fn offset_range(&self, z0: f64, z1: f64, l: (f32, f32)) -> ([f64; 2], [f64; 2]) {
        let (ax, ay) = self.offset(z0, l);
        let (bx, by) = self.offset(z1, l);
        ([ax.min(bx), ax.max(bx)], [ay.min(by), ay.max(by)])
    }

    /// Largest raster radius (x, y) of the circle of confusion over depths `[z0, z1]`
    /// (`z0 > 0`): `|1/zf − 1/z|` is largest at one end of the range.
    pub fn blur_radius(&self, z0: f64, z1: f64) -> (f64, f64) {
        let k = [z0, z1]
            .map(|z| (1.0 / self.focal_distance - 1.0 / z).abs())
            .into_iter()
            .fold(0.0, f64::max)
            * self.radius;
        (k * self.scale[0].abs(), k * self.scale[1].abs())
    }
}

/// How much coarser (per side) a piece is diced when every point of it is blurred by a circle
/// of confusion at least `coc` raster pixels across: `max(1, coc/16)`, PRMan's `"dice"
/// "focusfactor"` of 1, the lens twin of `refine::motion_factor`. Detail finer than the blur
/// does not show, and every micropolygon costs about one test per pixel its blur covers per
/// lens cell, so a fine dice of a blurred piece buys nothing but time. Non-finite counts as none.
pub(crate) fn focus_factor(coc: f64) -> f64 {
    if coc.is_finite() {
        (coc / 16.0).max(1.0)
    } else {
        1.0
    }
}

/// Rounding allowance of a lens box on the disk: the samples' lens positions come from the
/// f32 [`concentric_disk`], a few f32 ulps off the exact map.
const DISK_PAD: f64 = 1e-5;

/// A box `[x0, x1, y0, y1]` on the unit disk holding [`concentric_disk`]'s image of the cell
/// `[u0, u1] × [v0, v1]` of the unit square: the union of [`sector_bound`]s of its 4×4 parts
/// (a sector is loose where a cell's angular span changes with the radius; small parts keep
/// the union within a few per cent of the image's own box).
pub(crate) fn cell_disk_bound([u0, u1, v0, v1]: [f32; 4]) -> [f64; 4] {
    const PARTS: usize = 4;
    let (u0, u1, v0, v1) = (f64::from(u0), f64::from(u1), f64::from(v0), f64::from(v1));
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let at = |lo: f64, hi: f64, k: usize| lo + (hi - lo) * k as f64 / PARTS as f64;
    for i in 0..PARTS {
        for j in 0..PARTS {
            let [a0, a1] = [at(u0, u1, i), at(u0, u1, i + 1)].map(|u| 2.0 * u - 1.0);
            let [b0, b1] = [at(v0, v1, j), at(v0, v1, j + 1)].map(|v| 2.0 * v - 1.0);
            let p = sector_bound([a0, a1, b0, b1]);
            b = [
                b[0].min(p[0]),
                b[1].max(p[1]),
                b[2].min(p[2]),
                b[3].max(p[3]),
            ];
        }
    }
    b
}

/// A box `[x0, x1, y0, y1]` on the unit disk holding [`concentric_disk`]'s image of the
/// rectangle `[a0, a1] × [b0, b1]` of `[−1, 1]²` (`a = 2u − 1`, `b = 2v − 1`).
///
/// The map sends `(a, b)` to radius `max(|a|, |b|)` at an angle
/// `ψ = h(θ)` of its direction `θ = atan2(b, a)`, where `h` is increasing and fixes the axes and
/// diagonals (within an octant `ψ` is `π/4` times the ratio of the smaller to the larger
/// coordinate, offset to the octant). A cell that does not hold the origin sees directions
/// spanning at most a half turn (exactly one when the origin lies on an edge), extreme at two
/// of its corners other than the origin, so its image lies in the annular sector between its
/// least and greatest radius and its corners' angles (unwrapped about the cell centre's
/// direction; `ψ − θ` is under `π/4`). The sector's box is spanned by its corners and the
/// points on its outer arc where it crosses an axis. A cell holding the origin inside gets the
/// disk of its greatest radius.
fn sector_bound([a0, a1, b0, b1]: [f64; 4]) -> [f64; 4] {
    let near = |lo: f64, hi: f64| {
        if lo <= 0.0 && hi >= 0.0 {
            0.0
        } else {
            lo.abs().min(hi.abs())
        }
    };
    let far = |lo: f64, hi: f64| lo.abs().max(hi.abs());
    let r0 = near(a0, a1).max(near(b0, b1));
    let r1 = far(a0, a1).max(far(b0, b1)).min(1.0);
    let p = DISK_PAD;
    if a0 < 0.0 && a1 > 0.0 && b0 < 0.0 && b1 > 0.0 {
        return [-r1 - p, r1 + p, -r1 - p, r1 + p];
    }
    let wrap = |x: f64| x - 2.0 * PI * ((x + PI) / (2.0 * PI)).floor();
    let centre = (0.5 * (b0 + b1)).atan2(0.5 * (a0 + a1));
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (a, b) in [(a0, b0), (a1, b0), (a1, b1), (a0, b1)] {
        if a == 0.0 && b == 0.0 {
            continue;
        }
        let theta = b.atan2(a);
        let psi = centre + wrap(theta - centre) + wrap(disk_angle(a, b) - theta);
        (lo, hi) = (lo.min(psi), hi.max(psi));
    }
    let mut bx = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut add = |r: f64, phi: f64| {
        let (x, y) = (r * phi.cos(), r * phi.sin());
        bx = [bx[0].min(x), bx[1].max(x), bx[2].min(y), bx[3].max(y)];
    };
    for r in [r0, r1] {
        add(r, lo);
        add(r, hi);
    }
    let mut axis = (lo / FRAC_PI_2).ceil() * FRAC_PI_2;
    while axis <= hi {
        add(r1, axis);
        axis += FRAC_PI_2;
    }
    [bx[0] - p, bx[1] + p, bx[2] - p, bx[3] + p]
}

/// The direction of [`concentric_disk`]'s image of `(a, b) ≠ 0` (in `[−1, 1]²`), in f64.
fn disk_angle(a: f64, b: f64) -> f64 {
    if a.abs() > b.abs() {
        FRAC_PI_4 * (b / a) + if a < 0.0 { PI } else { 0.0 }
    } else {
        FRAC_PI_2 - FRAC_PI_4 * (a / b) + if b < 0.0 { PI } else { 0.0 }
    }
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disk: keeps strata
/// compact, so stratified lens samples stay stratified on the lens.
pub(crate) fn concentric_disk(u: f32, v: f32) -> (f32, f32) {
    let (a, b) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let q = std::f32::consts::FRAC_PI_4;
    let (r, phi) = if a.abs() > b.abs() {
        (a, q * (b / a))
    } else {
        (b, 2.0 * q - q * (a / b))
    };
    (r * phi.cos(), r * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat4, DVec3};
    use illume_ri::{Options, Projection};

    /// The screen offset against f64 ray geometry: trace from the lens point through the point
    /// and intersect the ray with the focal plane, then project that point through the pinhole.
    #[test]
    fn offset_matches_ray_geometry() {
        let o = Options {
            projection: Projection::Perspective { fov: 40.0 },
            xres: 200,
            yres: 100,
            depth_of_field: Some([2.8, 0.5, 4.0]),
            ..Options::default()
        };
        let cam = Camera::new(&o, DMat4::IDENTITY);
        let lens = Lens::new(o.depth_of_field, &cam).unwrap();
        // The lens radius from the same f32 inputs (2.8 is not exact in f32).
        let r = f64::from(0.5f32) / (2.0 * f64::from(2.8f32));
        for (p, l) in [
            (DVec3::new(0.3, -0.2, 2.0), (0.5f32, -0.25f32)),
            (DVec3::new(-1.0, 0.7, 9.0), (-0.9, 0.1)),
            (DVec3::new(0.0, 0.0, 4.0), (1.0, 0.0)),
        ] {
            let lp = DVec3::new(f64::from(l.0) * r, f64::from(l.1) * r, 0.0);
            let u = 4.0 / p.z;
            let f = lp + (p - lp) * u;
            let want = cam.raster_from_camera(f).unwrap();
            let pin = cam.raster_from_camera(p).unwrap();
            let (dx, dy) = lens.offset(p.z, l);
            assert!((pin.x + dx - want.x).abs() < 1e-9, "{p} {l:?}");
            assert!((pin.y + dy - want.y).abs() < 1e-9, "{p} {l:?}");
        }
    }

    /// Every point of every lens cell maps inside the cell's disk box, for grids with and
    /// without a centre cell, and the box is not much larger than the image's own bound (a
    /// fine sampling of the cell).
    #[test]
    fn cell_disk_bound_holds_the_cells_image_and_is_tight() {
        for spp in [[1u32, 1], [2, 2], [3, 3], [4, 3], [5, 2], [8, 8], [16, 16]] {
            for l in 0..spp[0] * spp[1] {
                let [u0, u1, v0, v1] = lens_cell(l, spp);
                let b = cell_disk_bound([u0, u1, v0, v1]);
                let mut seen = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
                let m = 48;
                for i in 0..=m {
                    for j in 0..=m {
                        let u = u0 + (u1 - u0) * i as f32 / m as f32;
                        let v = v0 + (v1 - v0) * j as f32 / m as f32;
                        let (x, y) = concentric_disk(u, v);
                        let (x, y) = (f64::from(x), f64::from(y));
                        assert!(
                            x >= b[0] && x <= b[1] && y >= b[2] && y <= b[3],
                            "spp {spp:?} cell {l}: ({x}, {y}) outside {b:?}"
                        );
                        seen = [
                            seen[0].min(x),
                            seen[1].max(x),
                            seen[2].min(y),
                            seen[3].max(y),
                        ];
                    }
                }
                let area = |b: [f64; 4]| (b[1] - b[0]) * (b[3] - b[2]);
                assert!(
                    area(b) <= 1.6 * area(seen) + 1e-4,
                    "spp {spp:?} cell {l}: box {b:?} against {seen:?}"
                );
            }
        }
    }

    /// The offset box of a depth range and a disk box against offsets at sampled depths and
    /// lens positions (f64 brute force), on both sides of the focal plane.
    #[test]
    fn offset_box_holds_every_offset_of_its_depths_and_lens_positions() {
        let o = Options {
            projection: Projection::Perspective { fov: 40.0 },
            xres: 200,
            yres: 100,
            depth_of_field: Some([2.0, 1.0, 4.0]),
            ..Options::default()
        };
        let cam = Camera::new(&o, DMat4::IDENTITY);
        let lens = Lens::new(o.depth_of_field, &cam).unwrap();
        for (z0, z1) in [(2.0, 3.0), (3.5, 6.0), (5.0, 50.0)] {
            for cell in [[-0.25, 0.375, -0.875, -0.5], [0.3125, 0.875, 0.125, 0.25]] {
                let b = lens.offset_box(z0, z1, cell);
                for i in 0..=8 {
                    let z = z0 + (z1 - z0) * f64::from(i) / 8.0;
                    for (a, c) in [(0, 2), (1, 3), (0, 3), (1, 2)] {
                        let l = (cell[a] as f32, cell[c] as f32);
                        let (dx, dy) = lens.offset(z, l);
                        assert!(dx >= b[0] - 1e-9 && dx <= b[1] + 1e-9, "{z} {l:?}");
                        assert!(dy >= b[2] - 1e-9 && dy <= b[3] + 1e-9, "{z} {l:?}");
                    }
                }
            }
        }
        assert_eq!(lens.min_blur_diameter(3.0, 5.0), 0.0);
        let (gx, gy) = lens.blur_radius(2.0, 3.0);
        let d = lens.min_blur_diameter(2.0, 3.0);
        assert!((d - 2.0 * gx.min(gy) * (0.25 - 1.0 / 3.0) / (0.25 - 0.5)).abs() < 1e-9);
    }

    #[test]
    fn concentric_map_stays_in_the_disk_and_reaches_its_rim() {
        for i in 0..=16 {
            for j in 0..=16 {
                let (x, y) = concentric_disk(i as f32 / 16.0, j as f32 / 16.0);
                assert!(x * x + y * y <= 1.0 + 1e-5);
            }
        }
        let (x, y) = concentric_disk(1.0, 0.5);
        assert!((x - 1.0).abs() < 1e-6 && y.abs() < 1e-6);
    }
}
