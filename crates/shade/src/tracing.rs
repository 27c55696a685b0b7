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
