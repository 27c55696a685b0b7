//! The traversal's ray-box test in `f32` SIMD lanes (glam's `Vec3A`), conservative by
//! construction: the tree's boxes are grown by [`pad`] of the scene's size, more than the
//! rounding of an `f32` slab test can move a ray (origin rounded to `f32`, one subtraction and
//! one product per slab: a few `f32` ulps of `|origin| + |box|`), so a ray the exact `f64`
//! triangle test hits always enters every box on the way. Rays whose origin lies far outside
//! the scene (where the padding would not cover their rounding) take the `f64` test instead.
//!
//! Why: the `f64` test with its NaN checks was most of an `occlusion()` frame's time (issue
//! 19: 16 rays per shaded point); four `f32` lanes and no branches per slab halve the
//! traversal.
//!
//! Parallel slabs: a zero direction component becomes ±[`TINY`] (its inverse finite), so an
//! origin on the slab's plane gives `0` rather than `0·∞ = NaN`: the boundary counts as
//! inside, as in the `f64` test, and elsewhere the slab's interval lies beyond any finite
//! `t_max` or is conservative (a box visited needlessly, never one missed).
use crate::triangle::PreparedRay;
use glam::{DVec3, Vec3, Vec3A};

/// A direction component's magnitude below which it counts as this (keeps the inverse finite).
const TINY: f32 = 1e-30;
/// The padding of every box, relative to the scene's largest coordinate (2⁻¹⁸ ≈ 3.8e-6: about
/// eight times the worst rounding of the `f32` test for origins inside the scene's cube).
const PAD: f32 = 1.0 / 262_144.0;
/// Origins up to this multiple of the scene's size still take the `f32` test (their rounding,
/// ≈ 5e-7·(|o| + 2·scale), stays under the padding).
const ORIGIN_REACH: f64 = 2.0;
/// Growth of the far distance, as the `f64` test's `1 + 4ε`, for `t_max`'s own rounding.
pub(crate) const FAR_GROWTH: f32 = 1.0 + 1.0 / 1_048_576.0;

/// How much every box is grown for a scene whose largest coordinate magnitude is `scale`.
pub(crate) fn pad(scale: f32) -> f32 {
    scale * PAD
}

/// A ray prepared for the `f32` box test.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlabRay {
    origin: Vec3A,
    inv_dir: Vec3A,
}

impl SlabRay {
    /// `None` when the origin lies too far outside a scene of size `scale` for the padding to
    /// cover its rounding (the caller uses the `f64` test).
    pub fn new(origin: DVec3, dir: DVec3, scale: f32) -> Option<SlabRay> {
        if origin.abs().max_element() > ORIGIN_REACH * f64::from(scale) {
            return None;
        }
        let d = dir.as_vec3();
        let safe = |c: f32| {
            if c.abs() < TINY {
                TINY.copysign(c)
            } else {
                c
            }
        };
        let d = Vec3::new(safe(d.x), safe(d.y), safe(d.z));
        Some(SlabRay {
            origin: Vec3A::from(origin.as_vec3()),
            inv_dir: Vec3A::ONE / Vec3A::from(d),
        })
    }

    pub fn origin(&self) -> Vec3A {
        self.origin
    }

    pub fn inv_dir(&self) -> Vec3A {
        self.inv_dir
    }
}

/// The exact slab test in `f64` against `(0, t_max)`: where the ray enters the box, if it
/// meets it. The `f32` box is exact in `f64`, and the `1 + 4ε` growth of the far distance
/// (pbrt's `gamma(3)` argument) keeps a ray grazing a face from missing the box of a
/// triangle it hits.
pub(crate) fn exact_entry(min: Vec3, max: Vec3, ray: &PreparedRay, t_max: f64) -> Option<f64> {
    let (mut t0, mut t1) = (0.0f64, t_max);
    for k in 0..3 {
        let a = (f64::from(min[k]) - ray.origin[k]) * ray.inv_dir[k];
        let b = (f64::from(max[k]) - ray.origin[k]) * ray.inv_dir[k];
        // NaN is 0·∞: the origin lies on a slab plane the ray runs parallel to, so the
        // slab does not constrain the ray (the boundary counts as inside).
        if a.is_nan() || b.is_nan() {
            continue;
        }
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    let t1 = t1 * (1.0 + 4.0 * f64::EPSILON);
    (t0 <= t1).then_some(t0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_exact_test_counts_a_face_plane_as_inside() {
        let ray = PreparedRay::new(DVec3::new(-1.0, 0.0, 0.5), DVec3::X).unwrap();
        assert_eq!(exact_entry(Vec3::ZERO, Vec3::ONE, &ray, 10.0), Some(1.0));
        let ray = PreparedRay::new(DVec3::new(-1.0, -0.01, 0.5), DVec3::X).unwrap();
        assert_eq!(exact_entry(Vec3::ZERO, Vec3::ONE, &ray, 10.0), None);
    }

    #[test]
    fn far_origins_are_refused() {
        assert!(SlabRay::new(DVec3::splat(100.0), DVec3::X, 10.0).is_none());
    }
}
