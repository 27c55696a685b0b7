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
    for mode in ["rgb", "a"] {
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
    let image = pattern(21, 17, "rgb");
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
fn png_stores_unassociated_alpha_and_reads_back_premultiplied() {
    let dir = scratch("pngalpha");
    // Premultiplied input: colour ≤ alpha.
    let mut image = Image::new(16, 8, "rgba");
    for y in 0..8u32 {
        for x in 0..16u32 {
            let a = (x + 1) as f32 / 16.0;
            let i = ((y * 16 + x) * 4) as usize;
            image.data[i..i + 4].copy_from_slice(&[a * 0.5, a * (y as f32 / 7.0), a * 0.8, a]);
        }
    }
    let path = dir.join("a.png");
    let q = Quantize {
        dither: 0.0,
        ..Quantize::RGBA_DEFAULT
    };
    write_display(&path, "png", &image, q, None).unwrap();
    // The stored (straight) colour of pixel (0, 0) is 0.5 → 128, not 0.5/16 → 8.
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    reader.next_frame(&mut buf).unwrap();
    assert_eq!(&buf[..4], &[128, 0, 204, 16]);
    // Reading multiplies back: within one 8-bit step of the stored straight colour, times alpha.
    let back = read_image(&path).unwrap();
    for (i, (&b, &a)) in back.data.iter().zip(&image.data).enumerate() {
        let alpha = image.data[i / 4 * 4 + 3];
        assert!(
            (b - a).abs() <= 0.5 / 255.0 * (1.0 + alpha) + 1e-6,
            "{i}: {a} → {b}"
        );
    }
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

#[test]
fn openexr_half_is_within_half_precision_and_float_and_z_are_exact() {
    let dir = scratch("exr");
    let image = pattern(31, 17, "rgbaz");
    let half_path = dir.join("half.exr");
    write_display(&half_path, "openexr", &image, Quantize::RGBA_DEFAULT, None).unwrap();
    let back = read_image(&half_path).unwrap();
    assert_eq!(back.channels, image.channels);
    let nc = image.channels.len();
    for (i, (&b, &a)) in back.data.iter().zip(&image.data).enumerate() {
        if i % nc == 4 {
            assert_eq!(b, a, "z is float in every EXR");
        } else {
            // Half has an 11-bit significand: relative error ≤ 2^-11, no clamping.
            assert!(
                (b - a).abs() <= a.abs() * 2f32.powi(-11) + 1e-7,
                "{a} → {b}"
            );
        }
    }
    assert!(back.data.iter().any(|&v| v < 0.0) && back.data.iter().any(|&v| v > 1.0));

    let float_path = dir.join("float.exr");
    write_display(&float_path, "exr", &image, Quantize::FLOAT, None).unwrap();
    assert_eq!(read_image(&float_path).unwrap(), image);
}

fn matrices() -> DepthMatrices {
    DepthMatrices {
        world_to_screen: std::array::from_fn(|i| 0.5 + i as f32 * 1.25),
        world_to_camera: std::array::from_fn(|i| -3.0 + i as f32 * 0.125),
    }
}

#[test]
fn zfile_round_trip_is_exact_in_both_byte_orders() {
    let dir = scratch("zfile");
    let image = pattern(23, 11, "z");
    let depth = matrices();
    for big in [false, true] {
        let path = dir.join(format!("{big}.z"));
        write_zfile_with_order(&path, &image, &depth, big).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes.len(), 136 + 4 * 23 * 11);
        let magic = [bytes[0], bytes[1], bytes[2], bytes[3]];
        let as_written = if big {
            u32::from_be_bytes(magic)
        } else {
            u32::from_le_bytes(magic)
        };
        assert_eq!(as_written, ZFILE_MAGIC);
        let (back, m) = read_zfile(&path).unwrap();
        assert_eq!(back, image);
        assert_eq!(m, depth);
        assert_eq!(read_image(&path).unwrap(), image);
    }
    // Through the display: the z channel of an rgbz image.
    let rgbz = pattern(9, 4, "rgbz");
    let path = dir.join("display.z");
    write_display(&path, "zfile", &rgbz, Quantize::FLOAT, Some(&depth)).unwrap();
    let (back, _) = read_zfile(&path).unwrap();
    let z: Vec<f32> = rgbz.data.chunks(4).map(|p| p[3]).collect();
    assert_eq!(back.data, z);
    // Without matrices a zfile would be silently wrong for shadows: error.
    assert!(write_display(&path, "zfile", &rgbz, Quantize::FLOAT, None).is_err());
}

#[test]
fn zfile_layout_matches_the_prman_header_byte_for_byte() {
    let dir = scratch("zlayout");
    let mut image = Image::new(3, 2, "z");
    image.data = vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    let path = dir.join("l.z");
    write_zfile_with_order(&path, &image, &matrices(), false).unwrap();
    let b = std::fs::read(&path).unwrap();
    assert_eq!(&b[..4], &[0xab, 0x67, 0x08, 0x2f]);
    assert_eq!(&b[4..8], &[3, 0, 2, 0]);
    assert_eq!(f32::from_le_bytes(b[8..12].try_into().unwrap()), 0.5);
    assert_eq!(f32::from_le_bytes(b[72..76].try_into().unwrap()), -3.0);
    // Top row first: the first depth is pixel (0,0), the fourth is (0,1).
    assert_eq!(f32::from_le_bytes(b[136..140].try_into().unwrap()), 1.0);
    assert_eq!(f32::from_le_bytes(b[148..152].try_into().unwrap()), 4.0);
}

#[test]
fn same_image_writes_identical_bytes() {
    let dir = scratch("determinism");
    let image = pattern(64, 64, "rgba");
    for kind in ["tiff", "png", "exr"] {
        let a = dir.join(format!("a.{kind}"));
        let b = dir.join(format!("b.{kind}"));
        write_display(&a, kind, &image, Quantize::RGBA_DEFAULT, None).unwrap();
        write_display(&b, kind, &image, Quantize::RGBA_DEFAULT, None).unwrap();
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{kind}"
        );
    }
}

#[test]
fn unknown_display_type_is_an_error_and_writes_nothing() {
    let dir = scratch("unknown");
    let path = dir.join("x.img");
    let err = write_display(
        &path,
        "sgi",
        &pattern(4, 4, "rgb"),
        Quantize::RGBA_DEFAULT,
        None,
    )
    .unwrap_err();
    assert!(matches!(err, ImageError::UnsupportedDisplay { ref kind, .. } if kind == "sgi"));
    assert!(err.to_string().contains("x.img"), "{err}");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

#[test]
fn failed_write_leaves_the_old_file_and_no_temporary() {
    let dir = scratch("atomic");
    let path = dir.join("keep.png");
    std::fs::write(&path, b"old contents").unwrap();
    // A depth-only PNG is refused.
    let err = write_display(
        &path,
        "png",
        &pattern(4, 4, "z"),
        Quantize::RGBA_DEFAULT,
        None,
    );
    assert!(err.is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"old contents");
    // The rename fails (the target is a non-empty directory) after the temporary was written:
    // the error names the path and the temporary is removed.
    let blocked = dir.join("blocked.tif");
    std::fs::create_dir(&blocked).unwrap();
    std::fs::write(blocked.join("inside"), b"x").unwrap();
    let err = write_display(
        &blocked,
        "tiff",
        &pattern(4, 4, "rgb"),
        Quantize::RGBA_DEFAULT,
        None,
    )
    .unwrap_err();
    assert!(err.to_string().contains("blocked.tif"), "{err}");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["blocked.tif", "keep.png"], "no temporary left");
    // A successful write replaces the old file and leaves nothing else.
    write_display(
        &path,
        "png",
        &pattern(4, 4, "rgb"),
        Quantize::RGBA_DEFAULT,
        None,
    )
    .unwrap();
    assert_ne!(std::fs::read(&path).unwrap(), b"old contents");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
}

#[test]
fn malformed_images_are_rejected_before_writing() {
    let dir = scratch("malformed");
    let mut image = pattern(4, 4, "rgb");
    image.data.pop();
    let err = write_display(
        &dir.join("m.tif"),
        "tiff",
        &image,
        Quantize::RGBA_DEFAULT,
        None,
    )
    .unwrap_err();
    assert!(err.to_string().contains("expected 48 samples"), "{err}");
}

#[test]
fn truncated_files_of_every_kind_give_errors_not_panics() {
    let dir = scratch("truncated");
    let image = pattern(16, 12, "rgba");
    let depth = matrices();
    let z = pattern(16, 12, "z");
    let files = [
        ("t.tif", "tiff", &image),
        ("t.png", "png", &image),
        ("t.exr", "exr", &image),
        ("t.z", "zfile", &z),
    ];
    for (name, kind, img) in files {
        let full = dir.join(name);
        write_display(&full, kind, img, Quantize::RGBA_DEFAULT, Some(&depth)).unwrap();
        let bytes = std::fs::read(&full).unwrap();
        let whole = read_image(&full).unwrap();
        let cut = dir.join(format!("cut-{name}"));
        let step = (bytes.len() / 97).max(1);
        for len in (0..bytes.len() - 1).step_by(step) {
            std::fs::write(&cut, &bytes[..len]).unwrap();
            // A truncated file must not panic, and must not pass for a different image.
            let result = std::panic::catch_unwind(|| read_image(&cut));
            let result = result.unwrap_or_else(|_| panic!("{name} cut at {len} panicked"));
            // Only a cut in the trailer (PNG's IEND) may still decode, and then to the full image.
            if let Ok(partial) = result {
                assert_eq!(
                    partial, whole,
                    "{name} cut at {len} read as a different image"
                );
            }
        }
    }
}

#[test]
fn corrupted_bytes_never_panic() {
    let dir = scratch("corrupt");
    let image = pattern(16, 12, "rgba");
    for (name, kind, q) in [
        ("c.tif", "tiff", Quantize::RGBA_DEFAULT),
        ("f.tif", "tiff", Quantize::FLOAT),
        ("c.exr", "exr", Quantize::RGBA_DEFAULT),
    ] {
        let full = dir.join(name);
        write_display(&full, kind, &image, q, None).unwrap();
        let bytes = std::fs::read(&full).unwrap();
        let bad = dir.join(format!("bad-{name}"));
        for i in 0..400u32 {
            let mut b = bytes.clone();
            let at = (dither_noise(i, 1, 2).abs() * b.len() as f64) as usize % b.len();
            b[at] ^= 1 << (i % 8);
            std::fs::write(&bad, &b).unwrap();
            let r = std::panic::catch_unwind(|| read_image(&bad));
            assert!(r.is_ok(), "{name}: flipping a bit at byte {at} panicked");
        }
    }
}

#[test]
fn hostile_headers_are_refused_without_allocating() {
    let dir = scratch("hostile");
    // zfile claiming 65535×65535 depths in a 136-byte file.
    let mut z = Vec::new();
    z.extend(ZFILE_MAGIC.to_le_bytes());
    z.extend(65535u16.to_le_bytes());
    z.extend(65535u16.to_le_bytes());
    z.extend([0u8; 128]);
    let path = dir.join("huge.z");
    std::fs::write(&path, &z).unwrap();
    let err = read_image(&path).unwrap_err().to_string();
    assert!(err.contains("expected at most"), "{err}");

    // A TIFF claiming 4 000 000 000 × 4 000 000 000 pixels.
    let mut t = b"II*\0".to_vec();
    t.extend(8u32.to_le_bytes());
    let entries: [(u16, u16, u32, u32); 4] = [
        (256, 4, 1, 4_000_000_000),
        (257, 4, 1, 4_000_000_000),
        (258, 3, 1, 8),
        (273, 4, 1, 0),
    ];
    t.extend((entries.len() as u16).to_le_bytes());
    for (tag, kind, count, value) in entries {
        t.extend(tag.to_le_bytes());
        t.extend(kind.to_le_bytes());
        t.extend(count.to_le_bytes());
        t.extend(value.to_le_bytes());
    }
    t.extend(0u32.to_le_bytes());
    let path = dir.join("huge.tif");
    std::fs::write(&path, &t).unwrap();
    let err = read_image(&path).unwrap_err().to_string();
    assert!(
        err.contains("expected at most 65536 pixels per side"),
        "{err}"
    );

    // Not an image at all.
    let path = dir.join("text.tif");
    std::fs::write(&path, b"hello, world").unwrap();
    let err = read_image(&path).unwrap_err().to_string();
    assert!(
        err.contains("expected a TIFF, PNG, JPEG, OpenEXR or zfile"),
        "{err}"
    );
    assert!(read_image(&dir.join("missing.tif")).is_err());
}

#[test]
fn tiff_compressions_from_the_tiff_crate_decode_exactly() {
    use tiff::encoder::{colortype, Compression, DeflateLevel, TiffEncoder};
    let dir = scratch("tiffcodecs");
    let (w, h) = (45u32, 29u32);
    let rgb8: Vec<u8> = (0..w * h * 3).map(|i| ((i * 37) % 251) as u8).collect();
    let gray16: Vec<u16> = (0..w * h).map(|i| ((i * 7919) % 65521) as u16).collect();
    for (name, method) in [
        ("lzw", Compression::Lzw),
        ("deflate", Compression::Deflate(DeflateLevel::Balanced)),
        ("packbits", Compression::Packbits),
        ("none", Compression::Uncompressed),
    ] {
        let path = dir.join(format!("{name}.tif"));
        TiffEncoder::new(std::fs::File::create(&path).unwrap())
            .unwrap()
            .with_compression(method)
            .write_image::<colortype::RGB8>(w, h, &rgb8)
            .unwrap();
        let back = read_image(&path).unwrap();
        assert_eq!(back.channels, ["r", "g", "b"], "{name}");
        let want: Vec<f32> = rgb8.iter().map(|&v| v as f32 / 255.0).collect();
        assert_eq!(back.data, want, "{name}");
    }
    let path = dir.join("gray16.tif");
    TiffEncoder::new(std::fs::File::create(&path).unwrap())
        .unwrap()
        .with_compression(Compression::Lzw)
        .write_image::<colortype::Gray16>(w, h, &gray16)
        .unwrap();
    let back = read_image(&path).unwrap();
    assert_eq!(back.channels, ["y"]);
    let want: Vec<f32> = gray16.iter().map(|&v| v as f32 / 65535.0).collect();
    assert_eq!(back.data, want);
}

#[test]
fn openexr_records_world_to_camera_and_world_to_ndc() {
    let dir = scratch("exrmatrices");
    // A perspective camera: camera = world shifted by (0,0,5); screen = x/z, y/z (fov 90).
    #[rustfmt::skip]
    let world_to_camera = [
        1.0, 0.0, 0.0, 0.0,
        0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 0.0,
        0.0, 0.0, 5.0, 1.0,
    ];
    #[rustfmt::skip]
    let camera_to_screen_w = [
        1.0, 0.0, 0.0, 0.0,
        0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 1.0, 1.0,
        0.0, 0.0, 0.0, 0.0,
    ];
    let mut world_to_screen = [0f32; 16];
    for r in 0..4 {
        for c in 0..4 {
            world_to_screen[r * 4 + c] = (0..4)
                .map(|k| world_to_camera[r * 4 + k] * camera_to_screen_w[k * 4 + c])
                .sum();
        }
    }
    let depth = DepthMatrices {
        world_to_screen,
        world_to_camera,
    };
    let path = dir.join("z.exr");
    write_display(
        &path,
        "exr",
        &pattern(4, 4, "z"),
        Quantize::FLOAT,
        Some(&depth),
    )
    .unwrap();
    let meta = exr::meta::MetaData::read_from_file(&path, false).unwrap();
    let attributes = &meta.headers[0].own_attributes;
    assert_eq!(attributes.world_to_camera, Some(world_to_camera));
    // World point (1, -1, 0) is at camera (1, -1, 5): screen (0.2, -0.2), NDC (0.6, 0.6).
    let ndc = attributes.world_to_normalized_device.expect("worldToNDC");
    let p = [1.0f32, -1.0, 0.0, 1.0];
    let h: Vec<f32> = (0..4)
        .map(|c| (0..4).map(|k| p[k] * ndc[k * 4 + c]).sum())
        .collect();
    assert!(
        (h[0] / h[3] - 0.6).abs() < 1e-6 && (h[1] / h[3] - 0.6).abs() < 1e-6,
        "{h:?}"
    );
}

#[test]
fn dithered_crops_tile_into_the_full_frame_bit_for_bit() {
    let dir = scratch("crops");
    let full = pattern(40, 30, "rgba");
    let q = Quantize::RGBA_DEFAULT;
    let full_path = dir.join("full.tif");
    write_display(&full_path, "tiff", &full, q, None).unwrap();
    let whole = read_image(&full_path).unwrap();
    // Four crop windows with uneven splits.
    let mut pasted = vec![f32::NAN; whole.data.len()];
    for (x0, x1, y0, y1) in [
        (0, 17, 0, 11),
        (17, 40, 0, 11),
        (0, 17, 11, 30),
        (17, 40, 11, 30),
    ] {
        let mut crop = Image::new(x1 - x0, y1 - y0, "rgba");
        for y in y0..y1 {
            for x in x0..x1 {
                for c in 0..4 {
                    let i = (((y - y0) * (x1 - x0) + (x - x0)) * 4 + c) as usize;
                    crop.data[i] = full.at(x, y, c as usize);
                }
            }
        }
        let path = dir.join(format!("crop{x0}-{y0}.tif"));
        write_display_cropped(&path, "tiff", &crop, q, None, [x0, y0]).unwrap();
        let back = read_image(&path).unwrap();
        for y in y0..y1 {
            for x in x0..x1 {
                for c in 0..4 {
                    pasted[((y * 40 + x) * 4 + c) as usize] = back.at(x - x0, y - y0, c as usize);
                }
            }
        }
    }
    assert_eq!(pasted, whole.data);
}

#[test]
fn hostile_openexr_and_png_sizes_are_refused() {
    let dir = scratch("hostile2");
    // OpenEXR: patch the dataWindow box to 2e9 × 2e9 pixels.
    let path = dir.join("ok.exr");
    write_display(
        &path,
        "exr",
        &pattern(4, 4, "rgba"),
        Quantize::RGBA_DEFAULT,
        None,
    )
    .unwrap();
    let mut b = std::fs::read(&path).unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = b.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 4;
    b[at + 8..at + 12].copy_from_slice(&2_000_000_000i32.to_le_bytes());
    b[at + 12..at + 16].copy_from_slice(&2_000_000_000i32.to_le_bytes());
    let bad = dir.join("huge.exr");
    std::fs::write(&bad, &b).unwrap();
    assert!(read_image(&bad).is_err());

    // PNG: an IHDR claiming 1 000 000 × 1 000 000 RGBA pixels (with a valid CRC).
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(1_000_000u32.to_be_bytes());
    ihdr.extend(1_000_000u32.to_be_bytes());
    ihdr.extend([8, 6, 0, 0, 0]);
    let mut png = vec![0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A];
    png.extend(13u32.to_be_bytes());
    png.extend(&ihdr);
    png.extend(crc32(&ihdr).to_be_bytes());
    let bad = dir.join("huge.png");
    std::fs::write(&bad, &png).unwrap();
    let err = read_image(&bad).unwrap_err().to_string();
    assert!(err.contains("huge.png"), "{err}");
}

/// CRC-32 (ISO 3309, as PNG uses), bit by bit: an independent reference for the test PNG.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    fn image_strategy() -> impl Strategy<Value = Image> {
        (
            1u32..20,
            1u32..20,
            prop::sample::select(vec!["rgb", "rgba", "a", "ya"]),
        )
            .prop_flat_map(|(w, h, mode)| {
                let n = (w * h) as usize * mode.len();
                prop::collection::vec(-0.5f32..1.5, n).prop_map(move |data| Image {
                    width: w,
                    height: h,
                    channels: mode.chars().map(|c| c.to_string()).collect(),
                    data,
                })
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn tiff_round_trip_equals_quantize(
            image in image_strategy(),
            one in prop::sample::select(vec![255, 1000, 65535]),
            dither in 0.0f32..1.0,
        ) {
            let q = Quantize { one, min: 0, max: one, dither };
            let dir = scratch("prop");
            let path = dir.join("p.tif");
            write_display(&path, "tiff", &image, q, None).unwrap();
            let back = read_image(&path).unwrap();
            let scale = if one <= 255 { 255.0 } else { 65535.0 };
            prop_assert_eq!(&back.channels, &image.channels);
            prop_assert_eq!(back.data, expected(&image, q, scale));
        }

        #[test]
        fn quantized_values_stay_within_min_max_and_error_bound(
            v in -10.0f32..10.0, x in 0u32..5000, y in 0u32..5000,
            min in 0i32..100, span in 1i32..60000, dither in 0.0f32..2.0,
        ) {
            let q = Quantize { one: 255, min, max: min + span, dither };
            let out = q.quantize(v, x, y, 0);
            prop_assert!(out >= min as f64 && out <= (min + span).min(65535) as f64);
            let unclamped = 255.0 * v as f64;
            if unclamped > min as f64 + 3.0 && unclamped < (min + span) as f64 - 3.0 {
                prop_assert!((out - unclamped).abs() <= 0.5 + dither as f64 + 1e-9);
            }
        }
    }
}

#[test]
fn lzw_tables_fill_and_reset_on_noisy_large_strips() {
    use tiff::encoder::{colortype, Compression, TiffEncoder};
    let dir = scratch("lzwbig");
    let (w, h) = (300u32, 200u32);
    // Noise (every code adds a table entry, so 12-bit codes and clears occur) mixed with runs
    // (long strings, deep prefix chains).
    let data: Vec<u8> = (0..w * h * 3)
        .map(|i| {
            if (i / 997) % 3 == 0 {
                (i / 4000) as u8
            } else {
                ((dither_noise(i, 7, 1) + 1.0) * 127.9) as u8
            }
        })
        .collect();
    let path = dir.join("big.tif");
    TiffEncoder::new(std::fs::File::create(&path).unwrap())
        .unwrap()
        .with_compression(Compression::Lzw)
        .write_image::<colortype::RGB8>(w, h, &data)
        .unwrap();
    let back = read_image(&path).unwrap();
    let want: Vec<f32> = data.iter().map(|&v| v as f32 / 255.0).collect();
    assert!(back.data == want, "LZW decode differs");
}
