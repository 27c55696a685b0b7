//! BMRT features (issue 9) through real RIB: ray-traced shadows and area lights, against
//! closed forms computed here in f64.
//!
//! * A sphere's ray-traced shadow on a plane under a distant light is the analytic ellipse
//!   (the plane points whose ray toward the light meets the sphere): a pixel may disagree only
//!   where the analytic boundary passes within 1 pixel of its centre (the shading grid's
//!   vertices are up to ½ pixel from the sample, the tessellation's chords a fraction more).
//! * No acne: shadows on vs off are identical wherever `N·L` exceeds the terminator band of
//!   the tessellation (0.1), for a lit sphere, and for a plane (a thin two-sided sheet) under
//!   grazing light (N·L = 0.1).
//! * The 10–90% penumbra width under a disk area light equals the width of the f64 integral
//!   of Listing 9.18 over the disk, within 5% (and that integral's support equals the
//!   similar-triangles width 2Rh/(H−h)).
//! * The noise of the soft shadow falls with the sample count n at least as 1/√n: measured
//!   log-log slope between −0.95 and −0.45 (−0.5 for independent samples; stratification
//!   gives −0.75 for a shadow edge crossing the strata).
//! * The same bits with 1 and 2 threads.
use illume_render::{render, RenderSettings, Rendered};
mod support;

use support::frames;

fn render_rib(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

fn red(r: &Rendered, x: u32, y: u32) -> f64 {
    f64::from(r.rgba[((y * r.width + x) * 4) as usize])
}

// ---- sphere on a plane under a distant light ------------------------------------------------

const RES: u32 = 200;
/// Orthographic view straight down at the plane, 50 pixels per unit over [-2,2]².
const PX: f64 = 50.0;
const SPHERE_R: f64 = 0.8;
/// Sphere centre above the plane (toward the camera).
const HEIGHT: f64 = 1.5;
const LIGHT_DIR: [f64; 3] = [0.5, 0.3, 1.0];

fn sphere_on_plane(light_attrs: &str, light: &str, sphere_attrs: &str) -> String {
    let [dx, dy, dz] = LIGHT_DIR;
    format!(
        "Format {RES} {RES} 1\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         WorldBegin\nTranslate 0 0 10\n\
         AttributeBegin\n{light_attrs}\n\
         LightSource {light} \"intensity\" [1] \"from\" [0 0 0] \"to\" [{dx} {dy} {dz}]\n\
         AttributeEnd\nIlluminate 1 1\nShadingRate 0.25\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\n\
         Polygon \"P\" [-2.2 -2.2 0  2.2 -2.2 0  2.2 2.2 0  -2.2 2.2 0]\n\
         AttributeBegin\n{sphere_attrs}\nTranslate 0 0 {}\nSphere {SPHERE_R} -{SPHERE_R} {SPHERE_R} 360\n\
         AttributeEnd\nWorldEnd\n",
        -HEIGHT
    )
}

/// Object-space (x, y) of the plane seen at raster (x, y).
fn plane_point(x: f64, y: f64) -> (f64, f64) {
    (x / PX - 2.0, 2.0 - y / PX)
}

/// Whether the plane point's ray toward the light meets the sphere (f64 closed form).
fn in_analytic_shadow(x: f64, y: f64) -> bool {
    let (gx, gy) = plane_point(x, y);
    let [dx, dy, dz] = LIGHT_DIR;
    let len = (dx * dx + dy * dy + dz * dz).sqrt();
    let d = [-dx / len, -dy / len, -dz / len]; // toward the light
    let c = [0.0, 0.0, -HEIGHT];
    let oc = [c[0] - gx, c[1] - gy, c[2]];
    let t = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    let dist2 = oc.iter().map(|v| v * v).sum::<f64>() - t * t;
    t > 0.0 && dist2 < SPHERE_R * SPHERE_R
}

fn sees_sphere(x: f64, y: f64, margin_px: f64) -> bool {
    let (gx, gy) = plane_point(x, y);
    (gx * gx + gy * gy).sqrt() < SPHERE_R + margin_px / PX
}

/// Pixels classified as shadow (below half the lit value) and the count of mismatches with
/// the analytic ellipse farther than 1 px from its boundary.
fn compare_with_ellipse(r: &Rendered) -> (usize, usize, usize) {
    let [dx, dy, dz] = LIGHT_DIR;
    let lit = dz / (dx * dx + dy * dy + dz * dz).sqrt();
    let (mut shadow, mut analytic, mut bad) = (0, 0, 0);
    for y in 0..RES {
        for x in 0..RES {
            let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            if sees_sphere(cx, cy, 1.5) {
                continue;
            }
            let rendered = red(r, x, y) < 0.5 * lit;
            let expected = in_analytic_shadow(cx, cy);
            shadow += rendered as usize;
            analytic += expected as usize;
            if rendered != expected {
                let near_boundary = (0..16).any(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 16.0;
                    in_analytic_shadow(cx + a.cos(), cy + a.sin()) != expected
                });
                if !near_boundary {
                    bad += 1;
                }
            }
        }
    }
    (shadow, analytic, bad)
}

#[test]
fn sphere_shadow_on_a_plane_is_the_analytic_ellipse_within_one_pixel() {
    let r = render_rib(&sphere_on_plane(
        "Attribute \"light\" \"shadows\" [\"on\"]",
        "\"distantlight\" 1",
        "",
    ));
    let (shadow, analytic, bad) = compare_with_ellipse(&r);
    assert!(analytic > 3000, "the ellipse is large: {analytic} px");
    eprintln!("ellipse: {shadow} shadow px rendered, {analytic} analytic, {bad} off by > 1 px");
    assert_eq!(
        bad, 0,
        "{bad} pixels disagree farther than 1 px from the boundary"
    );
    let rel = (shadow as f64 - analytic as f64).abs() / analytic as f64;
    assert!(rel < 0.02, "shadow area {shadow} vs analytic {analytic} px");
}

#[test]
fn shadowdistant_raytrace_matches_the_light_shadows_attribute() {
    let attr = render_rib(&sphere_on_plane(
        "Attribute \"light\" \"shadows\" [\"on\"]",
        "\"distantlight\" 1",
        "",
    ));
    let traced = render_rib(&sphere_on_plane(
        "",
        "\"shadowdistant\" 1 \"shadowname\" [\"raytrace\"] \"blur\" [0]",
        "",
    ));
    assert_eq!(attr.rgba, traced.rgba);
}

#[test]
fn transparent_transmission_and_casts_shadows_none_cast_no_shadow() {
    for attr in [
        "Attribute \"visibility\" \"string transmission\" [\"transparent\"]",
        "Attribute \"visibility\" \"int transmission\" [0]",
        "Attribute \"render\" \"string casts_shadows\" [\"none\"]",
    ] {
        let r = render_rib(&sphere_on_plane(
            "Attribute \"light\" \"shadows\" [\"on\"]",
            "\"distantlight\" 1",
            attr,
        ));
        let (shadow, analytic, _) = compare_with_ellipse(&r);
        assert!(analytic > 3000);
        assert_eq!(shadow, 0, "{attr}: the sphere must not cast a shadow");
    }
    // "Os" casts (as opaque).
    let r = render_rib(&sphere_on_plane(
        "Attribute \"light\" \"shadows\" [\"on\"]",
        "\"distantlight\" 1",
        "Attribute \"visibility\" \"string transmission\" [\"Os\"]",
    ));
    let (_, _, bad) = compare_with_ellipse(&r);
    assert_eq!(bad, 0);
}

// ---- acne --------------------------------------------------------------------------------

/// Renders `body` under one distant light along `dir`, with and without ray-traced shadows,
/// and returns the largest difference over pixels whose unshadowed value (= N·L for matte
/// Kd 1) exceeds `min_cos`, and how many such pixels there are.
fn acne(body: &str, dir: [f64; 3], min_cos: f64) -> (f64, usize) {
    let scene = |attr: &str| {
        format!(
            "Format 160 160 1\nProjection \"orthographic\"\nScreenWindow -1.2 1.2 -1.2 1.2\n\
             PixelSamples 2 2\nPixelFilter \"box\" 1 1\nWorldBegin\nTranslate 0 0 5\n\
             AttributeBegin\n{attr}\nLightSource \"distantlight\" 1 \"to\" [{} {} {}]\nAttributeEnd\nIlluminate 1 1\n\
             Surface \"matte\" \"Ka\" [0] \"Kd\" [1]\nShadingRate 0.5\n{body}\nWorldEnd\n",
            dir[0], dir[1], dir[2]
        )
    };
    let plain = render_rib(&scene(""));
    let traced = render_rib(&scene("Attribute \"light\" \"shadows\" [\"on\"]"));
    let (mut worst, mut count) = (0.0f64, 0);
    for (a, b) in plain.rgba.chunks_exact(4).zip(traced.rgba.chunks_exact(4)) {
        // Full coverage only: a silhouette pixel mixes background in.
        if f64::from(a[3]) > 0.999 && f64::from(a[0]) > min_cos {
            count += 1;
            worst = worst.max(f64::from((a[0] - b[0]).abs()));
        }
    }
    (worst, count)
}

#[test]
fn lit_sphere_has_no_self_shadowed_pixels_before_the_terminator() {
    // Light from the side and behind: the terminator crosses the visible disc.
    let (worst, count) = acne("Sphere 1 -1 1 360", [1.0, 0.4, 0.3], 0.1);
    assert!(count > 3000, "{count} lit pixels");
    assert!(worst < 1e-6, "largest lit-pixel difference {worst}");
}

/// The concave side of a shallow spherical cap, lit along its axis: the tessellation's chords
/// lie on the lit side of the surface there, so only the offset by the measured chord distance
/// keeps the cap from shadowing itself.
#[test]
fn concave_cap_does_not_shadow_itself_on_its_own_chords() {
    let (worst, count) = acne("Translate 0 0 0\nSphere 5 4.5 5 360", [0.0, 0.0, 1.0], 0.1);
    assert!(count > 15000, "{count} lit pixels");
    assert!(worst < 1e-6, "largest difference {worst}");
}

#[test]
fn plane_and_thin_sheet_under_grazing_light_have_no_acne() {
    // N·L = 0.1 on a plane facing the camera; a second sheet 0.002 behind it (thin geometry).
    let sheet = "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\n\
                 Polygon \"P\" [-1 -1 0.002  1 -1 0.002  1 1 0.002  -1 1 0.002]";
    let sin = (1.0f64 - 0.01).sqrt();
    let (worst, count) = acne(sheet, [sin * 0.6, sin * 0.8, 0.1], 0.05);
    assert!(count > 10000, "{count} lit pixels");
    assert!(worst < 1e-6, "largest difference {worst}");
}

// ---- disk area light -----------------------------------------------------------------------

/// Disk light radius, its height, the occluder's height and its edge x; the ground is z = 0
/// and "up" (toward the camera) is −z.
const LIGHT_R: f64 = 0.5;
const LIGHT_H: f64 = 4.0;
const OCC_H: f64 = 1.0;
const EDGE_X: f64 = 1.0;
/// Ground x where the penumbra is centred (similar triangles from the light centre x = 0).
const PEN_X: f64 = EDGE_X * LIGHT_H / (LIGHT_H - OCC_H);

/// The view: [PEN_X−0.5, PEN_X+0.5] × [−0.25, 0.25] of the ground at `w × w/2` pixels.
fn area_scene(w: u32, samples: u32, frame: u32, occluder_casts: bool) -> String {
    let casts = if occluder_casts { "opaque" } else { "none" };
    format!(
        "FrameBegin {frame}\nFormat {w} {} 1\nProjection \"orthographic\"\n\
         ScreenWindow {} {} -0.25 0.25\nPixelSamples 1 1\nPixelFilter \"box\" 1 1\n\
         Hider \"hidden\" \"jitter\" [0]\nWorldBegin\nTranslate 0 0 10\n\
         AttributeBegin\nAttribute \"light\" \"nsamples\" [{samples}]\n\
         Translate 0 0 {}\nAreaLightSource \"arealight\" 1 \"intensity\" [1]\n\
         Sides 1\nSurface \"constant\"\nDisk 0 {LIGHT_R} 360\nAttributeEnd\n\
         Illuminate 1 1\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\nShadingRate 1\n\
         Polygon \"P\" [-3 -3 0  4 -3 0  4 3 0  -3 3 0]\n\
         AttributeBegin\nAttribute \"render\" \"string casts_shadows\" [\"{casts}\"]\n\
         Polygon \"P\" [-3 -3 {}  {EDGE_X} -3 {}  {EDGE_X} 3 {}  -3 3 {}]\nAttributeEnd\n\
         WorldEnd\nFrameEnd\n",
        w / 2,
        PEN_X - 0.5,
        PEN_X + 0.5,
        -LIGHT_H,
        -OCC_H,
        -OCC_H,
        -OCC_H,
        -OCC_H,
    )
}

/// Listing 9.18 at a ground point: the area-uniform mean over the disk of
/// `visibility · cos θ / r²` (r the distance to the disk point), midpoint rule in (ρ², φ).
fn analytic_irradiance(x: f64, occluded: bool) -> f64 {
    let n = 600;
    let mut sum = 0.0;
    for a in 0..n {
        let rho = LIGHT_R * ((a as f64 + 0.5) / n as f64).sqrt();
        for b in 0..n {
            let phi = (b as f64 + 0.5) / n as f64 * std::f64::consts::TAU;
            let (sx, sy) = (rho * phi.cos(), rho * phi.sin());
            // Where the ray from (x, 0, 0) to the disk point crosses the occluder's height.
            let cross_x = x + (sx - x) * OCC_H / LIGHT_H;
            if occluded && cross_x < EDGE_X {
                continue;
            }
            let r2 = (sx - x).powi(2) + sy * sy + LIGHT_H * LIGHT_H;
            sum += LIGHT_H / r2.sqrt() / r2;
        }
    }
    sum / (n * n) as f64
}

/// Rendered lit fraction per column (occluded over unoccluded, mean over the rows).
fn rendered_profile(w: u32, samples: u32) -> Vec<f64> {
    let occ = render_rib(&area_scene(w, samples, 1, true));
    let free = render_rib(&area_scene(w, samples, 1, false));
    (0..w)
        .map(|x| {
            let (mut a, mut b) = (0.0, 0.0);
            for y in 0..w / 2 {
                a += red(&occ, x, y);
                b += red(&free, x, y);
            }
            a / b
        })
        .collect()
}

/// Ground x where `f(x)` (increasing) first reaches `level`, by linear interpolation of
/// samples at `xs`.
fn crossing(xs: &[f64], f: &[f64], level: f64) -> f64 {
    for k in 1..xs.len() {
        if f[k - 1] < level && f[k] >= level {
            let t = (level - f[k - 1]) / (f[k] - f[k - 1]);
            return xs[k - 1] + t * (xs[k] - xs[k - 1]);
        }
    }
    f64::NAN
}

#[test]
fn disk_light_penumbra_width_matches_similar_triangles_and_the_integral() {
    let w = 200u32;
    let xs: Vec<f64> = (0..w)
        .map(|x| PEN_X - 0.5 + (f64::from(x) + 0.5) / f64::from(w))
        .collect();
    let profile = rendered_profile(w, 256);
    // Columns that see the occluder, not the ground, are left of the edge: skip them.
    let first = xs.iter().position(|&x| x > EDGE_X + 0.02).unwrap();
    let (xs_g, prof_g) = (&xs[first..], &profile[first..]);
    let measured = crossing(xs_g, prof_g, 0.9) - crossing(xs_g, prof_g, 0.1);

    let fine: Vec<f64> = (0..400).map(|k| EDGE_X + k as f64 * 0.0025).collect();
    let reference: Vec<f64> = fine
        .iter()
        .map(|&x| analytic_irradiance(x, true) / analytic_irradiance(x, false))
        .collect();
    let expected = crossing(&fine, &reference, 0.9) - crossing(&fine, &reference, 0.1);
    // The reference's support is the similar-triangles penumbra 2Rh/(H−h).
    let full = 2.0 * LIGHT_R * OCC_H / (LIGHT_H - OCC_H);
    let support = crossing(&fine, &reference, 1.0 - 1e-9) - crossing(&fine, &reference, 1e-9);
    assert!(
        (support - full).abs() < 0.01,
        "reference support {support} vs 2Rh/(H-h) = {full}"
    );
    let rel = (measured - expected).abs() / expected;
    eprintln!("10-90% penumbra width {measured:.5} vs f64 integral {expected:.5}, full {full:.5}");
    assert!(
        rel < 0.05,
        "10-90% penumbra width {measured} vs {expected} (rel {rel}), full width {full}"
    );
}

#[test]
fn soft_shadow_noise_falls_at_least_as_one_over_sqrt_n() {
    let w = 100u32;
    let mut points = Vec::new();
    for n in [4u32, 16, 64, 256] {
        let a = render_rib(&area_scene(w, n, 1, true));
        let b = render_rib(&area_scene(w, n, 2, true));
        // Penumbra columns only (ground x within the similar-triangles penumbra).
        let half = LIGHT_R * OCC_H / (LIGHT_H - OCC_H);
        let (mut s2, mut count) = (0.0, 0usize);
        for y in 0..w / 2 {
            for x in 0..w {
                let gx = PEN_X - 0.5 + (f64::from(x) + 0.5) / f64::from(w);
                if (gx - PEN_X).abs() < half * 0.8 {
                    let d = red(&a, x, y) - red(&b, x, y);
                    s2 += d * d;
                    count += 1;
                }
            }
        }
        // Frames 1 and 2 draw independent samples: Var(a − b) = 2σ².
        let sigma = (s2 / count as f64 / 2.0).sqrt();
        assert!(
            sigma > 0.0,
            "n = {n}: no noise at all means no per-point sampling"
        );
        points.push(((n as f64).ln(), sigma.ln()));
    }
    let m = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x, b + y));
    let (mx, my) = (sx / m, sy / m);
    let slope = points
        .iter()
        .map(|&(x, y)| (x - mx) * (y - my))
        .sum::<f64>()
        / points.iter().map(|&(x, _)| (x - mx).powi(2)).sum::<f64>();
    eprintln!("soft-shadow noise log-log slope: {slope:.3} ({points:?})");
    assert!(
        (-0.95..=-0.45).contains(&slope),
        "noise slope {slope}, expected between -0.95 and -0.45"
    );
}

#[test]
fn ray_traced_images_are_identical_for_one_and_two_threads() {
    let scenes = [
        area_scene(80, 16, 1, true),
        sphere_on_plane(
            "Attribute \"light\" \"shadows\" [\"on\"]",
            "\"distantlight\" 1",
            "",
        ),
    ];
    for rib in scenes {
        let f = frames(&rib, None);
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| render(&f[0], &RenderSettings::default()))
        };
        let (one, two) = (run(1), run(2));
        let bits = |r: &Rendered| r.rgba.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&one), bits(&two));
    }
}

// ---- a caster small on screen with a magnified shadow ---------------------------------------

/// A disk of radius 0.1 one unit below a point light that is 10 units above a plane casts a
/// shadow of radius 0.1·10/1 = 1 (similar triangles): ten times its own size on screen. The
/// shadow's area must be π within 1%, so the caster's tessellation may not follow its small
/// raster size (an 11-gon, about what 4 px per edge gives, covers 5.4% less).
#[test]
fn magnified_shadow_of_a_small_disk_has_the_circles_area() {
    const N: u32 = 240;
    let px = f64::from(N) / 3.0; // ScreenWindow [-1.5, 1.5]²
    let scene = |caster: &str| {
        format!(
            "Format {N} {N} 1\nProjection \"orthographic\"\nScreenWindow -1.5 1.5 -1.5 1.5\n\
             PixelSamples 2 2\nPixelFilter \"box\" 1 1\nWorldBegin\nTranslate 0 0 20\n\
             AttributeBegin\nAttribute \"light\" \"shadows\" [\"on\"]\n\
             LightSource \"pointlight\" 1 \"intensity\" [100] \"from\" [0 0 -10]\n\
             AttributeEnd\nIlluminate 1 1\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\n\
             Polygon \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]\n\
             {caster}WorldEnd\n"
        )
    };
    // The disk faces the camera; shaded black, it reads as shadow wherever it hides the plane
    // (its projection lies inside the shadow).
    let with = render_rib(&scene(
        "AttributeBegin\nSurface \"constant\"\nColor [0 0 0]\nTranslate 0 0 -9\nDisk 0 0.1 360\nAttributeEnd\n",
    ));
    let without = render_rib(&scene(""));
    let mut shadow_px = 0.0;
    for (w, o) in with.rgba.chunks(4).zip(without.rgba.chunks(4)) {
        let lit = f64::from(o[0]);
        assert!(lit > 0.0, "the plane is lit everywhere in view");
        shadow_px += (1.0 - f64::from(w[0]) / lit).clamp(0.0, 1.0);
    }
    let area = shadow_px / (px * px);
    let expected = std::f64::consts::PI;
    eprintln!(
        "magnified shadow: area {area:.5} vs π (error {:+.3}%)",
        (area / expected - 1.0) * 100.0
    );
    assert!(
        (area / expected - 1.0).abs() < 0.01,
        "shadow area {area:.4} vs π·1² = {expected:.4} ({:+.2}%)",
        (area / expected - 1.0) * 100.0
    );
}
