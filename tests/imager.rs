//! `Imager` (RI Spec 3.2 §4.1.4): the imager runs on every filtered pixel before exposure and
//! quantization. Each test renders the same scene without the imager as the independent
//! reference and checks the imager's closed form per pixel.
use illume_render::{render, write_displays, RenderSettings, Rendered};
use std::path::PathBuf;
mod support;

use support::frames;

/// A 32×16 frame whose left half is covered by a square of colour `cs` and opacity `os`; the
/// box filter and 4×4 samples give fractional coverage along the square's right edge (it ends
/// mid-pixel) and `os` gives it inside.
fn scene(options: &str, cs: f32, os: f32) -> String {
    format!(
        "Format 32 16 1\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         ScreenWindow -2 2 -1 1\n{options}WorldBegin\nSurface \"constant\"\n\
         Color [{cs} {} {}]\nOpacity [{os} {os} {os}]\n\
         Polygon \"P\" [-3 -3 1  -0.03 -3 1  -0.03 3 1  -3 3 1]\nWorldEnd\n",
        cs * 0.5,
        cs * 0.25
    )
}

fn render_rib(rib: &str) -> Rendered {
    let frames = frames(rib, None);
    render(&frames[0], &RenderSettings::default())
}

fn pixels(r: &Rendered) -> Vec<[f32; 4]> {
    r.rgba
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-5
}

/// A fresh directory for files a test writes.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-imager-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn background_composites_under_partial_coverage() {
    let plain = pixels(&render_rib(&scene("", 0.8, 0.5)));
    let bg = [0.1, 0.3, 0.9];
    let imager = "Imager \"background\" \"color background\" [0.1 0.3 0.9]\n";
    let imaged = pixels(&render_rib(&scene(imager, 0.8, 0.5)));
    // The frame has empty, half-opaque and edge (fractional) pixels.
    let alphas: Vec<f32> = plain.iter().map(|p| p[3]).collect();
    assert!(alphas.contains(&0.0) && alphas.iter().any(|&a| a > 0.0 && a < 0.5));
    assert!(alphas.iter().any(|&a| close(a, 0.5)));
    for (k, (p, q)) in plain.iter().zip(&imaged).enumerate() {
        for c in 0..3 {
            let want = p[c] + (1.0 - p[3]) * bg[c];
            assert!(close(q[c], want), "pixel {k} channel {c}: {q:?} vs {want}");
        }
        assert_eq!(q[3], 1.0, "pixel {k}");
    }
}

#[test]
fn clamptoalpha_bounds_premultiplied_colour_by_alpha() {
    // Colour 3 at opacity 0.5 gives a premultiplied 1.5 > alpha.
    let plain = pixels(&render_rib(&scene("", 3.0, 0.5)));
    let imaged = pixels(&render_rib(&scene("Imager \"clamptoalpha\"\n", 3.0, 0.5)));
    assert!(plain.iter().any(|p| p[0] > p[3] + 0.1));
    for (p, q) in plain.iter().zip(&imaged) {
        for c in 0..3 {
            assert!(close(q[c], p[c].clamp(0.0, p[3])), "{p:?} → {q:?}");
        }
        assert_eq!(q[3], p[3]);
    }
}

#[test]
fn the_imager_sees_colour_before_exposure() {
    // Exposure gain 2: the imager composites first, so the background is doubled too; an
    // imager run after exposure would leave empty pixels at 0.25.
    let imager = "Imager \"background\" \"color background\" [0.25 0.25 0.25]\n";
    let plain = pixels(&render_rib(&scene("", 0.8, 0.5)));
    let imaged = pixels(&render_rib(&scene(
        &format!("Exposure 2 1\n{imager}"),
        0.8,
        0.5,
    )));
    for (p, q) in plain.iter().zip(&imaged) {
        for c in 0..3 {
            let want = 2.0 * (p[c] + (1.0 - p[3]) * 0.25);
            assert!(close(q[c], want), "{p:?} → {q:?}, want {want}");
        }
    }
    assert!(imaged.iter().any(|q| close(q[0], 0.5)), "an empty pixel");
}

/// Writes `source` as `name.sl` into `dir` and returns the option that finds it.
fn sl_imager(dir: &std::path::Path, name: &str, source: &str) -> String {
    std::fs::write(dir.join(format!("{name}.sl")), source).unwrap();
    format!(
        "Option \"searchpath\" \"shader\" [\"{}\"]\nImager \"{name}\"\n",
        dir.display()
    )
}

#[test]
fn an_sl_imager_sees_raster_p_and_sets_alpha() {
    let dir = temp_dir("raster");
    let options = sl_imager(
        &dir,
        "rasterramp",
        "imager rasterramp(float scale = 0.01) {\n\
         Ci = color(xcomp(P) * scale, ycomp(P) * scale, s + t);\n alpha = 0.25;\n}\n",
    );
    // A crop window: P is in full-frame raster pixels, not the crop's.
    let rib = scene(&format!("CropWindow 0.25 1 0.5 1\n{options}"), 0.8, 1.0);
    let r = render_rib(&rib);
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    assert_eq!((r.x0, r.y0, r.width, r.height), (8, 8, 24, 8));
    for (k, q) in pixels(&r).iter().enumerate() {
        let x = (r.x0 + k as u32 % r.width) as f32 + 0.5;
        let y = (r.y0 + k as u32 / r.width) as f32 + 0.5;
        let want = [x * 0.01, y * 0.01, x / 32.0 + y / 16.0, 0.25];
        for c in 0..4 {
            assert!(close(q[c], want[c]), "pixel ({x}, {y}): {q:?} vs {want:?}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn alpha_from_an_imagers_oi_reaches_the_file() {
    let dir = temp_dir("alpha");
    // Writes only Oi, as Aqsis's imageralphabug.sl does: the file's alpha follows it.
    let options = sl_imager(
        &dir,
        "halfopaque",
        "imager halfopaque() { Oi = 0.5; Ci = Ci * 0.5; }\n",
    );
    let out = dir.join("out.tif");
    let display = format!("Display \"{}\" \"file\" \"rgba\"\n", out.display());
    let frames = frames(&scene(&format!("{display}{options}"), 0.8, 1.0), None);
    let r = render(&frames[0], &RenderSettings::default());
    for w in write_displays(&frames[0], &r) {
        w.unwrap();
    }
    let img = illume_imageio::read_image(&out).unwrap();
    assert_eq!(img.channels.len(), 4);
    // 8-bit with dither: within one code of 0.5 everywhere, covered or not.
    for (x, y) in [(0, 0), (4, 8), (31, 15), (20, 3)] {
        let a = img.at(x, y, 3);
        assert!((a - 0.5).abs() <= 1.5 / 255.0, "({x}, {y}): alpha {a}");
    }
    // The colour half of the covered red (0.8).
    assert!((img.at(4, 8, 0) - 0.4).abs() <= 1.5 / 255.0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unknown_imager_warns_and_renders_without_one() {
    let plain = pixels(&render_rib(&scene("", 0.8, 0.5)));
    let r = render_rib(&scene("Imager \"nosuchimager\"\n", 0.8, 0.5));
    assert!(
        r.warnings
            .iter()
            .any(|w| w.message.contains("nosuchimager")),
        "{:?}",
        r.warnings
    );
    assert_eq!(pixels(&r), plain);
}
