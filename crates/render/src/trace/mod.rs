//! Ray tracing from the Shading Language (issue 19): the frame's [`FrameShading`] is the
//! shaders' [`RayTracer`]. Rays run on the [`RayScene`] tessellation; a `trace()` hit is shaded
//! by its primitive's own surface shader and lights as a one-point grid (`hit.rs`), one level
//! deeper, so a mirror sees a mirror's reflection until `Option "trace" "maxdepth"`.
//!
//! Partly transparent surfaces: `trace()` composites the hits along the ray front to back
//! (`Ci` is premultiplied) until the ray is nearly opaque; `transmission()` multiplies
//! `1 − Os` of the shadow-visible surfaces flagged `"Os"`/`"shader"` and stops at the first
//! opaque one.
//!
//! The colour a ray brings back is attenuated by the `Interior`/`Exterior` of the surface it
//! leaves (`volume.rs`).
//!
//! The scene is built on first use when no light needed it up front; that build runs
//! sequentially (it may happen inside a shading task, where waiting on rayon work could
//! deadlock on the once-cell).
pub(crate) mod analytic;
pub(crate) mod hit;
pub(crate) mod shell;
mod volume;

use crate::rayscene::RayScene;
use crate::shading::FrameShading;
use glam::{DVec3, Vec3};
use illume_raytrace::NO_GROUP;
use illume_shade::{blocked_by_transmission, RayDifferential, RayStart, RayTracer, TraceHit};

/// Surfaces composited along one `trace()` ray before it counts as opaque.
const MAX_LAYERS: usize = 16;
/// Transmission below this stops the walk (the rest cannot change 8-bit output).
const OPAQUE: f32 = 1e-4;
/// Relative rounding part of the ray offset (as `illume_shade`'s shadow rays).
const ROUNDING_OFFSET: f64 = 2e-5;

impl FrameShading<'_> {
    /// Where a ray from `from` along `dir` starts: pushed off the surface, on the side of `Ng`
    /// the ray leaves through, by the primitive's tessellation bound plus a rounding term.
    fn ray_origin(&self, scene: &RayScene, from: &RayStart, dir: DVec3) -> DVec3 {
        let (p, ng, offset) = self.origin_frame(scene, from);
        let side = if ng.dot(dir) < 0.0 { -1.0 } else { 1.0 };
        p + ng * (side * offset)
    }

    /// What [`Self::ray_origin`] needs of the start whatever the direction: the point, the
    /// unit `Ng` and the offset along it.
    fn origin_frame(&self, scene: &RayScene, from: &RayStart) -> (DVec3, DVec3, f64) {
        let p = from.p.as_dvec3();
        let ng = from.ng.as_dvec3().normalize_or_zero();
        let offset = f64::from(scene.offset(from.primitive).max(0.0))
            + ROUNDING_OFFSET * p.abs().max_element();
        (p, ng, offset)
    }

    /// The step past a hit at `t` before looking for the next surface along the ray.
    fn past(t: f64) -> f64 {
        t + 1e-5 * (1.0 + t)
    }
}

impl RayTracer for FrameShading<'_> {
    fn trace(&self, from: &RayStart, dir: DVec3, depth: u32, shade: bool) -> Option<TraceHit> {
        let scene = self.ray_scene();
        let origin = self.ray_origin(scene, from, dir);
        let keep = |id: u32| scene.prim_of(id).traced;
        let skip = scene.skip(from.primitive, origin, dir);
        let nearest = |t_min: f64| {
            scene
                .bvh()
                .nearest_hit_except(origin, dir, (t_min, f64::INFINITY), skip, &keep)
        };
        let Some(first) = nearest(0.0) else {
            return if shade {
                self.missed_ray_volume(scene, from, dir, depth)
            } else {
                None
            };
        };
        let (grid, _) = hit::hit_grid(scene, &first, origin, dir, &RayDifferential::default());
        let flip = |prim: usize| {
            self.frame
                .primitives
                .get(prim)
                .map_or(1.0, |fp| fp.normal_sign())
        };
        let first_prim = scene.prim_index(first.triangle);
        let mut out = TraceHit {
            t: first.t,
            p: grid.p[0],
            n: grid.n[0] * flip(first_prim),
            ci: Vec3::ZERO,
            oi: Vec3::ZERO,
        };
        if !shade {
            return Some(out);
        }
        let mut through = Vec3::ONE;
        let mut hit = first;
        for _ in 0..MAX_LAYERS {
            let (grid, prim) = hit::hit_grid(scene, &hit, origin, dir, &from.beam);
            let Some(attrs) = scene.prim(prim).and_then(|p| p.attributes.clone()) else {
                break;
            };
            let incident = (dir * hit.t).as_vec3();
            let (ci, oi) = self.shade_hit(&grid, &attrs, flip(prim), prim, depth + 1, incident);
            out.ci += through * ci;
            through *= Vec3::ONE - oi.clamp(Vec3::ZERO, Vec3::ONE);
            if through.max_element() < OPAQUE {
                break;
            }
            match nearest(Self::past(hit.t)) {
                Some(next) => hit = next,
                None => break,
            }
        }
        out.oi = Vec3::ONE - through;
        self.ray_volume(from, dir, &mut out, depth);
        Some(out)
    }

    fn transmission(&self, from: &RayStart, dir: DVec3, t_max: f64) -> Vec3 {
        let scene = self.ray_scene();
        let origin = self.ray_origin(scene, from, dir);
        // Opaque casters first, with an any-hit query (the common case, and the cheap one);
        // then the partly transparent ones, nearest first.
        let opaque = |id: u32| {
            let p = scene.prim_of(id);
            p.shadow && !p.shadow_os
        };
        let skip = scene.skip(from.primitive, origin, dir);
        if scene
            .bvh()
            .occluded_except(origin, dir, (0.0, t_max), skip, &opaque)
        {
            return Vec3::ZERO;
        }
        if !scene.has_partial_casters() {
            return Vec3::ONE;
        }
        let keep = |id: u32| {
            let p = scene.prim_of(id);
            p.shadow && p.shadow_os
        };
        let mut through = Vec3::ONE;
        let mut t_min = 0.0;
        // Each surface crossed is found once: at most one step per triangle on the segment.
        while let Some(hit) =
            scene
                .bvh()
                .nearest_hit_except(origin, dir, (t_min, t_max), skip, &keep)
        {
            let os = hit::hit_opacity(scene, &hit).clamp(Vec3::ZERO, Vec3::ONE);
            through *= Vec3::ONE - os;
            if through.max_element() < OPAQUE {
                return Vec3::ZERO;
            }
            t_min = Self::past(hit.t);
        }
        through
    }

    /// One point's `occlusion()` rays: the origin on either side of the surface, the view of
    /// its own primitive's shell and a traversal stack are set up once for all of them
    /// (per ray they were a sixth of the rays' time, issue 19). Each ray gives the same
    /// answer as [`RayTracer::transmission`].
    fn blocked(&self, from: &RayStart, dirs: &[DVec3], t_max: f64) -> f64 {
        let scene = self.ray_scene();
        if scene.has_partial_casters() {
            return blocked_by_transmission(self, from, dirs, t_max);
        }
        let mut blocked = 0.0f64;
        let opaque = |id: u32| {
            let p = scene.prim_of(id);
            p.shadow && !p.shadow_os
        };
        // `ray_origin` for rays leaving below (0) and above (1) the side of `Ng`.
        let (p, ng, offset) = self.origin_frame(scene, from);
        let origins = [p + ng * -offset, p + ng * offset];
        let seen = origins.map(|o| scene.seen_from(from.primitive, o));
        let bvh = scene.bvh();
        let mut stack = bvh.stack();
        for &dir in dirs {
            let side = if ng.dot(dir) < 0.0 { 0 } else { 1 };
            let skip = match seen[side] {
                Some(s) if s.excludes(dir) => from.primitive as u32,
                _ => NO_GROUP,
            };
            let range = (0.0, t_max);
            let hit = bvh.occluded_with(&mut stack, origins[side], dir, range, skip, &opaque);
            // As `transmission`'s 0 or 1 in every channel.
            blocked += if hit { 1.0 } else { 0.0 };
        }
        blocked
    }

    fn max_depth(&self) -> u32 {
        self.trace_max_depth
    }
}
