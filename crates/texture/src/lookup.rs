//! Optional lookup parameters (`"blur"`, `"width"`, `"swidth"`, `"filter"`, `"fill"`, `"samples"`,
//! `"bias"` …) and the footprint analysis shared by `texture` and `environment`.

use crate::FilterKind;

/// RenderMan optional parameters of `texture`, `environment` and `shadow`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LookupOptions {
    /// Extra blur added to the footprint, as a fraction of the texture (for environments a
    /// fraction of a cube face, i.e. 1.0 = 90°).
    pub blur: f32,
    /// Per-axis extra blur, added to `blur`.
    pub sblur: f32,
    pub tblur: f32,
    /// Multipliers of the footprint (`"width"` sets both).
    pub swidth: f32,
    pub twidth: f32,
    /// Weighting of the footprint: `Box` averages evenly, anything else is Gaussian.
    pub filter: FilterKind,
    /// Value of requested channels the file lacks.
    pub fill: f32,
    /// Shadow samples.
    pub samples: u32,
    /// Shadow depth bias.
    pub bias: f32,
    /// Largest footprint elongation followed exactly (more probes); beyond it, blur.
    pub max_anisotropy: u32,
}

impl Default for LookupOptions {
    fn default() -> Self {
        LookupOptions {
            blur: 0.0,
            sblur: 0.0,
            tblur: 0.0,
            swidth: 1.0,
            twidth: 1.0,
            filter: FilterKind::Gaussian,
            fill: 0.0,
            samples: 16,
            bias: 0.0,
            max_anisotropy: 16,
        }
    }
}

impl LookupOptions {
    /// Weight of a probe at normalised offset `(u, v)` (each in `[-½, ½]` of the footprint).
    pub(crate) fn probe_weight(&self, u: f32, v: f32) -> f32 {
        match self.filter {
            FilterKind::Box => 1.0,
            _ => (-2.0 * 4.0 * (u * u + v * v)).exp(),
        }
    }
}

/// An elliptical footprint: full widths along its two axes and the major axis direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Footprint {
    pub major: f32,
    pub minor: f32,
    /// Unit major axis.
    pub dir: [f32; 2],
}

/// Footprint of two axis vectors `a`, `b` plus isotropic-per-axis blur `(bx, by)` (all full
/// widths): the eigen-decomposition of `a aᵀ + b bᵀ + diag(bx², by²)`.
pub(crate) fn footprint(a: [f32; 2], b: [f32; 2], blur: [f32; 2]) -> Footprint {
    let sxx = (a[0] * a[0] + b[0] * b[0] + blur[0] * blur[0]) as f64;
    let syy = (a[1] * a[1] + b[1] * b[1] + blur[1] * blur[1]) as f64;
    let sxy = (a[0] * a[1] + b[0] * b[1]) as f64;
    let half_tr = 0.5 * (sxx + syy);
    let disc = (0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy).sqrt();
    let l1 = half_tr + disc;
    let l2 = (half_tr - disc).max(0.0);
    let dir = if sxy.abs() < 1e-30 {
        if sxx >= syy {
            [1.0, 0.0]
        } else {
            [0.0, 1.0]
        }
    } else {
        let (x, y) = (l1 - syy, sxy);
        let n = (x * x + y * y).sqrt();
        [(x / n) as f32, (y / n) as f32]
    };
    Footprint {
        major: l1.sqrt() as f32,
        minor: l2.sqrt() as f32,
        dir,
    }
}

/// Probe layout: `(n_major, n_minor)` probes, each covering `size`, for a footprint whose
/// smallest useful probe is `finest` and whose coarsest texel is `coarsest` (same units).
pub(crate) fn probe_grid(fp: &Footprint, max_aniso: u32, coarsest: f32) -> (usize, usize, f32) {
    let max_aniso = max_aniso.max(1) as f32;
    let mut minor = fp.minor.max(fp.major / max_aniso);
    let n_minor = if minor > coarsest {
        (minor / coarsest).ceil().min(8.0)
    } else {
        1.0
    };
    minor /= n_minor;
    let n_major = if minor > 0.0 {
        (fp.major / minor).ceil().clamp(1.0, max_aniso * n_minor)
    } else {
        1.0
    };
    let size = minor.max(fp.major / n_major);
    (n_major as usize, n_minor as usize, size)
}

/// The four corners (grid order) of the footprint of a point `(s, t)` whose coordinates change
/// by `(ds_dx, dt_dx)` and `(ds_dy, dt_dy)` from one shading sample to the next (the
/// single-point `texture(name, s, t)` form: derivatives from the grid).
pub fn corners_from_derivatives(
    s: f32,
    t: f32,
    ds_dx: f32,
    dt_dx: f32,
    ds_dy: f32,
    dt_dy: f32,
) -> [[f32; 2]; 4] {
    let (hx, hy) = ([0.5 * ds_dx, 0.5 * dt_dx], [0.5 * ds_dy, 0.5 * dt_dy]);
    [
        [s - hx[0] - hy[0], t - hx[1] - hy[1]],
        [s + hx[0] - hy[0], t + hx[1] - hy[1]],
        [s - hx[0] + hy[0], t - hx[1] + hy[1]],
        [s + hx[0] + hy[0], t + hx[1] + hy[1]],
    ]
}

/// Direction corners (grid order) for `environment(name, D)` / `shadow(name, P)` from a value
/// and its two screen differences (works for points as well as directions).
pub fn vector_corners(d: glam::Vec3, dd_dx: glam::Vec3, dd_dy: glam::Vec3) -> [glam::Vec3; 4] {
    let (hx, hy) = (dd_dx * 0.5, dd_dy * 0.5);
    [d - hx - hy, d + hx - hy, d - hx + hy, d + hx + hy]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_from_derivatives_span_one_sample_step_in_each_direction() {
        let c = corners_from_derivatives(0.5, 0.25, 0.1, 0.0, 0.02, 0.04);
        // (c1 - c0) is the x step, (c2 - c0) the y step; the centre is (s, t).
        assert!(((c[1][0] - c[0][0]) - 0.1).abs() < 1e-7 && (c[1][1] - c[0][1]).abs() < 1e-7);
        assert!(
            ((c[2][0] - c[0][0]) - 0.02).abs() < 1e-7 && ((c[2][1] - c[0][1]) - 0.04).abs() < 1e-7
        );
        let cs: f32 = c.iter().map(|p| p[0]).sum::<f32>() / 4.0;
        assert!((cs - 0.5).abs() < 1e-7);
        let v = vector_corners(glam::Vec3::Z, glam::Vec3::X, glam::Vec3::Y);
        assert_eq!(v[3] - v[0], glam::Vec3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn footprint_of_orthogonal_axes_recovers_their_lengths() {
        let f = footprint([0.0, 3.0], [0.5, 0.0], [0.0, 0.0]);
        assert!((f.major - 3.0).abs() < 1e-5 && (f.minor - 0.5).abs() < 1e-5);
        assert!(f.dir[0].abs() < 1e-6 && (f.dir[1].abs() - 1.0).abs() < 1e-6);
        // Diagonal: a = (1,1), b = 0 → major √2 along (1,1)/√2.
        let f = footprint([1.0, 1.0], [0.0, 0.0], [0.0, 0.0]);
        assert!((f.major - 2f32.sqrt()).abs() < 1e-5 && f.minor < 1e-3);
        assert!((f.dir[0] - f.dir[1]).abs() < 1e-5);
    }

    #[test]
    fn probe_grid_caps_anisotropy_and_splits_huge_footprints() {
        let f = Footprint {
            major: 100.0,
            minor: 1.0,
            dir: [1.0, 0.0],
        };
        let (nmaj, nmin, size) = probe_grid(&f, 16, 1e9);
        assert_eq!((nmaj, nmin), (16, 1));
        assert!((size - 100.0 / 16.0).abs() < 1e-4);
        let f = Footprint {
            major: 10.0,
            minor: 10.0,
            dir: [1.0, 0.0],
        };
        let (nmaj, nmin, size) = probe_grid(&f, 16, 2.5);
        assert_eq!((nmaj, nmin), (4, 4));
        assert!((size - 2.5).abs() < 1e-5);
    }
}
