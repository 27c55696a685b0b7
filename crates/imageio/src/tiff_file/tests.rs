use super::codec::{lzw_decode, packbits_decode};
use super::read::decode_tiff;
use std::path::Path;

#[test]
fn packbits_decodes_the_specification_example() {
    // TIFF 6.0 §9 example.
    let packed = [
        0xFE, 0xAA, 0x02, 0x80, 0x00, 0x2A, 0xFD, 0xAA, 0x03, 0x80, 0x00, 0x2A, 0x22, 0xF7, 0xAA,
    ];
    let unpacked = [
        0xAA, 0xAA, 0xAA, 0x80, 0x00, 0x2A, 0xAA, 0xAA, 0xAA, 0xAA, 0x80, 0x00, 0x2A, 0x22, 0xAA,
        0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA,
    ];
    assert_eq!(packbits_decode(&packed, unpacked.len()), unpacked);
}

#[test]
fn lzw_rejects_garbage_without_panicking() {
    for seed in 0..200u32 {
        let bytes: Vec<u8> = (0..64u32)
            .map(|i| (crate::dither_noise(i, seed, 9) * 127.0 + 128.0) as u8)
            .collect();
        let _ = lzw_decode(&bytes, 1000);
    }
}

/// A minimal big-endian ("MM") TIFF: 16-bit RGB, uncompressed, horizontal predictor,
/// two strips — byte order, predictor and strip bookkeeping built by hand from TIFF 6.0.
fn big_endian_tiff(pixels: &[[u16; 3]], width: u16, height: u16) -> Vec<u8> {
    let mut strip = Vec::new();
    for row in pixels.chunks(width as usize) {
        let mut prev = [0u16; 3];
        for px in row {
            for c in 0..3 {
                strip.extend(px[c].wrapping_sub(prev[c]).to_be_bytes());
            }
            prev = *px;
        }
    }
    let row_bytes = width as usize * 6;
    let split = 2 * row_bytes; // two rows per strip: the second strip is short
    let mut t = b"MM\0*".to_vec();
    let data_at = 8u32;
    let bps_at = data_at + strip.len() as u32;
    let ifd_at = bps_at + 6;
    t.extend(ifd_at.to_be_bytes());
    t.extend(&strip);
    t.extend([0, 16, 0, 16, 0, 16]);
    let entries: [(u16, u16, u32, u32); 10] = [
        (256, 3, 1, (width as u32) << 16),
        (257, 3, 1, (height as u32) << 16),
        (258, 3, 3, bps_at),
        (259, 3, 1, 1 << 16),
        (262, 3, 1, 2 << 16),
        (273, 4, 2, 0), // patched below: two offsets need an out-of-line array
        (277, 3, 1, 3 << 16),
        (278, 3, 1, 2 << 16),
        (279, 4, 2, 0),
        (317, 3, 1, 2 << 16),
    ];
    let arrays_at = ifd_at + 2 + 12 * entries.len() as u32 + 4;
    t.extend((entries.len() as u16).to_be_bytes());
    for (tag, kind, count, value) in entries {
        let value = match tag {
            273 => arrays_at,
            279 => arrays_at + 8,
            _ => value,
        };
        t.extend(tag.to_be_bytes());
        t.extend(kind.to_be_bytes());
        t.extend(count.to_be_bytes());
        t.extend(value.to_be_bytes());
    }
    t.extend(0u32.to_be_bytes());
    for v in [data_at, data_at + split as u32] {
        t.extend(v.to_be_bytes());
    }
    for v in [split as u32, (strip.len() - split) as u32] {
        t.extend(v.to_be_bytes());
    }
    t
}

#[test]
fn big_endian_16bit_with_horizontal_predictor_decodes_exactly() {
    let (w, h) = (5u16, 3u16);
    let pixels: Vec<[u16; 3]> = (0..(w * h) as u32)
        .map(|i| {
            [
                (i * 4099) as u16,
                65535 - (i * 77) as u16,
                (i * i * 1013) as u16,
            ]
        })
        .collect();
    let bytes = big_endian_tiff(&pixels, w, h);
    let image = decode_tiff(Path::new("mm.tif"), &bytes).unwrap();
    assert_eq!((image.width, image.height), (5, 3));
    assert_eq!(image.channels, ["r", "g", "b"]);
    let want: Vec<f32> = pixels
        .iter()
        .flatten()
        .map(|&v| (v as f64 / 65535.0) as f32)
        .collect();
    assert_eq!(image.data, want);
    // Every truncation is an error, never a panic.
    for len in 0..bytes.len() - 1 {
        let _ = decode_tiff(Path::new("mm.tif"), &bytes[..len]);
    }
}

/// A little-endian ("II") TIFF of one 64-bit IEEE float sample per pixel (SampleFormat 3),
/// uncompressed, one strip, built by hand from TIFF 6.0.
fn float64_tiff(values: &[f64], width: u16) -> Vec<u8> {
    let height = (values.len() / width as usize) as u32;
    let mut t = b"II*\0".to_vec();
    let data_at = 8u32;
    let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let ifd_at = data_at + data.len() as u32;
    t.extend(ifd_at.to_le_bytes());
    t.extend(&data);
    let entries: [(u16, u16, u32, u32); 10] = [
        (256, 3, 1, width as u32),
        (257, 4, 1, height),
        (258, 3, 1, 64),
        (259, 3, 1, 1),
        (262, 3, 1, 1),
        (273, 4, 1, data_at),
        (277, 3, 1, 1),
        (278, 4, 1, height),
        (279, 4, 1, data.len() as u32),
        (339, 3, 1, 3),
    ];
    t.extend((entries.len() as u16).to_le_bytes());
    for (tag, kind, count, value) in entries {
        t.extend(tag.to_le_bytes());
        t.extend(kind.to_le_bytes());
        t.extend(count.to_le_bytes());
        t.extend(value.to_le_bytes());
    }
    t.extend(0u32.to_le_bytes());
    t
}

#[test]
fn float64_samples_decode_to_their_values_without_overflow() {
    // 64-bit samples used to compute `(1 << 64) - 1` as the largest code: a panic in debug
    // builds (bad input must never panic, and 64-bit float TIFFs are valid input).
    let values = [0.25, 0.5, 0.75, -1.5, 2.0, 1e-3];
    let bytes = float64_tiff(&values, 3);
    let image = decode_tiff(Path::new("f64.tif"), &bytes).unwrap();
    assert_eq!((image.width, image.height), (3, 2));
    let want: Vec<f32> = values.iter().map(|&v| v as f32).collect();
    assert_eq!(image.data, want);
    for len in 0..bytes.len() - 1 {
        let _ = decode_tiff(Path::new("f64.tif"), &bytes[..len]);
    }
}

/// A test image whose samples vary per pixel and channel (some outside [0, 1]).
fn gradient(width: u32, height: u32, channels: &[&str]) -> crate::Image {
    let nc = channels.len();
    crate::Image {
        width,
        height,
        channels: channels.iter().map(|c| c.to_string()).collect(),
        data: (0..(width * height) as usize * nc)
            .map(|i| ((i * 37 % 101) as f32) / 90.0 - 0.05)
            .collect(),
    }
}

/// Rows `y0..y1` of `image`.
fn rows_of(image: &crate::Image, y0: u32, y1: u32) -> crate::Image {
    let per_row = image.width as usize * image.channels.len();
    crate::Image {
        width: image.width,
        height: y1 - y0,
        channels: image.channels.clone(),
        data: image.data[y0 as usize * per_row..y1 as usize * per_row].to_vec(),
    }
}

#[test]
fn rows_streamed_in_any_bands_make_the_whole_image_file_byte_for_byte() {
    let dir = std::env::temp_dir().join(format!("illume-tiffrows-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // 8-bit dithered colour (dither keyed on the crop origin plus the row), and all-float
    // with depth; 700 px wide RGBA rows make 23-row strips, so bands cut strips anywhere.
    for (channels, q) in [
        (&["r", "g", "b", "a"][..], crate::Quantize::RGBA_DEFAULT),
        (&["r", "g", "b", "z"][..], crate::Quantize::RGBA_DEFAULT),
    ] {
        let image = gradient(700, 61, channels);
        let whole = dir.join("whole.tif");
        super::write_tiff(&whole, &image, q, [5, 9]).unwrap();
        for bands in [
            &[61][..],
            &[1, 60][..],
            &[16, 16, 16, 13][..],
            &[23, 23, 15][..],
            &[7; 8][..],
        ] {
            let bands: Vec<u32> = bands
                .iter()
                .copied()
                .chain([61 - bands.iter().sum::<u32>()])
                .collect();
            let streamed = dir.join("streamed.tif");
            let names = image.channels.clone();
            let mut w = super::TiffRows::create(&streamed, [700, 61], &names, q, [5, 9]).unwrap();
            let mut y = 0;
            for b in bands.iter().filter(|&&b| b > 0) {
                w.write_rows(&rows_of(&image, y, y + b)).unwrap();
                y += b;
            }
            w.finish().unwrap();
            assert!(
                std::fs::read(&whole).unwrap() == std::fs::read(&streamed).unwrap(),
                "{channels:?} in bands {bands:?}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unfinished_stream_leaves_no_file_and_too_many_rows_are_an_error() {
    let dir = std::env::temp_dir().join(format!("illume-tiffrows-cut-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cut.tif");
    let image = gradient(8, 4, &["r", "g", "b"]);
    let q = crate::Quantize::RGBA_DEFAULT;
    let mut w = super::TiffRows::create(&path, [8, 4], &image.channels, q, [0, 0]).unwrap();
    w.write_rows(&rows_of(&image, 0, 3)).unwrap();
    assert!(w.write_rows(&image).is_err(), "7 rows accepted into 4");
    drop(w);
    let w = super::TiffRows::create(&path, [8, 4], &image.channels, q, [0, 0]).unwrap();
    assert!(w.finish().is_err(), "a file without its rows was finished");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "left behind: {left:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A tiled file streamed a column block at a time, each in bands of any height, is the file
/// `write_tiff_tiled` writes from the whole image, and it reads back as the striped file does:
/// the same quantized values, the padding of the edge tiles (the last column is 300 − 256 = 44
/// pixels wide, the last row of tiles 45 − 32 = 13 rows tall) cropped away.
#[test]
fn a_tiled_file_streamed_by_column_blocks_is_the_whole_image_file_and_reads_back() {
    let dir = std::env::temp_dir().join(format!("illume-tifftiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (channels, q) in [
        (&["r", "g", "b", "a"][..], crate::Quantize::RGBA_DEFAULT),
        (&["z"][..], crate::Quantize::FLOAT),
        (&["r", "g", "b"][..], crate::Quantize::FLOAT),
    ] {
        let image = gradient(300, 45, channels);
        let (whole, striped) = (dir.join("whole.tif"), dir.join("striped.tif"));
        super::write_tiff_tiled(&whole, &image, q, [5, 9], 128).unwrap();
        super::write_tiff(&striped, &image, q, [5, 9]).unwrap();
        let (a, b) = (
            super::read_tiff(&whole).unwrap(),
            super::read_tiff(&striped).unwrap(),
        );
        assert_eq!((a.width, a.height, &a.channels), (300, 45, &b.channels));
        assert!(
            a.data
                .iter()
                .zip(&b.data)
                .all(|(x, y)| x.to_bits() == y.to_bits()),
            "{channels:?}: tiled and striped files read back differently"
        );
        for bands in [&[45][..], &[16, 16, 13][..], &[7, 30, 8][..]] {
            let streamed = dir.join("streamed.tif");
            let mut w = super::TiffRows::create_tiled(
                &streamed,
                [300, 45],
                &image.channels,
                q,
                [5, 9],
                128,
            )
            .unwrap();
            for x in [0, 128, 256] {
                let block = image.columns(x, (x + 128).min(300));
                let mut y = 0;
                for b in bands {
                    w.write_block(&rows_of(&block, y, y + b), x).unwrap();
                    y += b;
                }
            }
            w.finish().unwrap();
            assert!(
                std::fs::read(&whole).unwrap() == std::fs::read(&streamed).unwrap(),
                "{channels:?} in bands {bands:?}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Blocks that are not whole columns of tiles at their next row are refused, and a file
/// missing a column's rows is not finished.
#[test]
fn a_tiled_file_takes_only_whole_tile_columns_in_order() {
    let dir = std::env::temp_dir().join(format!("illume-tifftiles-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.tif");
    let image = gradient(40, 20, &["r", "g", "b"]);
    let q = crate::Quantize::RGBA_DEFAULT;
    let names = image.channels.clone();
    assert!(super::TiffRows::create_tiled(&path, [40, 20], &names, q, [0, 0], 24).is_err());
    let mut w = super::TiffRows::create_tiled(&path, [40, 20], &names, q, [0, 0], 16).unwrap();
    assert!(
        w.write_block(&image.columns(8, 24), 8).is_err(),
        "off the tile grid"
    );
    assert!(
        w.write_block(&image.columns(0, 8), 0).is_err(),
        "half a tile column"
    );
    w.write_block(&rows_of(&image.columns(0, 16), 0, 5), 0)
        .unwrap();
    assert!(
        w.write_block(&image.columns(0, 32), 0).is_err(),
        "columns at different rows"
    );
    w.write_block(&rows_of(&image.columns(0, 16), 5, 20), 0)
        .unwrap();
    w.write_block(&image.columns(16, 40), 16).unwrap();
    assert!(
        w.write_block(&rows_of(&image.columns(16, 40), 0, 1), 16)
            .is_err(),
        "past the end"
    );
    w.finish().unwrap();
    let back = super::read_tiff(&path).unwrap();
    assert_eq!((back.width, back.height), (40, 20));
    let mut w = super::TiffRows::create_tiled(&path, [40, 20], &names, q, [0, 0], 16).unwrap();
    w.write_block(&image.columns(0, 16), 0).unwrap();
    assert!(w.finish().is_err(), "finished without the other columns");
    std::fs::remove_dir_all(&dir).unwrap();
}
