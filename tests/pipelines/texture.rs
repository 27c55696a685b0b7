//! The texture pipeline of `rib/pipelines/texture/`: the project's source images
//! (`textures/`) through `MakeTexture`/`txmake` onto a teapot and patches (`paintedplastic`,
//! the SL `blurtex.sl`, `TextureCoordinates`, `bumpy`). Both forms must write the same bits, and
//! the labelled checker must land where RenderMan's `st` convention puts it.
use super::forms::{assert_same_image, binaries, example_dir, scratch};
use crate::support::run_rib;
use std::path::{Path, PathBuf};
use std::process::Command;

fn textures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("textures")
}

/// The repository's layout under `root`: `rib/pipelines/texture/*` and `textures/*` (the
/// pipeline reads its sources as `../../../textures/...`). Returns the pipeline directory.
fn copy_layout(root: &Path) -> PathBuf {
    let pipeline = root.join("rib/pipelines/texture");
    for (from, to) in [
        (example_dir("texture"), &pipeline),
        (textures_dir(), &root.join("textures")),
    ] {
        std::fs::create_dir_all(to).unwrap();
        for entry in std::fs::read_dir(&from).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() {
                std::fs::copy(&path, to.join(path.file_name().unwrap())).unwrap();
            }
        }
    }
    pipeline
}

#[test]
fn texture_sh_and_render_single_rib_write_identical_files() {
    let Some((render_bin, txmake_bin)) = binaries() else {
        eprintln!("SKIPPED: render/txmake binaries not built (cargo build -p render -p txmake)");
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "CI=true: the render/txmake binaries must be built before the tests"
        );
        return;
    };
    let root = scratch("texture-forms");
    let dir = copy_layout(&root);
    let out = Command::new("sh")
        .arg(dir.join("texture.sh"))
        .env("RENDER", &render_bin)
        .env("TXMAKE", &txmake_bin)
        .output()
        .unwrap();
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "texture.sh: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let out = Command::new(&render_bin)
        .args(["-q", "texture_single.rib"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "render texture_single.rib: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |f: &str| illume_imageio::read_image(&dir.join(f)).unwrap();
    for (single, script) in [
        ("card_single.tif", "card_script.tif"),
        ("texture_single.tif", "texture_script.tif"),
    ] {
        assert_same_image(
            &read(single),
            &read(script),
            &format!("{single} vs {script}"),
        );
    }
    let scene = read("texture_single.tif");
    assert_eq!((scene.width, scene.height), (480, 320));
    let _ = std::fs::remove_dir_all(&root);
}

/// The card's frame (card_frame.rib) with `checker.tx` made from textures/checker.tif in
/// `dir`, rendered in-process: the pixel values before quantization.
fn render_card(dir: &Path) -> (Vec<f32>, usize) {
    let frame = std::fs::read_to_string(example_dir("texture").join("card_frame.rib")).unwrap();
    let tx = dir.join("checker.tx");
    let rib = format!(
        "MakeTexture \"{}\" \"{}\" \"periodic\" \"periodic\" \"gaussian\" 2 2\n{}",
        textures_dir().join("checker.tif").display(),
        tx.display(),
        frame.replace("\"checker.tx\"", &format!("\"{}\"", tx.display()))
    );
    let r = run_rib(&rib);
    assert_eq!(r.len(), 1);
    (r[0].rgba.clone(), 128)
}

#[test]
fn the_checkers_labelled_quadrants_land_where_s_and_t_say() {
    let dir = scratch("texture-card");
    let (rgba, n) = render_card(&dir);
    let src = illume_imageio::read_image(&textures_dir().join("checker.tif")).unwrap();
    assert_eq!((src.width, src.height), (256, 256));
    // Pixel (x, y) of the card sees s = (x + ½)/n, t = (y + ½)/n (the patch fills the view,
    // s = u rightwards, t = v downwards): the 2×2 texels under it, averaged. Mirrored or
    // transposed mappings are the wrong answers it must be far from.
    let texel = |x: u32, y: u32, c: usize| src.at(x, y, c);
    let expected = |x: u32, y: u32, c: usize| {
        (texel(2 * x, 2 * y, c)
            + texel(2 * x + 1, 2 * y, c)
            + texel(2 * x, 2 * y + 1, c)
            + texel(2 * x + 1, 2 * y + 1, c))
            / 4.0
    };
    let last = n as u32 - 1;
    let mean_diff = |map: &dyn Fn(u32, u32) -> (u32, u32)| {
        let mut sum = 0.0f64;
        for y in 0..n as u32 {
            for x in 0..n as u32 {
                let (sx, sy) = map(x, y);
                for c in 0..3 {
                    let got = rgba[(y as usize * n + x as usize) * 4 + c];
                    sum += f64::from((got - expected(sx, sy, c)).abs());
                }
            }
        }
        sum / (n * n * 3) as f64
    };
    let upright = mean_diff(&|x, y| (x, y));
    let flipped_t = mean_diff(&|x, y| (x, last - y));
    let flipped_s = mean_diff(&|x, y| (last - x, y));
    let transposed = mean_diff(&|x, y| (y, x));
    eprintln!(
        "card: mean |render - texture| upright {upright:.4}, t flipped {flipped_t:.4}, \
         s flipped {flipped_s:.4}, transposed {transposed:.4}"
    );
    // The texture filter's footprint reaches beyond each pixel's 2×2 texels (Gaussian mip
    // filtering), softening checker edges and glyph strokes. A vertex's lookup covers one
    // micropolygon centred on it (`ShadingGrid::centred_footprint`) and a micropolygon's
    // colour is the mean of its four vertices, so a pixel shows the texture filtered over the
    // 2×2 micropolygons around it (a tent two pixels wide, centred): measured 0.080 (0.036
    // when "constant" took the first vertex alone, whose lookup covered exactly its own
    // micropolygon, but whose lighting sat half a micropolygon off); 0.1 leaves room, and
    // every wrong orientation is about 0.32 (at least 3.5× the upright difference required).
    assert!(upright < 0.1, "upright mapping differs by {upright}");
    for (what, d) in [
        ("t flipped", flipped_t),
        ("s flipped", flipped_s),
        ("transposed", transposed),
    ] {
        assert!(
            d > 3.5 * upright,
            "{what} ({d}) is as close as upright ({upright})"
        );
    }
    // Each quadrant of the card is the colour its label names: quadrant s0t0 (top-left) red, ...
    let colours = [
        ("s0t0", [0.85, 0.15, 0.1]),
        ("s1t0", [0.15, 0.7, 0.2]),
        ("s0t1", [0.15, 0.3, 0.9]),
        ("s1t1", [0.95, 0.85, 0.15]),
    ];
    for (q, (label, c)) in colours.iter().enumerate() {
        // The quadrant's top-left 16×16 pixels: a light checker square, away from the label.
        let (x0, y0) = ((q % 2) * n / 2, (q / 2) * n / 2);
        // Pixels 2–4: a micropolygon's colour averages the lookups of its four vertices, so
        // the label's strokes reach a pixel further than one micropolygon's lookup would.
        for y in y0 + 2..y0 + 5 {
            for x in x0 + 2..x0 + 5 {
                let p = &rgba[(y * n + x) * 4..(y * n + x) * 4 + 3];
                let d = (0..3).map(|k| (p[k] - c[k]).abs()).fold(0.0, f32::max);
                assert!(
                    d < 0.02,
                    "{label}: pixel ({x}, {y}) is {p:?}, expected {c:?}"
                );
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
