//! Ray tracing as shaders see it (BMRT's `trace`, `visibility`, `fulltrace`, `rayhittest`,
//! PRMan's `transmission` and `occlusion`): the renderer answers through [`RayTracer`], so this
//! crate never depends on the ray tracer or on how the renderer shades a hit point.
//!
//! Every ray starts at a shaded point `P` (with its geometric normal `Ng`); the tracer pushes it
//! off the surface by the renderer's bound on its tessellation error (the same offset shadow
//! rays use), so a surface never hits its own chords.
use glam::{DVec3, Vec3};

/// What a traced ray saw: the nearest surface's shaded colour and opacity, and where it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceHit {
    /// Distance along the (unit) ray direction.
    pub t: f64,
    /// The hit point and its oriented shading normal, camera space.
    pub p: Vec3,
    pub n: Vec3,
    /// `Ci` and `Oi` of the hit point's surface shader (zero when not shaded).
    pub ci: Vec3,
    pub oi: Vec3,
}

/// Where a ray leaves from: the shaded point, its geometric normal and the frame primitive it
/// belongs to (for that primitive's ray offset), and the beam around the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayStart {
    pub p: Vec3,
    pub ng: Vec3,
    pub primitive: usize,
    pub beam: RayDifferential,
}

/// A ray's differentials (Igehy, "Tracing Ray Differentials", SIGGRAPH 1999; pbrt-v4's
/// `RayDifferential`): how its origin and unit direction change from the shaded point to its
/// two grid neighbours. Carried to a hit, they give the footprint the hit is shaded over, so
/// a texture lookup there is filtered over what the beam covers. All zero: no beam.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayDifferential {
    pub dp: [Vec3; 2],
    pub dd: [Vec3; 2],
}

impl RayDifferential {
    pub fn is_none(&self) -> bool {
        self.dp == [Vec3::ZERO; 2] && self.dd == [Vec3::ZERO; 2]
    }

    /// The two offsets of the hit point for a ray along the unit `dir` hitting a surface
    /// with normal `n` at distance `t` (Igehy's transfer: the offset rays meet the hit's
    /// tangent plane); `None` when the ray grazes that plane.
    pub fn transfer(&self, dir: DVec3, t: f64, n: DVec3) -> Option<[DVec3; 2]> {
        let dn = dir.dot(n);
        if dn.abs() < 1e-9 || !t.is_finite() {
            return None;
        }
        let at = |k: usize| {
            let d = self.dp[k].as_dvec3() + self.dd[k].as_dvec3() * t;
            d - dir * (d.dot(n) / dn)
        };
        Some([at(0), at(1)])
    }
}

/// The renderer's ray tracer. Implementations must be deterministic: the answer depends on
/// the ray only, never on threads.
pub trait RayTracer: Send + Sync {
    /// The nearest surface visible to reflection rays along the unit `dir` from `from`, shaded
    /// by its own surface shader and lights when `shade` (its `Ci`/`Oi` come back), at ray
    /// depth `depth` (the hit is shaded at `depth + 1`). `None` when nothing is hit.
    fn trace(&self, from: &RayStart, dir: DVec3, depth: u32, shade: bool) -> Option<TraceHit>;

    /// The fraction of light that reaches `from + dir·t_max` from `from` through the geometry
    /// that shadow rays see, per channel: the product of `1 − Os` over every surface crossed
    /// (opaque geometry gives 0).
    fn transmission(&self, from: &RayStart, dir: DVec3, t_max: f64) -> Vec3;

    /// The blocked part of each ray from `from` along the unit `dirs` within `t_max`
    /// (`1 −` the mean over channels of [`RayTracer::transmission`]), summed in order: what
    /// `occlusion()` needs of one shaded point. A tracer may override it to share the
    /// point's set-up among its rays; the sum must stay the same bits.
    fn blocked(&self, from: &RayStart, dirs: &[DVec3], t_max: f64) -> f64 {
        blocked_by_transmission(self, from, dirs, t_max)
    }

    /// `Option "trace" "maxdepth"`: rays at this depth return black.
    fn max_depth(&self) -> u32;
}

/// `visibility(P1, P2)` etc. need a unit direction and the distance; `None` when the points
/// coincide (nothing lies between them).
pub fn segment(from: Vec3, to: Vec3) -> Option<(DVec3, f64)> {
    let d = to.as_dvec3() - from.as_dvec3();
    let len = d.length();
    (len > 0.0 && len.is_finite()).then(|| (d / len, len))
}

/// A cosine-weighted direction about the unit normal `n` from two uniform numbers
/// (Malley's method: a uniform disk sample lifted to the hemisphere), the distribution whose
/// unoccluded fraction is PRMan's `occlusion()` weighting.
pub fn cosine_direction(n: DVec3, (a, b): (f64, f64)) -> DVec3 {
    let r = a.sqrt();
    let phi = std::f64::consts::TAU * b;
    let (x, y) = (r * phi.cos(), r * phi.sin());
    let z = (1.0 - a).max(0.0).sqrt();
    let (t, s) = orthonormal(n);
    (t * x + s * y + n * z).normalize_or_zero()
}

/// Stratified cosine-weighted directions for `occlusion()`, prepared once per sample count:
/// an `nx × ny` grid of strata of the unit square (`nx = ⌊√n⌋`; the `n − nx·ny` left over
/// on the R2 sequence, shifted per point). Per point, the angular coordinate of every stratum
/// is its midpoint shifted by one hashed angle (a rotation about the normal: the strata of a
/// periodic coordinate stay strata, and each sample is still uniform), and the radial one is
/// jittered within its stratum by a cheap hash per sample; then lifted to the hemisphere as
/// [`cosine_direction`] does (Malley's method).
///
/// Why: three hashes, a `sin`/`cos` and a normal frame per sample were a quarter of the time
/// of an `occlusion()` ray (issue 19); here the angle costs one rotation per point.
#[derive(Clone, Debug)]
pub struct CosinePattern {
    /// Radial strata.
    nx: u32,
    /// Per sample: its radial stratum (`u32::MAX`: an R2 point, whose radial coordinate is
    /// `r2`), and the cosine and sine of `2π·` its angular coordinate.
    strata: Vec<(u32, f64, f64, f64)>,
}

impl CosinePattern {
    pub fn new(n: u32) -> CosinePattern {
        let n = n.max(1);
        let nx = (f64::from(n).sqrt().floor() as u32).max(1);
        let ny = n / nx;
        let strata = (0..n)
            .map(|k| {
                let (i, a, b) = if k < nx * ny {
                    let (i, j) = (k % nx, k / nx);
                    (i, 0.0, (f64::from(j) + 0.5) / f64::from(ny))
                } else {
                    // R2 (Roberts 2018): the plastic number's powers.
                    let k = f64::from(k);
                    (
                        u32::MAX,
                        (0.5 + k * 0.754_877_666_246_692_8).fract(),
                        (0.5 + k * 0.569_840_290_998_053_2).fract(),
                    )
                };
                let (sin, cos) = (std::f64::consts::TAU * b).sin_cos();
                (i, a, cos, sin)
            })
            .collect();
        CosinePattern { nx, strata }
    }

    pub fn len(&self) -> usize {
        self.strata.len()
    }

    pub fn is_empty(&self) -> bool {
        self.strata.is_empty()
    }

    /// The pattern's directions about the unit normal `n` for a point whose two uniform
    /// numbers are `shift` and whose hash is `seed`, to `each` in sample order.
    pub fn directions(&self, n: DVec3, shift: (f64, f64), seed: u32, mut each: impl FnMut(DVec3)) {
        let (t, s) = orthonormal(n);
        let (sin, cos) = (std::f64::consts::TAU * shift.1).sin_cos();
        let nx = f64::from(self.nx);
        for (k, &(i, r2, ck, sk)) in (0u32..).zip(&self.strata) {
            let a = if i == u32::MAX {
                (r2 + shift.0).fract()
            } else {
                let h = crate::hash::lowbias32(seed ^ k.wrapping_mul(0x9e37_79b9));
                (f64::from(i) + f64::from(h >> 8) * (1.0 / 16_777_216.0)) / nx
            };
            let r = a.sqrt();
            let (c, sn) = (ck * cos - sk * sin, sk * cos + ck * sin);
            let z = (1.0 - a).max(0.0).sqrt();
            each(t * (r * c) + s * (r * sn) + n * z);
        }
    }
}

/// Two unit vectors completing `n` to an orthonormal frame (Duff et al. 2017).
fn orthonormal(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// [`RayTracer::blocked`] ray by ray through [`RayTracer::transmission`]: its default, and
/// what a tracer that overrides it falls back on where it cannot share the set-up.
pub fn blocked_by_transmission<T: RayTracer + ?Sized>(
    tracer: &T,
    from: &RayStart,
    dirs: &[DVec3],
    t_max: f64,
) -> f64 {
    let mut blocked = 0.0f64;
    for &dir in dirs {
        let through = tracer.transmission(from, dir, t_max);
        blocked += 1.0 - f64::from(through.x + through.y + through.z) / 3.0;
    }
    blocked
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parallel_beam_keeps_its_width_and_a_spreading_one_grows_with_distance() {
        // Rays along +z from (0,0,0) and its neighbours 0.1 away, onto the plane z = t.
        let beam = RayDifferential {
            dp: [Vec3::new(0.1, 0.0, 0.0), Vec3::new(0.0, 0.1, 0.0)],
            dd: [Vec3::ZERO; 2],
        };
        let [dx, dy] = beam.transfer(DVec3::Z, 5.0, DVec3::NEG_Z).unwrap();
        assert!((dx - DVec3::new(0.1, 0.0, 0.0)).length() < 1e-7);
        assert!((dy - DVec3::new(0.0, 0.1, 0.0)).length() < 1e-7);
        // Spreading by 0.01 per unit length: 0.1 + 0.01·t wide at t; a plane tilted by 45°
        // about y stretches the x offset by √2 (the beam meets it obliquely).
        let spread = RayDifferential {
            dd: [Vec3::new(0.01, 0.0, 0.0), Vec3::ZERO],
            ..beam
        };
        let [dx, _] = spread.transfer(DVec3::Z, 10.0, DVec3::NEG_Z).unwrap();
        assert!((dx.x - 0.2).abs() < 1e-7);
        let n = DVec3::new(1.0, 0.0, -1.0).normalize();
        let [dx, _] = spread.transfer(DVec3::Z, 10.0, n).unwrap();
        assert!((dx.length() - 0.2 * 2f64.sqrt()).abs() < 1e-6);
        assert!(spread.transfer(DVec3::Z, 1.0, DVec3::X).is_none());
    }

    #[test]
    fn pattern_directions_are_cosine_weighted_on_average() {
        // E[cos θ] = 2/3 and E[cos² θ] = 1/2 under the cosine density. The mean over 256
        // points of 64-sample estimates (18 of them R2 points) has a standard error below
        // 5e-4 (one point's is ≈ 0.005: radial jitter within 7 strata); 2e-3 is 4σ.
        let n = DVec3::new(-0.2, 0.9, 0.1).normalize();
        let pattern = CosinePattern::new(67);
        let (mut c1, mut c2, mut count) = (0.0, 0.0, 0);
        for point in 0..256u32 {
            let h = crate::hash::lowbias32(point);
            let unit = |h: u32| f64::from(h >> 8) / 16_777_216.0;
            let shift = (unit(h), unit(crate::hash::lowbias32(h)));
            pattern.directions(n, shift, h ^ 0x1234, |d| {
                assert!((d.length() - 1.0).abs() < 1e-12 && d.dot(n) >= 0.0);
                c1 += d.dot(n);
                c2 += d.dot(n) * d.dot(n);
                count += 1;
            });
        }
        assert_eq!(count, 256 * 67);
        let (c1, c2) = (c1 / f64::from(count), c2 / f64::from(count));
        assert!((c1 - 2.0 / 3.0).abs() < 2e-3, "E[cos] {c1}");
        assert!((c2 - 0.5).abs() < 2e-3, "E[cos²] {c2}");
    }

    #[test]
    fn cosine_directions_stay_in_the_hemisphere_and_average_two_thirds() {
        let n = DVec3::new(0.3, -0.5, 0.8).normalize();
        let mut sum = 0.0;
        let k = 64;
        for i in 0..k {
            for j in 0..k {
                let u = ((i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64);
                let d = cosine_direction(n, u);
                assert!((d.length() - 1.0).abs() < 1e-12);
                assert!(d.dot(n) >= 0.0);
                sum += d.dot(n);
            }
        }
        // E[cos θ] under the cosine density is 2/3.
        assert!((sum / (k * k) as f64 - 2.0 / 3.0).abs() < 1e-3);
    }
}
