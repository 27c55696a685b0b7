//! Depth of field against the thin lens's closed form (issue 21: depth of field at the peer's
//! speed must stay exact): a straight edge out of focus, still and moving, blurs into the
//! profile of the circle of confusion, and a piece out of focus dices coarser by its
//! `focusfactor`.
//!
//! With `DepthOfField fstop focallength focaldistance` the lens radius is
//! `R = focallength / (2·fstop)` (camera units) and a point at depth `z` seen through lens
//! position `l` (unit disk) moves on screen by `R·(1/zf − 1/z)·l` screen units times the
//! perspective scale: the circle of confusion has raster radius
//! `c = R·|1/zf − 1/z|·d·(pixels per screen unit)`, the spec's `A·f·(z − zf)/(z·(zf − f))` for
//! an aperture `A = f/fstop` once the image distance is scaled to the screen. A half-plane
//! `x ≥ e` (raster) is then seen at raster `X` through the lens positions with
//! `l_x ≥ (e − X)/c` (or `≤`, the same by symmetry): its coverage is the disk's segment
//! fraction `A(u) = (acos u − u·√(1 − u²))/π` at `u = (e − X)/c`.
use illume_render::{render, RenderSettings, Rendered};
mod support;
use support::frames;

const N: usize = 160;

fn render_one(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

/// Raster pixels per camera unit at depth 1: fov 30°, 160×160.
fn pixels_per_unit() -> f64 {
    80.0 / 15f64.to_radians().tan()
}

/// A white half-plane `x ≥ 0` at depth `z` (camera space), optionally moving right by `dx`
/// over the shutter; 16×16 samples, 1×1 box filter, so a pixel's alpha is its coverage.
fn edge_scene(dof: &str, z: f64, dx: f64) -> String {
    let poly = format!("Polygon \"P\" [0 -9 {z}  9 -9 {z}  9 9 {z}  0 9 {z}]");
    let body = if dx == 0.0 {
        poly
    } else {
        format!("MotionBegin [0 1]\nTranslate 0 0 0\nTranslate {dx} 0 0\nMotionEnd\n{poly}")
    };
    format!(
        "Format {N} {N} 1\nProjection \"perspective\" \"fov\" [30]\nPixelSamples 16 16\n\
         PixelFilter \"box\" 1 1\nShutter 0 1\n{dof}\nWorldBegin\nSurface \"constant\"\n\
         {body}\nWorldEnd\n"
    )
}

/// The fraction of the unit disk with `l_x ≥ u`.
fn segment(u: f64) -> f64 {
    let u = u.clamp(-1.0, 1.0);
    (u.acos() - u * (1.0 - u * u).sqrt()) / std::f64::consts::PI
}

/// The expected alpha of pixel column `px`: the segment fraction at the edge `e + s` (raster),
/// averaged over the pixel's width and over the shift `s ∈ [0, shift]` of the shutter
/// (midpoint rule in f64).
fn column_reference(px: usize, e: f64, c: f64, shift: f64) -> f64 {
    let (nx, ns) = (64, if shift > 0.0 { 64 } else { 1 });
    let mut sum = 0.0;
    for i in 0..nx {
        let x = px as f64 + (i as f64 + 0.5) / nx as f64;
        for k in 0..ns {
            let s = shift * (k as f64 + 0.5) / ns as f64;
            sum += segment((e + s - x) / c);
        }
    }
    sum / (nx * ns) as f64
}

/// Mean alpha of each pixel column over the middle rows (every row of a vertical edge has the
/// same expectation, so averaging rows leaves the profile and shrinks the sampling noise).
fn column_profile(r: &Rendered) -> Vec<f64> {
    let rows = 40..120;
    let n = rows.len() as f64;
    (0..N)
        .map(|x| {
            rows.clone()
                .map(|y| f64::from(r.rgba[(y * N + x) * 4 + 3]))
                .sum::<f64>()
                / n
        })
        .collect()
}

/// The largest difference between the rendered profile and the closed form.
fn profile_error(r: &Rendered, c: f64, shift: f64) -> f64 {
    let got = column_profile(r);
    (0..N)
        .map(|x| (got[x] - column_reference(x, 80.0, c, shift)).abs())
        .fold(0.0, f64::max)
}

// Half-plane at z = 3, lens focused at z = 8: fstop 2, focal length 1, R = 0.25.
const Z: f64 = 3.0;
const DOF: &str = "DepthOfField 2 1 8";

fn coc() -> f64 {
    0.25 * (1.0 / 8.0 - 1.0 / Z).abs() * pixels_per_unit()
}

/// Tolerance on a column's mean alpha: 80 rows of 256 samples are 20 480 samples per column;
/// a coverage fraction's binomial standard deviation is at most √(0.25/20480) = 0.0035, and
/// the stratified lens and time samples do better. 0.015 is four of those: a profile off by
/// 2% of the circle of confusion (0.3 px, where the profile's slope is 1/(πc/2) ≈ 0.04 per
/// pixel: 0.012) or by a wrong blur shape (a box or a Gaussian of the same width differ from
/// the disk's segment profile by 0.02–0.05 near its ends) does not fit inside it.
const TOLERANCE: f64 = 0.015;

#[test]
fn out_of_focus_edge_has_the_thin_lens_profile() {
    let c = coc();
    assert!(c > 10.0, "the test needs a visible blur, got {c}");
    let r = render_one(&edge_scene(DOF, Z, 0.0));
    let err = profile_error(&r, c, 0.0);
    eprintln!("still edge: coc {c:.3} px, max column error {err:.4}");
    assert!(err < TOLERANCE, "max column error {err}");
    // The wrong circle of confusion (5% larger) does not fit.
    assert!(profile_error(&r, 1.05 * c, 0.0) > TOLERANCE);
}

#[test]
fn moving_out_of_focus_edge_has_the_lens_profile_swept_over_the_shutter() {
    // Moving 0.15 camera units at z = 3: 0.05·ppu ≈ 14.9 pixels over the shutter, about
    // the circle of confusion's radius, so lens and time both shape the profile.
    let (c, dx) = (coc(), 0.15);
    let shift = dx / Z * pixels_per_unit();
    let r = render_one(&edge_scene(DOF, Z, dx));
    let err = profile_error(&r, c, shift);
    eprintln!("moving edge: coc {c:.3} px, shift {shift:.3} px, max column error {err:.4}");
    assert!(err < TOLERANCE, "max column error {err}");
    assert!(profile_error(&r, c, 0.0) > TOLERANCE);
    assert!(profile_error(&r, c, 1.1 * shift) > TOLERANCE);
}

#[test]
fn edge_on_the_focal_plane_stays_sharp() {
    let sharp = render_one(&edge_scene("", Z, 0.0));
    let lens = render_one(&edge_scene(&format!("DepthOfField 2 1 {Z}"), Z, 0.0));
    let max = sharp
        .rgba
        .iter()
        .zip(&lens.rgba)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    // The lens offset is exactly zero on the focal plane: only samples within rounding of the
    // edge may flip (one sample is 1/256 of a pixel).
    assert!(max <= 2.0 / 256.0 + 1e-6, "in-focus edge changed by {max}");
    let err = profile_error(&lens, 1e-9, 0.0);
    assert!(err < 0.01, "in-focus edge is not a step: {err}");
}

/// A patch out of focus dices `focusfactor` coarser per side: `max(1, coc/16)` for its
/// smallest circle of confusion `coc` (diameter, pixels), so about that squared fewer
/// micropolygons than the pinhole frame.
#[test]
fn out_of_focus_patch_dices_coarser_by_its_circle_of_confusion() {
    let patch = |dof: &str| {
        format!(
            "Format {N} {N} 1\nProjection \"perspective\" \"fov\" [30]\nPixelSamples 2 2\n\
             {dof}\nWorldBegin\nSurface \"constant\"\n\
             Patch \"bilinear\" \"P\" [-0.6 -0.6 {Z}  0.6 -0.6 {Z}  -0.6 0.6 {Z}  0.6 0.6 {Z}]\n\
             WorldEnd\n"
        )
    };
    let pinhole = render_one(&patch("")).stats.micropolygons as f64;
    let blurred = render_one(&patch(DOF)).stats.micropolygons as f64;
    let factor = (2.0 * coc() / 16.0).max(1.0);
    let ratio = pinhole / blurred;
    eprintln!(
        "micropolygons {pinhole} pinhole, {blurred} out of focus: ratio {ratio:.2}, factor² {:.2}",
        factor * factor
    );
    // Dice rates round up per piece, so the ratio falls a little short of factor².
    assert!(
        factor * factor > 3.5,
        "the test needs a coarse factor, got {factor}"
    );
    assert!(
        ratio > 0.8 * factor * factor && ratio < 1.1 * factor * factor,
        "ratio {ratio} vs {}",
        factor * factor
    );
}
