//! `shadow(name, P | P1 … P4)`: percentage-closer filtering of a depth map (Reeves, Salesin and
//! Cook 1987; chapter 9.6.3).
//!
//! The points go to the light's NDC through `worldToNDC` and to its camera depth through
//! `worldToCamera`. The footprint (bounding box of the four corners × width, plus blur, in NDC) is
//! first tested against the min/max pyramid: entirely nearer than the minimum depth means fully
//! lit, entirely beyond the maximum fully shadowed, with no sampling. Otherwise `samples`
//! stratified, deterministically jittered depth tests are averaged (jitter hashed from the lookup
//! position, so results never depend on threads or call order).

use crate::cache::TextureKind;
use crate::lookup::LookupOptions;
use crate::sampler::Sampler;
use crate::{TextureCache, TextureError};
use glam::{DVec4, Vec3};

use illume_core::hash::splitmix64 as mix;

fn unit(h: u64) -> f32 {
    (h >> 40) as f32 / (1u64 << 24) as f32
}

impl TextureCache {
    /// Fraction of the footprint in shadow: 0 fully lit, 1 fully occluded.
    pub fn shadow(
        &self,
        name: &str,
        p_world: [Vec3; 4],
        opts: &LookupOptions,
    ) -> Result<f32, TextureError> {
        let f = self.file(name)?;
        let (Some(to_ndc), Some(to_cam)) = (f.world_to_ndc, f.world_to_camera) else {
            return Err(TextureError::WrongKind {
                path: f.path.clone(),
                expected: "shadow map",
                found: if f.kind == TextureKind::Shadow {
                    "shadow map without worldToNDC/worldToCamera"
                } else {
                    "texture without worldToNDC/worldToCamera"
                },
            });
        };
        let (w, h) = f.levels[0];
        let mut smin = f64::INFINITY;
        let mut smax = f64::NEG_INFINITY;
        let mut tmin = f64::INFINITY;
        let mut tmax = f64::NEG_INFINITY;
        let mut z = 0.0f64;
        for p in p_world {
            let hp = DVec4::new(p.x as f64, p.y as f64, p.z as f64, 1.0);
            let q = to_ndc * hp;
            if q.w <= 0.0 {
                return Ok(0.0); // behind the light camera: not in the map
            }
            let (s, t) = (q.x / q.w, q.y / q.w);
            smin = smin.min(s);
            smax = smax.max(s);
            tmin = tmin.min(t);
            tmax = tmax.max(t);
            z += (to_cam * hp).z;
        }
        let z = (z * 0.25) as f32 - opts.bias;
        let (sc, tc) = (0.5 * (smin + smax), 0.5 * (tmin + tmax));
        let ws = (smax - smin) * opts.swidth as f64 + (opts.blur + opts.sblur) as f64;
        let wt = (tmax - tmin) * opts.twidth as f64 + (opts.blur + opts.tblur) as f64;
        let (s0, s1) = (sc - 0.5 * ws, sc + 0.5 * ws);
        let (t0, t1) = (tc - 0.5 * wt, tc + 0.5 * wt);
        if s1 < 0.0 || s0 > 1.0 || t1 < 0.0 || t0 > 1.0 {
            return Ok(0.0);
        }
        let mut sampler = Sampler::new(self, &f);
        let mut texel = [0.0f32; 8];
        let zc = f.order.first().copied().unwrap_or(0);
        // Texel range of the footprint at level 0.
        let tx = |s: f64| ((s * w as f64).floor() as i64).clamp(0, w as i64 - 1) as usize;
        let ty = |t: f64| ((t * h as f64).floor() as i64).clamp(0, h as i64 - 1) as usize;
        let (x0, x1, y0, y1) = (tx(s0), tx(s1), ty(t0), ty(t1));
        let fully_inside = s0 >= 0.0 && s1 <= 1.0 && t0 >= 0.0 && t1 <= 1.0;
        if let (Some(zmax), true) = (f.zmax, fully_inside) {
            // Coarsest level where the footprint spans at most 2×2 texels.
            let mut l = 0usize;
            while l + 1 < f.levels.len() && ((x1 >> l) - (x0 >> l) > 1 || (y1 >> l) - (y0 >> l) > 1)
            {
                l += 1;
            }
            let (lw, lh) = f.levels[l];
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            for yy in (y0 >> l).min(lh - 1)..=(y1 >> l).min(lh - 1) {
                for xx in (x0 >> l).min(lw - 1)..=(x1 >> l).min(lw - 1) {
                    sampler.texel(l, xx, yy, &mut texel)?;
                    lo = lo.min(texel[zc]);
                    hi = hi.max(texel[zmax]);
                }
            }
            if z <= lo {
                return Ok(0.0);
            }
            if z > hi {
                return Ok(1.0);
            }
        }
        let n = opts.samples.max(1) as usize;
        let gx = (n as f64).sqrt().ceil() as usize;
        let gy = n.div_ceil(gx);
        let seed = mix(sc.to_bits() ^ mix(tc.to_bits()));
        let mut occluded = 0usize;
        for i in 0..n {
            let hash = mix(seed ^ (i as u64).wrapping_mul(0x9e3779b97f4a7c15));
            let (cx, cy) = (i % gx, i / gx);
            let u = (cx as f32 + unit(hash)) / gx as f32;
            let v = (cy as f32 + unit(mix(hash))) / gy as f32;
            let s = s0 + u as f64 * ws;
            let t = t0 + v as f64 * wt;
            if !(0.0..1.0).contains(&s) || !(0.0..1.0).contains(&t) {
                continue;
            }
            sampler.texel(0, tx(s), ty(t), &mut texel)?;
            if z > texel[zc] {
                occluded += 1;
            }
        }
        Ok(occluded as f32 / n as f32)
    }
}
