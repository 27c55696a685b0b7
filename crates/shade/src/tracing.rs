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
/// belongs to (for that primitive's ray offset).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayStart {
    pub p: Vec3,
    pub ng: Vec3,
    pub primitive: usize,
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
