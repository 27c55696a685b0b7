//! Table rows for options: camera, display and hider requests that precede `WorldBegin`.
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// Options: camera, display and hider requests that precede `WorldBegin`.
pub(super) fn rows() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
        (
            t("Format 640 480 1"),
            R::Format {
                xres: 640,
                yres: 480,
                pixel_aspect: 1.0,
            },
        ),
        (t("FrameAspectRatio 1.5"), R::FrameAspectRatio(1.5)),
        (
            t("ScreenWindow -1 1 -.75 .75"),
            R::ScreenWindow {
                left: -1.0,
                right: 1.0,
                bottom: -0.75,
                top: 0.75,
            },
        ),
        (
            t("CropWindow [0 .5 0 1]"),
            R::CropWindow {
                xmin: 0.0,
                xmax: 0.5,
                ymin: 0.0,
                ymax: 1.0,
            },
        ),
        (
            t(r#"Projection "perspective" "fov" [45]"#),
            R::Projection {
                name: st("perspective"),
                params: vec![p("fov", i(&[45]))],
            },
        ),
        (
            t("Clipping 0.1 1E+4"),
            R::Clipping {
                near: 0.1,
                far: 1e4,
            },
        ),
        (
            t("ClippingPlane 0 0 1 0 0 -1"),
            R::ClippingPlane {
                x: 0.0,
                y: 0.0,
                z: 1.0,
                nx: 0.0,
                ny: 0.0,
                nz: -1.0,
            },
        ),
        (
            t("DepthOfField 22 0.05 10"),
            R::DepthOfField {
                fstop: 22.0,
                focal_length: 0.05,
                focal_distance: 10.0,
            },
        ),
        (
            // No arguments: depth of field off (pinhole), an infinite fstop.
            t("DepthOfField"),
            R::DepthOfField {
                fstop: f32::INFINITY,
                focal_length: 0.0,
                focal_distance: 0.0,
            },
        ),
        (
            t("Shutter 0 1"),
            R::Shutter {
                open: 0.0,
                close: 1.0,
            },
        ),
        (t("PixelVariance 0.01"), R::PixelVariance(0.01)),
        (t("PixelSamples 4 4"), R::PixelSamples { x: 4.0, y: 4.0 }),
        (
            t(r#"PixelFilter "gaussian" 2 2"#),
            R::PixelFilter {
                name: st("gaussian"),
                xwidth: 2.0,
                ywidth: 2.0,
            },
        ),
        (
            t("Exposure 1 2.2"),
            R::Exposure {
                gain: 1.0,
                gamma: 2.2,
            },
        ),
        (
            t(r#"Imager "background" "color background" [1 1 1]"#),
            R::Imager {
                name: st("background"),
                params: vec![p("color background", i(&[1, 1, 1]))],
            },
        ),
        (
            t(r#"Quantize "rgba" 255 0 255 0.5"#),
            R::Quantize {
                kind: st("rgba"),
                one: 255,
                min: 0,
                max: 255,
                dither: 0.5,
            },
        ),
        (
            t(r#"Display "out.tif" "file" "rgba" "quality" 90"#),
            R::Display {
                name: st("out.tif"),
                kind: st("file"),
                mode: st("rgba"),
                params: vec![p("quality", i(&[90]))],
            },
        ),
        (
            t(r#"Hider "hidden" "jitter" [1]"#),
            R::Hider {
                name: st("hidden"),
                params: vec![p("jitter", i(&[1]))],
            },
        ),
        (
            t("ColorSamples [1 0 0 0 1 0] [1 0 0 1 0 0]"),
            R::ColorSamples {
                n_rgb: vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
                rgb_n: vec![1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
            },
        ),
        (t("RelativeDetail 0.6"), R::RelativeDetail(0.6)),
        (
            t(r#"Option "searchpath" "shader" ["./:&"]"#),
            R::Option {
                name: st("searchpath"),
                params: vec![p("shader", s(&["./:&"]))],
            },
        ),
    ]
}
