//! TIFF: the `tiff`/`file` display driver and a TIFF reader.
//!
//! Both are written here against the TIFF 6.0 specification rather than through a codec crate,
//! because renderer TIFFs break the crates' assumptions: Aqsis and PRMan write RGB files with
//! extra samples (alpha, depth) and no `ExtraSamples` tag, and a depth display wants float and
//! 8-bit channels chosen per channel set.
//!
//! Writer: one IFD, little-endian, contiguous samples, Deflate-compressed strips of about 64 KiB,
//! `SampleFormat` 1 (unsigned) or 3 (IEEE float), `ExtraSamples` 1 (associated alpha — RenderMan
//! colour is premultiplied) for `a` and 0 (unspecified) for `z` and others, and the channel names
//! in `ImageDescription` as `Illume channels r,g,b,z` so a round trip restores them.
//!
//! Reader: classic TIFF in either byte order; strips or tiles; planar configuration 1 or 2;
//! compression none, LZW, Deflate (8 and 32946) and PackBits; predictors 2 (horizontal) and
//! 3 (floating point); 8/16/32-bit unsigned or signed integers, 16/32/64-bit floats; photometric
//! min-is-white, min-is-black, RGB and palette; any number of samples per pixel. Only the first
//! image (IFD) is read.

use crate::atomic_write::write_atomically;
use crate::quantize::{quantize_image, Samples};
use crate::raster_limits::check_size;
use crate::{format_error, io_error, Image, ImageError, Quantize};
use std::io::Write;
use std::path::Path;

const TAG_IMAGE_WIDTH: u16 = 256;
const TAG_IMAGE_LENGTH: u16 = 257;
const TAG_BITS_PER_SAMPLE: u16 = 258;
const TAG_COMPRESSION: u16 = 259;
const TAG_PHOTOMETRIC: u16 = 262;
const TAG_IMAGE_DESCRIPTION: u16 = 270;
const TAG_STRIP_OFFSETS: u16 = 273;
const TAG_SAMPLES_PER_PIXEL: u16 = 277;
const TAG_ROWS_PER_STRIP: u16 = 278;
const TAG_STRIP_BYTE_COUNTS: u16 = 279;
const TAG_PLANAR_CONFIG: u16 = 284;
const TAG_SOFTWARE: u16 = 305;
const TAG_PREDICTOR: u16 = 317;
const TAG_COLOR_MAP: u16 = 320;
const TAG_TILE_WIDTH: u16 = 322;
const TAG_TILE_LENGTH: u16 = 323;
const TAG_TILE_OFFSETS: u16 = 324;
const TAG_TILE_BYTE_COUNTS: u16 = 325;
const TAG_EXTRA_SAMPLES: u16 = 338;
const TAG_SAMPLE_FORMAT: u16 = 339;

const TYPE_ASCII: u16 = 2;
const TYPE_SHORT: u16 = 3;
const TYPE_LONG: u16 = 4;

const DESCRIPTION_PREFIX: &str = "Illume channels ";

// ---------------------------------------------------------------------------------------------
// Writing

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

// ---------------------------------------------------------------------------------------------
// Reading

/// The whole file and its byte order; every read is bounds-checked.
struct TiffBytes<'a> {
    path: &'a Path,
    data: &'a [u8],
    big_endian: bool,
}

impl TiffBytes<'_> {
    fn truncated(&self, what: &str, at: u64) -> ImageError {
        format_error(
            self.path,
            format!(
                "truncated TIFF: expected {what} at byte {at}, found end of file at {}",
                self.data.len()
            ),
        )
    }

    fn bytes(&self, at: u64, len: u64, what: &str) -> Result<&[u8], ImageError> {
        let end = at.checked_add(len).filter(|&e| e <= self.data.len() as u64);
        match end {
            Some(end) => Ok(&self.data[at as usize..end as usize]),
            None => Err(self.truncated(what, at)),
        }
    }

    fn u16_at(&self, at: u64) -> Result<u16, ImageError> {
        let b = self.bytes(at, 2, "a 16-bit value")?;
        let b = [b[0], b[1]];
        Ok(if self.big_endian {
            u16::from_be_bytes(b)
        } else {
            u16::from_le_bytes(b)
        })
    }

    fn u32_at(&self, at: u64) -> Result<u32, ImageError> {
        let b = self.bytes(at, 4, "a 32-bit value")?;
        let b = [b[0], b[1], b[2], b[3]];
        Ok(if self.big_endian {
            u32::from_be_bytes(b)
        } else {
            u32::from_le_bytes(b)
        })
    }
}

/// One IFD entry as read: where its values live.
#[derive(Clone, Copy)]
struct RawEntry {
    tag: u16,
    kind: u16,
    count: u32,
    /// Offset of the values (inline entries point into the IFD itself).
    at: u64,
}

fn type_size(kind: u16) -> u64 {
    match kind {
        1 | 2 | 6 | 7 => 1,
        3 | 8 => 2,
        4 | 9 | 11 | 13 => 4,
        5 | 10 | 12 | 16 | 17 | 18 => 8,
        _ => 0,
    }
}

struct Ifd<'a> {
    file: &'a TiffBytes<'a>,
    entries: Vec<RawEntry>,
}

impl Ifd<'_> {
    fn find(&self, tag: u16) -> Option<RawEntry> {
        self.entries.iter().copied().find(|e| e.tag == tag)
    }

    /// Unsigned integer values of `tag` (BYTE, SHORT, LONG), at most `limit` of them.
    fn uints(&self, tag: u16, limit: u64) -> Result<Option<Vec<u64>>, ImageError> {
        let Some(e) = self.find(tag) else {
            return Ok(None);
        };
        let size = type_size(e.kind);
        if !matches!(e.kind, 1 | 3 | 4 | 16) {
            return Err(format_error(
                self.file.path,
                format!(
                    "TIFF tag {tag}: expected an unsigned integer type, found type {}",
                    e.kind
                ),
            ));
        }
        if e.count as u64 > limit {
            return Err(format_error(
                self.file.path,
                format!(
                    "TIFF tag {tag}: expected at most {limit} values, found {}",
                    e.count
                ),
            ));
        }
        let bytes = self.file.bytes(e.at, size * e.count as u64, "tag values")?;
        let mut out = Vec::with_capacity(e.count as usize);
        for c in bytes.chunks_exact(size as usize) {
            let v = match (size, self.file.big_endian) {
                (1, _) => c[0] as u64,
                (2, false) => u16::from_le_bytes([c[0], c[1]]) as u64,
                (2, true) => u16::from_be_bytes([c[0], c[1]]) as u64,
                (4, false) => u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as u64,
                (4, true) => u32::from_be_bytes([c[0], c[1], c[2], c[3]]) as u64,
                (_, false) => u64::from_le_bytes(c.try_into().unwrap_or([0; 8])),
                (_, true) => u64::from_be_bytes(c.try_into().unwrap_or([0; 8])),
            };
            out.push(v);
        }
        Ok(Some(out))
    }

    fn uint(&self, tag: u16) -> Result<Option<u64>, ImageError> {
        Ok(self.uints(tag, 1 << 24)?.and_then(|v| v.first().copied()))
    }

    fn required(&self, tag: u16, name: &str) -> Result<u64, ImageError> {
        self.uint(tag)?.ok_or_else(|| {
            format_error(
                self.file.path,
                format!("TIFF: expected the {name} tag ({tag}), found none"),
            )
        })
    }

    fn ascii(&self, tag: u16) -> Option<String> {
        let e = self.find(tag)?;
        if e.kind != TYPE_ASCII {
            return None;
        }
        let b = self.file.bytes(e.at, e.count as u64, "text").ok()?;
        let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
        Some(String::from_utf8_lossy(&b[..end]).into_owned())
    }
}

/// How one sample is stored.
#[derive(Clone, Copy, PartialEq, Debug)]
enum SampleKind {
    Unsigned,
    Signed,
    Float,
}

/// Reads the first image of a TIFF file.
pub(crate) fn read_tiff(path: &Path) -> Result<Image, ImageError> {
    let data = std::fs::read(path).map_err(|e| io_error(path, e))?;
    decode_tiff(path, &data)
}

pub(crate) fn decode_tiff(path: &Path, data: &[u8]) -> Result<Image, ImageError> {
    let big_endian = match data.get(..2) {
        Some(b"II") => false,
        Some(b"MM") => true,
        _ => {
            return Err(format_error(
                path,
                "expected a TIFF byte-order mark II or MM",
            ));
        }
    };
    let file = TiffBytes {
        path,
        data,
        big_endian,
    };
    let version = file.u16_at(2)?;
    if version != 42 {
        return Err(format_error(
            path,
            format!("expected classic TIFF (version 42), found version {version}"),
        ));
    }
    let ifd_at = file.u32_at(4)? as u64;
    let count = file.u16_at(ifd_at)? as u64;
    let mut entries = Vec::with_capacity(count as usize);
    for i in 0..count {
        let e = ifd_at + 2 + 12 * i;
        let tag = file.u16_at(e)?;
        let kind = file.u16_at(e + 2)?;
        let n = file.u32_at(e + 4)?;
        let size = type_size(kind) * n as u64;
        let at = if size <= 4 {
            e + 8
        } else {
            file.u32_at(e + 8)? as u64
        };
        entries.push(RawEntry {
            tag,
            kind,
            count: n,
            at,
        });
    }
    let ifd = Ifd {
        file: &file,
        entries,
    };

    let width = ifd.required(TAG_IMAGE_WIDTH, "ImageWidth")?;
    let height = ifd.required(TAG_IMAGE_LENGTH, "ImageLength")?;
    let spp = ifd.uint(TAG_SAMPLES_PER_PIXEL)?.unwrap_or(1);
    if spp == 0 || spp > 64 {
        return Err(format_error(
            path,
            format!("TIFF: expected 1 to 64 samples per pixel, found {spp}"),
        ));
    }
    check_size(path, width, height, spp)?;
    let bps_all = ifd.uints(TAG_BITS_PER_SAMPLE, 64)?.unwrap_or(vec![1]);
    let bits = bps_all[0];
    if bps_all.iter().any(|&b| b != bits) {
        return Err(format_error(
            path,
            format!("TIFF: expected one BitsPerSample for all samples, found {bps_all:?}"),
        ));
    }
    let format_code = ifd
        .uints(TAG_SAMPLE_FORMAT, 64)?
        .and_then(|v| v.first().copied())
        .unwrap_or(1);
    let kind = match format_code {
        1 | 4 => SampleKind::Unsigned,
        2 => SampleKind::Signed,
        3 => SampleKind::Float,
        other => {
            return Err(format_error(
                path,
                format!("TIFF: expected SampleFormat 1, 2 or 3, found {other}"),
            ))
        }
    };
    let supported = match kind {
        SampleKind::Float => matches!(bits, 16 | 32 | 64),
        _ => matches!(bits, 1 | 2 | 4 | 8 | 16 | 32),
    };
    if !supported {
        return Err(format_error(
            path,
            format!("TIFF: unsupported {bits}-bit {kind:?} samples (expected 8, 16 or 32 bits)"),
        ));
    }
    let compression = ifd.uint(TAG_COMPRESSION)?.unwrap_or(1);
    if !matches!(compression, 1 | 5 | 8 | 32946 | 32773) {
        return Err(format_error(
            path,
            format!(
                "TIFF: unsupported compression {compression} (expected none, LZW, Deflate or PackBits)"
            ),
        ));
    }
    let photometric = ifd.uint(TAG_PHOTOMETRIC)?.unwrap_or(1);
    let planar = ifd.uint(TAG_PLANAR_CONFIG)?.unwrap_or(1);
    let predictor = ifd.uint(TAG_PREDICTOR)?.unwrap_or(1);
    if !matches!(predictor, 1..=3) || (predictor == 3 && kind != SampleKind::Float) {
        return Err(format_error(
            path,
            format!("TIFF: unsupported predictor {predictor} for {kind:?} samples"),
        ));
    }
    if bits < 8 && predictor != 1 {
        return Err(format_error(
            path,
            "TIFF: a predictor with sub-byte samples is not supported",
        ));
    }

    // Chunk geometry: strips are tiles as wide as the image.
    let tiled = ifd.find(TAG_TILE_WIDTH).is_some();
    let (chunk_w, chunk_h, offsets_tag, counts_tag) = if tiled {
        (
            ifd.required(TAG_TILE_WIDTH, "TileWidth")?,
            ifd.required(TAG_TILE_LENGTH, "TileLength")?,
            TAG_TILE_OFFSETS,
            TAG_TILE_BYTE_COUNTS,
        )
    } else {
        let rps = ifd.uint(TAG_ROWS_PER_STRIP)?.unwrap_or(height).min(height);
        (width, rps, TAG_STRIP_OFFSETS, TAG_STRIP_BYTE_COUNTS)
    };
    if chunk_w == 0 || chunk_h == 0 || chunk_w > 1 << 16 || chunk_h > 1 << 16 {
        return Err(format_error(
            path,
            format!(
                "TIFF: expected chunks of 1 to 65536 pixels per side, found {chunk_w}×{chunk_h}"
            ),
        ));
    }
    let across = width.div_ceil(chunk_w);
    let down = height.div_ceil(chunk_h);
    let planes = if planar == 2 { spp } else { 1 };
    let chunk_spp = if planar == 2 { 1 } else { spp };
    let n_chunks = across * down * planes;
    let offsets = ifd
        .uints(offsets_tag, n_chunks)?
        .ok_or_else(|| format_error(path, "TIFF: expected strip or tile offsets, found none"))?;
    let counts = ifd.uints(counts_tag, n_chunks)?;
    if (offsets.len() as u64) < n_chunks {
        return Err(format_error(
            path,
            format!(
                "TIFF: expected {n_chunks} strip/tile offsets, found {}",
                offsets.len()
            ),
        ));
    }

    let nc = spp as usize;
    let (w, h) = (width as usize, height as usize);
    let mut out = vec![0f32; w * h * nc];
    let row_bytes = (chunk_w * chunk_spp * bits).div_ceil(8) as usize;
    let chunk_bytes = row_bytes * chunk_h as usize;
    let bytes_per_sample = (bits as usize).div_ceil(8);
    let max_value = match (kind, bits) {
        (SampleKind::Signed, b) => ((1u64 << (b - 1)) - 1) as f64,
        (_, b) => ((1u64 << b) - 1) as f64,
    };
    for chunk in 0..n_chunks as usize {
        let plane = chunk as u64 / (across * down);
        let in_plane = chunk as u64 % (across * down);
        let (cx, cy) = (in_plane % across, in_plane / across);
        let offset = offsets[chunk];
        let length = match &counts {
            Some(c) if chunk < c.len() => c[chunk],
            _ if compression == 1 => chunk_bytes as u64,
            _ => {
                return Err(format_error(
                    path,
                    "TIFF: expected StripByteCounts/TileByteCounts, found none",
                ))
            }
        };
        let raw = file.bytes(offset, length, "strip or tile data")?;
        // The last strip may be short: decode only the rows it holds.
        let rows_here = if tiled {
            chunk_h
        } else {
            chunk_h.min(height - cy * chunk_h)
        } as usize;
        let expected = row_bytes * rows_here;
        let mut bytes = decompress(path, compression, raw, expected)?;
        if bytes.len() < expected {
            return Err(format_error(
                path,
                format!(
                    "TIFF chunk {chunk}: expected {expected} decoded bytes, found {}",
                    bytes.len()
                ),
            ));
        }
        bytes.truncate(expected);
        undo_predictor(
            &mut bytes,
            predictor,
            row_bytes,
            bytes_per_sample,
            chunk_spp as usize,
            big_endian,
        );
        let x0 = cx as usize * chunk_w as usize;
        let cols = (chunk_w as usize).min(w.saturating_sub(x0));
        let mut values = Vec::with_capacity(cols * chunk_spp as usize);
        for row in 0..rows_here {
            let y = cy as usize * chunk_h as usize + row;
            if y >= h {
                break;
            }
            let row_data = &bytes[row * row_bytes..(row + 1) * row_bytes];
            row_to_f32(
                row_data,
                cols * chunk_spp as usize,
                bits as usize,
                kind,
                big_endian,
                max_value,
                &mut values,
            );
            let start = (y * w + x0) * nc;
            if planar == 2 {
                let c = plane as usize;
                for (i, &v) in values.iter().enumerate() {
                    out[start + i * nc + c] = v;
                }
            } else {
                out[start..start + values.len()].copy_from_slice(&values);
            }
        }
    }

    let extra = ifd.uints(TAG_EXTRA_SAMPLES, 64)?.unwrap_or_default();
    let description = ifd.ascii(TAG_IMAGE_DESCRIPTION);
    let mut channels = channel_names(photometric, nc, &extra);
    if let Some(names) = description
        .as_deref()
        .and_then(|d| d.strip_prefix(DESCRIPTION_PREFIX))
    {
        let names: Vec<String> = names.split(',').map(|s| s.trim().to_string()).collect();
        if names.len() == nc {
            channels = names;
        }
    }
    // Unassociated alpha (ExtraSamples 2): premultiply, so every reader returns associated
    // colour (as OpenImageIO does).
    let first_extra = nc - extra.len().min(nc);
    if let Some(a) = channels.iter().position(|c| c == "a") {
        if a >= first_extra && extra.get(a - first_extra) == Some(&2) {
            for px in out.chunks_exact_mut(nc) {
                let alpha = px[a];
                for (c, v) in px.iter_mut().enumerate() {
                    if c != a && channels[c] != "z" {
                        *v *= alpha;
                    }
                }
            }
        }
    }
    if photometric == 3 {
        return expand_palette(&ifd, path, w, h, nc, bits, &out, max_value);
    }
    if photometric == 0 && kind != SampleKind::Float {
        // WhiteIsZero: invert the grey sample.
        for px in out.chunks_exact_mut(nc) {
            px[0] = 1.0 - px[0];
        }
    }
    Ok(Image {
        width: width as u32,
        height: height as u32,
        channels,
        data: out,
    })
}

/// Default channel names from the photometric interpretation and `ExtraSamples`.
fn channel_names(photometric: u64, nc: usize, extra: &[u64]) -> Vec<String> {
    let color = photometric == 2 && nc >= 3;
    let mut names: Vec<String> = if color {
        vec!["r".into(), "g".into(), "b".into()]
    } else {
        vec!["y".into()]
    };
    let first_extra = names.len();
    let mut have_alpha = false;
    let mut have_z = false;
    for i in first_extra..nc {
        let declared = extra.get(i - first_extra).copied();
        let name = match declared {
            Some(1) | Some(2) if !have_alpha => {
                have_alpha = true;
                "a".to_string()
            }
            // No ExtraSamples tag (old renderers): the first extra is alpha, the next depth.
            None if !have_alpha => {
                have_alpha = true;
                "a".to_string()
            }
            _ if !have_z && (declared.is_none() || declared == Some(0)) => {
                have_z = true;
                "z".to_string()
            }
            _ => format!("channel{i}"),
        };
        names.push(name);
    }
    names
}

#[allow(clippy::too_many_arguments)]
fn expand_palette(
    ifd: &Ifd,
    path: &Path,
    w: usize,
    h: usize,
    nc: usize,
    bits: u64,
    indices: &[f32],
    max_value: f64,
) -> Result<Image, ImageError> {
    let n = 1usize << bits.min(16);
    let map = ifd
        .uints(TAG_COLOR_MAP, 3 * n as u64)?
        .ok_or_else(|| format_error(path, "TIFF palette image: expected a ColorMap, found none"))?;
    if map.len() < 3 * n {
        return Err(format_error(
            path,
            format!(
                "TIFF ColorMap: expected {} entries, found {}",
                3 * n,
                map.len()
            ),
        ));
    }
    let mut data = Vec::with_capacity(w * h * 3);
    for px in indices.chunks_exact(nc) {
        let i = ((px[0] as f64 * max_value).round() as usize).min(n - 1);
        for c in 0..3 {
            data.push(map[c * n + i] as f32 / 65535.0);
        }
    }
    Ok(Image {
        width: w as u32,
        height: h as u32,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data,
    })
}

/// The first `n` samples of a decoded row, normalised, into `out` (cleared first). The common
/// 8/16/32-bit cases are tight loops; the rest go through [`sample`].
fn row_to_f32(
    row: &[u8],
    n: usize,
    bits: usize,
    kind: SampleKind,
    be: bool,
    max: f64,
    out: &mut Vec<f32>,
) {
    out.clear();
    match (bits, kind) {
        (8, SampleKind::Unsigned) => out.extend(row[..n].iter().map(|&b| b as f32 / 255.0)),
        (16, SampleKind::Unsigned) => out.extend(row[..2 * n].chunks_exact(2).map(|c| {
            let v = if be {
                u16::from_be_bytes([c[0], c[1]])
            } else {
                u16::from_le_bytes([c[0], c[1]])
            };
            v as f32 / 65535.0
        })),
        (32, SampleKind::Float) => out.extend(row[..4 * n].chunks_exact(4).map(|c| {
            let b = [c[0], c[1], c[2], c[3]];
            if be {
                f32::from_be_bytes(b)
            } else {
                f32::from_le_bytes(b)
            }
        })),
        _ => out.extend((0..n).map(|i| sample(row, i, bits, kind, be, max))),
    }
}

/// Sample `index` of a decoded row, normalised: integers to [0, 1] (signed to [-1, 1]).
fn sample(row: &[u8], index: usize, bits: usize, kind: SampleKind, be: bool, max: f64) -> f32 {
    if bits < 8 {
        let bit = index * bits;
        let byte = row[bit / 8];
        let shift = 8 - bits - bit % 8;
        let v = (byte >> shift) & ((1u8 << bits) - 1);
        return (v as f64 / max) as f32;
    }
    let b = &row[index * bits / 8..(index + 1) * bits / 8];
    let uint = |b: &[u8]| -> u64 {
        let mut v = 0u64;
        if be {
            for &x in b {
                v = (v << 8) | x as u64;
            }
        } else {
            for &x in b.iter().rev() {
                v = (v << 8) | x as u64;
            }
        }
        v
    };
    let u = uint(b);
    match kind {
        SampleKind::Unsigned => (u as f64 / max) as f32,
        SampleKind::Signed => {
            let shift = 64 - bits;
            let s = ((u << shift) as i64) >> shift;
            (s as f64 / max).max(-1.0) as f32
        }
        SampleKind::Float => match bits {
            16 => half::f16::from_bits(u as u16).to_f32(),
            32 => f32::from_bits(u as u32),
            _ => f64::from_bits(u) as f32,
        },
    }
}

fn decompress(
    path: &Path,
    compression: u64,
    raw: &[u8],
    expected: usize,
) -> Result<Vec<u8>, ImageError> {
    match compression {
        1 => Ok(raw.to_vec()),
        5 => lzw_decode(raw, expected).map_err(|m| format_error(path, format!("TIFF LZW: {m}"))),
        8 | 32946 => {
            use std::io::Read;
            let mut out = Vec::with_capacity(expected);
            flate2::read::ZlibDecoder::new(raw)
                .take(expected as u64)
                .read_to_end(&mut out)
                .map_err(|e| format_error(path, format!("TIFF Deflate: {e}")))?;
            Ok(out)
        }
        _ => Ok(packbits_decode(raw, expected)),
    }
}

/// TIFF LZW (MSB-first codes, 9 to 12 bits, "early change"), stopping at `expected` bytes.
fn lzw_decode(input: &[u8], expected: usize) -> Result<Vec<u8>, String> {
    const CLEAR: usize = 256;
    const EOI: usize = 257;
    if input.len() >= 2 && input[0] == 0 && input[1] & 1 == 1 {
        return Err("old-style (LSB-first) LZW is not supported".into());
    }
    // Each table entry: (prefix code, last byte, length).
    let mut table: Vec<(u16, u8, u32)> = Vec::with_capacity(4096);
    let reset = |t: &mut Vec<(u16, u8, u32)>| {
        t.clear();
        for b in 0..256u16 {
            t.push((u16::MAX, b as u8, 1));
        }
        t.push((u16::MAX, 0, 0));
        t.push((u16::MAX, 0, 0));
    };
    reset(&mut table);
    let mut out = Vec::with_capacity(expected);
    let mut bitpos = 0usize;
    let mut width = 9usize;
    let mut prev: Option<usize> = None;
    let mut scratch = Vec::new();
    let emit = |code: usize, table: &[(u16, u8, u32)], scratch: &mut Vec<u8>| {
        scratch.clear();
        let mut c = code;
        loop {
            let (p, b, _) = table[c];
            scratch.push(b);
            if p == u16::MAX {
                break;
            }
            c = p as usize;
        }
        scratch.reverse();
    };
    while out.len() < expected {
        if bitpos + width > input.len() * 8 {
            break; // ran out of codes: the caller reports the short chunk
        }
        let mut code = 0usize;
        for i in 0..width {
            let bit = bitpos + i;
            code = (code << 1) | ((input[bit / 8] >> (7 - bit % 8)) & 1) as usize;
        }
        bitpos += width;
        if code == CLEAR {
            reset(&mut table);
            width = 9;
            prev = None;
            continue;
        }
        if code == EOI {
            break;
        }
        match prev {
            None => {
                if code >= 256 {
                    return Err(format!(
                        "expected a literal after a clear code, found {code}"
                    ));
                }
                out.push(code as u8);
            }
            Some(p) => {
                if code < table.len() {
                    emit(code, &table, &mut scratch);
                    if table.len() < 4096 {
                        table.push((p as u16, scratch[0], table[p].2 + 1));
                    }
                } else if code == table.len() {
                    emit(p, &table, &mut scratch);
                    let first = scratch[0];
                    scratch.push(first);
                    if table.len() < 4096 {
                        table.push((p as u16, first, table[p].2 + 1));
                    }
                } else {
                    return Err(format!(
                        "expected a code up to {}, found {code}",
                        table.len()
                    ));
                }
                out.extend_from_slice(&scratch);
            }
        }
        prev = Some(code);
        // Early change: widen one code before the table fills the current width.
        if table.len() + 1 >= (1 << width) && width < 12 {
            width += 1;
        }
    }
    out.truncate(expected);
    Ok(out)
}

/// PackBits run-length decoding (TIFF 6.0 §9), stopping at `expected` bytes.
fn packbits_decode(input: &[u8], expected: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(expected);
    let mut i = 0;
    while i < input.len() && out.len() < expected {
        let n = input[i] as i8;
        i += 1;
        if n >= 0 {
            let len = n as usize + 1;
            let end = (i + len).min(input.len());
            out.extend_from_slice(&input[i..end]);
            i = end;
        } else if n != -128 {
            if let Some(&b) = input.get(i) {
                out.extend(std::iter::repeat_n(b, (1 - n as isize) as usize));
            }
            i += 1;
        }
    }
    out.truncate(expected);
    out
}

/// Undoes the horizontal (2) or floating-point (3) predictor on each row of a chunk.
fn undo_predictor(
    bytes: &mut [u8],
    predictor: u64,
    row_bytes: usize,
    bps: usize,
    spp: usize,
    be: bool,
) {
    match predictor {
        2 => {
            for row in bytes.chunks_exact_mut(row_bytes) {
                match bps {
                    1 => {
                        for i in spp..row.len() {
                            row[i] = row[i].wrapping_add(row[i - spp]);
                        }
                    }
                    2 | 4 | 8 => {
                        let n = row.len() / bps;
                        let get = |r: &[u8], i: usize| -> u64 {
                            let b = &r[i * bps..(i + 1) * bps];
                            let mut v = 0u64;
                            if be {
                                b.iter().for_each(|&x| v = (v << 8) | x as u64);
                            } else {
                                b.iter().rev().for_each(|&x| v = (v << 8) | x as u64);
                            }
                            v
                        };
                        for i in spp..n {
                            let v = get(row, i).wrapping_add(get(row, i - spp));
                            let dst = &mut row[i * bps..(i + 1) * bps];
                            for (k, d) in dst.iter_mut().enumerate() {
                                let shift = if be { 8 * (bps - 1 - k) } else { 8 * k };
                                *d = (v >> shift) as u8;
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        3 => {
            // Bytes are differenced across the row, then stored as byte planes, most
            // significant first (Adobe Photoshop TIFF technical note 3).
            for row in bytes.chunks_exact_mut(row_bytes) {
                for i in spp..row.len() {
                    row[i] = row[i].wrapping_add(row[i - spp]);
                }
                let n = row.len() / bps;
                let planes = row.to_vec();
                for i in 0..n {
                    for k in 0..bps {
                        let b = planes[k * n + i];
                        let dst = if be { k } else { bps - 1 - k };
                        row[i * bps + dst] = b;
                    }
                }
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packbits_decodes_the_specification_example() {
        // TIFF 6.0 §9 example.
        let packed = [
            0xFE, 0xAA, 0x02, 0x80, 0x00, 0x2A, 0xFD, 0xAA, 0x03, 0x80, 0x00, 0x2A, 0x22, 0xF7,
            0xAA,
        ];
        let unpacked = [
            0xAA, 0xAA, 0xAA, 0x80, 0x00, 0x2A, 0xAA, 0xAA, 0xAA, 0xAA, 0x80, 0x00, 0x2A, 0x22,
            0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA,
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
}
