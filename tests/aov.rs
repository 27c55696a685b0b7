//! Arbitrary output variables (issue 20), end to end: RIB `Display` modes and `DisplayChannel`
//! through the hider into float OpenEXR files, read back by our reader and by OpenEXR's
//! `exrheader` and OpenImageIO's `oiiotool`.
//!
//! Metrics and thresholds (each with its reason):
//! - components: per pixel and channel, |Ci − (__ambient + __diffuse + __specular +
//!   __reflection)| ≤ 1e-5 (the issue's): each material's `components` repeats its `shade`
//!   term by term, so only float rounding separates them.
//! - `N` of an orthographic unit sphere, normalised, within 1e-3 of the closed-form normal at
//!   the pixel centre; `P` and `z` within 1e-3 of the closed-form point and depth (one sample
//!   per pixel at its centre, box filter 1×1, shading rate 0.25, smooth shading interpolation:
//!   what remains is the chord error of micropolygons ~0.02 units wide, about 1e-4).
//! - an SL `output varying color` equals the value the shader wrote (also its `Ci`) to 1e-6.
use illume_imageio::{read_image, Image};
use std::path::{Path, PathBuf};
use std::process::Command;
mod support;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-aov-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn textures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("textures")
}

/// The values of channel `name` (lower-cased, as our reader names them).
fn channel(img: &Image, name: &str) -> Vec<f32> {
    let k = img
        .channel_index(&name.to_ascii_lowercase())
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", img.channels));
    let nc = img.channels.len();
    img.data.iter().skip(k).step_by(nc).copied().collect()
}

const LIGHTS: &str = r#"LightSource "ambientlight" 1 "intensity" 0.2
LightSource "distantlight" 2 "from" [0 1 -1] "to" [0 0 0] "intensity" 0.9
LightSource "pointlight" 3 "from" [-3 2 -2] "intensity" 12
"#;

/// Renders `surface` on a sphere and a plane behind it with the four components and `Ci` in
/// one float EXR; returns the file read back.
fn components_render(case: &str, surface: &str) -> Image {
    let dir = scratch(case);
    let exr = dir.join("c.exr");
    let rib = format!(
        r#"Format 48 40 1
PixelSamples 3 3
Quantize "rgba" 0 0 0 0
Display "{}" "openexr" "Ci,__ambient,__diffuse,__specular,__reflection"
Projection "perspective" "fov" 40
Translate 0 0 5
WorldBegin
{LIGHTS}
AttributeBegin
Color [0.9 0.6 0.3]
Opacity [0.8 0.7 0.9]
{surface}
Sphere 1 -1 1 360
AttributeEnd
Surface "plastic"
Polygon "P" [-3 -3 2  3 -3 2  3 3 2  -3 3 2] "st" [0 0 1 0 1 1 0 1]
WorldEnd
"#,
        exr.display()
    );
    support::run_rib(&rib);
    let img = read_image(&exr).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    img
}

fn assert_components_sum_to_ci(case: &str, img: &Image, expect_reflection: bool) {
    let mut worst = 0.0f32;
    for c in ["R", "G", "B"] {
        let ci = channel(img, &format!("Ci.{c}"));
        let parts: Vec<Vec<f32>> = ["__ambient", "__diffuse", "__specular", "__reflection"]
            .iter()
            .map(|n| channel(img, &format!("{n}.{c}")))
            .collect();
        for (p, &v) in ci.iter().enumerate() {
            let sum: f32 = parts.iter().map(|k| k[p]).sum();
            worst = worst.max((v - sum).abs());
        }
        for (k, part) in parts.iter().enumerate() {
            let max = part.iter().copied().fold(0.0f32, f32::max);
            let wanted = k < 3 || expect_reflection;
            assert_eq!(
                max > 1e-3,
                wanted,
                "{case}: component {k} channel {c} max {max}"
            );
        }
    }
    eprintln!("{case}: max |Ci − Σ components| = {worst:e}");
    assert!(worst <= 1e-5, "{case}: components miss Ci by {worst}");
}

#[test]
fn plastic_components_sum_to_ci() {
    let img = components_render("plastic", r#"Surface "plastic" "Ks" 0.7"#);
    assert_components_sum_to_ci("plastic", &img, false);
}

#[test]
fn shinymetal_components_with_an_environment_sum_to_ci() {
    let sky = textures().join("sky.exr");
    let surface = format!(
        r#"Surface "shinymetal" "texturename" "{}" "Kd" 0.3"#,
        sky.display()
    );
    let img = components_render("shinymetal", &surface);
    assert_components_sum_to_ci("shinymetal", &img, true);
}

#[test]
fn textured_paintedplastic_components_sum_to_ci() {
    let checker = textures().join("checker.tif");
    let surface = format!(
        r#"Surface "paintedplastic" "texturename" "{}""#,
        checker.display()
    );
    let img = components_render("painted", &surface);
    assert_components_sum_to_ci("paintedplastic", &img, false);
}

/// An orthographic unit sphere at z = 5 filling a 2.5-unit screen, 64×64 pixels, one sample
/// per pixel centre; `mode` names the variables.
fn sphere_geometry(case: &str, mode: &str) -> (Image, PathBuf) {
    let dir = scratch(case);
    let exr = dir.join("g.exr");
    let rib = format!(
        r#"Format 64 64 1
PixelSamples 1 1
PixelFilter "box" 1 1
Hider "hidden" "jitter" [0]
ShadingRate 0.25
ShadingInterpolation "smooth"
Quantize "rgba" 0 0 0 0
Display "{}" "openexr" "{mode}"
Projection "orthographic"
ScreenWindow -1.25 1.25 -1.25 1.25
Translate 0 0 5
WorldBegin
Surface "matte"
Sphere 1 -1 1 360
WorldEnd
"#,
        exr.display()
    );
    support::run_rib(&rib);
    (read_image(&exr).unwrap(), dir)
}

/// Camera-space (x, y) of pixel (i, j)'s centre, and whether it lies well inside the sphere.
fn pixel_centre(i: usize, j: usize) -> (f64, f64, bool) {
    let x = -1.25 + (i as f64 + 0.5) * 2.5 / 64.0;
    let y = 1.25 - (j as f64 + 0.5) * 2.5 / 64.0;
    (x, y, x * x + y * y < 0.8 * 0.8)
}

#[test]
fn n_p_and_z_of_an_orthographic_sphere_match_the_closed_form() {
    let (img, dir) = sphere_geometry("geometry", "rgba,N,P,z");
    let (nx, ny, nz) = (
        channel(&img, "N.X"),
        channel(&img, "N.Y"),
        channel(&img, "N.Z"),
    );
    let (px, py, pz) = (
        channel(&img, "P.X"),
        channel(&img, "P.Y"),
        channel(&img, "P.Z"),
    );
    let z = channel(&img, "z");
    let (mut worst_n, mut worst_p, mut worst_z, mut inside) = (0.0f64, 0.0f64, 0.0f64, 0);
    for j in 0..64 {
        for i in 0..64 {
            let (x, y, ok) = pixel_centre(i, j);
            if !ok {
                continue;
            }
            inside += 1;
            let k = j * 64 + i;
            let front = -(1.0 - x * x - y * y).sqrt();
            let n = glam::DVec3::new(nx[k] as f64, ny[k] as f64, nz[k] as f64).normalize();
            worst_n = worst_n.max((n - glam::DVec3::new(x, y, front)).abs().max_element());
            let p = glam::DVec3::new(px[k] as f64, py[k] as f64, pz[k] as f64);
            worst_p = worst_p.max(
                (p - glam::DVec3::new(x, y, 5.0 + front))
                    .abs()
                    .max_element(),
            );
            worst_z = worst_z.max((z[k] as f64 - (5.0 + front)).abs());
        }
    }
    eprintln!("{inside} pixels: max error N {worst_n:e}, P {worst_p:e}, z {worst_z:e}");
    assert!(inside > 1200, "{inside}");
    assert!(worst_n <= 1e-3, "N off by {worst_n}");
    assert!(worst_p <= 1e-3, "P off by {worst_p}");
    assert!(worst_z <= 1e-3, "z off by {worst_z}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_sl_output_varying_colour_reaches_the_file_as_the_shader_wrote_it() {
    let dir = scratch("sl");
    std::fs::write(
        dir.join("aovout.sl"),
        "surface aovout (output varying color mine = 0) {\n\
           mine = color (s, t, 0.25);\n\
           Oi = Os;\n\
           Ci = Os * mine;\n\
         }\n",
    )
    .unwrap();
    let exr = dir.join("sl.exr");
    let rib = format!(
        r#"Option "searchpath" "shader" ["{}"]
Format 32 32 1
PixelSamples 2 2
Quantize "rgba" 0 0 0 0
DisplayChannel "color mine"
Display "{}" "openexr" "rgba,mine"
Projection "orthographic"
WorldBegin
Translate 0 0 5
Surface "aovout"
Polygon "P" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] "st" [0 0 1 0 1 1 0 1]
WorldEnd
"#,
        dir.display(),
        exr.display()
    );
    support::run_rib(&rib);
    let img = read_image(&exr).unwrap();
    for (beauty, aov) in [("r", "mine.R"), ("g", "mine.G"), ("b", "mine.B")] {
        let (a, b) = (channel(&img, beauty), channel(&img, aov));
        let worst = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f32::max);
        assert!(worst <= 1e-6, "{aov} differs from {beauty} by {worst}");
    }
    // The blue channel is the constant the shader wrote (where the polygon covers the
    // pixel's whole filter: the border pixels also weigh empty samples).
    let alpha = channel(&img, "a");
    let blue = channel(&img, "mine.B");
    let covered: Vec<f32> = (0..blue.len())
        .filter(|&p| alpha[p] >= 1.0)
        .map(|p| blue[p])
        .collect();
    assert!(covered.len() > 500, "{}", covered.len());
    assert!(
        covered.iter().all(|&v| (v - 0.25).abs() < 1e-6),
        "{covered:?}"
    );
    let s = channel(&img, "mine.R");
    assert!(
        s.iter().copied().fold(0.0, f32::max) > 0.8,
        "s varies across the frame"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_crop_carries_every_aov_bit_for_bit() {
    let rib = r#"Format 40 30 1
PixelSamples 2 2
Display "unused.exr" "openexr" "rgba,__diffuse,N,s"
Projection "perspective" "fov" 40
Translate 0 0 5
WorldBegin
LightSource "distantlight" 1
Surface "plastic"
Sphere 1 -1 1 360
WorldEnd
"#;
    let full_frame = &support::frames(rib, None)[0];
    let full = illume_render::render(full_frame, &Default::default());
    let crop_frame = &support::frames(rib, Some([0.25, 0.75, 0.2, 0.7]))[0];
    let crop = illume_render::render(crop_frame, &Default::default());
    let stride = full.aov_layout.stride;
    assert_eq!(stride, 7);
    assert_eq!(crop.aov_layout, full.aov_layout);
    for y in 0..crop.height {
        for x in 0..crop.width {
            let c = (y * crop.width + x) as usize * stride;
            let f = ((y + crop.y0) * full.width + x + crop.x0) as usize * stride;
            let bits = |v: &[f32]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&crop.aov[c..c + stride]),
                bits(&full.aov[f..f + stride])
            );
        }
    }
}

#[test]
fn unused_aovs_cost_nothing_and_leave_the_beauty_unchanged() {
    let rib = |mode: &str| {
        format!(
            "Format 32 24 1\nDisplay \"unused.tif\" \"tiff\" \"{mode}\"\nProjection \"perspective\"\n\
             Translate 0 0 5\nWorldBegin\nLightSource \"distantlight\" 1\nSurface \"plastic\"\n\
             Sphere 1 -1 1 360\nWorldEnd\n"
        )
    };
    let plain = illume_render::render(&support::frames(&rib("rgba"), None)[0], &Default::default());
    let with = illume_render::render(
        &support::frames(&rib("rgba,__specular"), None)[0],
        &Default::default(),
    );
    assert_eq!(plain.aov_layout.stride, 0);
    assert!(plain.aov.is_empty());
    assert_eq!(plain.stats.aov_bucket_peak_bytes, 0);
    assert!(with.stats.aov_bucket_peak_bytes > 0);
    let bits = |v: &[f32]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        bits(&plain.rgba),
        bits(&with.rgba),
        "AOVs changed the beauty"
    );
}

#[test]
fn formats_that_cannot_hold_the_channels_are_errors_naming_the_file() {
    let rib = r#"Format 16 16 1
Display "five.tif" "tiff" "rgba,N"
Display "+normal.png" "png" "N"
Display "+bad.exr" "openexr" "nosuchvariable"
WorldBegin
Sphere 1 -1 1 360
WorldEnd
"#;
    let frame = &support::frames(rib, None)[0];
    let dir = scratch("formats");
    let r = illume_render::render(frame, &Default::default());
    let mut frame_here = support::frames(rib, None).remove(0);
    for d in &mut frame_here.options.displays {
        d.name = dir.join(&d.name).display().to_string();
    }
    let results = illume_render::write_displays(&frame_here, &r);
    let errors: Vec<String> = results
        .into_iter()
        .map(|r| r.expect_err("each display is impossible").to_string())
        .collect();
    assert!(
        errors[0].contains("five.tif") && errors[0].contains("at most 4"),
        "{}",
        errors[0]
    );
    assert!(
        errors[1].contains("normal.png") && errors[1].contains("PNG"),
        "{}",
        errors[1]
    );
    assert!(
        errors[2].contains("bad.exr") && errors[2].contains("nosuchvariable"),
        "{}",
        errors[2]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `exrheader` lists the named channels; `oiiotool --stats` agrees with our reader on every
/// channel's minimum, maximum and average (to 1e-5 relative: both read the same floats).
#[test]
fn exrheader_and_oiiotool_read_the_aov_file() {
    let (Some(_), Some(_)) = (
        illume_testenv::require_tool("exrheader"),
        illume_testenv::require_tool("oiiotool"),
    ) else {
        return;
    };
    let (img, dir) = sphere_geometry("interop", "rgba,N,s,__diffuse");
    let exr = dir.join("g.exr");
    let out = Command::new("exrheader").arg(&exr).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    for name in [
        "N.X",
        "N.Y",
        "N.Z",
        "s,",
        "__diffuse.R",
        "__diffuse.G",
        "__diffuse.B",
        "A,",
    ] {
        assert!(
            text.contains(&format!("    {name}")),
            "exrheader lacks {name}: {text}"
        );
    }
    let out = Command::new("oiiotool")
        .args(["--info", "-v", "--stats"])
        .arg(&exr)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}");
    let line = |key: &str| -> &str {
        text.lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .unwrap_or_else(|| panic!("no {key} in {text}"))
    };
    let names: Vec<String> = line("channel list:")
        .split(',')
        .map(|n| n.trim().to_ascii_lowercase())
        .collect();
    let row = |key: &str| -> Vec<f64> {
        line(key)
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect()
    };
    let (min, max, avg) = (row("Stats Min:"), row("Stats Max:"), row("Stats Avg:"));
    assert_eq!(names.len(), img.channels.len(), "{text}");
    assert_eq!(min.len(), names.len(), "{text}");
    for (c, name) in names.iter().enumerate() {
        let v: Vec<f64> = channel(&img, name).iter().map(|&x| x as f64).collect();
        let mn = v.iter().copied().fold(f64::INFINITY, f64::min);
        let mx = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let av = v.iter().sum::<f64>() / v.len() as f64;
        for (theirs, ours) in [(min[c], mn), (max[c], mx), (avg[c], av)] {
            // oiiotool prints 6 decimals.
            assert!(
                (theirs - ours).abs() <= 2e-6,
                "{name}: oiiotool {theirs} vs ours {ours}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn inline_declare_and_displaychannel_types_shape_the_channels() {
    let dir = scratch("types");
    std::fs::write(
        dir.join("outs.sl"),
        "surface outs (output varying float f = 0; output varying vector w = 0;\n\
                        output varying color c = 0) {\n\
           f = s; w = vector (1, 2, 3); c = color (t, 0, 0);\n\
           Oi = Os; Ci = Os;\n\
         }\n",
    )
    .unwrap();
    let exr = dir.join("t.exr");
    let rib = format!(
        r#"Option "searchpath" "shader" ["{}"]
Format 8 8 1
Declare "w" "varying vector"
DisplayChannel "color c"
Display "{}" "openexr" "varying float f,w,c,Cs"
WorldBegin
Surface "outs"
Polygon "P" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]
WorldEnd
"#,
        dir.display(),
        exr.display()
    );
    support::run_rib(&rib);
    let img = read_image(&exr).unwrap();
    let mut names = img.channels.clone();
    names.sort();
    assert_eq!(
        names,
        ["c.b", "c.g", "c.r", "cs.b", "cs.g", "cs.r", "f", "w.x", "w.y", "w.z"]
    );
    assert!(channel(&img, "w.Y").iter().all(|&v| (v - 2.0).abs() < 1e-6));
    // A DisplayChannel without a name is an error at its request.
    let mut ri = illume_ri::Ri::new();
    let parser = illume_rib::Parser::new(
        std::io::Cursor::new(b"DisplayChannel \"color\"\n".to_vec()),
        "bad.rib",
    );
    for item in parser {
        ri.request(item.unwrap());
    }
    let d = ri.drain_diagnostics();
    assert!(
        d.iter().any(|d| d.severity == illume_ri::Severity::Error
            && d.to_string().contains("bad.rib:1")
            && d.to_string().contains("type name")),
        "{d:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Channel `name` component `k` of every pixel of a render, straight from the hider.
fn rendered(r: &illume_render::Rendered, name: &str, k: usize) -> Vec<f32> {
    let l = &r.aov_layout;
    let c = l.channels.iter().position(|c| c.name == name).unwrap();
    let off = l.offsets[c] + k;
    r.aov.iter().skip(off).step_by(l.stride).copied().collect()
}

/// Every built-in surface and the components it must light up (ambient, diffuse, specular,
/// reflection) under `LIGHTS` with no environment map.
const SURFACES: [(&str, [bool; 4]); 13] = [
    ("constant", [true, false, false, false]),
    ("defaultsurface", [true, true, false, false]),
    ("matte", [true, true, false, false]),
    ("plastic", [true, true, true, false]),
    ("paintedplastic", [true, true, true, false]),
    ("metal", [true, false, true, false]),
    ("roughmetal", [true, true, true, false]),
    ("thinplastic", [true, true, true, false]),
    ("shinymetal", [true, false, true, false]),
    ("shinyplastic", [true, true, true, false]),
    ("orennayar", [true, true, false, false]),
    ("wardanisotropic", [true, true, true, false]),
    ("glossy", [true, true, true, false]),
];

/// Table test over every built-in surface: one orthographic frame of a 4×4 grid of spheres,
/// sphere k (surface `SURFACES[k]`) in cell (k % 4, k / 4) of 24×24 pixels; in each cell
/// |Ci − Σ components| ≤ 1e-5 and exactly the expected components are non-black (> 1e-3).
#[test]
fn every_builtin_surface_splits_into_components_that_sum_to_ci() {
    let mut world = String::new();
    for (k, (name, _)) in SURFACES.iter().enumerate() {
        let (cx, cy) = ((k % 4) as f32 - 1.5, 1.5 - (k / 4) as f32);
        world += &format!(
            "AttributeBegin\nTranslate {cx} {cy} 0\nSurface \"{name}\"\nSphere 0.45 -0.45 0.45 360\nAttributeEnd\n"
        );
    }
    let rib = format!(
        "Format 96 96 1\nPixelSamples 2 2\nDisplay \"t.exr\" \"openexr\" \"Ci,__ambient,__diffuse,__specular,__reflection\"\n\
         Projection \"orthographic\"\nScreenWindow -2 2 -2 2\nTranslate 0 0 5\nWorldBegin\n{LIGHTS}\
         Color [0.9 0.6 0.3]\nOpacity [0.8 0.7 0.9]\n{world}WorldEnd\n"
    );
    let r = illume_render::render(&support::frames(&rib, None)[0], &Default::default());
    let names = ["__ambient", "__diffuse", "__specular", "__reflection"];
    for (k, (name, lit)) in SURFACES.iter().enumerate() {
        let (x0, y0) = ((k % 4) * 24, (k / 4) * 24);
        let (mut worst, mut ci_max, mut max) = (0.0f32, 0.0f32, [0.0f32; 4]);
        for c in 0..3 {
            let ci = rendered(&r, "Ci", c);
            let parts: Vec<Vec<f32>> = names.iter().map(|n| rendered(&r, n, c)).collect();
            for p in (y0..y0 + 24).flat_map(|y| (x0..x0 + 24).map(move |x| y * 96 + x)) {
                let sum: f32 = parts.iter().map(|v| v[p]).sum();
                worst = worst.max((ci[p] - sum).abs());
                ci_max = ci_max.max(ci[p]);
                for (m, v) in max.iter_mut().zip(&parts) {
                    *m = m.max(v[p].abs());
                }
            }
        }
        eprintln!("{name}: max |Ci − Σ| = {worst:e}, component maxima {max:?}");
        assert!(ci_max > 0.05, "{name}: sphere missing (Ci max {ci_max})");
        assert!(worst <= 1e-5, "{name}: components miss Ci by {worst}");
        let got = max.map(|m| m > 1e-3);
        assert_eq!(&got, lit, "{name}: which components are lit {max:?}");
    }
}

/// Components are what the surface wrote (PRMan): an `Atmosphere "fog"` changes `Ci` (and, on
/// a half-transparent surface, `Oi`) but not `__diffuse`, which must be bit for bit the
/// fog-free render's. One layer (a square): behind a transparent layer the fog's `Oi` would
/// rightly change how much of the next layer shows.
#[test]
fn the_atmosphere_changes_ci_but_not_the_components() {
    let rib = |atmosphere: &str| {
        format!(
            "Format 32 24 1\nDisplay \"fog.exr\" \"openexr\" \"Ci,__diffuse\"\nProjection \"perspective\"\n\
             Translate 0 0 5\nWorldBegin\n{LIGHTS}{atmosphere}\nColor [0.9 0.6 0.3]\nOpacity [0.6 0.6 0.6]\nSurface \"plastic\"\n\
             Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\nWorldEnd\n"
        )
    };
    let clear = illume_render::render(&support::frames(&rib(""), None)[0], &Default::default());
    let fog = r#"Atmosphere "fog" "distance" 2 "background" [0.2 0.4 0.9]"#;
    let foggy = illume_render::render(&support::frames(&rib(fog), None)[0], &Default::default());
    let bits = |v: Vec<f32>| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
    let moved = (0..3)
        .flat_map(|c| {
            let (a, b) = (rendered(&clear, "Ci", c), rendered(&foggy, "Ci", c));
            a.into_iter().zip(b).map(|(a, b)| (a - b).abs())
        })
        .fold(0.0f32, f32::max);
    assert!(moved > 0.05, "the fog did not change Ci ({moved})");
    for c in 0..3 {
        assert_eq!(
            bits(rendered(&clear, "__diffuse", c)),
            bits(rendered(&foggy, "__diffuse", c)),
            "fog changed __diffuse channel {c}"
        );
    }
}

/// `Exposure` (and a display's own `"exposure"`) reach colour variables as `(gain·c)^(1/γ)`,
/// never `N`, `P`, `s` or `z`. Metrics: colour within 1e-5 relative of the closed form
/// applied to the unexposed render's value; non-colour bit for bit the unexposed file's.
#[test]
fn exposure_reaches_colour_variables_only() {
    let dir = scratch("exposure");
    let run = |exposure: &str| {
        let rib = format!(
            "Format 24 16 1\n{exposure}\nQuantize \"rgba\" 0 0 0 0\n\
             Display \"{0}/e.exr\" \"openexr\" \"rgba,Ci,__diffuse,N,P,s,z\"\n\
             Display \"+{0}/own.exr\" \"openexr\" \"__diffuse,t\" \"exposure\" [3 1]\n\
             Projection \"perspective\"\nTranslate 0 0 5\nWorldBegin\n{LIGHTS}\
             Surface \"plastic\"\nSphere 1 -1 1 360\nWorldEnd\n",
            dir.display()
        );
        support::run_rib(&rib);
        (
            read_image(&dir.join("e.exr")).unwrap(),
            read_image(&dir.join("own.exr")).unwrap(),
        )
    };
    let (plain, plain_own) = run("");
    let (exposed, own) = run("Exposure 2 2");
    let bits = |v: Vec<f32>| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
    for name in ["N.X", "N.Y", "N.Z", "P.X", "P.Z", "s", "z"] {
        assert_eq!(
            bits(channel(&plain, name)),
            bits(channel(&exposed, name)),
            "{name} exposed"
        );
    }
    assert_eq!(
        bits(channel(&plain_own, "t")),
        bits(channel(&own, "t")),
        "t exposed"
    );
    let close = |got: f32, want: f32| (got - want).abs() <= 1e-5 * want.abs().max(1.0);
    let mut lit = 0;
    for c in ["R", "G", "B"] {
        let (ci0, ci) = (
            channel(&plain, &format!("Ci.{c}")),
            channel(&exposed, &format!("Ci.{c}")),
        );
        let (d0, d) = (
            channel(&plain, &format!("__diffuse.{c}")),
            channel(&exposed, &format!("__diffuse.{c}")),
        );
        let d_own = channel(&own, &format!("__diffuse.{c}"));
        let beauty = channel(&exposed, c);
        for p in 0..ci.len() {
            lit += usize::from(d0[p] > 0.05);
            assert!(
                close(ci[p], (2.0 * ci0[p]).sqrt()),
                "Ci.{c}[{p}] {} vs {}",
                ci[p],
                ci0[p]
            );
            assert!(close(d[p], (2.0 * d0[p]).sqrt()), "__diffuse.{c}[{p}]");
            assert!(
                close(d_own[p], 3.0 * d0[p]),
                "own exposure __diffuse.{c}[{p}]"
            );
            // The beauty's letters and the Ci variable are exposed alike.
            assert!(
                close(beauty[p], ci[p]),
                "{c}[{p}] {} vs Ci {}",
                beauty[p],
                ci[p]
            );
        }
    }
    assert!(lit > 30, "too few lit pixels ({lit})");
    let _ = std::fs::remove_dir_all(&dir);
}
