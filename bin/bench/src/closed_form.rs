//! Closed-form references for the three analytic scenes, evaluated in f64.
//!
//! Every scene uses a box 1×1 pixel filter, so a pixel is the mean of the radiance over its
//! square. Where that mean has no elementary antiderivative it is a midpoint-rule average over
//! a sub-grid of the pixel (the integrand is the closed form itself; the sub-grid sizes below
//! keep the quadrature error under 1e-4 RMS, well under the errors measured). Each reference
//! has a mask of the pixels where it holds: pixels the sphere's silhouette crosses are left
//! out, because there the renderer's answer also depends on how finely the silhouette is
//! diced, which is not what the closed form is about.

use crate::scene::{DISK_HEIGHT, DISK_RADIUS, LIGHT_HEIGHT, PLANE_WINDOW, SPHERE_WINDOW};
use illume_imageio::{write_display, Image, ImageError, Quantize};
use std::path::Path;

/// The direction the matte scene's distantlight travels (`to - from`), camera = world space.
pub const LIGHT_TRAVEL: [f64; 3] = [1.0, -1.0, 2.0];
/// The disk scene's shadowspot: intensity = height² makes the lit centre exactly 1.
pub const SPOT_INTENSITY: f64 = LIGHT_HEIGHT * LIGHT_HEIGHT;
/// Cone half-angle (radians): with conedeltaangle 0.1 the inner cone (0.8 rad) holds the whole
/// visible plane (its corners are at atan(2√2/4) = 0.615 rad), so smoothstep is 1 everywhere.
pub const SPOT_CONE: f64 = 0.9;

/// A reference image (RGB per pixel, top row first) and the pixels it is compared on.
#[derive(Clone, Debug)]
pub struct Reference {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<[f64; 3]>,
    pub mask: Vec<bool>,
}

/// Screen position of sub-pixel (u, v) ∈ [0,1)² of pixel (px, py) for the orthographic window
/// [-w, w]² (raster y down, screen y up).
fn screen(px: u32, py: u32, u: f64, v: f64, res: u32, w: f64) -> (f64, f64) {
    let scale = 2.0 * w / f64::from(res);
    (
        -w + (f64::from(px) + u) * scale,
        w - (f64::from(py) + v) * scale,
    )
}

/// Mean of `f(x, y)` over pixel (px, py) on an n×n midpoint grid.
fn pixel_mean(
    px: u32,
    py: u32,
    res: u32,
    w: f64,
    n: u32,
    f: &dyn Fn(f64, f64) -> [f64; 3],
) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for j in 0..n {
        for i in 0..n {
            let (u, v) = (
                (f64::from(i) + 0.5) / f64::from(n),
                (f64::from(j) + 0.5) / f64::from(n),
            );
            let (x, y) = screen(px, py, u, v, res, w);
            let c = f(x, y);
            for k in 0..3 {
                sum[k] += c[k];
            }
        }
    }
    sum.map(|s| s / f64::from(n * n))
}

/// Nearest and farthest distance from the origin of pixel (px, py)'s square.
fn radius_range(px: u32, py: u32, res: u32, w: f64) -> (f64, f64) {
    let (x0, y1) = screen(px, py, 0.0, 0.0, res, w);
    let (x1, y0) = screen(px, py, 1.0, 1.0, res, w);
    let near = |a: f64, b: f64| {
        if a > 0.0 {
            a
        } else if b < 0.0 {
            -b
        } else {
            0.0
        }
    };
    let far = |a: f64, b: f64| a.abs().max(b.abs());
    (
        near(x0, x1).hypot(near(y0, y1)),
        far(x0, x1).hypot(far(y0, y1)),
    )
}

/// Unit sphere at distance 5, seen orthographically: the visible point under screen (x, y)
/// has the normal (x, y, -√(1-x²-y²)) in camera space.
fn sphere_normal(x: f64, y: f64) -> Option<[f64; 3]> {
    let rho2 = x * x + y * y;
    (rho2 < 1.0).then(|| [x, y, -(1.0 - rho2).sqrt()])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Builds a reference for a sphere scene: `f` inside the silhouette, black outside, masked to
/// the pixels wholly inside radius `inner` or wholly outside the sphere.
fn sphere_reference(res: u32, inner: f64, n: u32, f: &dyn Fn([f64; 3]) -> [f64; 3]) -> Reference {
    let w = SPHERE_WINDOW;
    let mut rgb = Vec::with_capacity((res * res) as usize);
    let mut mask = Vec::with_capacity((res * res) as usize);
    for py in 0..res {
        for px in 0..res {
            let (near, far) = radius_range(px, py, res, w);
            if far < inner {
                rgb.push(pixel_mean(px, py, res, w, n, &|x, y| {
                    sphere_normal(x, y).map_or([0.0; 3], f)
                }));
                mask.push(true);
            } else {
                rgb.push([0.0; 3]);
                mask.push(near > 1.0);
            }
        }
    }
    Reference {
        width: res,
        height: res,
        rgb,
        mask,
    }
}

/// Matte sphere (Kd 1, white) under a distantlight of intensity 1: Kd·Cl·max(0, N·L), with L
/// towards the light. 16×16 sub-samples: the terminator's kink is the only non-smooth part.
pub fn matte_sphere(res: u32) -> Reference {
    let len = dot(LIGHT_TRAVEL, LIGHT_TRAVEL).sqrt();
    let l = LIGHT_TRAVEL.map(|c| -c / len);
    sphere_reference(res, 1.0, 16, &|n| [dot(n, l).max(0.0); 3])
}

/// The analytic environment: smooth, every channel different, no symmetry a flipped or
/// rotated cube face could hide behind. Values stay within [0.02, 0.98].
pub fn environment(d: [f64; 3]) -> [f64; 3] {
    [
        0.5 + 0.4 * d[0] + 0.08 * (6.0 * d[1]).sin(),
        0.5 + 0.4 * d[1] + 0.08 * (6.0 * d[2]).sin(),
        0.5 + 0.4 * d[2] + 0.08 * (6.0 * d[0]).sin(),
    ]
}

/// Mirror sphere (shinymetal Kr 1, no other terms): environment(R), R = I − 2(N·I)N with
/// I = +z (orthographic). Masked to radius 0.9: towards the rim R sweeps half the sphere of
/// directions within a pixel and the pixel is dominated by micropolygon facets.
pub fn mirror_sphere(res: u32) -> Reference {
    sphere_reference(res, 0.9, 8, &|n| {
        let ni = n[2];
        let r = [-2.0 * ni * n[0], -2.0 * ni * n[1], 1.0 - 2.0 * ni * n[2]];
        environment(r)
    })
}

/// Disk shadow on the plane y = 0 under a shadowspot at height H straight above the disk's
/// centre: at plane radius ρ, d² = ρ² + H², cos of the beam and of the surface are both H/d,
/// so matte Kd 1 gives I·(H/d)^beam(2)·(H/d)/d² = I·H³/d⁵. The disk (radius r at height h)
/// hides the light inside ρ < r·H/(H − h) (similar triangles): a hard edge, which is what a
/// shadow map with blur 0 and enough resolution and samples tends to. Pixels the edge crosses
/// use 64×64 sub-samples, the rest 4×4. Every pixel is compared.
pub fn disk_shadow(res: u32) -> Reference {
    let w = PLANE_WINDOW;
    let h = LIGHT_HEIGHT;
    let umbra = DISK_RADIUS * h / (h - DISK_HEIGHT);
    let lit = |x: f64, y: f64| {
        let rho2 = x * x + y * y;
        let v = if rho2 < umbra * umbra {
            0.0
        } else {
            SPOT_INTENSITY * h.powi(3) / (rho2 + h * h).powf(2.5)
        };
        [v; 3]
    };
    let mut rgb = Vec::with_capacity((res * res) as usize);
    for py in 0..res {
        for px in 0..res {
            let (near, far) = radius_range(px, py, res, w);
            let n = if near <= umbra && umbra <= far { 64 } else { 4 };
            rgb.push(pixel_mean(px, py, res, w, n, &lit));
        }
    }
    Reference {
        width: res,
        height: res,
        rgb,
        mask: vec![true; (res * res) as usize],
    }
}

/// A cube face: its file, view axis, axis toward the top, axis toward the right.
type Face = (&'static str, [f64; 3], [f64; 3], [f64; 3]);

/// The six faces of Table 9.1.
const FACES: [Face; 6] = [
    ("px.tif", [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]),
    ("nx.tif", [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
    ("py.tif", [0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
    ("ny.tif", [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
    ("pz.tif", [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    (
        "nz.tif",
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
    ),
];

/// Writes the analytic environment as six float TIFF faces of `size`², as a 90° camera at the
/// centre would render them (Table 9.1), for `MakeCubeFaceEnvironment`.
pub fn write_cube_faces(dir: &Path, size: u32) -> Result<(), ImageError> {
    for (file, view, up, right) in FACES {
        let mut img = Image::new(size, size, "rgb");
        for j in 0..size {
            for i in 0..size {
                let a = (f64::from(i) + 0.5) / f64::from(size) * 2.0 - 1.0;
                let b = 1.0 - (f64::from(j) + 0.5) / f64::from(size) * 2.0;
                let d: [f64; 3] = std::array::from_fn(|k| view[k] + a * right[k] + b * up[k]);
                let len = dot(d, d).sqrt();
                let c = environment(d.map(|x| x / len));
                let at = ((j * size + i) * 3) as usize;
                for (dst, v) in img.data[at..at + 3].iter_mut().zip(c) {
                    *dst = v as f32;
                }
            }
        }
        write_display(&dir.join(file), "tiff", &img, Quantize::FLOAT, None)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matte_centre_pixel_is_the_cosine_at_the_centre() {
        // Odd resolution: the centre pixel is centred on the view axis, N = -z there, so the
        // value is ≈ L·(-z) = 2/√6 (a pixel 2.5/101 wide: curvature changes it by < 1e-3).
        let r = matte_sphere(101);
        let c = r.rgb[(50 * 101 + 50) as usize][0];
        assert!((c - 2.0 / 6f64.sqrt()).abs() < 1e-3, "{c}");
        assert!(r.mask[0] && r.rgb[0] == [0.0; 3]);
    }

    #[test]
    fn disk_shadow_is_dark_inside_the_umbra_and_one_at_the_lit_centre_limit() {
        let r = disk_shadow(64);
        let centre = r.rgb[(32 * 64 + 32) as usize];
        assert_eq!(centre, [0.0; 3]);
        // Corner pixel: ρ ≈ 2√2 → 16·64/24^2.5 = 0.3629.
        let corner = r.rgb[0][0];
        assert!((corner - 0.3629).abs() < 0.01, "{corner}");
        // Pixels more than about half in shadow (lit values are all above 0.36) cover the
        // umbra's share of the 4×4 window, π·1²/16.
        let dark = r.rgb.iter().filter(|c| c[0] < 0.3).count() as f64 / (64.0 * 64.0);
        assert!((dark - std::f64::consts::PI / 16.0).abs() < 0.01, "{dark}");
    }

    #[test]
    fn mirror_centre_reflects_straight_back() {
        // At the centre N = -z, R = -z.
        let r = mirror_sphere(101);
        let c = r.rgb[(50 * 101 + 50) as usize];
        let e = environment([0.0, 0.0, -1.0]);
        for k in 0..3 {
            assert!((c[k] - e[k]).abs() < 2e-3, "{c:?} {e:?}");
        }
    }
}
