//! `textures/`: the committed source images are exactly what their generator
//! (crates/imageio/examples/make_textures.rs, run by textures/make_textures.sh) writes, so they
//! can be rewritten at any time and their README's descriptions are checked facts.
#[allow(dead_code)]
#[path = "../crates/imageio/examples/make_textures.rs"]
mod make_textures;

use std::path::Path;

fn textures_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/textures"))
}

#[test]
fn committed_textures_are_what_the_generator_writes() {
    let sources = make_textures::all();
    assert_eq!(sources.len(), 4);
    for s in sources {
        let path = textures_dir().join(s.name);
        let got = illume_imageio::read_image(&path)
            .unwrap_or_else(|e| panic!("{e} (rewrite with textures/make_textures.sh)"));
        let want = &s.image;
        assert_eq!(
            (got.width, got.height, &got.channels),
            (want.width, want.height, &want.channels),
            "{}",
            s.name
        );
        // 8-bit files hold round(255 v) (no dither; in f64, as the RI's Quantize is computed:
        // 0.7f32 is 178.49999… code values, so 178); float files hold the values themselves.
        let expect = |v: f32| {
            if s.quantize.one == 0 {
                v
            } else {
                (255.0 * f64::from(v.clamp(0.0, 1.0))).round() as f32 / 255.0
            }
        };
        let differ: Vec<(usize, f32, f32)> = got
            .data
            .iter()
            .zip(&want.data)
            .enumerate()
            .filter(|(_, (g, w))| (**g - expect(**w)).abs() > 1e-6)
            .map(|(i, (g, w))| (i, *g, *w))
            .collect();
        let first = differ.first();
        let differ = differ.len();
        eprintln!("{}: first difference {first:?}", s.name);
        assert_eq!(
            differ, 0,
            "{}: {differ} values differ from the generator",
            s.name
        );
    }
}

#[test]
fn textures_stay_small_and_have_a_readme_line_each() {
    let readme = std::fs::read_to_string(textures_dir().join("README.md")).unwrap();
    let mut total = 0;
    for s in make_textures::all() {
        total += std::fs::metadata(textures_dir().join(s.name))
            .unwrap()
            .len();
        assert!(
            readme.contains(&format!("| `{}` |", s.name)),
            "textures/README.md has no row for {}",
            s.name
        );
    }
    assert!(
        total < 2 << 20,
        "textures/ holds {total} bytes, more than 2 MB"
    );
}

/// The labels sit where the README says: the checker's quadrant (s < ½, t < ½) is the image's
/// top-left (t = 0 is the top row) and red; the label box is white with black ink.
#[test]
fn checker_quadrants_are_coloured_and_labelled_as_documented() {
    let c = make_textures::checker();
    let px = |x: u32, y: u32| [c.at(x, y, 0), c.at(x, y, 1), c.at(x, y, 2)];
    // A checker square's light corner in each quadrant: (x, y) = (2, 2) + quadrant origin.
    assert_eq!(px(2, 2), [0.85, 0.15, 0.1]);
    assert_eq!(px(130, 2), [0.15, 0.7, 0.2]);
    assert_eq!(px(2, 130), [0.15, 0.3, 0.9]);
    assert_eq!(px(130, 130), [0.95, 0.85, 0.15]);
    // Ink and paper in the top-left label: ink covers 20–50 % of its box.
    let (x0, y0, w, h) = (64 - 46, 64 - 14, 92, 28);
    let ink = (y0..y0 + h)
        .flat_map(|y| (x0..x0 + w).map(move |x| (x, y)))
        .filter(|&(x, y)| px(x, y) == [0.0; 3])
        .count();
    let frac = ink as f64 / f64::from(w * h);
    assert!((0.2..0.5).contains(&frac), "ink fraction {frac}");
}
