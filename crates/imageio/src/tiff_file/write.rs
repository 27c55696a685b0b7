//! Writing: one IFD, little-endian, Deflate-compressed strips (see the module documentation).

use super::*;
use crate::atomic_write::write_atomically;
use crate::quantize::{quantize_image, Samples};
use crate::{format_error, io_error, Image, ImageError, Quantize};
use std::io::Write;
use std::path::Path;

/// One IFD entry before layout: tag, type, and its values as bytes (little-endian).
struct Entry {
    tag: u16,
    kind: u16,
    count: u32,
    bytes: Vec<u8>,
}

fn shorts(tag: u16, values: &[u16]) -> Entry {
    Entry {
        tag,
        kind: TYPE_SHORT,
        count: values.len() as u32,
        bytes: values.iter().flat_map(|v| v.to_le_bytes()).collect(),
    }
}

fn longs(tag: u16, values: &[u32]) -> Entry {
    Entry {
        tag,
        kind: TYPE_LONG,
        count: values.len() as u32,
        bytes: values.iter().flat_map(|v| v.to_le_bytes()).collect(),
    }
}

fn ascii(tag: u16, text: &str) -> Entry {
    let mut bytes = text.as_bytes().to_vec();
    bytes.push(0);
    Entry {
        tag,
        kind: TYPE_ASCII,
        count: bytes.len() as u32,
        bytes,
    }
}

/// Writes `image` as a TIFF (see the module documentation for the layout).
pub(crate) fn write_tiff(
    path: &Path,
    image: &Image,
    quantize: Quantize,
    origin: [u32; 2],
) -> Result<(), ImageError> {
    // Depth is never quantized, and TIFF readers expect one sample format per file.
    let quantize = if image.channel_index("z").is_some() {
        Quantize::FLOAT
    } else {
        quantize
    };
    let samples = quantize_image(image, quantize, origin);
    let (bits, format, bytes): (u16, u16, Vec<u8>) = match &samples {
        Samples::U8(v) => (8, 1, v.clone()),
        Samples::U16(v) => (16, 1, v.iter().flat_map(|s| s.to_le_bytes()).collect()),
        Samples::F32(v) => (32, 3, v.iter().flat_map(|s| s.to_le_bytes()).collect()),
    };
    let nc = image.channels.len();
    let row_bytes = image.width as usize * nc * bits as usize / 8;
    let rows_per_strip = (65536 / row_bytes.max(1)).clamp(1, image.height as usize);

    // Compress each strip on its own so readers can decode strips independently; strips are
    // independent, so they compress in parallel and the bytes do not depend on thread count.
    use rayon::prelude::*;
    let strips = bytes
        .par_chunks(rows_per_strip * row_bytes)
        .map(|rows| {
            let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
            z.write_all(rows)?;
            z.finish()
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| io_error(path, e))?;

    let color = nc >= 3 && image.channels[..3] == ["r", "g", "b"];
    let photometric_samples = if color { 3 } else { 1 };
    let extra: Vec<u16> = image.channels[photometric_samples..]
        .iter()
        .map(|c| if c == "a" { 1 } else { 0 })
        .collect();
    let description = format!("{DESCRIPTION_PREFIX}{}", image.channels.join(","));

    // Layout: header (8) · strips · IFD · out-of-line tag values.
    let mut offset = 8u64;
    let mut strip_offsets = Vec::with_capacity(strips.len());
    for s in &strips {
        strip_offsets.push(offset);
        offset += s.len() as u64;
    }
    offset += offset & 1; // IFDs start on a word boundary
    if offset > u32::MAX as u64 / 2 {
        return Err(format_error(
            path,
            format!("expected a TIFF under 2 GiB, found {offset} bytes of pixels"),
        ));
    }
    let strip_offsets: Vec<u32> = strip_offsets.iter().map(|&o| o as u32).collect();
    let strip_counts: Vec<u32> = strips.iter().map(|s| s.len() as u32).collect();

    let mut entries = vec![
        longs(TAG_IMAGE_WIDTH, &[image.width]),
        longs(TAG_IMAGE_LENGTH, &[image.height]),
        shorts(TAG_BITS_PER_SAMPLE, &vec![bits; nc]),
        shorts(TAG_COMPRESSION, &[8]),
        shorts(TAG_PHOTOMETRIC, &[if color { 2 } else { 1 }]),
        ascii(TAG_IMAGE_DESCRIPTION, &description),
        longs(TAG_STRIP_OFFSETS, &strip_offsets),
        shorts(TAG_SAMPLES_PER_PIXEL, &[nc as u16]),
        longs(TAG_ROWS_PER_STRIP, &[rows_per_strip as u32]),
        longs(TAG_STRIP_BYTE_COUNTS, &strip_counts),
        shorts(TAG_PLANAR_CONFIG, &[1]),
        ascii(TAG_SOFTWARE, "Illume"),
        shorts(TAG_SAMPLE_FORMAT, &vec![format; nc]),
    ];
    if !extra.is_empty() {
        entries.push(shorts(TAG_EXTRA_SAMPLES, &extra));
    }
    entries.sort_by_key(|e| e.tag);

    let ifd_offset = offset as u32;
    let ifd_size = 2 + 12 * entries.len() as u32 + 4;
    let mut value_offset = ifd_offset + ifd_size;
    let mut ifd = Vec::with_capacity(ifd_size as usize);
    let mut values = Vec::new();
    ifd.extend((entries.len() as u16).to_le_bytes());
    for e in &entries {
        ifd.extend(e.tag.to_le_bytes());
        ifd.extend(e.kind.to_le_bytes());
        ifd.extend(e.count.to_le_bytes());
        if e.bytes.len() <= 4 {
            let mut inline = [0u8; 4];
            inline[..e.bytes.len()].copy_from_slice(&e.bytes);
            ifd.extend(inline);
        } else {
            ifd.extend(value_offset.to_le_bytes());
            values.extend(&e.bytes);
            if values.len() % 2 == 1 {
                values.push(0);
            }
            value_offset = ifd_offset + ifd_size + values.len() as u32;
        }
    }
    ifd.extend(0u32.to_le_bytes()); // no next IFD

    write_atomically(path, |w| {
        let io = |e| io_error(path, e);
        w.write_all(b"II*\0").map_err(io)?;
        w.write_all(&ifd_offset.to_le_bytes()).map_err(io)?;
        let mut written = 8u64;
        for s in &strips {
            w.write_all(s).map_err(io)?;
            written += s.len() as u64;
        }
        if written < ifd_offset as u64 {
            w.write_all(&[0]).map_err(io)?;
        }
        w.write_all(&ifd).map_err(io)?;
        w.write_all(&values).map_err(io)
    })
}
