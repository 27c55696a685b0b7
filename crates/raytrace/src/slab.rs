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
const FAR_GROWTH: f32 = 1.0 + 1.0 / 1_048_576.0;

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

    /// Whether the ray meets the (padded) box within `(0, t_max)`.
    #[inline]
    pub fn hits(&self, min: Vec3, max: Vec3, t_max: f32) -> bool {
        let a = (Vec3A::from(min) - self.origin) * self.inv_dir;
        let b = (Vec3A::from(max) - self.origin) * self.inv_dir;
        let t0 = a.min(b).max_element().max(0.0);
        let t1 = a.max(b).min_element().min(t_max * FAR_GROWTH);
        t0 <= t1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_origin_on_a_face_plane_running_along_it_is_inside() {
        let r = SlabRay::new(DVec3::new(-1.0, 0.0, 0.5), DVec3::X, 10.0).unwrap();
        assert!(r.hits(Vec3::ZERO, Vec3::ONE, 10.0));
        let r = SlabRay::new(DVec3::new(-1.0, -0.01, 0.5), DVec3::X, 10.0).unwrap();
        assert!(!r.hits(Vec3::ZERO, Vec3::ONE, 10.0));
    }

    #[test]
    fn far_origins_are_refused() {
        assert!(SlabRay::new(DVec3::splat(100.0), DVec3::X, 10.0).is_none());
    }
}
