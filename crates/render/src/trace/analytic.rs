//! Quadrics in the ray scene (issue 19): a whole, undisplaced sphere, disk, cylinder or cone
//! goes into the BVH as one closed-form leaf ([`illume_raytrace::Quadric`]) instead of its
//! triangles. Shadow and occlusion rays then see the true surface, and one test replaces a
//! subtree of thousands of triangles (the spheres of the `occlusion` bench were 8k each).
//!
//! A hit on a quadric is shaded from its `(u, v)`: `P`, `dPdu`, `dPdv` and the normal are the
//! surface's own there (`Shape::eval`), and everything else the tessellation vertices carry
//! (`Cs`, `Os`, `s`, `t`, primitive variables) is interpolated bilinearly in the cell of the
//! regular (u, v) grid the quadric was diced into, which is exact for the bilinear primitive
//! variables quadrics have.
use glam::{DMat4, DVec3, Vec3};
use illume_geom::quadric::Shape;
use illume_geom::Grid;
use illume_raytrace::{Quadric, QuadricShape};

/// A quadric primitive's closed form and the layout of its coarse tessellation grid.
#[derive(Clone, Debug)]
pub(crate) struct Analytic {
    shape: Shape,
    camera_from_object: DMat4,
    /// Index of the grid's first vertex in the scene's vertices, and vertices per side.
    pub base: u32,
    cu: usize,
    cv: usize,
    /// The grid's parameter range `[u0, u1, v0, v1]`.
    range: [f64; 4],
}

/// The ray tracer's form of `shape` at `camera_from_object`, if it has one; `bound` is the
/// primitive's camera-space box.
pub(crate) fn ray_quadric(
    shape: &Shape,
    camera_from_object: DMat4,
    bound: (Vec3, Vec3),
) -> Option<Quadric> {
    let s = match *shape {
        Shape::Sphere {
            radius,
            phimin,
            phimax,
            thetamax,
        } => QuadricShape::Sphere {
            radius,
            phimin,
            phimax,
            thetamax,
        },
        Shape::Disk {
            height,
            radius,
            thetamax,
        } => QuadricShape::Disk {
            height,
            radius,
            thetamax,
        },
        Shape::Cylinder {
            radius,
            zmin,
            zmax,
            thetamax,
        } => QuadricShape::Cylinder {
            radius,
            zmin,
            zmax,
            thetamax,
        },
        Shape::Cone {
            height,
            radius,
            thetamax,
        } => QuadricShape::Cone {
            height,
            radius,
            thetamax,
        },
        _ => return None,
    };
    let object_from_camera = camera_from_object.inverse();
    if !s.supported() || !object_from_camera.is_finite() || !bound.0.is_finite() {
        return None;
    }
    // The primitive's box is rounded to f32: grow it by more than that rounding.
    let pad = Vec3::splat(1e-5 * bound.0.abs().max(bound.1.abs()).max_element() + 1e-6);
    Some(Quadric::new(
        s,
        object_from_camera,
        (bound.0 - pad, bound.1 + pad),
    ))
}

impl Analytic {
    /// The layout of the coarse grid of the diced `g` (its even vertices, as `hit_vertices`
    /// stores them from `base`).
    pub fn new(shape: Shape, camera_from_object: DMat4, g: &Grid, base: u32) -> Option<Analytic> {
        let (cu, cv) = (g.nu.div_ceil(2), g.nv.div_ceil(2));
        let last = g.len().checked_sub(1)?;
        let range = [
            f64::from(*g.u.first()?),
            f64::from(*g.u.get(last)?),
            f64::from(*g.v.first()?),
            f64::from(*g.v.get(last)?),
        ];
        let ok = cu >= 2 && cv >= 2 && range[1] != range[0] && range[3] != range[2];
        ok.then_some(Analytic {
            shape,
            camera_from_object,
            base,
            cu,
            cv,
            range,
        })
    }

    /// The four coarse vertices (scene indices) around `(u, v)` and their bilinear weights.
    pub fn corners(&self, u: f64, v: f64) -> [(u32, f64); 4] {
        let cell = |x: f64, lo: f64, hi: f64, n: usize| {
            let f = ((x - lo) / (hi - lo)).clamp(0.0, 1.0) * (n - 1) as f64;
            let i = (f.floor() as usize).min(n - 2);
            (i, f - i as f64)
        };
        let (i, fu) = cell(u, self.range[0], self.range[1], self.cu);
        let (j, fv) = cell(v, self.range[2], self.range[3], self.cv);
        let at = |i: usize, j: usize| self.base + (j * self.cu + i) as u32;
        [
            (at(i, j), (1.0 - fu) * (1.0 - fv)),
            (at(i + 1, j), fu * (1.0 - fv)),
            (at(i, j + 1), (1.0 - fu) * fv),
            (at(i + 1, j + 1), fu * fv),
        ]
    }

    /// Camera-space `dPdu`, `dPdv` and the unit geometric normal `dPdu × dPdv` at `(u, v)`
    /// (a zero normal at a pole).
    pub fn frame(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let [_, du, dv] = self.shape.eval(u, v);
        let m = &self.camera_from_object;
        let (du, dv) = (m.transform_vector3(du), m.transform_vector3(dv));
        (du, dv, du.cross(dv).normalize_or_zero())
    }

    /// The parameter offsets `(Δu, Δv)` that move the surface by `offset` (a vector in its
    /// tangent plane at `(u, v)`), by least squares on `dPdu`, `dPdv`.
    pub fn param_offset(&self, u: f64, v: f64, offset: DVec3) -> [f64; 2] {
        let (du, dv, _) = self.frame(u, v);
        let (a, b, c) = (du.dot(du), du.dot(dv), dv.dot(dv));
        let det = a * c - b * b;
        if det.abs() <= f64::MIN_POSITIVE || !det.is_finite() {
            return [0.0, 0.0];
        }
        let (x, y) = (offset.dot(du), offset.dot(dv));
        [(c * x - b * y) / det, (a * y - b * x) / det]
    }
}
