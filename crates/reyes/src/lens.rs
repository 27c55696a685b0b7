//! Depth of field: the thin lens of `DepthOfField fstop focallength focaldistance` (RI Spec 3.2
//! §4.1.3; Potmesil and Chakravarty 1981, as PRMan models it).
//!
//! The pinhole ray of screen point `s` meets the focal plane `z = zf` at `F = (s·zf/d, zf)`
//! (`d` the perspective scale). Through the lens point `L = (lx, ly, 0)` the ray `L + u(F − L)`
//! passes the camera-space point `P` when `u = z/zf`, so `P` is seen at
//! `s = d·x/z + d·lx·(1/zf − 1/z)`: every point moves on screen by the lens offset times
//! `d·(1/zf − 1/z)`, zero on the focal plane. The hider shifts each micropolygon vertex by that
//! amount for the sample's lens position instead of tracing rays.
use illume_ri::Camera;

/// The lens of one frame, in raster units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lens {
    /// Lens radius `focallength / (2·fstop)`, camera-space units.
    pub radius: f64,
    pub focal_distance: f64,
    /// Raster pixels per screen unit times the perspective scale, for x and y (y flips).
    scale: [f64; 2],
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
        })
    }

    /// Raster offset of a point at depth `z` seen through lens position `(lu, lv)` (unit disk).
    #[inline]
    pub fn offset(&self, z: f64, (lu, lv): (f32, f32)) -> (f64, f64) {
        let k = self.radius * (1.0 / self.focal_distance - 1.0 / z);
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
