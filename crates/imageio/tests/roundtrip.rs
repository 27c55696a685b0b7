//! Every display writer → `read_image` round trip, plus zfile and the independent `tiff` crate.

use illume_imageio::*;
use std::path::PathBuf;

/// A fresh directory per test under the target dir.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("imageio")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A test pattern with values spanning [-0.25, 1.25] so clamping is exercised, and a depth
/// channel with large values.
fn pattern(width: u32, height: u32, mode: &str) -> Image {
    let mut image = Image::new(width, height, mode);
    let nc = image.channels.len();
    for y in 0..height {
        for x in 0..width {
            for (c, name) in image.channels.clone().iter().enumerate() {
                let v = if name == "z" {
                    1.0 + 997.25 * (x as f32 + 0.37 * y as f32) / width as f32
                } else {
                    -0.25 + 1.5 * ((x * 7 + y * 13 + c as u32 * 29) % 101) as f32 / 100.0
                };
                image.data[((y * width + x) as usize) * nc + c] = v;
            }
        }
    }
    image
}

/// Expected value after quantizing with `q` and reading back normalised by `scale`.
fn expected(image: &Image, q: Quantize, scale: f64) -> Vec<f32> {
    let nc = image.channels.len();
    image
        .data
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let px = i / nc;
            let (x, y) = (
                (px % image.width as usize) as u32,
                (px / image.width as usize) as u32,
            );
            (q.quantize(v, x, y, (i % nc) as u32) / scale) as f32
        })
        .collect()
}

#[test]
fn tiff_8bit_round_trip_is_exact_after_quantize() {
    let dir = scratch("tiff8");
    for mode in ["rgb", "rgba", "a"] {
        let image = pattern(37, 23, mode);
        let path = dir.join(format!("{mode}.tif"));
        let q = Quantize::RGBA_DEFAULT;
        write_display(&path, "tiff", &image, q, None).unwrap();
        let back = read_image(&path).unwrap();
        assert_eq!((back.width, back.height), (37, 23));
        assert_eq!(back.channels, image.channels, "{mode}");
        assert_eq!(back.data, expected(&image, q, 255.0), "{mode}");
    }
}

#[test]
fn tiff_16bit_and_float_round_trip_exactly() {
    let dir = scratch("tiff16");
    let image = pattern(40, 9, "rgba");
    let q = Quantize {
        one: 65535,
        min: 0,
        max: 65535,
        dither: 0.5,
    };
    let path = dir.join("a.tif");
    write_display(&path, "file", &image, q, None).unwrap();
    assert_eq!(
        read_image(&path).unwrap().data,
        expected(&image, q, 65535.0)
    );

    for mode in ["rgbz", "z", "rgbaz"] {
        let image = pattern(19, 31, mode);
        let path = dir.join(format!("{mode}.tif"));
        write_display(&path, "tiff", &image, Quantize::FLOAT, None).unwrap();
        let back = read_image(&path).unwrap();
        assert_eq!(back, image, "{mode}");
    }
    // z forces float even under an 8-bit setting: depth is never quantized.
    let image = pattern(8, 8, "rgbz");
    let path = dir.join("forced.tif");
    write_display(&path, "tiff", &image, Quantize::RGBA_DEFAULT, None).unwrap();
    assert_eq!(read_image(&path).unwrap(), image);
}

#[test]
fn png_8_and_16bit_round_trip_exactly() {
    let dir = scratch("png");
    for mode in ["rgb", "rgba", "a"] {
        let image = pattern(21, 17, mode);
        let path = dir.join(format!("{mode}.png"));
        let q = Quantize::RGBA_DEFAULT;
        write_display(&path, "png", &image, q, None).unwrap();
        let back = read_image(&path).unwrap();
        let want_names: Vec<String> = if mode == "a" {
            vec!["y".into()]
        } else {
            image.channels.clone()
        };
        assert_eq!(back.channels, want_names);
        assert_eq!(back.data, expected(&image, q, 255.0), "{mode}");
    }
    let image = pattern(21, 17, "rgba");
    let q = Quantize {
        one: 65535,
        min: 0,
        max: 65535,
        dither: 0.5,
    };
    let path = dir.join("16.png");
    write_display(&path, "png", &image, q, None).unwrap();
    assert_eq!(
        read_image(&path).unwrap().data,
        expected(&image, q, 65535.0)
    );
}

#[test]
fn tiff_written_by_us_reads_in_the_tiff_crate() {
    use tiff::decoder::{Decoder, DecodingResult};
    let dir = scratch("tiffcrate");
    let image = pattern(33, 20, "rgba");
    let path = dir.join("a.tif");
    let q = Quantize::RGBA_DEFAULT;
    write_display(&path, "tiff", &image, q, None).unwrap();
    let mut d = Decoder::new(std::fs::File::open(&path).unwrap()).unwrap();
    assert_eq!(d.dimensions().unwrap(), (33, 20));
    let DecodingResult::U8(v) = d.read_image().unwrap() else {
        panic!("expected 8-bit samples")
    };
    let want: Vec<u8> = expected(&image, q, 1.0).iter().map(|&f| f as u8).collect();
    assert_eq!(v, want);

    let image = pattern(33, 20, "rgb");
    write_display(&path, "tiff", &image, Quantize::FLOAT, None).unwrap();
    let mut d = Decoder::new(std::fs::File::open(&path).unwrap()).unwrap();
    let DecodingResult::F32(v) = d.read_image().unwrap() else {
        panic!("expected float samples")
    };
    assert_eq!(v, image.data);
}
