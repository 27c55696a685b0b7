//! Quadrics intersected in closed form: spheres, disks, cylinders and cones (RI Spec 3.2 §5.3),
//! each a surface of revolution about its object z axis with `θ = u·thetamax`, placed in the
//! scene by a camera → object transformation.
//!
//! Why: a tessellated sphere is 8k triangles, and the boxes and triangle tests of those were
//! most of an `occlusion()` frame (issue 19: 16 rays per shaded point). One closed-form test
//! replaces a subtree, and the surface is exact: no chords, so a quadric's shadow and
//! occlusion are those of the true surface.
//!
//! The ray is taken to object space (an affine map keeps the ray parameter `t`), the quadric's
//! equation solved in `f64` with the cancellation-free form of the quadratic formula, and each
//! root kept when it lies in `(t_min, t_max)` and inside the surface's parameter range (`z`
//! between its limits, `θ` within `thetamax`). Both faces count, as for triangles. The hit's
//! `(u, v)` are the RenderMan parameters, so the caller can look up shading data there.
use glam::{DMat4, DVec3, Vec3};
use std::f64::consts::{FRAC_PI_2, TAU};

/// The profile of a quadric, angles in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum QuadricShape {
    /// `φ = φmin + v(φmax−φmin)`, `P = r(cosθ cosφ, sinθ cosφ, sinφ)`.
    Sphere {
        radius: f64,
        phimin: f64,
        phimax: f64,
        thetamax: f64,
    },
    /// `P = (r(1−v) cosθ, r(1−v) sinθ, height)`.
    Disk {
        height: f64,
        radius: f64,
        thetamax: f64,
    },
    /// `P = (r cosθ, r sinθ, zmin + v(zmax−zmin))`.
    Cylinder {
        radius: f64,
        zmin: f64,
        zmax: f64,
        thetamax: f64,
    },
    /// `P = (r(1−v) cosθ, r(1−v) sinθ, v·height)`.
    Cone {
        height: f64,
        radius: f64,
        thetamax: f64,
    },
}

/// A quadric in the scene: its shape, where it is, and a camera-space box around it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quadric {
    pub shape: QuadricShape,
    pub object_from_camera: DMat4,
    /// Camera-space box (the caller's conservative bound of the surface).
    pub bound: (Vec3, Vec3),
    /// A sphere's range of `z / radius` (`sin` of its φ limits), computed once.
    z_range: [f64; 2],
    /// A whole sphere under a similarity (rotation, uniform scale, translation): its
    /// camera-space centre and squared radius, so an any-hit test needs no transformation.
    ball: Option<(DVec3, f64)>,
}

impl QuadricShape {
    fn thetamax(&self) -> f64 {
        match *self {
            QuadricShape::Sphere { thetamax, .. }
            | QuadricShape::Disk { thetamax, .. }
            | QuadricShape::Cylinder { thetamax, .. }
            | QuadricShape::Cone { thetamax, .. } => thetamax,
        }
    }

    /// Whether the closed-form test handles this shape: finite, positive sizes and
    /// `0 < thetamax ≤ 2π` (others stay tessellated).
    pub fn supported(&self) -> bool {
        let tm = self.thetamax();
        let sizes_ok = match *self {
            QuadricShape::Sphere {
                radius,
                phimin,
                phimax,
                ..
            } => radius > 0.0 && phimin.is_finite() && phimax.is_finite() && phimin != phimax,
            QuadricShape::Disk { height, radius, .. } => radius > 0.0 && height.is_finite(),
            QuadricShape::Cylinder {
                radius, zmin, zmax, ..
            } => radius > 0.0 && zmin.is_finite() && zmax.is_finite() && zmin != zmax,
            QuadricShape::Cone { height, radius, .. } => {
                radius > 0.0 && height.is_finite() && height != 0.0
            }
        };
        sizes_ok && tm > 0.0 && tm <= TAU * (1.0 + 1e-12) && radius_finite(self)
    }

    /// Whether an object-space point of the untrimmed surface lies within the surface's
    /// parameter range (`θ` within `thetamax`, the profile within its limits), and its
    /// `(u, v)` when `uv` asks for them (`[0, 0]` otherwise: the any-hit rays of shadows and
    /// `occlusion()` need no parameters, and a full surface of revolution then needs no
    /// `atan2`).
    fn params(&self, p: DVec3, uv: bool, z_range: [f64; 2]) -> Option<[f64; 2]> {
        let tm = self.thetamax();
        let theta = if uv || tm < TAU {
            let theta = p.y.atan2(p.x);
            let theta = if theta < 0.0 { theta + TAU } else { theta };
            if theta > tm {
                return None;
            }
            theta
        } else {
            0.0
        };
        let v = match *self {
            QuadricShape::Sphere {
                radius,
                phimin,
                phimax,
                ..
            } => {
                let z = (p.z / radius).clamp(-1.0, 1.0);
                if z < z_range[0] || z > z_range[1] {
                    return None;
                }
                if uv {
                    (z.asin() - phimin) / (phimax - phimin)
                } else {
                    0.0
                }
            }
            QuadricShape::Disk { radius, .. } => {
                let rho2 = p.x * p.x + p.y * p.y;
                if rho2 > radius * radius {
                    return None;
                }
                if uv {
                    1.0 - rho2.sqrt() / radius
                } else {
                    0.0
                }
            }
            QuadricShape::Cylinder { zmin, zmax, .. } => {
                let v = (p.z - zmin) / (zmax - zmin);
                if !(0.0..=1.0).contains(&v) {
                    return None;
                }
                v
            }
            QuadricShape::Cone { height, .. } => {
                let v = p.z / height;
                if !(0.0..=1.0).contains(&v) {
                    return None;
                }
                v
            }
        };
        Some([if uv { theta / tm } else { 0.0 }, v])
    }

    /// The ray parameters where `o + t·d` (object space) meets the untrimmed surface, in
    /// increasing order (at most two).
    fn roots(&self, o: DVec3, d: DVec3) -> [Option<f64>; 2] {
        match *self {
            QuadricShape::Disk { height, .. } => {
                if d.z == 0.0 {
                    return [None, None];
                }
                [Some((height - o.z) / d.z), None]
            }
            QuadricShape::Sphere { radius, .. } => {
                quadratic(d.dot(d), 2.0 * o.dot(d), o.dot(o) - radius * radius)
            }
            QuadricShape::Cylinder { radius, .. } => quadratic(
                d.x * d.x + d.y * d.y,
                2.0 * (o.x * d.x + o.y * d.y),
                o.x * o.x + o.y * o.y - radius * radius,
            ),
            QuadricShape::Cone { height, radius, .. } => {
                // x² + y² = (r − k·z)², k = r/h.
                let k = radius / height;
                let rz = radius - k * o.z;
                quadratic(
                    d.x * d.x + d.y * d.y - k * k * d.z * d.z,
                    2.0 * (o.x * d.x + o.y * d.y + k * d.z * rz),
                    o.x * o.x + o.y * o.y - rz * rz,
                )
            }
        }
    }
}

/// The camera-space ball of a whole sphere whose placement is a similarity (`None` for
/// anything else): the object's axes stay orthogonal and equally scaled to within 1e-12.
fn whole_sphere_ball(
    shape: &QuadricShape,
    z_range: [f64; 2],
    object_from_camera: &DMat4,
) -> Option<(DVec3, f64)> {
    let QuadricShape::Sphere {
        radius, thetamax, ..
    } = *shape
    else {
        return None;
    };
    let whole =
        thetamax >= TAU * (1.0 - 1e-12) && z_range[0] <= -1.0 + 1e-12 && z_range[1] >= 1.0 - 1e-12;
    if !whole {
        return None;
    }
    let m = object_from_camera.inverse();
    let axes = [
        m.x_axis.truncate(),
        m.y_axis.truncate(),
        m.z_axis.truncate(),
    ];
    let s2 = axes[0].length_squared();
    let similar = (axes[1].length_squared() - s2).abs() <= 1e-12 * s2
        && (axes[2].length_squared() - s2).abs() <= 1e-12 * s2
        && axes[0].dot(axes[1]).abs() <= 1e-12 * s2
        && axes[1].dot(axes[2]).abs() <= 1e-12 * s2
        && axes[0].dot(axes[2]).abs() <= 1e-12 * s2;
    let centre = m.w_axis.truncate();
    (similar && s2 > 0.0 && centre.is_finite()).then_some((centre, radius * radius * s2))
}

fn radius_finite(s: &QuadricShape) -> bool {
    match *s {
        QuadricShape::Sphere { radius, .. }
        | QuadricShape::Disk { radius, .. }
        | QuadricShape::Cylinder { radius, .. }
        | QuadricShape::Cone { radius, .. } => radius.is_finite(),
    }
}

/// The real roots of `a·t² + b·t + c`, smaller first (Numerical Recipes' form: no
/// cancellation between `−b` and the discriminant's root).
fn quadratic(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if a == 0.0 {
        return if b == 0.0 {
            [None, None]
        } else {
            [Some(-c / b), None]
        };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 || !disc.is_finite() {
        return [None, None];
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    let (lo, hi) = (t0.min(t1), t0.max(t1));
    [Some(lo), Some(hi)]
}

impl Quadric {
    pub fn new(shape: QuadricShape, object_from_camera: DMat4, bound: (Vec3, Vec3)) -> Quadric {
        // sin is increasing on [−π/2, π/2]: a sphere's φ range is a range of z.
        let z_range = match shape {
            QuadricShape::Sphere { phimin, phimax, .. } => {
                let (lo, hi) = (phimin.min(phimax), phimin.max(phimax));
                [lo.max(-FRAC_PI_2).sin(), hi.min(FRAC_PI_2).sin()]
            }
            _ => [-1.0, 1.0],
        };
        Quadric {
            shape,
            object_from_camera,
            bound,
            z_range,
            ball: whole_sphere_ball(&shape, z_range, &object_from_camera),
        }
    }

    /// A whole sphere placed by a similarity: its camera-space centre and radius (`None` for
    /// other quadrics), so a caller can tell which rays cannot meet it.
    pub fn sphere_ball(&self) -> Option<(DVec3, f64)> {
        self.ball.map(|(c, r2)| (c, r2.sqrt()))
    }

    /// The nearest hit in `(t_min, t_max)` along `origin + t·dir` (camera space) as `t` and
    /// the surface's `(u, v)` there.
    pub fn intersect(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
    ) -> Option<(f64, [f64; 2])> {
        self.intersect_with(origin, dir, (t_min, t_max), true)
    }

    /// [`Quadric::intersect`]; `uv: false` leaves the parameters `[0, 0]` (cheaper).
    pub(crate) fn intersect_with(
        &self,
        origin: DVec3,
        dir: DVec3,
        (t_min, t_max): (f64, f64),
        uv: bool,
    ) -> Option<(f64, [f64; 2])> {
        if let (Some((c, r2)), false) = (self.ball, uv) {
            let oc = origin - c;
            let (b, c) = (oc.dot(dir), oc.dot(oc) - r2);
            // Outside and moving away: both roots are ≤ 0 (the quadratic below finds that
            // too, after a square root and two divisions).
            if c > 0.0 && b >= 0.0 && t_min >= 0.0 {
                return None;
            }
            let roots = quadratic(dir.dot(dir), 2.0 * b, c);
            return roots
                .into_iter()
                .flatten()
                .find(|&t| t > t_min && t < t_max)
                .map(|t| (t, [0.0, 0.0]));
        }
        let o = self.object_from_camera.transform_point3(origin);
        let d = self.object_from_camera.transform_vector3(dir);
        for t in self.shape.roots(o, d).into_iter().flatten() {
            if !(t > t_min && t < t_max) {
                continue;
            }
            if let Some(uv) = self.shape.params(o + d * t, uv, self.z_range) {
                return Some((t, uv));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(radius: f64, at: DVec3) -> Quadric {
        Quadric::new(
            QuadricShape::Sphere {
                radius,
                phimin: -std::f64::consts::FRAC_PI_2,
                phimax: std::f64::consts::FRAC_PI_2,
                thetamax: TAU,
            },
            DMat4::from_translation(-at),
            (
                (at - radius).as_vec3() - Vec3::splat(1e-3),
                (at + radius).as_vec3() + Vec3::splat(1e-3),
            ),
        )
    }

    #[test]
    fn a_sphere_is_hit_at_its_near_and_far_sides() {
        let s = sphere(2.0, DVec3::new(0.0, 0.0, 10.0));
        let (t, uv) = s.intersect(DVec3::ZERO, DVec3::Z, 0.0, 100.0).unwrap();
        assert!((t - 8.0).abs() < 1e-12);
        // The pole facing the eye: φ = −π/2, v = 0.
        assert!(uv[1].abs() < 1e-9);
        let (t, _) = s.intersect(DVec3::ZERO, DVec3::Z, 8.5, 100.0).unwrap();
        assert!((t - 12.0).abs() < 1e-12);
        assert!(s.intersect(DVec3::ZERO, DVec3::X, 0.0, 100.0).is_none());
        assert!(s.intersect(DVec3::ZERO, DVec3::Z, 0.0, 7.9).is_none());
    }

    #[test]
    fn a_placed_whole_sphere_answers_any_hit_rays_as_the_general_test_does() {
        // Scaled by 3, rotated and moved: the ball test (no parameters) and the object-space
        // test agree on every ray's first hit.
        let camera_from_object = DMat4::from_translation(DVec3::new(1.0, -2.0, 9.0))
            * DMat4::from_axis_angle(DVec3::new(1.0, 2.0, 0.5).normalize(), 0.7)
            * DMat4::from_scale(DVec3::splat(3.0));
        let q = Quadric::new(
            QuadricShape::Sphere {
                radius: 0.5,
                phimin: -std::f64::consts::FRAC_PI_2,
                phimax: std::f64::consts::FRAC_PI_2,
                thetamax: TAU,
            },
            camera_from_object.inverse(),
            (Vec3::new(-1.0, -4.0, 7.0), Vec3::new(3.0, 0.0, 11.0)),
        );
        assert!(q.ball.is_some());
        let mut hits = 0;
        for k in 0..200 {
            let a = f64::from(k) * 0.731;
            // A spiral about the direction of the centre (1, −2, 9).
            let r = 0.3 * f64::from(k) / 200.0;
            let dir = DVec3::new(a.sin() * r + 1.0 / 9.0, a.cos() * r - 2.0 / 9.0, 1.0);
            let fast = q.intersect_with(DVec3::ZERO, dir, (0.0, 100.0), false);
            let full = q.intersect_with(DVec3::ZERO, dir, (0.0, 100.0), true);
            assert_eq!(fast.is_some(), full.is_some(), "ray {k}");
            if let (Some(f), Some(g)) = (fast, full) {
                assert!(
                    (f.0 - g.0).abs() < 1e-9 * g.0,
                    "ray {k}: {} vs {}",
                    f.0,
                    g.0
                );
                hits += 1;
            }
        }
        assert!(hits > 20 && hits < 200, "{hits} of 200 rays hit");
    }

    #[test]
    fn a_partial_disk_and_cylinder_keep_to_their_ranges() {
        let disk = Quadric::new(
            QuadricShape::Disk {
                height: 1.0,
                radius: 1.0,
                thetamax: std::f64::consts::PI,
            },
            DMat4::IDENTITY,
            (Vec3::splat(-1.0), Vec3::splat(1.0)),
        );
        let down = DVec3::NEG_Z;
        let (t, uv) = disk
            .intersect(DVec3::new(0.0, 0.5, 3.0), down, 0.0, 10.0)
            .unwrap();
        assert!((t - 2.0).abs() < 1e-12);
        assert!((uv[0] - 0.5).abs() < 1e-12 && (uv[1] - 0.5).abs() < 1e-12);
        // The half with y < 0 is cut away, as is everything beyond the radius.
        assert!(disk
            .intersect(DVec3::new(0.0, -0.5, 3.0), down, 0.0, 10.0)
            .is_none());
        assert!(disk
            .intersect(DVec3::new(0.0, 1.5, 3.0), down, 0.0, 10.0)
            .is_none());
        let cyl = Quadric::new(
            QuadricShape::Cylinder {
                radius: 1.0,
                zmin: 0.0,
                zmax: 2.0,
                thetamax: TAU,
            },
            DMat4::IDENTITY,
            (Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 2.0)),
        );
        let (t, uv) = cyl
            .intersect(DVec3::new(-5.0, 0.0, 1.5), DVec3::X, 0.0, 10.0)
            .unwrap();
        assert!((t - 4.0).abs() < 1e-12 && (uv[1] - 0.75).abs() < 1e-12);
        assert!(cyl
            .intersect(DVec3::new(-5.0, 0.0, 2.5), DVec3::X, 0.0, 10.0)
            .is_none());
    }

    #[test]
    fn a_cone_is_hit_on_its_slant() {
        let cone = Quadric::new(
            QuadricShape::Cone {
                height: 2.0,
                radius: 1.0,
                thetamax: TAU,
            },
            DMat4::IDENTITY,
            (Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 2.0)),
        );
        // At z = 1 the radius is 0.5.
        let (t, uv) = cone
            .intersect(DVec3::new(-3.0, 0.0, 1.0), DVec3::X, 0.0, 10.0)
            .unwrap();
        assert!((t - 2.5).abs() < 1e-12 && (uv[1] - 0.5).abs() < 1e-12);
        // Above the apex: the other nappe of the double cone is not the surface.
        assert!(cone
            .intersect(DVec3::new(-3.0, 0.0, 3.0), DVec3::X, 0.0, 10.0)
            .is_none());
    }
}
