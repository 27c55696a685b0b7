//! `ShadingInterpolation "constant"` against a closed form (issue 21 part 4): a micropolygon's
//! one colour is the mean of its four shaded vertices, not its first vertex's colour.
//!
//! Scene: an orthographic unit sphere (pole facing the camera) under an `ambientlight` and a
//! `distantlight`, surface `matte` Ka 0.2 Kd 0.7, at the RI defaults ShadingRate 1 and
//! PixelSamples 2 2, box 1×1 pixel filter, jitter off so the samples sit at their stratum
//! centres. The closed form at a sample (x, y) is Ka + Kd·max(0, N·L) with
//! N = (x, y, −√(1−x²−y²)); the reference pixel is its mean, in f64, over exactly the pixel's
//! four sample positions, so what is left is the shading interpolation's error alone.
//! The light is chosen so that N·L > 0 on every compared pixel (no terminator kink inside).
use illume_render::{render, RenderSettings, Rendered};
mod support;

use support::frames;

const RES: u32 = 200;
const SPP: u32 = 2;
const KA: f64 = 0.2;
const KD: f64 = 0.7;
/// The distantlight's `to` (from the origin): light travels mostly away from the camera.
const TO: [f64; 3] = [0.3, -0.2, 1.0];

fn scene(interpolation: &str, rate: f64) -> String {
    format!(
        "Format {RES} {RES} 1\nScreenWindow -1.25 1.25 -1.25 1.25\nProjection \"orthographic\"\n\
         PixelSamples {SPP} {SPP}\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" [1]\n\
         LightSource \"distantlight\" 2 \"intensity\" [1] \"from\" [0 0 0] \"to\" [{} {} {}]\n\
         ShadingRate {rate}\nShadingInterpolation \"{interpolation}\"\n\
         Surface \"matte\" \"Ka\" [{KA}] \"Kd\" [{KD}]\nTranslate 0 0 5\n\
         Sphere 1 -1 1 360\nWorldEnd\n",
        TO[0], TO[1], TO[2]
    )
}

fn render_rib(rib: &str) -> Rendered {
    let frames = frames(rib, None);
    assert_eq!(frames.len(), 1);
    render(&frames[0], &RenderSettings::default())
}

/// Screen position of sample (i, j) of pixel (px, py) with jitter off.
fn sample_xy(px: u32, py: u32, i: u32, j: u32) -> (f64, f64) {
    let scale = 2.5 / f64::from(RES);
    let n = f64::from(SPP);
    (
        -1.25 + (f64::from(px) + (f64::from(i) + 0.5) / n) * scale,
        1.25 - (f64::from(py) + (f64::from(j) + 0.5) / n) * scale,
    )
}

/// Ka + Kd·max(0, N·L) at screen (x, y) inside the silhouette.
fn closed_form(x: f64, y: f64) -> f64 {
    let len = (TO[0] * TO[0] + TO[1] * TO[1] + TO[2] * TO[2]).sqrt();
    let l = TO.map(|c| -c / len);
    let nz = -(1.0 - x * x - y * y).max(0.0).sqrt();
    KA + KD * (x * l[0] + y * l[1] + nz * l[2]).max(0.0)
}

/// Whether every sample of the pixel lies within `radius` of the sphere's centre.
fn inside(px: u32, py: u32, radius: f64) -> bool {
    (0..SPP * SPP).all(|s| {
        let (x, y) = sample_xy(px, py, s % SPP, s / SPP);
        x * x + y * y < radius * radius
    })
}

/// Mean and largest |pixel − reference| of the red channel over pixels whose samples all lie
/// within radius 0.9 (near the silhouette the normal turns faster than ShadingRate 1 follows,
/// for any interpolation), and the count of those pixels.
fn errors(r: &Rendered) -> (f64, f64, usize) {
    let (mut sum, mut worst, mut n) = (0.0, 0.0f64, 0usize);
    for py in 0..RES {
        for px in 0..RES {
            if !inside(px, py, 0.9) {
                continue;
            }
            let reference = (0..SPP * SPP)
                .map(|s| {
                    let (x, y) = sample_xy(px, py, s % SPP, s / SPP);
                    closed_form(x, y)
                })
                .sum::<f64>()
                / f64::from(SPP * SPP);
            let got = f64::from(r.rgba[((py * RES + px) * 4) as usize]);
            let e = (got - reference).abs();
            sum += e;
            worst = worst.max(e);
            n += 1;
        }
    }
    (sum / n as f64, worst, n)
}

#[test]
fn constant_shading_matches_the_closed_form_per_pixel() {
    let r = render_rib(&scene("constant", 1.0));
    let (mean, max, n) = errors(&r);
    eprintln!("constant, ShadingRate 1: mean error {mean:.2e}, max {max:.2e} over {n} pixels");
    // π·0.9²·80² ≈ 16,300 pixel centres lie within radius 0.9.
    assert!(n > 15_000, "only {n} compared pixels");
    // The bound on any pixel: 0.01 (2.5 8-bit code values). Measured 4.1e-3; the
    // first vertex's colour gave 1.26e-2 here, Aqsis 1.8.4's "constant" 1.2e-2.
    assert!(max <= 0.01, "max error {max}");
    // Measured 6.2e-4. The first vertex's colour shifts the image by half a micropolygon:
    // 3.5e-3 here, and Aqsis 1.8.4 (which takes the first vertex too) 3.3e-3 on this scene at
    // these settings; 1.5e-3 fails both by 2× and leaves 2.4× for changes in dicing.
    assert!(mean <= 1.5e-3, "mean error {mean}");
}

#[test]
fn constant_shading_leaves_no_crack_inside_the_sphere() {
    // Every pixel whose samples all lie within radius 0.98 is wholly covered (alpha 1): the
    // per-micropolygon constants change colours, never coverage.
    let r = render_rib(&scene("constant", 1.0));
    let mut checked = 0;
    for py in 0..RES {
        for px in 0..RES {
            if inside(px, py, 0.98) {
                let a = r.rgba[((py * RES + px) * 4 + 3) as usize];
                assert!(a >= 1.0 - 1e-6, "pixel ({px}, {py}) alpha {a}");
                checked += 1;
            }
        }
    }
    assert!(checked > 18_000, "only {checked} pixels checked");
}

#[test]
fn constant_shading_error_falls_with_the_shading_rate() {
    // A micropolygon's side ÷8 (ShadingRate 4 → 1/16) divides the mean error by at least 4:
    // the error is the micropolygon's, first order in its size (measured 2.2e-3 → 2.5e-4).
    // Not 1 → 1/4: with jitter off, 2×2 samples per pixel and micropolygons of half a pixel,
    // every sample sits at the same offset in its micropolygon and nothing averages out
    // (measured 6.2e-4 → 4.9e-4), where one-pixel micropolygons let a pixel's four samples
    // cancel.
    let (coarse, _, _) = errors(&render_rib(&scene("constant", 4.0)));
    let (fine, _, _) = errors(&render_rib(&scene("constant", 0.0625)));
    eprintln!("constant: mean error {coarse:.2e} at ShadingRate 4, {fine:.2e} at 1/16");
    assert!(fine <= 0.25 * coarse, "{fine} vs {coarse}");
}
