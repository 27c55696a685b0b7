//! Ray tracing from the Shading Language (issue 19) through real RIB and `.sl` files, against
//! closed forms computed here in f64. Every scene is orthographic, looking down camera +z at
//! 50 pixels per unit over [-2, 2]², one unjittered sample per pixel and a box filter, so a
//! pixel is the colour shaded near its centre.
//!
//! * Mirror sphere over a checkerboard: `trace(P, reflect(I, N))` returns the checker colour at
//!   the f64 reflected ray's hit point, within 1e-3, at every pixel whose reflected hit points
//!   at the pixel's centre ±1 pixel in x and y all lie in one checker cell (the shaded point is
//!   a grid vertex up to ½ pixel from the centre; colours interpolate across micropolygons).
//! * `transmission()` / `visibility()` through an occluder: 0.5 behind `Opacity 0.5` seen as
//!   `"Os"`, 0 behind an opaque one, 1 where it is `"transparent"` or hidden from shadow rays by
//!   `Attribute "render" "visibility"`, 1 beside it (pixels 2 or more from its edge), within 1e-6.
//! * `occlusion(P, N, 256)`: 0 (exactly) with nothing above the plane; next to a wall of height
//!   H, the column mean equals `½(1 − d/√(d² + H²))` (the cosine-weighted fraction of the
//!   hemisphere behind the wall) within 0.02: 4σ of a 50-pixel mean of 256-sample estimates
//!   (σ ≤ 0.5/√(256·50) ≈ 0.0044 for independent samples; stratification only lowers it).
//! * `Option "trace" "maxdepth"`: two facing mirrors each adding 0.2 give 0.2·(maxdepth + 1).
//! * The same bits with 1 and 2 threads (samples are hashed from the point).
use illume_render::{render, RenderSettings, Rendered};
use std::path::{Path, PathBuf};
mod support;

use support::frames;

const RES: u32 = 200;
const PX: f64 = 50.0;

/// A fresh directory holding `(name, source)` shaders.
fn shader_dir(case: &str, shaders: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("illume-sltrace-{}-{case}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    for (name, src) in shaders {
        std::fs::write(d.join(format!("{name}.sl")), src).unwrap();
    }
    d
}

/// The orthographic frame around `world` with `dir` on the shader searchpath.
fn scene(dir: &Path, options: &str, world: &str) -> String {
    format!(
        "Option \"searchpath\" \"shader\" [\"{}\"]\n{options}\n\
         Format {RES} {RES} 1\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         ShadingRate 0.25\nWorldBegin\n{world}\nWorldEnd\n",
        dir.display()
    )
}

fn render_rib(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    let r = render(&f[0], &RenderSettings::default());
    for w in &r.warnings {
        assert!(!w.message.contains("not implemented"), "{w}");
    }
    r
}

fn pixel(r: &Rendered, x: u32, y: u32) -> [f64; 3] {
    let k = ((y * r.width + x) * 4) as usize;
    [0, 1, 2].map(|c| f64::from(r.rgba[k + c]))
}

/// Camera-space (x, y) of raster (x, y).
fn camera_xy(x: f64, y: f64) -> (f64, f64) {
    (x / PX - 2.0, 2.0 - y / PX)
}

// ---- mirror sphere over a checkerboard ------------------------------------------------------

const MIRROR: &str = "surface tmirror() {
    normal Nf = faceforward(normalize(N), I);
    Ci = trace(P, reflect(normalize(I), Nf));
    Oi = 1;
}";
const CHECKER: &str = "surface tchecker(float lo = 0.1; float hi = 0.9) {
    float c = mod(floor(xcomp(P) / 2) + floor(ycomp(P) / 2), 2);
    Ci = mix(color(lo, lo, lo), color(hi, hi, hi), c);
    Oi = 1;
}";
/// Sphere centre (camera z) and radius; the checker plane at camera z = -1, behind the eye
/// (the camera cannot see it; rays can).
const SPHERE_Z: f64 = 3.0;
const PLANE_Z: f64 = -1.0;

/// The checker cell `(⌊x/2⌋ + ⌊y/2⌋) mod 2` that the reflection of the camera ray at camera
/// (x, y) hits, if it hits the plane.
fn reflected_cell(x: f64, y: f64) -> Option<i64> {
    let (hx, hy) = support::mirror_sphere_reflection(x, y, SPHERE_Z, PLANE_Z)?;
    Some(((hx / 2.0).floor() as i64 + (hy / 2.0).floor() as i64).rem_euclid(2))
}

#[test]
fn a_mirror_sphere_reflects_the_checkerboard_at_the_f64_reflected_hit() {
    let dir = shader_dir("mirror", &[("tmirror", MIRROR), ("tchecker", CHECKER)]);
    let world = format!(
        "AttributeBegin\nSurface \"tchecker\"\n\
         Polygon \"P\" [-60 -60 {PLANE_Z}  60 -60 {PLANE_Z}  60 60 {PLANE_Z}  -60 60 {PLANE_Z}]\n\
         AttributeEnd\nAttributeBegin\nSurface \"tmirror\"\nTranslate 0 0 {SPHERE_Z}\n\
         Sphere 1 -1 1 360\nAttributeEnd"
    );
    let r = render_rib(&scene(&dir, "", &world));
    let (mut checked, mut bad) = (0, Vec::new());
    for y in 0..RES {
        for x in 0..RES {
            let (cx, cy) = camera_xy(f64::from(x) + 0.5, f64::from(y) + 0.5);
            // The reflections stay on the plane's finite extent well inside 0.6 R.
            if cx * cx + cy * cy > 0.36 {
                continue;
            }
            let cells: Vec<Option<i64>> = [-1.0, 0.0, 1.0]
                .iter()
                .flat_map(|dx| [-1.0, 0.0, 1.0].map(|dy| (dx, dy)))
                .map(|(dx, dy)| reflected_cell(cx + dx / PX, cy + dy / PX))
                .collect();
            let Some(c) = cells[4] else { continue };
            if cells.iter().any(|k| *k != Some(c)) {
                continue;
            }
            checked += 1;
            let want = if c == 1 { 0.9 } else { 0.1 };
            let got = pixel(&r, x, y);
            if got.iter().any(|v| (v - want).abs() > 1e-3) {
                bad.push((x, y, got[0], want));
            }
        }
    }
    assert!(
        checked > 1000,
        "only {checked} pixels away from checker edges"
    );
    assert!(
        bad.is_empty(),
        "{} of {checked} pixels differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(10)]
    );
}

// ---- transmission and visibility -----------------------------------------------------------

const TRANS: &str = "surface ttrans(float mode = 0) {
    point far = P + vector(0, 0, 10);
    if (mode == 0) {
        Ci = transmission(P, far);
    } else {
        float v = visibility(P, far);
        Ci = color(v, v, v);
    }
    Oi = 1;
}";

/// The receiver plane at z = 10 (shader `ttrans` in `mode`), and behind it at z = 15 an
/// occluder over x < 0 with `attrs`. Returns the mean colour left (x < −2 px from the edge)
/// and right of the edge, and their largest deviations from those means.
fn transmitted(case: &str, mode: u32, attrs: &str) -> ([f64; 2], f64) {
    let dir = shader_dir(case, &[("ttrans", TRANS)]);
    let world = format!(
        "AttributeBegin\nSurface \"ttrans\" \"mode\" [{mode}]\n\
         Polygon \"P\" [-3 -3 10  3 -3 10  3 3 10  -3 3 10]\nAttributeEnd\n\
         AttributeBegin\n{attrs}\nSurface \"constant\"\n\
         Polygon \"P\" [-5 -5 15  0 -5 15  0 5 15  -5 5 15]\nAttributeEnd"
    );
    let r = render_rib(&scene(&dir, "", &world));
    let (mut left, mut right) = (Vec::new(), Vec::new());
    for y in 0..RES {
        for x in 0..RES {
            let (cx, _) = camera_xy(f64::from(x) + 0.5, 0.0);
            let v = pixel(&r, x, y)[0];
            if cx < -2.0 / PX {
                left.push(v);
            } else if cx > 2.0 / PX {
                right.push(v);
            }
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (ml, mr) = (mean(&left), mean(&right));
    let spread = left
        .iter()
        .map(|v| (v - ml).abs())
        .chain(right.iter().map(|v| (v - mr).abs()))
        .fold(0.0, f64::max);
    ([ml, mr], spread)
}

#[test]
fn transmission_through_a_half_opaque_occluder_is_one_half() {
    let os = "Opacity 0.5 0.5 0.5\nAttribute \"visibility\" \"transmission\" \"Os\"";
    for (case, mode) in [("trans-os", 0), ("vis-os", 1)] {
        let ([l, r], spread) = transmitted(case, mode, os);
        assert!(
            (l - 0.5).abs() < 1e-6 && (r - 1.0).abs() < 1e-6,
            "{case}: {l} {r}"
        );
        assert!(spread < 1e-6, "{case}: spread {spread}");
    }
}

#[test]
fn opaque_transparent_and_ray_invisible_occluders() {
    let cases = [
        ("opaque", "", 0.0),
        (
            "transparent",
            "Attribute \"visibility\" \"transmission\" \"transparent\"",
            1.0,
        ),
        // BMRT's bits: camera and reflection rays only, no shadow rays.
        ("render-vis", "Attribute \"render\" \"visibility\" [3]", 1.0),
    ];
    for (case, attrs, want) in cases {
        let ([l, r], spread) = transmitted(case, 0, attrs);
        assert!(
            (l - want).abs() < 1e-6 && (r - 1.0).abs() < 1e-6,
            "{case}: {l} {r}"
        );
        assert!(spread < 1e-6, "{case}: spread {spread}");
    }
}

// ---- occlusion ------------------------------------------------------------------------------

const OCC: &str = "surface tocc(float samples = 256) {
    normal Nf = faceforward(normalize(N), I);
    float o = occlusion(P, Nf, samples);
    Ci = color(o, o, o);
    Oi = 1;
}";
/// The receiver at camera z = 10 faces the camera; the wall x = 0 rises WALL_H toward it.
const WALL_H: f64 = 2.0;

fn occlusion_rib(case: &str, wall: bool, samples: u32) -> String {
    let dir = shader_dir(case, &[("tocc", OCC)]);
    let z0 = 10.0 - WALL_H;
    let wall = if wall {
        format!(
            "AttributeBegin\nSurface \"constant\"\n\
             Polygon \"P\" [0 -100 {z0}  0 100 {z0}  0 100 10  0 -100 10]\nAttributeEnd"
        )
    } else {
        String::new()
    };
    let world = format!(
        "AttributeBegin\nSurface \"tocc\" \"samples\" [{samples}]\n\
         Polygon \"P\" [-3 -3 10  3 -3 10  3 3 10  -3 3 10]\nAttributeEnd\n{wall}"
    );
    scene(&dir, "", &world)
}

#[test]
fn occlusion_is_zero_under_nothing() {
    let r = render_rib(&occlusion_rib("occ-open", false, 16));
    let worst = r.rgba.chunks(4).map(|p| p[0].abs()).fold(0.0f32, f32::max);
    assert_eq!(worst, 0.0);
}

#[test]
fn occlusion_next_to_a_wall_matches_the_closed_form() {
    let r = render_rib(&occlusion_rib("occ-wall", true, 256));
    let (mut checked, mut worst) = (0, 0.0f64);
    // Columns at distances d from the wall on both sides, 50 rows each (rows 75..125).
    for x in (0..RES).step_by(7) {
        let (cx, _) = camera_xy(f64::from(x) + 0.5, 0.0);
        let d = cx.abs();
        if d < 3.0 / PX {
            continue; // the wall itself, seen edge-on
        }
        let want = 0.5 * (1.0 - d / (d * d + WALL_H * WALL_H).sqrt());
        let got = (75..125).map(|y| pixel(&r, x, y)[0]).sum::<f64>() / 50.0;
        worst = worst.max((got - want).abs());
        assert!(
            (got - want).abs() < 0.02,
            "column {x} (d = {d:.3}): occlusion {got:.4}, closed form {want:.4}"
        );
        checked += 1;
    }
    eprintln!("occlusion by a wall: {checked} columns, worst |mean − closed form| = {worst:.4}");
    assert!(checked > 20);
}

#[test]
fn occlusion_is_the_same_for_any_thread_count() {
    let f = frames(&occlusion_rib("occ-threads", true, 16), None);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&f[0], &RenderSettings::default()))
    };
    let bits = |r: &Rendered| r.rgba.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&run(1)), bits(&run(2)));
}

// ---- maxdepth ------------------------------------------------------------------------------

const GLOW: &str = "surface tglow(float glow = 0.2) {
    normal Nf = faceforward(normalize(N), I);
    Ci = glow + trace(P, reflect(normalize(I), Nf));
    Oi = 1;
}";

#[test]
fn maxdepth_limits_the_bounces_between_two_facing_mirrors() {
    let dir = shader_dir("maxdepth", &[("tglow", GLOW)]);
    // Mirror A at z = 10 faces the camera; mirror B at z = −1 (behind the eye) faces A.
    let world = "Surface \"tglow\"\n\
         Polygon \"P\" [-5 -5 10  5 -5 10  5 5 10  -5 5 10]\n\
         Polygon \"P\" [-5 -5 -1  5 -5 -1  5 5 -1  -5 5 -1]";
    for (option, depth) in [
        ("", 2),
        ("Option \"trace\" \"maxdepth\" [0]", 0),
        ("Option \"trace\" \"maxdepth\" [1]", 1),
        ("Option \"trace\" \"maxdepth\" [3]", 3),
    ] {
        let r = render_rib(&scene(&dir, option, world));
        let want = 0.2 * f64::from(depth + 1);
        let got = pixel(&r, RES / 2, RES / 2)[0];
        assert!(
            (got - want).abs() < 1e-5,
            "maxdepth {depth}: {got}, want {want}"
        );
    }
}

// ---- SL area lights ------------------------------------------------------------------------

/// Listing 9.18 in SL with a ray-traced shadow per sample.
const AREA: &str = "light tarea(float intensity = 1; color lightcolor = 1) {
    illuminate(P, N, PI/2) {
        float s = shadow(\"raytrace\", Ps);
        Cl = (1 - s) * (intensity / (L . L)) * lightcolor;
    }
}";

/// `tests/raytrace.rs`'s penumbra scene: a disk light of radius 0.5 at height 4 over the
/// ground, an occluder at height 1 with its edge at x = 1, the view across the penumbra.
fn area_scene(dir: &Path, light: &str) -> String {
    format!(
        "Option \"searchpath\" \"shader\" [\"{}\"]\n\
         Format 160 80 1\nProjection \"orthographic\"\n\
         ScreenWindow 0.8333 1.8333 -0.25 0.25\nPixelSamples 1 1\nPixelFilter \"box\" 1 1\n\
         Hider \"hidden\" \"jitter\" [0]\nWorldBegin\nTranslate 0 0 10\n\
         AttributeBegin\nAttribute \"light\" \"nsamples\" [16]\n\
         Translate 0 0 -4\nAreaLightSource \"{light}\" 1 \"intensity\" [1]\n\
         Sides 1\nSurface \"constant\"\nDisk 0 0.5 360\nAttributeEnd\n\
         Illuminate 1 1\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\nShadingRate 1\n\
         Polygon \"P\" [-3 -3 0  4 -3 0  4 3 0  -3 3 0]\n\
         Polygon \"P\" [-3 -3 -1  1 -3 -1  1 3 -1  -3 3 -1]\n\
         WorldEnd\n",
        dir.display()
    )
}

/// An SL area light samples its geometry as the built-in `arealight` does (the same points:
/// both draw the built-in's stratified numbers) and shadows each sample with
/// `shadow("raytrace")`, so its penumbra equals the built-in's, whose penumbra
/// `tests/raytrace.rs` checks against the f64 integral of Listing 9.18 (10–90% width within
/// 5%). Metric, relative to the lit value: per-pixel differences within 2e-3 (f32 rounding of
/// `Cl` in two implementations) except at most 1 pixel in 1000, and those by at most one
/// sample's share (1/16): a shadow ray grazing the occluder's edge may decide differently when
/// cast from the other end (the built-in aims from the surface, `shadow()` from its segment).
/// Under `ShadingInterpolation "constant"` a micropolygon's colour is the mean of its four
/// vertices, so one vertex that decides differently moves the four micropolygons around it by
/// a quarter as much: up to 4 pixels in 1000 (measured 20 of 12,800, in groups of 4).
/// A point light in place of the disk, or a sample lost, differs in whole swaths.
#[test]
fn an_sl_area_light_gives_the_builtin_arealight_penumbra() {
    let dir = shader_dir("area", &[("tarea", AREA)]);
    let sl = render_rib(&area_scene(&dir, "tarea"));
    let builtin = render_rib(&area_scene(&dir, "arealight"));
    let lit = builtin.rgba.chunks(4).map(|p| p[0]).fold(0.0f32, f32::max);
    let dark = builtin
        .rgba
        .chunks(4)
        .map(|p| p[0])
        .fold(f32::MAX, f32::min);
    // The view spans the penumbra: fully lit and fully shadowed pixels both appear.
    assert!(lit > 0.01 && dark < 0.1 * lit, "lit {lit}, dark {dark}");
    let worst = sl
        .rgba
        .iter()
        .zip(&builtin.rgba)
        .map(|(a, b)| (a - b).abs() / lit)
        .fold(0.0f32, f32::max);
    let over: Vec<(usize, f32, f32)> = sl
        .rgba
        .chunks(4)
        .zip(builtin.rgba.chunks(4))
        .enumerate()
        .filter(|(_, (a, b))| (a[0] - b[0]).abs() / lit >= 2e-3)
        .map(|(i, (a, b))| (i, a[0] / lit, b[0] / lit))
        .collect();
    assert!(
        worst < 1.0 / 16.0 + 2e-3 && over.len() * 1000 <= 4 * (sl.rgba.len() / 4),
        "largest difference {worst} of the lit value; {} pixels over 2e-3: {:?}",
        over.len(),
        &over[..over.len().min(12)]
    );
}

// ---- Interior/Exterior on traced rays ------------------------------------------------------

/// Mirror at z = 10 (`mirror_attrs` before it; its vertices run clockwise as the camera sees
/// them, so its outside, `Ng`, faces the camera), a constant plane of colour `RAY_C` behind
/// the eye at z = −1: reflected rays cross `RAY_D` = 11 units. Returns one pixel near the
/// centre.
fn ray_volume_pixel(case: &str, mirror_attrs: &str) -> [f64; 3] {
    let dir = shader_dir(
        case,
        &[("tmirror", MIRROR), ("tdist", TDIST), ("teye", TEYE)],
    );
    let [r, g, b] = RAY_C;
    let world = format!(
        "AttributeBegin\nColor {r} {g} {b}\nSurface \"constant\"\n\
         Polygon \"P\" [-60 -60 -1  60 -60 -1  60 60 -1  -60 60 -1]\nAttributeEnd\n\
         AttributeBegin\n{mirror_attrs}\nSurface \"tmirror\"\n\
         Polygon \"P\" [-5 -5 10  -5 5 10  5 5 10  5 -5 10]\nAttributeEnd"
    );
    let r = render_rib(&scene(&dir, "", &world));
    pixel(&r, RES / 2 + 7, RES / 2 - 11)
}

const RAY_C: [f64; 3] = [0.9, 0.5, 0.2];
const RAY_BG: [f64; 3] = [0.2, 0.3, 0.7];
const RAY_D: f64 = 11.0;
/// An SL volume reporting the distance from `E` to `P` (as 1/100 of it).
const TDIST: &str = "volume tdist() { float d = length(P - E) / 100; Ci = color(d, d, d); }";
/// An SL volume reporting `E` itself (offset so negative coordinates show).
const TEYE: &str = "volume teye() { Ci = color(xcomp(E), ycomp(E), zcomp(E)) / 100 + 0.5; }";

fn fogged(distance: f64) -> [f64; 3] {
    let e = (-RAY_D / distance).exp();
    [0, 1, 2].map(|c| RAY_BG[c] + (RAY_C[c] - RAY_BG[c]) * e)
}

fn assert_near(got: [f64; 3], want: [f64; 3], tol: f64, what: &str) {
    for c in 0..3 {
        assert!(
            (got[c] - want[c]).abs() < tol,
            "{what}: got {got:?}, want {want:?}"
        );
    }
}

#[test]
fn an_exterior_fog_attenuates_a_reflection_by_the_closed_form() {
    let fog = |slot: &str, d: f64| {
        format!("{slot} \"fog\" \"distance\" [{d}] \"background\" [0.2 0.3 0.7]")
    };
    assert_near(ray_volume_pixel("vol-none", ""), RAY_C, 1e-6, "no volume");
    for d in [5.0, 30.0] {
        let got = ray_volume_pixel("vol-ext", &fog("Exterior", d));
        assert_near(got, fogged(d), 1e-3, &format!("Exterior fog {d}"));
    }
    // The reflected ray leaves on the outside: the Interior is not crossed.
    let got = ray_volume_pixel("vol-int", &fog("Interior", 5.0));
    assert_near(got, RAY_C, 1e-6, "Interior of a reflection");
    // Reversed, the camera and the reflection are on the inside: now the Interior applies.
    let both = format!(
        "ReverseOrientation\n{}\n{}",
        fog("Interior", 5.0),
        fog("Exterior", 30.0)
    );
    let got = ray_volume_pixel("vol-rev", &both);
    assert_near(got, fogged(5.0), 1e-3, "Interior after ReverseOrientation");
}

#[test]
fn an_sl_exterior_sees_e_at_the_ray_origin() {
    // |P − E| is the segment length (11), not the hit's distance from the camera.
    let got = ray_volume_pixel("vol-sl-dist", "Exterior \"tdist\"");
    assert_near(got, [RAY_D / 100.0; 3], 1e-4, "length(P - E)");
    // E is the mirror point the centre ray reflects from: (x, y, 10).
    let (x, y) = camera_xy(f64::from(RES / 2 + 7) + 0.5, f64::from(RES / 2 - 11) + 0.5);
    let got = ray_volume_pixel("vol-sl-eye", "Exterior \"teye\"");
    let want = [x, y, 10.0].map(|v| v / 100.0 + 0.5);
    // The shaded point is a grid vertex within half a pixel (1/100 unit) of the centre.
    assert_near(got, want, 0.011 / 100.0 + 1e-5, "E");
}

/// A reflection that hits nothing crosses the mirror's `Exterior` up to the far clipping
/// distance `far` (measured along the ray): `fog` over black gives `bg·(1 − e^(−far/D))`.
#[test]
fn an_exterior_fog_colours_a_reflection_that_misses_everything() {
    let dir = shader_dir("vol-miss", &[("tmirror", MIRROR)]);
    let miss = |clipping: &str, attrs: &str| {
        let world = format!(
            "AttributeBegin\n{attrs}\nSurface \"tmirror\"\n\
             Polygon \"P\" [-5 -5 10  -5 5 10  5 5 10  5 -5 10]\nAttributeEnd"
        );
        let r = render_rib(&scene(&dir, clipping, &world));
        pixel(&r, RES / 2 + 7, RES / 2 - 11)
    };
    let fog = "Exterior \"fog\" \"distance\" [10] \"background\" [0.2 0.3 0.7]";
    assert_near(miss("Clipping 0.1 20", ""), [0.0; 3], 1e-6, "no volume");
    let k = 1.0 - (-20.0f64 / 10.0).exp();
    let want = RAY_BG.map(|c| c * k);
    assert_near(
        miss("Clipping 0.1 20", fog),
        want,
        1e-3,
        "fog to the far plane",
    );
    // The Interior is not on the reflection's side: still black.
    let interior = fog.replace("Exterior", "Interior");
    assert_near(
        miss("Clipping 0.1 20", &interior),
        [0.0; 3],
        1e-6,
        "Interior",
    );
}

// ---- ray differentials ---------------------------------------------------------------------

/// The mirror divides what it sees by its own micropolygon's area; the plane it sees shows
/// the area of the footprint the beam covers there. A pixel is then (times `BEAM_SCALE`) the
/// area magnification of the reflection, whatever the dicing rate.
const TBEAM: &str = "surface tbeam() {
    normal Nf = faceforward(normalize(N), I);
    Ci = trace(P, reflect(normalize(I), Nf)) * (0.002 / area(P));
    Oi = 1;
}";
const TAREA: &str = "surface tarea() { Ci = color(area(P)); Oi = 1; }";
const BEAM_SCALE: f64 = 0.002;

/// The mirror point and the plane point (z = `PLANE_Z`) the reflection of the camera ray at
/// camera (x, y) reaches, in f64.
fn mirror_and_hit(x: f64, y: f64) -> ([f64; 3], [f64; 3]) {
    let z = SPHERE_Z - (1.0 - x * x - y * y).sqrt();
    let n = [x, y, z - SPHERE_Z];
    let r = [
        -2.0 * n[2] * n[0],
        -2.0 * n[2] * n[1],
        1.0 - 2.0 * n[2] * n[2],
    ];
    let t = (PLANE_Z - z) / r[2];
    ([x, y, z], [x + t * r[0], y + t * r[1], PLANE_Z])
}

/// `|∂H/∂x × ∂H/∂y| / |∂M/∂x × ∂M/∂y|`: how much larger a patch of the plane is than the
/// patch of mirror reflecting it (central differences of the closed form).
fn magnification(x: f64, y: f64) -> f64 {
    let h = 1e-5;
    let d = |f: &dyn Fn(f64, f64) -> [f64; 3], ax: bool| {
        let (a, b) = if ax {
            (f(x + h, y), f(x - h, y))
        } else {
            (f(x, y + h), f(x, y - h))
        };
        [0, 1, 2].map(|k| (a[k] - b[k]) / (2.0 * h))
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
    };
    let m = |x: f64, y: f64| mirror_and_hit(x, y).0;
    let hit = |x: f64, y: f64| mirror_and_hit(x, y).1;
    cross(d(&hit, true), d(&hit, false)) / cross(d(&m, true), d(&m, false))
}

/// Traced rays carry differentials: the footprint at the hit is the beam's, so its area
/// over the mirror's is the reflection's area magnification (49 at the centre, where the
/// convex mirror's beam spreads from its focal point r/2 behind it: (0.5 + 3)/0.5 = 7 per
/// axis at the plane 3 in front; growing outwards, to 110 at the pixels farthest from the
/// axis here) within 5% (second-order terms
/// over a micropolygon, and the shaded vertex lying up to half a micropolygon from the pixel
/// centre; nearer the rim, where it grows past 600, the linear beam falls 9% short). Without
/// differentials the hit's area is 0.
#[test]
fn a_traced_beam_spreads_as_the_reflection_magnifies() {
    let dir = shader_dir("beam", &[("tbeam", TBEAM), ("tarea", TAREA)]);
    let world = format!(
        "AttributeBegin\nSurface \"tarea\"\n\
         Polygon \"P\" [-60 -60 {PLANE_Z}  60 -60 {PLANE_Z}  60 60 {PLANE_Z}  -60 60 {PLANE_Z}]\n\
         AttributeEnd\n\
         AttributeBegin\nSurface \"tbeam\"\nTranslate 0 0 {SPHERE_Z}\nSphere 1 -1 1 360\n\
         AttributeEnd"
    );
    let r = render_rib(&scene(&dir, "", &world));
    let mut checked = 0;
    for (px, py) in [(100u32, 100u32), (112, 95), (90, 115), (110, 108), (86, 90)] {
        let (x, y) = camera_xy(f64::from(px) + 0.5, f64::from(py) + 0.5);
        let want = magnification(x, y);
        let got = pixel(&r, px, py)[0] / BEAM_SCALE;
        eprintln!("beam ({x:.3}, {y:.3}): {got:.3} vs {want:.3}");
        assert!(
            (got / want - 1.0).abs() < 0.05,
            "pixel ({px}, {py}) at ({x:.3}, {y:.3}): magnification {got:.3}, closed form {want:.3}"
        );
        checked += 1;
    }
    assert_eq!(checked, 5);
    let centre = magnification(0.0, 0.0);
    assert!((centre - 49.0).abs() < 1e-3, "{centre}");
}

// ---- blurred environment("raytrace") -------------------------------------------------------

const TENV: &str = "surface tenv(float blur = 0; float samples = 16; float usetrace = 0) {
    normal Nf = faceforward(normalize(N), I);
    vector R = reflect(normalize(I), Nf);
    if (usetrace > 0) {
        Ci = trace(P, R);
    } else {
        Ci = environment(\"raytrace\", R, \"blur\", blur, \"samples\", samples);
    }
    Oi = 1;
}";
/// A checker of unit cells (0.1 / 0.9).
const FINE_CHECKER: &str = "surface tfine() {
    float c = mod(floor(xcomp(P)) + floor(ycomp(P)), 2);
    Ci = mix(color(0.1), color(0.9), c);
    Oi = 1;
}";

/// A 24² view of a mirror at z = 10 shaded by `tenv` with `params`, reflecting a checker
/// behind the eye at z = −1; the red channel of every pixel.
fn environment_pixels(case: &str, params: &str) -> Vec<f64> {
    let dir = shader_dir(case, &[("tenv", TENV), ("tfine", FINE_CHECKER)]);
    let rib = format!(
        "Option \"searchpath\" \"shader\" [\"{}\"]\n\
         Format 24 24 1\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         ShadingRate 1\nWorldBegin\n\
         AttributeBegin\nSurface \"tfine\"\n\
         Polygon \"P\" [-60 -60 -1  60 -60 -1  60 60 -1  -60 60 -1]\nAttributeEnd\n\
         AttributeBegin\nSurface \"tenv\" {params}\n\
         Polygon \"P\" [-5 -5 10  5 -5 10  5 5 10  -5 5 10]\nAttributeEnd\nWorldEnd\n",
        dir.display()
    );
    let r = render_rib(&rib);
    r.rgba.chunks(4).map(|p| f64::from(p[0])).collect()
}

#[test]
fn a_blur_zero_environment_is_the_single_traced_ray() {
    let traced = environment_pixels("env-trace", "\"usetrace\" [1]");
    let env = environment_pixels("env-blur0", "\"blur\" [0] \"samples\" [16]");
    assert_eq!(traced, env);
    // The checker shows through unblurred: both colours appear.
    assert!(env.iter().any(|&v| (v - 0.1).abs() < 1e-6));
    assert!(env.iter().any(|&v| (v - 0.9).abs() < 1e-6));
}

#[test]
fn a_blurred_environment_converges_as_samples_grow() {
    // Cone half-angle 0.3 over 11 units: a disk of radius ≈ 3.4 cells, mean ≈ 0.5. The mean
    // squared difference from a 256-sample reference falls with the sample count (for
    // independent samples as 1/n: 16× from 4 to 64; asserted ≥ 4×, the reference's own noise
    // and the strata's correlation taking the rest).
    let reference = environment_pixels("env-ref", "\"blur\" [0.3] \"samples\" [256]");
    let mse = |n: u32| {
        let p = environment_pixels(
            &format!("env-{n}"),
            &format!("\"blur\" [0.3] \"samples\" [{n}]"),
        );
        p.iter()
            .zip(&reference)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            / p.len() as f64
    };
    let (m4, m16, m64) = (mse(4), mse(16), mse(64));
    assert!(m4 > m16 && m16 > m64, "mse {m4} {m16} {m64}");
    assert!(m4 > 4.0 * m64, "mse {m4} {m64}");
    // Blurred, the pixels lie near the checker's mean, not at its two colours.
    let mean = reference.iter().sum::<f64>() / reference.len() as f64;
    assert!((mean - 0.5).abs() < 0.05, "mean {mean}");
}
