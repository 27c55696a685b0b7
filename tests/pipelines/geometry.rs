//! Independent `f64` reference geometry for the pipeline tests: the pinhole camera of a RIB
//! `Projection "perspective"`, ray–sphere hits and mirror reflection, written from the RI spec
//! and the chapter, not from the renderer's code.
use glam::DVec3;

/// A perspective camera: eye, world-space right/up/view axes (RenderMan's left-handed camera,
/// right × up = view), raster size and field of view across the shorter axis.
pub struct Camera {
    pub eye: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub view: DVec3,
    pub width: f64,
    pub height: f64,
    pub fov_degrees: f64,
}

impl Camera {
    /// The unit world-space direction through raster position (x, y) (y down, pixel centres at
    /// i + 0.5). The screen window is [-a,a]×[-1,1] for aspect a ≥ 1, else [-1,1]×[-1/a,1/a].
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        let a = self.width / self.height;
        let (sx_half, sy_half) = if a >= 1.0 { (a, 1.0) } else { (1.0, 1.0 / a) };
        let sx = (2.0 * x / self.width - 1.0) * sx_half;
        let sy = (1.0 - 2.0 * y / self.height) * sy_half;
        let t = (0.5 * self.fov_degrees.to_radians()).tan();
        (self.right * sx * t + self.up * sy * t + self.view).normalize()
    }
}

/// Nearest hit `t > 1e-9` of the ray `o + t·d` (`d` unit) with the sphere (`centre`, `radius`).
pub fn hit_sphere(o: DVec3, d: DVec3, centre: DVec3, radius: f64) -> Option<f64> {
    let e = o - centre;
    let b = e.dot(d);
    let c = e.dot(e) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    [-b - s, -b + s].into_iter().find(|&t| t > 1e-9)
}

/// R = I − 2(N·I)N.
pub fn reflect(i: DVec3, n: DVec3) -> DVec3 {
    i - 2.0 * n.dot(i) * n
}

/// Listing 9.5's lookup direction: from `p` (inside the sphere of radius `envrad` about the
/// origin) along `r` to that sphere; the point hit, as a direction from the centre.
pub fn environment_direction(p: DVec3, r: DVec3, envrad: f64) -> DVec3 {
    let t = hit_sphere(p, r, DVec3::ZERO, envrad).expect("p is inside the environment sphere");
    p + t * r
}
