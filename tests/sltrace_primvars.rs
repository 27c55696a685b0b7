//! Primitive variables at `trace()` hits (issue 19): a hit point is shaded by its surface's own
//! shader with that surface's user primitive variables interpolated at the hit.
//!
//! A mirror sphere (`trace(P, reflect(I, N))`) reflects a bilinear patch behind the eye whose
//! shader shows its `varying float g` as grey. `g` is given at the patch's corners so that it
//! is linear over the patch, `g(x, y) = 0.5 + 0.2·x/30 + 0.1·y/30`: every interpolation the
//! renderer may use (bilinear over the patch, barycentric over its triangles) gives that
//! function exactly, up to `f32` rounding. Each pixel must equal `g` at the f64 reflected ray's
//! hit point for the pixel's centre, within the spread of `g` over the hits of the pixel's
//! neighbours one pixel away (the shaded point is a grid vertex up to half a pixel from the
//! centre, and colours interpolate across micropolygons) plus 2e-3. Without the primitive
//! variable at the hit the shader reads its default, −1, and the pixels are black.
use illume_render::{render, RenderSettings, Rendered};
mod support;

use support::frames;

const RES: u32 = 200;
const PX: f64 = 50.0;
const SPHERE_Z: f64 = 3.0;
const PLANE_Z: f64 = -1.0;
/// Half the patch's side.
const HALF: f64 = 30.0;

const MIRROR: &str = "surface tmirror() {
    normal Nf = faceforward(normalize(N), I);
    Ci = trace(P, reflect(normalize(I), Nf));
    Oi = 1;
}";
const SHOW: &str = "surface tshowg(varying float g = -1) {
    Ci = color(g, g, g);
    Oi = 1;
}";

fn g_at(x: f64, y: f64) -> f64 {
    0.5 + 0.2 * x / HALF + 0.1 * y / HALF
}

/// Where on the plane the reflection of the camera ray at camera (x, y) lands, if it does
/// (within the patch).
fn reflected_hit(x: f64, y: f64) -> Option<(f64, f64)> {
    let (hx, hy) = support::mirror_sphere_reflection(x, y, SPHERE_Z, PLANE_Z)?;
    (hx.abs() < HALF * 0.95 && hy.abs() < HALF * 0.95).then_some((hx, hy))
}

fn render_rib(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

#[test]
fn a_mirror_shows_the_reflected_patchs_varying_primvar_at_the_f64_hit() {
    let dir = std::env::temp_dir().join(format!("illume-sltrace-pv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tmirror.sl"), MIRROR).unwrap();
    std::fs::write(dir.join("tshowg.sl"), SHOW).unwrap();
    let (h, z) = (HALF, PLANE_Z);
    let corners = [(-h, -h), (h, -h), (-h, h), (h, h)];
    let p: Vec<String> = corners
        .iter()
        .map(|(x, y)| format!("{x} {y} {z}"))
        .collect();
    let g: Vec<String> = corners
        .iter()
        .map(|&(x, y)| format!("{}", g_at(x, y)))
        .collect();
    let rib = format!(
        "Option \"searchpath\" \"shader\" [\"{}\"]\n\
         Format {RES} {RES} 1\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         ShadingRate 0.25\nWorldBegin\n\
         AttributeBegin\nSurface \"tshowg\"\n\
         Patch \"bilinear\" \"P\" [{}] \"varying float g\" [{}]\nAttributeEnd\n\
         AttributeBegin\nSurface \"tmirror\"\nTranslate 0 0 {SPHERE_Z}\n\
         Sphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n",
        dir.display(),
        p.join("  "),
        g.join(" ")
    );
    let r = render_rib(&rib);
    let _ = std::fs::remove_dir_all(&dir);
    let (mut checked, mut bad, mut worst) = (0, Vec::new(), 0.0f64);
    for y in 0..RES {
        for x in 0..RES {
            let cx = (f64::from(x) + 0.5) / PX - 2.0;
            let cy = 2.0 - (f64::from(y) + 0.5) / PX;
            if cx * cx + cy * cy > 0.5 {
                continue;
            }
            let hits: Option<Vec<(f64, f64)>> = [-1.0, 0.0, 1.0]
                .iter()
                .flat_map(|dx| [-1.0, 0.0, 1.0].map(|dy| (dx, dy)))
                .map(|(dx, dy)| reflected_hit(cx + dx / PX, cy + dy / PX))
                .collect();
            let Some(hits) = hits else { continue };
            let want = g_at(hits[4].0, hits[4].1);
            let spread = hits
                .iter()
                .map(|&(hx, hy)| (g_at(hx, hy) - want).abs())
                .fold(0.0, f64::max);
            let k = ((y * r.width + x) * 4) as usize;
            let got = f64::from(r.rgba[k]);
            worst = worst.max((got - want).abs());
            if (got - want).abs() > spread + 2e-3 {
                bad.push((x, y, got, want, spread));
            }
            checked += 1;
        }
    }
    eprintln!("primvar at hits: {checked} pixels, worst |g − g(f64 hit)| = {worst:.2e}");
    assert!(checked > 1000, "only {checked} pixels checked");
    assert!(
        bad.is_empty(),
        "{} of {checked} pixels differ (x, y, got, want, spread): {:?}",
        bad.len(),
        &bad[..bad.len().min(10)]
    );
}
