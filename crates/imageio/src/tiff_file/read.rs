//! The decode pipeline: header and IFD, pixel format, chunk grid, samples, then channels.

use super::codec::{decompress, undo_predictor};
use super::ifd::{Ifd, TiffBytes};
use super::photometric::interpret_channels;
use super::samples::{row_to_f32, SampleKind};
use super::*;
use crate::raster_limits::check_size;
use crate::{format_error, io_error, Image, ImageError};
use std::path::Path;

/// Reads the first image of a TIFF file.
pub(crate) fn read_tiff(path: &Path) -> Result<Image, ImageError> {
    let data = std::fs::read(path).map_err(|e| io_error(path, e))?;
    decode_tiff(path, &data)
}

pub(crate) fn decode_tiff(path: &Path, data: &[u8]) -> Result<Image, ImageError> {
    let file = TiffBytes::parse(path, data)?;
    let ifd = file.first_ifd()?;
    let format = PixelFormat::from_ifd(&ifd, path)?;
    let grid = ChunkGrid::from_ifd(&ifd, path, &format)?;
    let max_value = format.max_value();
    let out = decode_chunks(&file, &format, &grid, max_value)?;
    interpret_channels(&ifd, path, &format, out, max_value)
}

/// What the IFD says about the pixels: size, sample encoding, compression and interpretation.
#[derive(Clone, Copy)]
pub(super) struct PixelFormat {
    pub(super) width: u64,
    pub(super) height: u64,
    pub(super) spp: u64,
    pub(super) bits: u64,
    pub(super) kind: SampleKind,
    pub(super) compression: u64,
    pub(super) photometric: u64,
    pub(super) planar: u64,
    pub(super) predictor: u64,
}

impl PixelFormat {
    /// Reads and validates the format tags, rejecting what the decoder does not support.
    fn from_ifd(ifd: &Ifd, path: &Path) -> Result<Self, ImageError> {
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
        let Some(&bits) = bps_all.first() else {
            return Err(format_error(
                path,
                "TIFF: expected a BitsPerSample value, found an empty BitsPerSample tag",
            ));
        };
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
                format!(
                    "TIFF: unsupported {bits}-bit {kind:?} samples (expected 8, 16 or 32 bits)"
                ),
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
        Ok(PixelFormat {
            width,
            height,
            spp,
            bits,
            kind,
            compression,
            photometric,
            planar,
            predictor,
        })
    }

    /// The largest stored integer, which normalises integer samples to [0, 1] ([-1, 1] signed).
    fn max_value(&self) -> f64 {
        // Float samples are values, not codes: nothing to normalise by. For integers the largest
        // code is computed with a checked shift, since `1 << 64` overflows (64-bit samples).
        let bits = self.bits.min(64) as u32;
        match self.kind {
            SampleKind::Float => 1.0,
            SampleKind::Signed => u64::MAX.checked_shr(65 - bits.max(1)).unwrap_or(0) as f64,
            SampleKind::Unsigned => u64::MAX.checked_shr(64 - bits).unwrap_or(0) as f64,
        }
    }
}

/// Where the strips or tiles are: strips are tiles as wide as the image.
struct ChunkGrid {
    tiled: bool,
    chunk_w: u64,
    chunk_h: u64,
    /// Chunks per row and per column of one plane.
    across: u64,
    down: u64,
    /// Samples per pixel within one chunk (1 for planar configuration 2).
    chunk_spp: u64,
    n_chunks: u64,
    offsets: Vec<u64>,
    counts: Option<Vec<u64>>,
}

impl ChunkGrid {
    fn from_ifd(ifd: &Ifd, path: &Path, format: &PixelFormat) -> Result<Self, ImageError> {
        let PixelFormat {
            width,
            height,
            spp,
            planar,
            ..
        } = *format;
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
        let offsets = ifd.uints(offsets_tag, n_chunks)?.ok_or_else(|| {
            format_error(path, "TIFF: expected strip or tile offsets, found none")
        })?;
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

        Ok(ChunkGrid {
            tiled,
            chunk_w,
            chunk_h,
            across,
            down,
            chunk_spp,
            n_chunks,
            offsets,
            counts,
        })
    }
}

/// Decodes every chunk into one interleaved f32 raster of all samples.
fn decode_chunks(
    file: &TiffBytes,
    format: &PixelFormat,
    grid: &ChunkGrid,
    max_value: f64,
) -> Result<Vec<f32>, ImageError> {
    let path = file.path;
    let big_endian = file.big_endian;
    let PixelFormat {
        width,
        height,
        spp,
        bits,
        kind,
        compression,
        planar,
        predictor,
        ..
    } = *format;
    let ChunkGrid {
        tiled,
        chunk_w,
        chunk_h,
        across,
        down,
        chunk_spp,
        n_chunks,
        ref offsets,
        ref counts,
    } = *grid;
    let nc = spp as usize;
    let (w, h) = (width as usize, height as usize);
    let mut out = vec![0f32; w * h * nc];
    let row_bytes = (chunk_w * chunk_spp * bits).div_ceil(8) as usize;
    let chunk_bytes = row_bytes * chunk_h as usize;
    let bytes_per_sample = (bits as usize).div_ceil(8);
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

    Ok(out)
}
