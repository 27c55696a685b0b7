//! Motion blur and depth of field (issue 10, part 3) through real RIB, against closed forms and
//! independent f64 references.
//!
//! Coverage references: with a 1×1 box pixel filter a pixel's alpha is the fraction of its
//! samples the surface covers, whose expectation is the time average over the shutter of the
//! area of (pixel ∩ polygon(t)). The reference integrates that in f64: the polygon's corners
//! at time t (piecewise linear between the motion keys, as RenderMan interpolates), clipped to
//! the pixel (Sutherland–Hodgman), midpoint rule over 2000 time steps.
use illume_render::{render, RenderSettings, Rendered};
mod support;
use support::frames;

fn render_one(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

const W: usize = 48;
const H: usize = 24;

/// Orthographic, one screen unit per pixel (raster x = screen x, raster y = H − screen y),
/// 16×16 samples, box filter 1×1, constant white surface.
fn ortho(options: &str, world: &str) -> String {
    format!(
        "Format {W} {H} 1\nScreenWindow 0 {W} 0 {H}\nPixelSamples 16 16\nPixelFilter \"box\" 1 1\n\
         {options}\nWorldBegin\nSurface \"constant\"\n{world}\nWorldEnd\n"
    )
}

/// Area of the convex polygon `p` (raster) inside the pixel box `[x, x+1]×[y, y+1]`.
fn clipped_area(p: &[[f64; 2]], x: f64, y: f64) -> f64 {
    let mut poly = p.to_vec();
    let planes: [(usize, f64, f64); 4] = [
        (0, x, 1.0),
        (0, x + 1.0, -1.0),
        (1, y, 1.0),
        (1, y + 1.0, -1.0),
    ];
    for (axis, at, sign) in planes {
        let inside = |q: &[f64; 2]| (q[axis] - at) * sign >= 0.0;
        let mut out = Vec::new();
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if inside(&a) {
                out.push(a);
            }
            if inside(&a) != inside(&b) {
                let s = (at - a[axis]) / (b[axis] - a[axis]);
                out.push([a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s]);
            }
        }
        poly = out;
        if poly.is_empty() {
            return 0.0;
        }
    }
    let mut area = 0.0;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        area += a[0] * b[1] - a[1] * b[0];
    }
    0.5 * area.abs()
}

/// Time-averaged coverage per pixel of the polygon `corners(t)` (screen coordinates) over the
/// shutter `[open, close]`.
fn reference(corners: impl Fn(f64) -> Vec<[f64; 2]>, [open, close]: [f64; 2]) -> Vec<f64> {
    const STEPS: usize = 2000;
    let mut cov = vec![0.0; W * H];
    for s in 0..STEPS {
        let t = open + (close - open) * (s as f64 + 0.5) / STEPS as f64;
        let p: Vec<[f64; 2]> = corners(t).iter().map(|q| [q[0], H as f64 - q[1]]).collect();
        for y in 0..H {
            for x in 0..W {
                cov[y * W + x] += clipped_area(&p, x as f64, y as f64) / STEPS as f64;
            }
        }
    }
    cov
}

fn lerp(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
}

/// Compares rendered alpha with the reference. Thresholds from the sampling error: 256
/// stratified samples per pixel in x/y and, independently permuted, 256 time strata; a pixel an
/// edge sweeps through has its coverage estimated with a standard error of about 0.5/√256 ≈
/// 0.03 at worst (unstratified) and far less in practice, so no pixel may be off by more than
/// 0.08 (≈ 2.5 σ of the unstratified worst case) and the mean error must stay below 0.006. The total
/// coverage is an area integral over all samples, good to 0.5 %.
fn assert_coverage(r: &Rendered, want: &[f64], what: &str) {
    let got: Vec<f64> = r.rgba.chunks_exact(4).map(|p| f64::from(p[3])).collect();
    let max = got
        .iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs())
        .fold(0.0, f64::max);
    let mean = got
        .iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs())
        .sum::<f64>()
        / got.len() as f64;
    let (sg, sw) = (got.iter().sum::<f64>(), want.iter().sum::<f64>());
    eprintln!("{what}: max |error| {max:.4}, mean {mean:.5}, total {sg:.2} vs {sw:.2}");
    assert!(sw > 20.0, "{what}: reference covers too little to test");
    assert!(max < 0.08, "{what}: max pixel error {max}");
    assert!(mean < 0.006, "{what}: mean pixel error {mean}");
    assert!((sg - sw).abs() < 5e-3 * sw, "{what}: total {sg} vs {sw}");
    // The blur is really there: some pixels are partly covered in the middle of the sweep.
    assert!(
        want.iter().filter(|&&w| w > 0.1 && w < 0.9).count() > 10,
        "{what}"
    );
}

const SQUARE: [[f64; 2]; 4] = [[6.0, 5.5], [14.25, 5.5], [14.25, 17.0], [6.0, 17.0]];

fn polygon(c: &[[f64; 2]]) -> String {
    let p: Vec<String> = c.iter().map(|q| format!("{} {} 0", q[0], q[1])).collect();
    format!("Polygon \"P\" [{}]", p.join("  "))
}

#[test]
fn translating_square_covers_its_time_averaged_area() {
    let d = 23.7;
    let world = format!(
        "Translate 0 0 5\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate {d} 0 0\nMotionEnd\n{}",
        polygon(&SQUARE)
    );
    let r = render_one(&ortho("Shutter 0 1", &world));
    let want = reference(
        |t| SQUARE.iter().map(|q| [q[0] + d * t, q[1]]).collect(),
        [0.0, 1.0],
    );
    assert_coverage(&r, &want, "translate");
}

#[test]
fn motion_times_outside_a_partial_shutter_shape_the_interpolation() {
    // Keys at 0 and 2, shutter open over [0.5, 1.5]: the square sweeps the middle half.
    let d = 30.0;
    let world = format!(
        "Translate 0 0 5\nMotionBegin [0 2]\nTranslate -4 0 0\nTranslate {} 0 0\nMotionEnd\n{}",
        d - 4.0,
        polygon(&SQUARE)
    );
    let r = render_one(&ortho("Shutter 0.5 1.5", &world));
    let want = reference(
        |t| {
            SQUARE
                .iter()
                .map(|q| [q[0] - 4.0 + d * t / 2.0, q[1]])
                .collect()
        },
        [0.5, 1.5],
    );
    assert_coverage(&r, &want, "partial shutter");
}

#[test]
fn rotating_square_matches_piecewise_linear_corners() {
    // Rotate 0 → 50° about the square's centre (the z axis through (10, 11)); between the two
    // keys the matrices, hence the corners, interpolate linearly.
    let c = [10.0, 11.0];
    let a = 50f64.to_radians();
    let rot = |q: [f64; 2]| {
        let (x, y) = (q[0] - c[0], q[1] - c[1]);
        [
            c[0] + x * a.cos() - y * a.sin(),
            c[1] + x * a.sin() + y * a.cos(),
        ]
    };
    let local: Vec<[f64; 2]> = SQUARE.iter().map(|q| [q[0] - c[0], q[1] - c[1]]).collect();
    let world = format!(
        "Translate {} {} 5\nMotionBegin [0 1]\nRotate 0 0 0 1\nRotate 50 0 0 1\nMotionEnd\n{}",
        c[0],
        c[1],
        polygon(&local)
    );
    let r = render_one(&ortho("Shutter 0 1", &world));
    let want = reference(
        |t| SQUARE.iter().map(|&q| lerp(q, rot(q), t)).collect(),
        [0.0, 1.0],
    );
    assert_coverage(&r, &want, "rotate");
}

#[test]
fn deforming_polygon_interpolates_its_vertices() {
    let b = [[9.0, 3.0], [30.5, 7.25], [27.0, 21.0], [12.0, 15.5]];
    let world = format!(
        "Translate 0 0 5\nMotionBegin [0 1]\n{}\n{}\nMotionEnd",
        polygon(&SQUARE),
        polygon(&b)
    );
    let r = render_one(&ortho("Shutter 0 1", &world));
    let want = reference(
        |t| (0..4).map(|k| lerp(SQUARE[k], b[k], t)).collect(),
        [0.0, 1.0],
    );
    assert_coverage(&r, &want, "deform");
}

#[test]
fn camera_motion_blurs_the_world() {
    // The camera moves −17 in x over the shutter, so the world moves +17 in camera space.
    let opts = "Shutter 0 1\nMotionBegin [0 1]\nTranslate 0 0 5\nTranslate 17 0 5\nMotionEnd";
    let r = render_one(&ortho(opts, &polygon(&SQUARE)));
    let want = reference(
        |t| SQUARE.iter().map(|q| [q[0] + 17.0 * t, q[1]]).collect(),
        [0.0, 1.0],
    );
    assert_coverage(&r, &want, "camera");
}

fn bits(r: &Rendered) -> Vec<u32> {
    r.rgba.iter().chain(&r.z).map(|v| v.to_bits()).collect()
}

#[test]
fn closed_shutter_renders_the_first_key_bit_for_bit() {
    let moving = format!(
        "Translate 0 0 5\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate 20 0 0\nMotionEnd\n{}",
        polygon(&SQUARE)
    );
    let still = format!("Translate 0 0 5\n{}", polygon(&SQUARE));
    let a = render_one(&ortho("Shutter 0 0", &moving));
    let b = render_one(&ortho("", &still));
    let c = render_one(&ortho("Shutter 0 0", &still));
    assert!(a.rgba.chunks_exact(4).map(|p| f64::from(p[3])).sum::<f64>() > 50.0);
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(bits(&b), bits(&c));
}

/// A perspective scene with a moving sphere, a deforming patch and depth of field.
const BLUR_SCENE: &str = "Format 64 48 1\nProjection \"perspective\" \"fov\" [40]\n\
    PixelSamples 4 4\nShutter 0 1\nDepthOfField 2.8 0.3 5\n\
    WorldBegin\nTranslate 0 0 5\nLightSource \"distantlight\" 1\nSurface \"plastic\"\n\
    AttributeBegin\nMotionBegin [0 0.5 1]\nTranslate -1 0 0\nTranslate 0 0.3 0\nTranslate 1 0 -1\nMotionEnd\n\
    Sphere 0.8 -0.8 0.8 360\nAttributeEnd\n\
    MotionBegin [0 1]\nPatch \"bilinear\" \"P\" [-3 -1 0  3 -1 0  -3 -1 4  3 -1 4]\n\
    Patch \"bilinear\" \"P\" [-3 -1.5 0  3 -0.5 0  -3 -1.5 4  3 -0.5 4]\nMotionEnd\nWorldEnd\n";

#[test]
fn blur_and_depth_of_field_give_the_same_bits_on_one_and_two_threads() {
    let f = frames(BLUR_SCENE, None);
    let run = |n| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap();
        pool.install(|| render(&f[0], &RenderSettings::default()))
    };
    let (a, b) = (run(1), run(2));
    assert!(a.rgba.chunks_exact(4).map(|p| f64::from(p[3])).sum::<f64>() > 300.0);
    assert_eq!(bits(&a), bits(&b));
}

/// Perspective, fov 30°, 160×160: a camera-space length `l` at depth `z` spans
/// `l/z · 80/tan 15°` pixels.
fn lens_scene(dof: &str, disk_z: f64, disk_r: f64) -> String {
    format!(
        "Format 160 160 1\nProjection \"perspective\" \"fov\" [30]\nPixelSamples 16 16\n\
         PixelFilter \"box\" 1 1\n{dof}\nWorldBegin\nSurface \"constant\"\n\
         Translate 0 0 {disk_z}\nDisk 0 {disk_r} 360\nWorldEnd\n"
    )
}

/// Total alpha and its second moment about the centroid (pixel centres), in pixels².
fn spot(r: &Rendered) -> (f64, f64) {
    let (mut s, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for (k, p) in r.rgba.chunks_exact(4).enumerate() {
        let a = f64::from(p[3]);
        let (x, y) = ((k % 160) as f64 + 0.5, (k / 160) as f64 + 0.5);
        (s, sx, sy) = (s + a, sx + a * x, sy + a * y);
    }
    let (cx, cy) = (sx / s, sy / s);
    let m2 = r
        .rgba
        .chunks_exact(4)
        .enumerate()
        .map(|(k, p)| {
            let (x, y) = ((k % 160) as f64 + 0.5 - cx, (k / 160) as f64 + 0.5 - cy);
            f64::from(p[3]) * (x * x + y * y)
        })
        .sum::<f64>();
    (s, m2 / s)
}

#[test]
fn out_of_focus_disk_blurs_by_the_thin_lens_circle_of_confusion() {
    // Disk of radius 0.05 at z = 3, lens focused at z = 8: fstop 2, focal length 1 gives a lens
    // radius 0.25 and a circle of confusion of radius R·|1/zf − 1/z|·(80/tan 15°) pixels.
    let px = 80.0 / 15f64.to_radians().tan();
    let (z, zf, rad): (f64, f64, f64) = (3.0, 8.0, 0.05);
    let coc = 0.25 * (1.0 / zf - 1.0 / z).abs() * px;
    let rho = rad / z * px;
    let r = render_one(&lens_scene(&format!("DepthOfField 2 1 {zf}"), z, rad));
    let (area, m2) = spot(&r);
    // The spot is the disk image convolved with the circle of confusion: areas are kept, and
    // the second moments of two uniform disks add (ρ²/2 + c²/2), plus 1/6 px² for measuring
    // at pixel centres (a uniform position inside a pixel has variance 1/12 per axis).
    let measured = (2.0 * (m2 - 1.0 / 6.0) - rho * rho).sqrt();
    eprintln!(
        "coc: predicted {coc:.3} px, measured {measured:.3} px; area {area:.2} vs {:.2}",
        std::f64::consts::PI * rho * rho
    );
    assert!(coc > 8.0, "the test needs a visible blur, got {coc}");
    // 2 % on the radius (measured 0.2 %): the spot covers ~π·c² ≈ 760 pixels of 256 samples
    // each, so the second moment's sampling error is far smaller; the disk's own size enters
    // only through ρ²/2 (ρ ≈ 5 px against c ≈ 15.5 px). 7 % on the area (measured +5.4 %;
    // +1.4 % when the disk was diced at the full rate): grid borders reach outward by up to
    // twice a border chord's sagitta so neighbouring grids never crack (`seam_reach` in the
    // hider), and out of focus the disk dices `focusfactor` 1.94× coarser (`lens::focus_factor`),
    // 2-pixel chords whose reach (about 0.2 px around a 31-pixel rim) adds about 6 px².
    assert!(
        (measured - coc).abs() < 0.02 * coc,
        "coc {measured} vs {coc}"
    );
    let want_area = std::f64::consts::PI * rho * rho;
    assert!(
        (area - want_area).abs() < 0.07 * want_area,
        "area {area} vs {want_area}"
    );
}

#[test]
fn in_focus_disk_stays_sharp() {
    let (z, rad) = (6.0, 0.3);
    let sharp = render_one(&lens_scene("", z, rad));
    let lens = render_one(&lens_scene(&format!("DepthOfField 1.4 1 {z}"), z, rad));
    let max = sharp
        .rgba
        .iter()
        .zip(&lens.rgba)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    // On the focal plane the lens offset is exactly zero; only samples lying within rounding
    // of an edge may flip (one sample is 1/256 of a pixel).
    assert!(max <= 2.0 / 256.0 + 1e-6, "in-focus disk changed by {max}");
    assert!(sharp.rgba.chunks_exact(4).map(|p| p[3]).sum::<f32>() > 100.0);
}

/// `∫_{−∞}^{u} clamp(v, 0, 1) dv`: the coverage integral of a pixel-wide ramp.
fn ramp_integral(u: f64) -> f64 {
    if u <= 0.0 {
        0.0
    } else if u <= 1.0 {
        0.5 * u * u
    } else {
        u - 0.5
    }
}

#[test]
fn fast_edge_ramp_matches_the_closed_form() {
    // A rectangle [l0, r0] × [2, 22] translating d pixels right over the shutter, 8×8 samples,
    // box filter: in a row it fully spans, pixel [x, x+1] is covered on average by
    // aL + aR − 1, with aL = (G(x+1−l0) − G(x+1−l0−d))/d the time average of the left edge's
    // clamped overlap, aR likewise for the right edge and G = `ramp_integral` (closed form).
    // d = 13.4 pixels cuts the shutter into 14 time strata, which do not divide the 64 samples.
    let (l0, r0, d) = (3.3, 27.6, 13.4);
    let rect = [[l0, 2.0], [r0, 2.0], [r0, 22.0], [l0, 22.0]];
    let world = format!(
        "Translate 0 0 5\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate {d} 0 0\nMotionEnd\n{}",
        polygon(&rect)
    );
    let rib = ortho("Shutter 0 1", &world).replace("PixelSamples 16 16", "PixelSamples 8 8");
    let r = render_one(&rib);
    let (mut max, mut sum, mut count) = (0.0f64, 0.0, 0);
    // Raster rows 3..=20 lie inside y ∈ [2, 22] (raster y = H − screen y).
    for y in 3..=20 {
        let mut row = 0.0;
        for x in 0..W {
            let xf = x as f64;
            let al = (ramp_integral(xf + 1.0 - l0) - ramp_integral(xf + 1.0 - l0 - d)) / d;
            let ar = (ramp_integral(r0 + d - xf) - ramp_integral(r0 - xf)) / d;
            let want = (al + ar - 1.0).max(0.0);
            let got = f64::from(r.rgba[(y * W + x) * 4 + 3]);
            row += got;
            let e = (got - want).abs();
            max = max.max(e);
            sum += e;
            count += 1;
        }
        // The row's total is the rectangle's width at every instant: only the sampling of
        // pixels the edges sweep adds noise, so 1 %.
        assert!((row - (r0 - l0)).abs() < 0.01 * (r0 - l0), "row {y}: {row}");
    }
    let mean = sum / count as f64;
    eprintln!("edge ramp: max |error| {max:.4}, mean {mean:.5}");
    // 64 samples per pixel: an unstratified estimate has σ ≤ 0.5/8 = 0.0625, so 4σ = 0.25 bounds
    // the largest of these ~900 pixels and 0.02 their mean (stratified x, y and time do better).
    assert!(max < 0.25, "max pixel error {max}");
    assert!(mean < 0.02, "mean pixel error {mean}");
}

/// Fuzz finding `fuzz/regressions/render_rib_slow_motion_eye.rib` (issue 23): a mutated
/// motion-blur scene whose moving spheres pass around the eye. Pieces near the eye at shutter
/// open were diced finely there (millions of 1-pixel micropolygons) and each was tested along
/// a path sweeping the whole frame: over 30 s of CPU for a 24×18 frame. A moving piece is now
/// diced coarser by its motion blur (`refine::motion_factor`). Rendered as the fuzz target
/// clamps it (24×18, 2×2 samples); a test may not time it, so it bounds the micropolygon
/// count instead: 2,763,560 before the fix, a few thousand after (the still frame at shutter
/// open dices 4,576).
#[test]
fn moving_spheres_around_the_eye_dice_a_bounded_number_of_micropolygons() {
    let raw = include_bytes!("../fuzz/regressions/render_rib_slow_motion_eye.rib");
    let rib = String::from_utf8_lossy(raw)
        .replace("Format 200 150 1", "Format 24 18 1")
        .replace("PixelSamples 4 4", "PixelSamples 2 2");
    let (f, _) = support::frames_and_diagnostics(&rib, None);
    assert_eq!(f.len(), 1);
    let r = render(&f[0], &RenderSettings::default());
    assert_eq!((r.width, r.height), (24, 18));
    let mp = r.stats.micropolygons;
    assert!(mp > 0 && mp < 50_000, "{mp} micropolygons");
    assert!(r.rgba.iter().all(|v| v.is_finite()));
}
