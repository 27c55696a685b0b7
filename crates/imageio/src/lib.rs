//! Display drivers and image readers.
//!
//! # Contract
//! * The hider hands a display a float [`Image`] (after pixel filter and `Exposure`), plus the
//!   `Quantize` settings; this crate quantizes, dithers (deterministically per pixel), and writes
//!   the file through a temporary name and a rename, so an interrupted render never leaves a
//!   half-written image under the real name.
//! * [`read_image`] reads any supported file into float RGBA-ish channels for `txmake` and
//!   textures used directly.
//!
//! # Display types ([`write_display`])
//! | kind | file | samples |
//! |---|---|---|
//! | `tiff`, `file` | TIFF, Deflate-compressed strips | 8-bit when `max ≤ 255`, 16-bit when `max ≤ 65535`, else 32-bit float (always when `one == 0`, see [`Quantize::sample_depth`]); any image with a `z` channel is all float (depth is never quantized) |
//! | `png` | PNG | 8/16-bit per [`Quantize`] (float settings write 16-bit); colour divided by alpha (PNG alpha is unassociated); a `z` channel is dropped |
//! | `openexr`, `exr` | OpenEXR, ZIP | colour as `half` unless `Quantize` has `one == 0`, then 32-bit float; `Z` always float; never quantized or clamped (EXR is linear HDR) |
//! | `zfile` | PRMan zfile | the `z` channel as float32 plus the [`DepthMatrices`] |
//! | `framebuffer` | PNG at [`framebuffer_path`] | as `png` |
//!
//! `shadow` (a `.sm` texture) is written by the texture crate, not here.
//!
//! `read_image` returns premultiplied colour whatever the format (PNG colour is multiplied by
//! its alpha on reading, as OpenImageIO does).
//!
//! # Channel names
//! Images carry lower-case names: `r`, `g`, `b`, `a`, `z`, and `y` for a single grey channel
//! read from a file (TIFF/PNG/JPEG grey, OpenEXR `Y`). OpenEXR channels keep their lower-cased
//! names, ordered r, g, b, a, z, y, then the rest. TIFF has no channel names: our writer stores
//! them in `ImageDescription` (`Illume channels r,g,b,z`); other TIFFs get r,g,b (or y) and then,
//! for extra samples, `a` for the first alpha (or the first extra when `ExtraSamples` is absent,
//! as in old Aqsis/PRMan files), `z` for the next unspecified one, and `channelN` after that.
//!
//! # Reading
//! [`read_image`] picks the decoder from the file's signature: TIFF (own decoder: strips or
//! tiles, contiguous or planar, none/LZW/Deflate/PackBits, predictors 2 and 3, 8/16/32-bit
//! integers, 16/32/64-bit floats, grey/RGB/palette, any sample count), PNG and JPEG (the `image`
//! crate), OpenEXR (scanline or tiled, first layer, largest level) and PRMan zfile (either byte
//! order). Sizes are checked against [`MAX_DIMENSION`] and [`MAX_SAMPLES`] before allocating.
//!
//! # Crop windows
//! [`write_display_cropped`] takes the full-frame position of the image's top-left pixel; dither
//! is a hash of full-frame (x, y, channel), so crops tile into the full frame bit for bit.
#![forbid(unsafe_code)]

mod atomic_write;
mod framebuffer;
mod openexr;
mod png_file;
mod quantize;
mod raster_limits;
mod tiff_file;
mod zfile;

pub use atomic_write::{remove_temporary_files, write_atomically, AtomicFile};
pub use framebuffer::framebuffer_path;
pub use openexr::world_to_ndc;
pub use quantize::{dither_noise, SampleDepth};
pub use raster_limits::{MAX_DIMENSION, MAX_SAMPLES};
pub use tiff_file::TiffRows;
pub use zfile::{read_zfile, write_zfile, write_zfile_with_order, ZFILE_MAGIC};

use std::path::Path;
use thiserror::Error;

/// A float image, channels interleaved, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// Channel names in order, lower-case RenderMan display modes' letters: "r","g","b","a","z".
    pub channels: Vec<String>,
    /// `width·height·channels.len()` values.
    pub data: Vec<f32>,
}

impl Image {
    /// A zero-filled image with the given channel names (`"rgba"` → r,g,b,a).
    pub fn new(width: u32, height: u32, mode: &str) -> Image {
        let channels: Vec<String> = mode.chars().map(|c| c.to_string()).collect();
        let n = width as usize * height as usize * channels.len();
        Image {
            width,
            height,
            channels,
            data: vec![0.0; n],
        }
    }

    /// Index of the channel called `name`, if present.
    pub fn channel_index(&self, name: &str) -> Option<usize> {
        self.channels.iter().position(|c| c == name)
    }

    /// The value of channel `c` at pixel (`x`, `y`).
    pub fn at(&self, x: u32, y: u32, c: usize) -> f32 {
        let nc = self.channels.len();
        self.data[(y as usize * self.width as usize + x as usize) * nc + c]
    }

    /// Columns `x0..x1` of every row (a copy): a column block of a frame.
    pub(crate) fn columns(&self, x0: u32, x1: u32) -> Image {
        let nc = self.channels.len();
        let span = x0 as usize * nc..x1 as usize * nc;
        Image {
            width: x1 - x0,
            height: self.height,
            channels: self.channels.clone(),
            data: (self.data.chunks_exact((self.width as usize * nc).max(1)))
                .flat_map(|row| &row[span.clone()])
                .copied()
                .collect(),
        }
    }

    /// Checks the invariants an encoder relies on.
    fn validate(&self, path: &Path) -> Result<(), ImageError> {
        let expected = self.width as u64 * self.height as u64 * self.channels.len() as u64;
        let found = self.data.len() as u64;
        if self.width == 0 || self.height == 0 || self.channels.is_empty() {
            return Err(format_error(
                path,
                format!(
                    "expected a non-empty image, found {}×{} with {} channels",
                    self.width,
                    self.height,
                    self.channels.len()
                ),
            ));
        }
        if expected != found {
            return Err(format_error(
                path,
                format!(
                    "expected {expected} samples ({}×{}×{}), found {found}",
                    self.width,
                    self.height,
                    self.channels.len()
                ),
            ));
        }
        Ok(())
    }

    /// A copy holding only the channels `keep` accepts (in their original order).
    fn select(&self, keep: impl Fn(&str) -> bool) -> Image {
        let nc = self.channels.len();
        let idx: Vec<usize> = (0..nc).filter(|&i| keep(&self.channels[i])).collect();
        let mut data = Vec::with_capacity(self.width as usize * self.height as usize * idx.len());
        for px in self.data.chunks_exact(nc) {
            data.extend(idx.iter().map(|&i| px[i]));
        }
        Image {
            width: self.width,
            height: self.height,
            channels: idx.iter().map(|&i| self.channels[i].clone()).collect(),
            data,
        }
    }
}

/// `Quantize "rgba" one min max dither`: `one == 0` means float output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantize {
    pub one: i32,
    pub min: i32,
    pub max: i32,
    pub dither: f32,
}

impl Default for Quantize {
    /// [`Quantize::RGBA_DEFAULT`]: 8-bit, dither amplitude 0.5.
    fn default() -> Self {
        Quantize::RGBA_DEFAULT
    }
}

/// Camera matrices a depth display records (zfile `Np`/`Nl`, shadow-map attributes), RIB order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthMatrices {
    /// world → screen (screen window mapped to [-1,1]², y up).
    pub world_to_screen: [f32; 16],
    /// world → camera.
    pub world_to_camera: [f32; 16],
}

#[derive(Debug, Error)]
pub enum ImageError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}: unsupported display type `{kind}` (expected tiff, file, png, openexr, exr, zfile or framebuffer)")]
    UnsupportedDisplay { path: String, kind: String },
    #[error("{path}: {message}")]
    Format { path: String, message: String },
}

pub(crate) fn format_error(path: &Path, message: impl Into<String>) -> ImageError {
    ImageError::Format {
        path: path.display().to_string(),
        message: message.into(),
    }
}

pub(crate) fn io_error(path: &Path, source: std::io::Error) -> ImageError {
    ImageError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Writes one display (`Display "name" "type" "mode"`): `kind` is the display type
/// (`tiff`/`file`, `png`, `openexr`/`exr`, `zfile`, `framebuffer`), case-insensitive.
/// `framebuffer` writes to [`framebuffer_path`]`(path)`, not to `path`.
/// `depth` is required by `zfile`, recorded by `openexr` (`worldToCamera`, `worldToNDC`) and
/// ignored by the other kinds.
pub fn write_display(
    path: &Path,
    kind: &str,
    image: &Image,
    quantize: Quantize,
    depth: Option<&DepthMatrices>,
) -> Result<(), ImageError> {
    write_display_cropped(path, kind, image, quantize, depth, [0, 0])
}

/// [`write_display`] for an image that is a `CropWindow` of a larger frame: `origin` is the
/// full-frame raster position (x, y) of its top-left pixel. Dither depends on full-frame pixel
/// positions only, so crops rendered separately and pasted together equal the full render
/// bit for bit.
pub fn write_display_cropped(
    path: &Path,
    kind: &str,
    image: &Image,
    quantize: Quantize,
    depth: Option<&DepthMatrices>,
    origin: [u32; 2],
) -> Result<(), ImageError> {
    image.validate(path)?;
    match kind.to_ascii_lowercase().as_str() {
        "tiff" | "file" => tiff_file::write_tiff(path, image, quantize, origin),
        "png" => png_file::write_png(path, image, quantize, origin),
        "framebuffer" => png_file::write_png(&framebuffer_path(path), image, quantize, origin),
        "openexr" | "exr" => openexr::write_exr(path, image, quantize, depth),
        "zfile" => {
            let Some(depth) = depth else {
                return Err(format_error(
                    path,
                    "zfile display expected the camera's depth matrices, found none",
                ));
            };
            zfile::write_zfile(path, image, depth)
        }
        _ => Err(ImageError::UnsupportedDisplay {
            path: path.display().to_string(),
            kind: kind.to_string(),
        }),
    }
}

/// [`write_display_cropped`] for a `tiff` display of a frame rendered in column blocks
/// `tile_width` pixels wide (a multiple of 16): a tiled TIFF, its tiles that wide and 16 rows
/// tall, column of tiles after column of tiles: the file [`TiffRows::create_tiled`] streams
/// from such a frame, byte for byte.
pub fn write_tiff_tiled(
    path: &Path,
    image: &Image,
    quantize: Quantize,
    origin: [u32; 2],
    tile_width: u32,
) -> Result<(), ImageError> {
    image.validate(path)?;
    tiff_file::write_tiff_tiled(path, image, quantize, origin, tile_width)
}

/// Reads TIFF, PNG, JPEG, OpenEXR or PRMan zfile into a float image, choosing the decoder
/// from the file's first bytes (not its name). Integer samples are normalised to [0, 1].
pub fn read_image(path: &Path) -> Result<Image, ImageError> {
    let mut magic = [0u8; 8];
    let n = {
        use std::io::Read;
        let mut f = std::fs::File::open(path).map_err(|e| io_error(path, e))?;
        let mut n = 0;
        while n < magic.len() {
            match f.read(&mut magic[n..]) {
                Ok(0) => break,
                Ok(k) => n += k,
                Err(e) => return Err(io_error(path, e)),
            }
        }
        n
    };
    let magic = &magic[..n];
    if magic.starts_with(b"II*\0") || magic.starts_with(b"MM\0*") {
        tiff_file::read_tiff(path)
    } else if magic.starts_with(b"II+\0") || magic.starts_with(b"MM\0+") {
        Err(format_error(
            path,
            "BigTIFF is not supported (expected classic TIFF)",
        ))
    } else if magic.starts_with(&[0x89, b'P', b'N', b'G']) || magic.starts_with(&[0xFF, 0xD8]) {
        png_file::read_png_or_jpeg(path)
    } else if magic.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        openexr::read_exr(path)
    } else if magic.len() >= 4 && zfile::is_zfile_magic(&magic[..4]) {
        zfile::read_zfile(path).map(|(image, _)| image)
    } else {
        Err(format_error(
            path,
            format!(
                "expected a TIFF, PNG, JPEG, OpenEXR or zfile signature, found bytes {:02x?}",
                magic
            ),
        ))
    }
}
