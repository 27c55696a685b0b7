//! Writing: one IFD, little-endian, Deflate-compressed strips (see the module documentation),
//! whole images or rows as they arrive ([`TiffRows`], streaming output).

use super::tiles::{Tiles, TILE_LENGTH};
use super::*;
use crate::atomic_write::AtomicFile;
use crate::quantize::{quantize_image, Samples};
use crate::{format_error, io_error, Image, ImageError, Quantize, SampleDepth};
use std::io::{Seek, SeekFrom, Write};
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
    let mut rows = TiffRows::create(
        path,
        [image.width, image.height],
        &image.channels,
        quantize,
        origin,
    )?;
    rows.write_rows(image)?;
    rows.finish()
}

/// Writes `image` as a tiled TIFF, tiles `tile_width` pixels wide, column of tiles after
/// column of tiles: the file [`TiffRows::create_tiled`] makes from a frame rendered in column
/// blocks of that width, byte for byte.
pub(crate) fn write_tiff_tiled(
    path: &Path,
    image: &Image,
    quantize: Quantize,
    origin: [u32; 2],
    tile_width: u32,
) -> Result<(), ImageError> {
    let size = [image.width, image.height];
    let mut tiled =
        TiffRows::create_tiled(path, size, &image.channels, quantize, origin, tile_width)?;
    for x in (0..image.width).step_by(tile_width as usize) {
        let block = image.columns(x, (x + tile_width).min(image.width));
        tiled.write_block(&block, x)?;
    }
    tiled.finish()
}

/// A TIFF written as its rows arrive (streaming output): each strip is compressed and written
/// as soon as its rows are in, and the IFD goes at the end, its offset patched into the header.
/// The file is the one [`write_tiff`] writes for the whole image, byte for byte.
pub struct TiffRows {
    file: AtomicFile,
    path: std::path::PathBuf,
    size: [u32; 2],
    channels: Vec<String>,
    quantize: Quantize,
    origin: [u32; 2],
    bits: u16,
    format: u16,
    row_bytes: usize,
    rows_per_strip: usize,
    /// Quantized bytes of rows not yet in a strip.
    pending: Vec<u8>,
    /// Rows received so far.
    rows: u32,
    strip_offsets: Vec<u64>,
    strip_counts: Vec<u32>,
    offset: u64,
    /// The tile grid of a tiled file (`None`: strips).
    tiles: Option<Tiles>,
}

impl TiffRows {
    /// Starts a TIFF of `size` (width, height) pixels with these channels; `origin` is the
    /// full-frame position of its top-left pixel (dither is keyed on it).
    pub fn create(
        path: &Path,
        size: [u32; 2],
        channels: &[String],
        quantize: Quantize,
        origin: [u32; 2],
    ) -> Result<TiffRows, ImageError> {
        // Depth is never quantized, and TIFF readers expect one sample format per file.
        let quantize = if channels.iter().any(|c| c == "z") {
            Quantize::FLOAT
        } else {
            quantize
        };
        let (bits, format) = match quantize.sample_depth() {
            SampleDepth::U8 => (8u16, 1u16),
            SampleDepth::U16 => (16, 1),
            SampleDepth::Float => (32, 3),
        };
        let row_bytes = size[0] as usize * channels.len() * bits as usize / 8;
        let rows_per_strip = (65536 / row_bytes.max(1)).clamp(1, (size[1] as usize).max(1));
        let mut file = AtomicFile::create(path)?;
        // The IFD offset is patched in by `finish`.
        file.writer()
            .write_all(b"II*\0\0\0\0\0")
            .map_err(|e| io_error(path, e))?;
        Ok(TiffRows {
            file,
            path: path.to_path_buf(),
            size,
            channels: channels.to_vec(),
            quantize,
            origin,
            bits,
            format,
            row_bytes,
            rows_per_strip,
            pending: Vec::new(),
            rows: 0,
            strip_offsets: Vec::new(),
            strip_counts: Vec::new(),
            offset: 8,
            tiles: None,
        })
    }

    /// [`TiffRows::create`] for a tiled file: tiles `tile_width` pixels wide (a multiple of
    /// 16) and 16 rows tall, filled by blocks of whole columns of tiles
    /// ([`TiffRows::write_block`]), each column top to bottom.
    pub fn create_tiled(
        path: &Path,
        size: [u32; 2],
        channels: &[String],
        quantize: Quantize,
        origin: [u32; 2],
        tile_width: u32,
    ) -> Result<TiffRows, ImageError> {
        if tile_width == 0 || tile_width % 16 != 0 {
            return Err(format_error(
                path,
                format!("expected a tile width that is a multiple of 16, found {tile_width}"),
            ));
        }
        let mut rows = TiffRows::create(path, size, channels, quantize, origin)?;
        rows.tiles = Some(Tiles::new(size, tile_width));
        Ok(rows)
    }

    /// Appends the next rows (an image of the file's width and channels).
    pub fn write_rows(&mut self, rows: &Image) -> Result<(), ImageError> {
        self.write_block(rows, 0)
    }

    /// Appends the next rows of the columns `x .. x + rows.width`: the whole width for a
    /// striped file, whole columns of tiles (at the same row) for a tiled one.
    pub fn write_block(&mut self, rows: &Image, x: u32) -> Result<(), ImageError> {
        let fits = |y: u32| {
            y.checked_add(rows.height)
                .is_some_and(|e| e <= self.size[1])
        };
        let place = match &self.tiles {
            None => (x == 0 && rows.width == self.size[0]).then_some((self.rows, None)),
            Some(t) => t.columns(x, rows.width, self.size[0]).and_then(|(c0, c1)| {
                let y = t.rows[c0];
                t.rows[c0..c1]
                    .iter()
                    .all(|&r| r == y)
                    .then_some((y, Some((c0, c1))))
            }),
        }
        .filter(|&(y, _)| rows.channels == self.channels && fits(y));
        let Some((y, columns)) = place else {
            let tiles = self.tiles.as_ref().map_or(String::new(), |t| {
                format!(" (whole columns of {}-pixel tiles)", t.width)
            });
            return Err(format_error(
                &self.path,
                format!(
                    "expected rows of the next {} columns{tiles} with channels {}, \
                     below the rows already written; found {}x{} at column {x} with {}",
                    self.size[0],
                    self.channels.join(","),
                    rows.width,
                    rows.height,
                    rows.channels.join(",")
                ),
            ));
        };
        let origin = [self.origin[0] + x, self.origin[1] + y];
        let bytes = match quantize_image(rows, self.quantize, origin) {
            Samples::U8(v) => v,
            Samples::U16(v) => v.iter().flat_map(|s| s.to_le_bytes()).collect(),
            Samples::F32(v) => v.iter().flat_map(|s| s.to_le_bytes()).collect(),
        };
        if let Some((c0, c1)) = columns {
            return self.write_tile_columns(&bytes, rows, (c0, c1));
        }
        self.pending.extend(bytes);
        self.rows += rows.height;
        let strip = self.rows_per_strip * self.row_bytes;
        let full = if self.rows == self.size[1] {
            self.pending.len()
        } else {
            self.pending.len() / strip.max(1) * strip
        };
        self.write_strips(full)
    }

    /// Adds a block's quantized rows to its columns of tiles and writes the tiles they
    /// complete (compressed in parallel, written column by column, top to bottom).
    fn write_tile_columns(
        &mut self,
        bytes: &[u8],
        rows: &Image,
        (c0, c1): (usize, usize),
    ) -> Result<(), ImageError> {
        let size = self.size;
        let pixel_bytes = self.channels.len() * self.bits as usize / 8;
        let tiles = self.tiles.as_mut().expect("a tiled file");
        for row in bytes.chunks_exact(rows.width as usize * pixel_bytes) {
            let mut at = 0;
            for c in c0..c1 {
                let w = tiles.column_width(c, size[0]) as usize * pixel_bytes;
                tiles.pending[c].extend_from_slice(&row[at..at + w]);
                at += w;
            }
        }
        let mut done = Vec::new();
        for c in c0..c1 {
            tiles.rows[c] += rows.height;
            done.extend(tiles.complete(c, size, pixel_bytes));
        }
        use rayon::prelude::*;
        let compressed = done
            .par_iter()
            .map(|(_, tile)| deflate(tile))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| io_error(&self.path, e))?;
        for ((index, _), data) in done.iter().zip(compressed) {
            let tiles = self.tiles.as_mut().expect("a tiled file");
            tiles.offsets[*index] = self.offset;
            tiles.counts[*index] = data.len() as u32;
            self.offset += data.len() as u64;
            self.file
                .writer()
                .write_all(&data)
                .map_err(|e| io_error(&self.path, e))?;
        }
        self.check_size()
    }

    /// A classic TIFF's offsets are 32-bit: refuse to write past 2 GiB of pixels.
    fn check_size(&self) -> Result<(), ImageError> {
        if self.offset > u32::MAX as u64 / 2 {
            return Err(format_error(
                &self.path,
                format!(
                    "expected a TIFF under 2 GiB, found {} bytes of pixels",
                    self.offset
                ),
            ));
        }
        Ok(())
    }

    /// Compresses and writes the first `n` pending bytes (whole strips, or the last rows).
    /// Strips are compressed on their own (readers decode them independently) and in parallel;
    /// the bytes do not depend on the thread count.
    fn write_strips(&mut self, n: usize) -> Result<(), ImageError> {
        if n == 0 {
            return Ok(());
        }
        let path = self.path.clone();
        use rayon::prelude::*;
        let strips = self.pending[..n]
            .par_chunks(self.rows_per_strip * self.row_bytes)
            .map(deflate)
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| io_error(&path, e))?;
        self.pending.drain(..n);
        for s in &strips {
            self.strip_offsets.push(self.offset);
            self.strip_counts.push(s.len() as u32);
            self.offset += s.len() as u64;
            self.file
                .writer()
                .write_all(s)
                .map_err(|e| io_error(&path, e))?;
        }
        self.check_size()
    }

    /// Writes the IFD and renames the file into place; every row must have arrived.
    pub fn finish(mut self) -> Result<(), ImageError> {
        let path = self.path.clone();
        let rows = match &self.tiles {
            None => self.rows,
            Some(t) => t.rows.iter().copied().min().unwrap_or(0),
        };
        if rows != self.size[1] {
            return Err(format_error(
                &path,
                format!("expected {} rows, found {rows}", self.size[1]),
            ));
        }
        let (ifd_offset, ifd, values) = self.directory();
        let io = |e| io_error(&path, e);
        let w = self.file.writer();
        if self.offset < ifd_offset as u64 {
            w.write_all(&[0]).map_err(io)?;
        }
        w.write_all(&ifd).map_err(io)?;
        w.write_all(&values).map_err(io)?;
        w.seek(SeekFrom::Start(4)).map_err(io)?;
        w.write_all(&ifd_offset.to_le_bytes()).map_err(io)?;
        self.file.commit()
    }

    /// The IFD's offset, its bytes and its out-of-line values.
    fn directory(&self) -> (u32, Vec<u8>, Vec<u8>) {
        let (nc, bits, format) = (self.channels.len(), self.bits, self.format);
        let color = nc >= 3 && self.channels[..3] == ["r", "g", "b"];
        let photometric_samples = if color { 3 } else { 1 };
        let extra: Vec<u16> = self.channels[photometric_samples.min(nc)..]
            .iter()
            .map(|c| if c == "a" { 1 } else { 0 })
            .collect();
        let description = format!("{DESCRIPTION_PREFIX}{}", self.channels.join(","));
        let offset = self.offset + (self.offset & 1); // IFDs start on a word boundary
        let strip_offsets: Vec<u32> = self.strip_offsets.iter().map(|&o| o as u32).collect();
        let chunks = match &self.tiles {
            None => vec![
                longs(TAG_STRIP_OFFSETS, &strip_offsets),
                longs(TAG_ROWS_PER_STRIP, &[self.rows_per_strip as u32]),
                longs(TAG_STRIP_BYTE_COUNTS, &self.strip_counts),
            ],
            Some(t) => {
                let offsets: Vec<u32> = t.offsets.iter().map(|&o| o as u32).collect();
                vec![
                    longs(TAG_TILE_WIDTH, &[t.width]),
                    longs(TAG_TILE_LENGTH, &[TILE_LENGTH]),
                    longs(TAG_TILE_OFFSETS, &offsets),
                    longs(TAG_TILE_BYTE_COUNTS, &t.counts),
                ]
            }
        };
        let mut entries = vec![
            longs(TAG_IMAGE_WIDTH, &[self.size[0]]),
            longs(TAG_IMAGE_LENGTH, &[self.size[1]]),
            shorts(TAG_BITS_PER_SAMPLE, &vec![bits; nc]),
            shorts(TAG_COMPRESSION, &[8]),
            shorts(TAG_PHOTOMETRIC, &[if color { 2 } else { 1 }]),
            ascii(TAG_IMAGE_DESCRIPTION, &description),
            shorts(TAG_SAMPLES_PER_PIXEL, &[nc as u16]),
            shorts(TAG_PLANAR_CONFIG, &[1]),
            ascii(TAG_SOFTWARE, "Illume"),
            shorts(TAG_SAMPLE_FORMAT, &vec![format; nc]),
        ];
        entries.extend(chunks);
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
        (ifd_offset, ifd, values)
    }
}

/// One strip or tile compressed on its own (Deflate, the fast level: readers decode each
/// independently).
fn deflate(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    z.write_all(bytes)?;
    z.finish()
}
