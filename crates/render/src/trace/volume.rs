//! `Interior`/`Exterior` on traced rays (RI 3.2 §9): the colour a `trace()` ray brings back is
//! attenuated by the volume shader of the space it crossed between the shaded point and the
//! hit.
//!
//! Which volume: the one of the surface the ray *leaves*, on the side it leaves through. With
//! `Ng` the shaded point's oriented geometric normal (the outside of the surface, as the
//! attributes' orientation says), a ray with `dot(dir, Ng) ≥ 0` leaves into the outside and
//! crosses the surface's `Exterior` (a reflection off a closed object, or any ray from an
//! open sheet's front); a ray with `dot(dir, Ng) < 0` goes into the object (a refraction) and
//! crosses its `Interior`. The hit surface's own volumes are not consulted: a ray that enters
//! a closed object is shaded at its far wall by that wall, whose next ray leaves again.
//!
//! The segment is one volume grid point: `P` the hit, `I = P − origin` (its length the
//! distance crossed), `E` the ray's origin, `Ci`/`Oi` what the hit surfaces composited.
//!
//! Rays that hit nothing: the volume runs over a segment from the origin to a far point with
//! `Ci = Oi = 0` behind it, so a reflection into fog sees the fog's colour rather than black
//! (as ray tracers that run volumes on every ray segment do: BMRT, RenderPipe; REYES PRMan
//! runs no `Atmosphere` where there is no geometry, and a miss there stays black). The far
//! point is at the camera's far clipping distance when one is set, otherwise where the ray
//! leaves the bounding box of the ray scene (a marching shader then takes a bounded number of
//! steps, and a volume farther than all geometry adds nothing a renderer could show). Such a
//! result comes back with `t = ∞`.
use crate::rayscene::RayScene;
use crate::shading::FrameShading;
use crate::volumes::{GridRelight, VolumeSlot};
use glam::{DVec3, Vec3};
use illume_shade::{LightCache, RayStart, ShadingGrid, TraceHit};
use illume_slvm::{LightSource, Lights, Messages};

impl FrameShading<'_> {
    /// Attenuates `hit.ci`/`hit.oi` by the volume the ray from `from` along `dir` crossed to
    /// reach it; `depth` is the depth of the tracing shader (the volume runs one deeper, as
    /// the hit was shaded). Nothing happens when that side of the surface has no volume.
    pub(super) fn ray_volume(&self, from: &RayStart, dir: DVec3, hit: &mut TraceHit, depth: u32) {
        let Some(fp) = self.frame.primitives.get(from.primitive) else {
            return;
        };
        let attrs = &fp.attributes;
        let slot = volume_side(from.ng, dir);
        if self.volumes.get(attrs, slot).is_none() {
            return;
        }
        let mut g = ShadingGrid::new(1, 1);
        g.p = vec![hit.p];
        g.i = vec![(hit.p.as_dvec3() - from.p.as_dvec3()).as_vec3()];
        g.n = vec![hit.n];
        g.ng = vec![hit.n];
        g.ci = vec![hit.ci];
        g.oi = vec![hit.oi];
        let mut env = self.env(attrs, from.primitive);
        env.ray_depth = depth + 1;
        // The lights of the surface that owns the volume, at the segment's end (and through
        // the relight hook at any point a marching shader asks for).
        let lights: Vec<&illume_shade::Light> = attrs
            .lights
            .iter()
            .filter_map(|&i| self.lights.get(i).and_then(Option::as_ref))
            .collect();
        let messages = Messages::default();
        let mut cache = LightCache::run(&lights, &g, &env);
        let builtin_count = cache.lights.len();
        let mut sl_outputs = Vec::new();
        for (proxy, samples, outputs) in self.sl.run_lights(&attrs.lights, &g, &env, &messages) {
            cache.lights.push((proxy, samples));
            sl_outputs.push(outputs);
        }
        let mut view = Lights::from_cache(&cache);
        for (light, outputs) in view.lights[builtin_count..].iter_mut().zip(&sl_outputs) {
            if let LightSource::Builtin(request) = light.source {
                light.source = LightSource::Sl { outputs, request };
            }
        }
        let relight = GridRelight {
            builtin: &lights,
            sl: &self.sl,
            indices: &attrs.lights,
            env: &env,
            messages: &messages,
        };
        let nonfinite = self.volumes.volume_along(
            attrs,
            slot,
            &mut g,
            &env,
            &view,
            Some(&relight),
            Some(from.p),
        );
        if nonfinite > 0 {
            self.nonfinite
                .fetch_add(nonfinite as u64, std::sync::atomic::Ordering::Relaxed);
        }
        hit.ci = g.ci[0];
        hit.oi = g.oi[0];
    }
}

impl FrameShading<'_> {
    /// [`FrameShading::ray_volume`] for a ray that hit nothing (module comment); `None` when
    /// the side it leaves through has no volume.
    pub(super) fn missed_ray_volume(
        &self,
        scene: &RayScene,
        from: &RayStart,
        dir: DVec3,
        depth: u32,
    ) -> Option<TraceHit> {
        let attrs = &self.frame.primitives.get(from.primitive)?.attributes;
        self.volumes.get(attrs, volume_side(from.ng, dir))?;
        let far = miss_distance(self.frame.camera.far, scene.bvh().bound(), from.p, dir)?;
        let mut out = TraceHit {
            t: f64::INFINITY,
            p: (from.p.as_dvec3() + dir * far).as_vec3(),
            n: (-dir).as_vec3(),
            ci: Vec3::ZERO,
            oi: Vec3::ZERO,
        };
        self.ray_volume(from, dir, &mut out, depth);
        out.t = f64::INFINITY;
        Some(out)
    }
}

/// How far a missing ray's volume segment reaches: the far clipping distance when it is
/// finite, otherwise the exit from the scene's box `bound` (grown to hold the origin);
/// `None` when that is no distance at all.
pub(crate) fn miss_distance(
    far: f64,
    bound: Option<(Vec3, Vec3)>,
    origin: Vec3,
    dir: DVec3,
) -> Option<f64> {
    let d = if far.is_finite() && far > 0.0 {
        far
    } else {
        let (lo, hi) = bound?;
        let (lo, hi) = (lo.min(origin).as_dvec3(), hi.max(origin).as_dvec3());
        let o = origin.as_dvec3();
        // The exit: the nearest far slab plane along the ray.
        (0..3)
            .filter(|&k| dir[k] != 0.0)
            .map(|k| {
                let plane = if dir[k] > 0.0 { hi[k] } else { lo[k] };
                (plane - o[k]) / dir[k]
            })
            .fold(f64::INFINITY, f64::min)
    };
    (d.is_finite() && d > 0.0).then_some(d)
}

/// The volume a ray along `dir` crosses when it leaves a surface whose oriented geometric
/// normal is `ng`: `Exterior` on the normal's side (a zero normal counts as outside).
pub(crate) fn volume_side(ng: Vec3, dir: DVec3) -> VolumeSlot {
    if ng.as_dvec3().dot(dir) < 0.0 {
        VolumeSlot::Interior
    } else {
        VolumeSlot::Exterior
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_ray_reaches_the_far_plane_or_the_box_exit() {
        let b = Some((Vec3::splat(-1.0), Vec3::splat(2.0)));
        assert_eq!(miss_distance(50.0, b, Vec3::ZERO, DVec3::X), Some(50.0));
        assert_eq!(
            miss_distance(f64::INFINITY, b, Vec3::ZERO, DVec3::X),
            Some(2.0)
        );
        let diag = DVec3::new(1.0, -1.0, 0.0).normalize();
        let d = miss_distance(f64::INFINITY, b, Vec3::ZERO, diag).unwrap();
        assert!((d - std::f64::consts::SQRT_2).abs() < 1e-12);
        // An origin outside the box counts as inside it (grown), so a segment is never negative.
        assert_eq!(
            miss_distance(f64::INFINITY, b, Vec3::splat(5.0), DVec3::X),
            None
        );
        assert_eq!(
            miss_distance(f64::INFINITY, None, Vec3::ZERO, DVec3::X),
            None
        );
    }
}
