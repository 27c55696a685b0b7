//! Ray-traced visibility as the lights see it (BMRT's `shadow("raytrace", …)`,
//! `Attribute "light" "shadows" ["on"]`, area lights): the renderer answers "is anything between
//! here and there?" through [`Occlusion`], so this crate never depends on the ray tracer.
//!
//! Rays start on the shaded surface, pushed off it along `Ng` by [`ShadingEnv::ray_offset`]
//! (the renderer's bound on how far its ray-tracing tessellation lies from the true surface)
//! plus a float-rounding term proportional to `|P|`: the shading points lie on the true
//! surface, the occluding triangles on chords inside a convex one, and without the push a lit
//! curved surface would shadow itself (acne).
use crate::hash::lowbias32 as hash;
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::{DVec3, Vec3};

/// Shadow-ray queries against the scene's shadow-casting geometry, camera space.
pub trait Occlusion: Send + Sync {
    /// Whether anything blocks `origin + t·dir` for `t ∈ (0, t_max)`.
    fn occluded(&self, origin: DVec3, dir: DVec3, t_max: f64) -> bool;
}

/// Relative size of the rounding part of the offset: the f32 shading points and triangle
/// vertices carry ~6e-8·|P| error each; 2e-5 leaves a wide margin yet stays far below any
/// feature a shadow should resolve.
const ROUNDING_OFFSET: f64 = 2e-5;

/// The start of a shadow ray from grid point `i` toward `dir`: pushed off the surface on the
/// side of `Ng` the ray leaves through.
pub(crate) fn ray_origin(grid: &ShadingGrid, i: usize, dir: DVec3, env: &ShadingEnv) -> DVec3 {
    let p = grid.p[i].as_dvec3();
    let ng = grid.ng[i].as_dvec3();
    let side = if ng.dot(dir) < 0.0 { -1.0 } else { 1.0 };
    let offset = f64::from(env.ray_offset.max(0.0)) + ROUNDING_OFFSET * p.abs().max_element();
    p + ng * (side * offset)
}

/// Two uniform numbers for sample `k` of a shaded point: a hash of the point's position, the
/// sample, the light and the frame only, so images do not depend on threads or buckets.
pub(crate) fn point_random(p: Vec3, k: u32, stream: u32) -> (f64, f64) {
    let h = hash(
        p.x.to_bits()
            ^ hash(
                p.y.to_bits() ^ hash(p.z.to_bits() ^ hash(k.wrapping_mul(0x9e37_79b9) ^ stream)),
            ),
    );
    let unit = |h: u32| f64::from(h >> 8) * (1.0 / 16_777_216.0);
    (unit(hash(h ^ 0x68bc_21eb)), unit(hash(h ^ 0x02e5_be93)))
}

/// Jittered stratified sample `k` of `n` in the unit square: an `nx × ny` grid of strata
/// (`nx = ⌊√n⌋`), the `n − nx·ny` left over drawn uniformly.
pub(crate) fn stratified(k: u32, n: u32, (a, b): (f64, f64)) -> (f64, f64) {
    let nx = (f64::from(n).sqrt().floor() as u32).max(1);
    let ny = n / nx;
    if k >= nx * ny {
        return (a, b);
    }
    let (i, j) = (k % nx, k / nx);
    (
        (f64::from(i) + a) / f64::from(nx),
        (f64::from(j) + b) / f64::from(ny),
    )
}

/// Stratified sample `k` of `n` for a point at `p`, numbers hashed from the point, the sample
/// and `stream` (as the built-in lights draw theirs): for the SL ray-tracing calls.
pub fn stratified_sample(p: Vec3, k: u32, n: u32, stream: u32) -> (f64, f64) {
    stratified(k, n, point_random(p, k, stream))
}
