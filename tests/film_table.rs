//! The film's tabulated pixel filter (issue 21 part 3) against the exact kernel on real scenes:
//! each scene renders twice, once through the frame's tables and once through
//! `render_with_exact_filter` (every factor from the closed form, the path the tables
//! replaced), and the images must agree within what the tables' error allows.
//!
//! Bound: every tabulated factor is within `TABLE_ERROR` = 2e-6 of the exact one (its own unit
//! test), so a weight (a product of two factors of magnitude ≤ 1) is within 4e-6; a pixel's
//! value is a normalised weighted sum, so for premultiplied colours in [0, 1] the difference is
//! at most `Σ|Δw| / |Σw| · 2`, which for these filters (weight sums of 3×3 to 6×6 samples,
//! each ≥ a few tenths) is below 1e-4 (measured: at most 1.1e-6, the sinc). Anything structural (a missed sample, a wrong offset,
//! a weight at the wrong pixel) moves pixels by far more than that: `a_moved_filter_fails`
//! shows the metric sees a sub-pixel change of the filter itself.
mod support;

use illume_render::{render, render_with_exact_filter, RenderSettings};
use support::frames;

/// The largest absolute difference over every channel of every pixel.
fn max_difference(scene: &str, crop: Option<[f32; 4]>) -> f32 {
    let frame = &frames(scene, crop)[0];
    let settings = RenderSettings::default();
    let table = render(frame, &settings);
    let exact = render_with_exact_filter(frame, &settings);
    assert_eq!(table.rgba.len(), exact.rgba.len());
    assert!(
        table.rgba.iter().any(|&v| v > 0.1),
        "the scene shows something"
    );
    table
        .rgba
        .iter()
        .zip(&exact.rgba)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f32::max)
}

fn scene(name: &str) -> String {
    let path = format!("{}/rib/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The metric's threshold (see the module comment).
const BOUND: f32 = 1e-4;

#[test]
fn gallery_scenes_match_the_exact_filter() {
    // A central crop of each keeps the debug-build test short.
    let crop = Some([0.3, 0.7, 0.3, 0.7]);
    for name in ["sphere.rib", "teapot.rib", "geometry.rib"] {
        let d = max_difference(&scene(name), crop);
        eprintln!("{name}: max difference {d:e}");
        assert!(d <= BOUND, "{name}: max difference {d:e}");
    }
}

#[test]
fn wide_and_negative_lobed_filters_match_the_exact_filter() {
    let base = scene("sphere.rib").replace("PixelSamples 3 3", "PixelSamples 4 4");
    for filter in [
        "\"gaussian\" 3 3",
        "\"sinc\" 6 6",
        "\"mitchell\" 4 4",
        "\"lanczos\" 5 3",
        "\"triangle\" 2 2",
        "\"box\" 1 1",
    ] {
        let rib = base.replace(
            "PixelSamples 4 4",
            &format!("PixelSamples 4 4\nPixelFilter {filter}"),
        );
        assert!(rib.contains("PixelFilter"));
        let d = max_difference(&rib, Some([0.35, 0.65, 0.35, 0.65]));
        eprintln!("{filter}: max difference {d:e}");
        assert!(d <= BOUND, "{filter}: max difference {d:e}");
    }
}

#[test]
fn a_moved_filter_fails() {
    // A Gaussian 2.05 wide instead of 2: a 2.5 % wider kernel, far less than any wrong weight
    // placement would change (it moves pixels by about 8e-4). Its images must differ by
    // several times the bound.
    let base = scene("sphere.rib");
    let crop = Some([0.3, 0.7, 0.3, 0.7]);
    let a = render(
        &frames(
            &base.replace("PixelSamples", "PixelFilter \"gaussian\" 2 2\nPixelSamples"),
            crop,
        )[0],
        &RenderSettings::default(),
    );
    let b = render_with_exact_filter(
        &frames(
            &base.replace(
                "PixelSamples",
                "PixelFilter \"gaussian\" 2.05 2.05\nPixelSamples",
            ),
            crop,
        )[0],
        &RenderSettings::default(),
    );
    let d = a
        .rgba
        .iter()
        .zip(&b.rgba)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f32::max);
    assert!(
        d > 4.0 * BOUND,
        "a 2.5% wider filter moved pixels by only {d:e}"
    );
}
