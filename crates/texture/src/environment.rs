//! `environment(name[channel], D | D1 … D4)` on cube-face and lat-long maps.
//!
//! The footprint is laid out on the sphere, not on a face: probes are directions around the
//! centre direction in its tangent plane, so the probe pattern does not change when the centre
//! crosses a face edge. Each probe picks its own face and mip level (the level follows the local
//! texel solid angle, which shrinks as `r^1.5` toward face corners), and OpenEXR's layout puts
//! duplicated texels on every edge (welded bit-identical by the builder), so bilinear probes are
//! continuous across edges and corners: no seam at any blur.

use crate::cache::{TexFile, TextureKind};
use crate::cubeface::{coord_to_texel, face_coords};
use crate::lookup::{footprint, probe_grid, LookupOptions};
use crate::sampler::Sampler;
use crate::wrapmode::WrapMode;
use crate::{TextureCache, TextureError};
use glam::Vec3;
use std::f32::consts::PI;

/// Lat-long (s,t) of a direction in the RenderMan (z-up) orientation, as OpenImageIO reads
/// PRMan lat-long maps: +z is the top row (t = θ/π from +z) and s = ½ + φ/2π with
/// φ = atan2(y, x), so −x is at the left edge, +x in the middle, +y at s = ¾.
pub fn latlong_st(d: Vec3) -> (f32, f32) {
    let d = d.normalize_or_zero();
    let t = d.z.clamp(-1.0, 1.0).acos() / PI;
    let s = (0.5 + d.y.atan2(d.x) / (2.0 * PI)).rem_euclid(1.0);
    (s, t)
}

/// Inverse of [`latlong_st`].
pub fn latlong_direction(s: f32, t: f32) -> Vec3 {
    let (phi, theta) = ((s - 0.5) * 2.0 * PI, t * PI);
    Vec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

impl TextureCache {
    /// Filtered environment lookup over the cone of the four directions (grid order like
    /// `texture`); all four equal means a point lookup. `blur` is in face widths (1.0 = 90°).
    pub fn environment(
        &self,
        name: &str,
        first_channel: usize,
        nchannels: usize,
        dirs: [Vec3; 4],
        opts: &LookupOptions,
    ) -> Result<[f32; 4], TextureError> {
        let f = self.file(name)?;
        if f.kind == TextureKind::Shadow {
            return Err(TextureError::WrongKind {
                path: f.path.clone(),
                expected: "environment map",
                found: "shadow map",
            });
        }
        let d: Vec<Vec3> = dirs.iter().map(|d| d.normalize_or_zero()).collect();
        let c = (d[0] + d[1] + d[2] + d[3]).normalize_or_zero();
        let mut s = Sampler::new(self, &f);
        if c == Vec3::ZERO {
            return Ok(s.select(&[0.0; 8], first_channel, nchannels, opts.fill));
        }
        let big_a = ((d[1] - d[0]) + (d[3] - d[2])) * 0.5 * opts.swidth;
        let big_b = ((d[2] - d[0]) + (d[3] - d[1])) * 0.5 * opts.twidth;
        let (t1, t2) = c.any_orthonormal_pair();
        let blur = (opts.blur + 0.5 * (opts.sblur + opts.tblur)) * 0.5 * PI;
        let mut fp = footprint(
            [big_a.dot(t1), big_a.dot(t2)],
            [big_b.dot(t1), big_b.dot(t2)],
            [blur, blur],
        );
        fp.major = fp.major.min(PI);
        fp.minor = fp.minor.min(PI);
        let cube = f.kind == TextureKind::Cube;
        let (texel0, max_lod) = if cube {
            let n0 = f.levels[0].0.max(2);
            let face_levels = (usize::BITS - n0.leading_zeros()) as usize;
            (2.0 / (n0 - 1) as f32, face_levels.saturating_sub(2))
        } else {
            (PI / f.levels[0].1 as f32, f.levels.len() - 1)
        };
        let coarsest = texel0 * (1u64 << max_lod) as f32;
        let (nmaj, nmin, size) = probe_grid(&fp, opts.max_anisotropy, coarsest);
        let minor = fp.minor.max(fp.major / opts.max_anisotropy.max(1) as f32);
        let e_major = t1 * fp.dir[0] + t2 * fp.dir[1];
        let e_minor = t1 * -fp.dir[1] + t2 * fp.dir[0];
        let mut acc = [0.0f32; 8];
        let mut wsum = 0.0f32;
        for i in 0..nmaj {
            let u = (i as f32 + 0.5) / nmaj as f32 - 0.5;
            for j in 0..nmin {
                let v = (j as f32 + 0.5) / nmin as f32 - 0.5;
                let pd = c + e_major * (u * fp.major) + e_minor * (v * minor);
                let wt = opts.probe_weight(u, v);
                if cube {
                    cube_trilinear(&mut s, &f, pd, size, texel0, max_lod, wt, &mut acc)?;
                } else {
                    let (ps, pt) = latlong_st(pd);
                    let lod = if size > texel0 {
                        (size / texel0).log2()
                    } else {
                        0.0
                    };
                    s.trilinear(
                        ps,
                        pt,
                        lod,
                        max_lod,
                        [WrapMode::Periodic, WrapMode::Clamp],
                        wt,
                        &mut acc,
                    )?;
                }
                wsum += wt;
            }
        }
        if wsum > 0.0 {
            acc.iter_mut().for_each(|v| *v /= wsum);
        }
        Ok(s.select(&acc, first_channel, nchannels, opts.fill))
    }
}

#[allow(clippy::too_many_arguments)]
fn cube_trilinear(
    s: &mut Sampler,
    f: &TexFile,
    d: Vec3,
    size: f32,
    texel0: f32,
    max_lod: usize,
    weight: f32,
    acc: &mut [f32; 8],
) -> Result<(), TextureError> {
    let (face, col, row) = face_coords(d);
    let r2 = 1.0 + col * col + row * row;
    // Plane length per radian grows as r (tangential) and r² (radial): use the geometric mean.
    let texels = size * r2.powf(0.75) / texel0;
    let lod = if texels > 1.0 {
        texels.log2().min(max_lod as f32)
    } else {
        0.0
    };
    let l0 = lod.floor() as usize;
    let fr = lod - l0 as f32;
    cube_bilinear(s, f, face as usize, col, row, l0, weight * (1.0 - fr), acc)?;
    if fr > 0.0 {
        cube_bilinear(s, f, face as usize, col, row, l0 + 1, weight * fr, acc)?;
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn cube_bilinear(
    s: &mut Sampler,
    f: &TexFile,
    face: usize,
    col: f32,
    row: f32,
    level: usize,
    weight: f32,
    acc: &mut [f32; 8],
) -> Result<(), TextureError> {
    let n = f.levels[level].0;
    let x = coord_to_texel(col, n).clamp(0.0, (n - 1) as f32);
    let y = coord_to_texel(row, n).clamp(0.0, (n - 1) as f32);
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(n - 1), (y0 + 1).min(n - 1));
    let (ax, ay) = (x - x0 as f32, y - y0 as f32);
    let nch = f.nch.min(8);
    let mut t = [0.0f32; 8];
    for (yy, wy) in [(y0, 1.0 - ay), (y1, ay)] {
        for (xx, wx) in [(x0, 1.0 - ax), (x1, ax)] {
            let wt = weight * wx * wy;
            if wt == 0.0 {
                continue;
            }
            s.texel(level, xx, face * n + yy, &mut t)?;
            for k in 0..nch {
                acc[k] += wt * t[k];
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latlong_round_trips_and_puts_plus_z_on_top() {
        assert!(latlong_st(Vec3::Z).1 < 1e-6);
        assert!((latlong_st(Vec3::NEG_Z).1 - 1.0).abs() < 1e-6);
        // OpenImageIO's z-up convention: +x mid-image, +y three quarters across.
        assert!((latlong_st(Vec3::X).0 - 0.5).abs() < 1e-6);
        assert!((latlong_st(Vec3::Y).0 - 0.75).abs() < 1e-6);
        for &(s, t) in &[(0.1, 0.3), (0.7, 0.9), (0.5, 0.5)] {
            let (s2, t2) = latlong_st(latlong_direction(s, t));
            assert!((s - s2).abs() < 1e-5 && (t - t2).abs() < 1e-5);
        }
    }
}
