//! A triangle and the watertight ray-triangle intersection (Woop, Benthin, Wald, "Watertight
//! Ray/Triangle Intersection", JCGT 2(1) 2013; pbrt-v4 `IntersectTriangle`).
//!
//! Why watertight: shadow rays aimed at a diced grid's shared edges must hit one of the two
//! triangles, or light leaks through closed surfaces as bright speckles. The test translates
//! the vertices to the ray origin, permutes the axes so the ray's dominant axis is z, shears
//! the ray onto +z and evaluates the 2D edge functions; a point on an edge gives exactly 0 for
//! both triangles sharing it, counted as a hit by both. `f64` throughout: the only rounding
//! is in the stored `f32` vertices, the same for every triangle sharing a vertex.
use glam::{DVec3, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub p: [Vec3; 3],
}

/// A ray prepared for many triangle tests: the permutation and shear depend only on the
/// direction.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedRay {
    pub origin: DVec3,
    pub inv_dir: DVec3,
    /// The permutation and shear as three rows: `row_x·q = q[kx] + sx·q[kz]`,
    /// `row_y·q = q[ky] + sy·q[kz]`, `row_z·q = q[kz]` (the zero and unit entries make each
    /// dot product round exactly as the two-term sum it stands for, so the test stays
    /// watertight; it only avoids indexing by the permutation at every vertex).
    row_x: DVec3,
    row_y: DVec3,
    row_z: DVec3,
    sz: f64,
}

impl PreparedRay {
    /// `None` for a zero or non-finite direction (it can hit nothing).
    pub fn new(origin: DVec3, dir: DVec3) -> Option<PreparedRay> {
        if !origin.is_finite() || !dir.is_finite() || dir == DVec3::ZERO {
            return None;
        }
        let a = dir.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let kx = (kz + 1) % 3;
        let ky = (kx + 1) % 3;
        let unit = |k: usize| DVec3::AXES[k];
        let (sx, sy) = (-dir[kx] / dir[kz], -dir[ky] / dir[kz]);
        Some(PreparedRay {
            origin,
            inv_dir: DVec3::ONE / dir,
            row_x: unit(kx) + unit(kz) * sx,
            row_y: unit(ky) + unit(kz) * sy,
            row_z: unit(kz),
            sz: 1.0 / dir[kz],
        })
    }
}

impl Triangle {
    pub fn new(a: Vec3, b: Vec3, c: Vec3) -> Triangle {
        Triangle { p: [a, b, c] }
    }

    /// Twice the area (zero for a degenerate triangle).
    pub fn double_area(&self) -> f64 {
        let [a, b, c] = self.p.map(|v| v.as_dvec3());
        (b - a).cross(c - a).length()
    }

    /// The ray parameter `t` of the hit in `(t_min, t_max)`, if any. Both faces count.
    pub fn intersect(&self, origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let ray = PreparedRay::new(origin, dir)?;
        self.intersect_prepared(&ray, t_min, t_max)
    }

    pub(crate) fn intersect_prepared(
        &self,
        ray: &PreparedRay,
        t_min: f64,
        t_max: f64,
    ) -> Option<f64> {
        self.intersect_barycentric(ray, t_min, t_max)
            .map(|(t, _)| t)
    }

    /// The hit's `t` and barycentric weights of `p[0]`, `p[1]`, `p[2]` (they sum to 1), for
    /// interpolating the vertices' shading data at the hit.
    pub(crate) fn intersect_barycentric(
        &self,
        ray: &PreparedRay,
        t_min: f64,
        t_max: f64,
    ) -> Option<(f64, [f64; 3])> {
        let sheared = |v: Vec3| {
            let d = v.as_dvec3() - ray.origin;
            DVec3::new(ray.row_x.dot(d), ray.row_y.dot(d), ray.row_z.dot(d))
        };
        let (p0, p1, p2) = (sheared(self.p[0]), sheared(self.p[1]), sheared(self.p[2]));
        let e0 = p1.x * p2.y - p1.y * p2.x;
        let e1 = p2.x * p0.y - p2.y * p0.x;
        let e2 = p0.x * p1.y - p0.y * p1.x;
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let t_scaled = (e0 * p0.z + e1 * p1.z + e2 * p2.z) * ray.sz;
        let t = t_scaled / det;
        (t > t_min && t < t_max).then_some((t, [e0 / det, e1 / det, e2 / det]))
    }
}
