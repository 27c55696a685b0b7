//! Interop with OpenImageIO (Debian `openimageio-tools`): every display kind we write must open
//! in `iinfo` with the right size, channels and sample type, and `oiiotool --stats` must agree
//! with our own reader's min/max/average. Corpus TIFFs read by us must equal OpenImageIO's
//! decoding of them. When the tools are absent the tests say so loudly and pass, except under
//! `CI=true`, where they fail (`illume-testenv`).

use illume_imageio::*;
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("imageio-interop")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Whether `tool` is installed; when not, the test skips loudly (a failure under `CI=true`).
fn have(tool: &str) -> bool {
    illume_testenv::require_tool(tool).is_some()
}

fn pattern(width: u32, height: u32, mode: &str) -> Image {
    let mut image = Image::new(width, height, mode);
    let nc = image.channels.len();
    for y in 0..height {
        for x in 0..width {
            for (c, name) in image.channels.clone().iter().enumerate() {
                let v = if name == "z" {
                    2.0 + 50.0 * (x as f32 / width as f32) + 0.5 * y as f32
                } else {
                    ((x * 3 + y * 5 + c as u32 * 11) % 64) as f32 / 63.0
                };
                image.data[((y * width + x) as usize) * nc + c] = v;
            }
        }
    }
    image
}

/// `iinfo -v` first line: (width, height, channels, type word, format word); plus channel list.
fn iinfo(path: &Path) -> (u32, u32, usize, String, String, Vec<String>) {
    let out = Command::new("iinfo").arg("-v").arg(path).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "iinfo failed on {}: {text}",
        path.display()
    );
    let first = text.lines().next().unwrap();
    // "name :  W x  H, N channel, TYPE FORMAT"
    let rest = first.rsplit_once(" : ").map(|p| p.1).unwrap_or(first);
    let words: Vec<&str> = rest
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|w| !w.is_empty())
        .collect();
    let channels = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("channel list:"))
        .map(|l| l.split(',').map(|s| s.trim().to_string()).collect())
        .unwrap_or_default();
    (
        words[0].parse().unwrap(),
        words[2].parse().unwrap(),
        words[3].parse().unwrap(),
        words[5].to_string(),
        words[6].to_string(),
        channels,
    )
}

/// `oiiotool --stats`: per-channel (min, max, avg), normalised by the "(of N)" integer range.
fn oiio_stats(path: &Path) -> Vec<[f64; 3]> {
    let out = Command::new("oiiotool")
        .arg("--stats")
        .arg(path)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "oiiotool failed: {text}");
    let line = |key: &str| -> (Vec<f64>, f64) {
        let l = text
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .unwrap_or_else(|| panic!("no `{key}` in {text}"));
        // Integer files print "(of 255)", float files "(float)" or "(half)".
        let (nums, scale) = match l.split_once('(') {
            Some((n, s)) => match s.strip_prefix("of ") {
                Some(s) => (n, s.trim_end_matches(')').trim().parse().unwrap()),
                None => (n, 1.0),
            },
            None => (l, 1.0),
        };
        (
            nums.split_whitespace()
                .map(|s| s.parse::<f64>().unwrap())
                .collect(),
            scale,
        )
    };
    let (min, s) = line("Stats Min:");
    let (max, _) = line("Stats Max:");
    let (avg, _) = line("Stats Avg:");
    (0..min.len())
        .map(|c| [min[c] / s, max[c] / s, avg[c] / s])
        .collect()
}

fn our_stats(image: &Image) -> Vec<[f64; 3]> {
    let nc = image.channels.len();
    (0..nc)
        .map(|c| {
            let v: Vec<f64> = image
                .data
                .iter()
                .skip(c)
                .step_by(nc)
                .map(|&v| v as f64)
                .collect();
            let min = v.iter().cloned().fold(f64::INFINITY, f64::min);
            let max = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            [min, max, v.iter().sum::<f64>() / v.len() as f64]
        })
        .collect()
}

struct Case {
    file: &'static str,
    kind: &'static str,
    mode: &'static str,
    quantize: Quantize,
    oiio_type: &'static str,
    oiio_format: &'static str,
    oiio_channels: &'static [&'static str],
}

const Q16: Quantize = Quantize {
    one: 65535,
    min: 0,
    max: 65535,
    dither: 0.5,
};

/// One display kind: file, display type, mode, quantization, and what OpenImageIO should say.
fn case(
    file: &'static str,
    kind: &'static str,
    mode: &'static str,
    quantize: Quantize,
    oiio_type: &'static str,
    oiio_format: &'static str,
    oiio_channels: &'static [&'static str],
) -> Case {
    Case {
        file,
        kind,
        mode,
        quantize,
        oiio_type,
        oiio_format,
        oiio_channels,
    }
}

/// Every display kind we write, with what OpenImageIO should call it. TIFF has no channel names:
/// OpenImageIO calls an unspecified extra sample `channel3` and a lone grey sample `Y` (our
/// reader restores `z` from the ImageDescription we write). PNG alpha is unassociated: we
/// divide on writing, and both readers multiply back.
fn display_kinds() -> Vec<Case> {
    let d = Quantize::RGBA_DEFAULT;
    let f = Quantize::FLOAT;
    let rgb: &[&str] = &["R", "G", "B"];
    let rgba: &[&str] = &["R", "G", "B", "A"];
    #[rustfmt::skip]
    let cases = vec![
        case("rgb8.tif", "tiff", "rgb", d, "uint8", "tiff", rgb),
        case("rgba16.tif", "file", "rgba", Q16, "uint16", "tiff", rgba),
        case("a8.tif", "tiff", "a", d, "uint8", "tiff", &["Y"]),
        case("rgbaf.tif", "tiff", "rgba", f, "float", "tiff", rgba),
        case("rgbz.tif", "tiff", "rgbz", d, "float", "tiff", &["R", "G", "B", "channel3"]),
        case("z.tif", "tiff", "z", f, "float", "tiff", &["Y"]),
        case("rgb8.png", "png", "rgb", d, "uint8", "png", rgb),
        case("rgba16.png", "png", "rgba", Q16, "uint16", "png", rgba),
        case("fb.tif", "framebuffer", "rgba", d, "uint8", "png", rgba),
        case("rgba.exr", "openexr", "rgba", d, "half", "openexr", rgba),
        case("rgbaf.exr", "exr", "rgba", f, "float", "openexr", rgba),
        case("z.zfile", "zfile", "z", f, "float", "zfile", &["z"]),
    ];
    cases
}

/// `iinfo`'s size, channel count, type, format and channel names against `case`'s.
fn check_header(case: &Case, path: &Path, failures: &mut Vec<String>) {
    let (w, h, nc, ty, format, names) = iinfo(path);
    let want = (
        29,
        13,
        case.oiio_channels.len(),
        case.oiio_type,
        case.oiio_format,
    );
    if (w, h, nc, ty.as_str(), format.as_str()) != want {
        failures.push(format!(
            "{}: iinfo says {w}x{h} {nc} {ty} {format}, expected {want:?}",
            case.file
        ));
    }
    let want_names: Vec<String> = case.oiio_channels.iter().map(|s| s.to_string()).collect();
    if names != want_names && case.oiio_format != "zfile" {
        failures.push(format!(
            "{}: channel list {names:?}, expected {want_names:?}",
            case.file
        ));
    }
}

/// The depth matrices: named attributes in OpenEXR, both matrices in file order in a zfile.
fn check_matrices(case: &Case, path: &Path, depth: &DepthMatrices, failures: &mut Vec<String>) {
    if case.oiio_format != "openexr" && case.oiio_format != "zfile" {
        return;
    }
    let out = Command::new("iinfo").arg("-v").arg(path).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    if case.oiio_format == "openexr" {
        for attr in ["worldToCamera", "worldToNDC"] {
            if !text.contains(attr) {
                failures.push(format!("{}: iinfo shows no {attr}:\n{text}", case.file));
            }
        }
        return;
    }
    for (key, m) in [
        ("worldtocamera:", depth.world_to_camera),
        ("worldtoscreen:", depth.world_to_screen),
    ] {
        let shown: Vec<f32> = text
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .map(|l| l.split(',').map(|v| v.trim().parse().unwrap()).collect())
            .unwrap_or_default();
        if shown != m {
            failures.push(format!("zfile {key} {shown:?}, expected {m:?}"));
        }
    }
}

/// Per-channel min, max and mean as `oiiotool --stats` reads the file against our reader's.
fn check_stats(case: &Case, path: &Path, failures: &mut Vec<String>) {
    let theirs = oiio_stats(path);
    let ours = our_stats(&read_image(path).unwrap());
    assert_eq!(theirs.len(), ours.len(), "{}", case.file);
    for (c, (t, o)) in theirs.iter().zip(&ours).enumerate() {
        for k in 0..3 {
            // oiiotool prints 2 decimals of integer codes, or 6 significant float digits.
            let mut tol = 1e-4 * (1.0 + o[k].abs());
            if case.oiio_format == "png" && case.oiio_type == "uint8" && c < 3 {
                // OpenImageIO premultiplies an 8-bit PNG in 8-bit, rounding each result
                // to a code value; we premultiply in float.
                tol = 0.5 / 255.0 + 1e-6;
            }
            if (t[k] - o[k]).abs() > tol {
                failures.push(format!(
                    "{} channel {c} stat {k}: oiiotool {} vs ours {}",
                    case.file, t[k], o[k]
                ));
            }
        }
    }
}

#[test]
fn oiio_reads_every_display_kind_we_write() {
    if !have("iinfo") || !have("oiiotool") {
        return;
    }
    let dir = scratch("kinds");
    let depth = DepthMatrices {
        world_to_screen: std::array::from_fn(|i| if i % 5 == 0 { 1.5 } else { 0.0 }),
        world_to_camera: std::array::from_fn(|i| if i % 5 == 0 { 1.0 } else { 0.25 * i as f32 }),
    };
    let mut failures = Vec::new();
    for case in &display_kinds() {
        let image = pattern(29, 13, case.mode);
        let written = dir.join(case.file);
        write_display(&written, case.kind, &image, case.quantize, Some(&depth)).unwrap();
        let path = if case.kind == "framebuffer" {
            framebuffer_path(&written)
        } else {
            written
        };
        check_header(case, &path, &mut failures);
        check_matrices(case, &path, &depth, &mut failures);
        check_stats(case, &path, &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn corpus_tiffs_decode_like_openimageio() {
    let Some(corpus) = illume_testenv::shared_dir("corpus") else {
        return; // skipped loudly; a failure under CI=true
    };
    let dir = scratch("corpus");
    let oiio = have("oiiotool");
    for (name, nc) in [
        ("Image1.tif", 5),
        ("px.tif", 3),
        ("nx.tif", 3),
        ("py.tif", 3),
        ("ny.tif", 3),
        ("pz.tif", 3),
        ("nz.tif", 3),
    ] {
        let path = corpus.join("aqsis2001").join(name);
        let ours = read_image(&path).unwrap();
        assert_eq!(ours.channels.len(), nc, "{name}");
        if name == "Image1.tif" {
            assert_eq!((ours.width, ours.height), (414, 301));
            assert_eq!(ours.channels, ["r", "g", "b", "a", "z"]);
        } else {
            assert_eq!((ours.width, ours.height), (200, 200), "{name}");
            assert_eq!(ours.channels, ["r", "g", "b"]);
        }
        if !oiio {
            continue;
        }
        // OpenImageIO decodes the file and writes float OpenEXR; we read that through the
        // OpenEXR path and must find the same values.
        let exr = dir.join(format!("{name}.exr"));
        let status = Command::new("oiiotool")
            .arg(&path)
            .args(["-d", "float", "-o"])
            .arg(&exr)
            .status()
            .unwrap();
        assert!(status.success());
        let theirs = read_image(&exr).unwrap();
        assert_eq!((theirs.width, theirs.height), (ours.width, ours.height));
        assert_eq!(theirs.data.len(), ours.data.len());
        let worst = theirs
            .data
            .iter()
            .zip(&ours.data)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f32::max);
        assert!(worst < 1e-6, "{name}: worst difference {worst}");
    }
}

#[test]
fn jpeg_decodes_like_openimageio() {
    if !have("oiiotool") {
        return;
    }
    let dir = scratch("jpeg");
    let jpg = dir.join("p.jpg");
    let exr = dir.join("p.exr");
    let ok = Command::new("oiiotool")
        .args([
            "--pattern",
            "fill:topleft=0,0,0:topright=1,0,0:bottomleft=0,1,0:bottomright=1,1,1",
            "64x48",
            "3",
        ])
        .args(["-d", "uint8", "-o"])
        .arg(&jpg)
        .status()
        .unwrap()
        .success()
        && Command::new("oiiotool")
            .arg(&jpg)
            .args(["-d", "float", "-o"])
            .arg(&exr)
            .status()
            .unwrap()
            .success();
    assert!(ok);
    let ours = read_image(&jpg).unwrap();
    let theirs = read_image(&exr).unwrap();
    assert_eq!(ours.channels, ["r", "g", "b"]);
    assert_eq!((ours.width, ours.height), (64, 48));
    let worst = ours
        .data
        .iter()
        .zip(&theirs.data)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f32::max);
    // Two JPEG decoders may differ by a code value or two (IDCT and upsampling rounding).
    assert!(worst <= 3.0 / 255.0, "worst difference {worst}");
}

#[test]
fn tiffs_written_by_openimageio_read_back_equal() {
    if !have("oiiotool") {
        return;
    }
    let dir = scratch("oiio-tiff");
    // The reference: a float EXR we write and read ourselves.
    let image = pattern(70, 45, "rgba");
    let src = dir.join("src.exr");
    write_display(&src, "exr", &image, Quantize::FLOAT, None).unwrap();
    let variants: &[(&str, &[&str], f32)] = &[
        (
            "u8-lzw.tif",
            &["-d", "uint8", "--compression", "lzw"],
            0.5 / 255.0,
        ),
        (
            "u16-zip-tiled.tif",
            &["-d", "uint16", "--compression", "zip", "--tile", "32", "32"],
            0.5 / 65535.0,
        ),
        (
            "f32-lzw-tiled.tif",
            &["-d", "float", "--compression", "lzw", "--tile", "16", "16"],
            0.0,
        ),
        (
            "f32-separate.tif",
            &["-d", "float", "--planarconfig", "separate"],
            0.0,
        ),
        (
            "u8-packbits.tif",
            &["-d", "uint8", "--compression", "packbits"],
            0.5 / 255.0,
        ),
        (
            "u16-separate-lzw.tif",
            &[
                "-d",
                "uint16",
                "--compression",
                "lzw",
                "--planarconfig",
                "separate",
            ],
            0.5 / 65535.0,
        ),
        ("half.tif", &["-d", "half"], 1e-3),
        ("u8.png", &["-d", "uint8", "--ch", "R,G,B"], 0.5 / 255.0),
        ("tiled.exr", &["-d", "half", "--tile", "16", "16"], 1e-3),
    ];
    for (file, args, tol) in variants {
        let out = dir.join(file);
        let status = Command::new("oiiotool")
            .arg(&src)
            .args(*args)
            .arg("-o")
            .arg(&out)
            .status()
            .unwrap();
        assert!(status.success(), "oiiotool {args:?}");
        check_close(
            &read_image(&out).unwrap_or_else(|e| panic!("{file}: {e}")),
            &image,
            *tol,
            file,
        );
    }
    // A mip-mapped tiled EXR from maketx: we read level 0.
    if have("maketx") {
        let out = dir.join("mip.exr");
        let status = Command::new("maketx")
            .arg(&src)
            .args(["-d", "half", "--tile", "16", "16", "-o"])
            .arg(&out)
            .status()
            .unwrap();
        assert!(status.success());
        check_close(&read_image(&out).unwrap(), &image, 1e-3, "maketx mip.exr");
    }
}

fn check_close(back: &Image, image: &Image, tol: f32, file: &str) {
    assert_eq!((back.width, back.height), (70, 45), "{file}");
    let nc = back.channels.len();
    let mut worst = 0f32;
    for p in 0..(70 * 45) {
        for c in 0..nc.min(4) {
            worst = worst.max((back.data[p * nc + c] - image.data[p * 4 + c]).abs());
        }
    }
    assert!(
        worst <= tol + 1e-7,
        "{file}: worst difference {worst} > {tol}"
    );
}

#[test]
fn zfile_written_by_openimageio_reads_exactly() {
    if !have("oiiotool") {
        return;
    }
    let dir = scratch("oiio-zfile");
    let z = dir.join("ramp.zfile");
    let exr = dir.join("ramp.exr");
    let ok = Command::new("oiiotool")
        .args([
            "--pattern",
            "fill:top=1:bottom=9",
            "13x7",
            "1",
            "-d",
            "float",
            "-o",
        ])
        .arg(&z)
        .status()
        .unwrap()
        .success()
        && Command::new("oiiotool")
            .arg(&z)
            .args(["-d", "float", "-o"])
            .arg(&exr)
            .status()
            .unwrap()
            .success();
    assert!(ok);
    let (ours, matrices) = read_zfile(&z).unwrap();
    assert_eq!((ours.width, ours.height), (13, 7));
    assert_eq!(ours.channels, ["z"]);
    let identity: [f32; 16] = std::array::from_fn(|i| if i % 5 == 0 { 1.0 } else { 0.0 });
    assert_eq!(matrices.world_to_camera, identity);
    let theirs = read_image(&exr).unwrap();
    assert_eq!(ours.data, theirs.data);
    // Top row first: the ramp runs from 1 at the top to 9 at the bottom.
    assert!(ours.at(0, 0, 0) < ours.at(0, 6, 0));
}

#[test]
fn unassociated_alpha_tiff_reads_back_premultiplied() {
    if !have("oiiotool") {
        return;
    }
    let dir = scratch("unassociated");
    // A premultiplied source (colour ≤ alpha), written as float EXR.
    let mut image = Image::new(32, 8, "rgba");
    for y in 0..8u32 {
        for x in 0..32u32 {
            let a = (x + 1) as f32 / 32.0;
            let i = ((y * 32 + x) * 4) as usize;
            image.data[i..i + 4].copy_from_slice(&[a * 0.25, a * y as f32 / 7.0, a, a]);
        }
    }
    let src = dir.join("src.exr");
    write_display(&src, "exr", &image, Quantize::FLOAT, None).unwrap();
    // OpenImageIO divides by alpha (`--unpremult`) and tags ExtraSamples = 2 (unassociated).
    let tif = dir.join("straight.tif");
    let ok = Command::new("oiiotool")
        .arg(&src)
        .args([
            "--unpremult",
            "--attrib",
            "oiio:UnassociatedAlpha",
            "1",
            "-d",
            "float",
            "-o",
        ])
        .arg(&tif)
        .status()
        .unwrap()
        .success();
    assert!(ok);
    let back = read_image(&tif).unwrap();
    for (i, (&b, &a)) in back.data.iter().zip(&image.data).enumerate() {
        assert!((b - a).abs() <= 1e-6, "sample {i}: {a} → {b}");
    }
}
