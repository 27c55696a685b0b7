//! TIFF: the `tiff`/`file` display driver and a TIFF reader.
//!
//! Both are written here against the TIFF 6.0 specification rather than through a codec crate,
//! because renderer TIFFs break the crates' assumptions: Aqsis and PRMan write RGB files with
//! extra samples (alpha, depth) and no `ExtraSamples` tag, and a depth display wants float and
//! 8-bit channels chosen per channel set.
//!
//! Writer: one IFD, little-endian, contiguous samples, Deflate-compressed strips of about 64 KiB
//! (or, for a frame rendered in column blocks, tiles a block wide and 16 rows tall: `tiles`),
//! `SampleFormat` 1 (unsigned) or 3 (IEEE float), `ExtraSamples` 1 (associated alpha — RenderMan
//! colour is premultiplied) for `a` and 0 (unspecified) for `z` and others, and the channel names
//! in `ImageDescription` as `Illume channels r,g,b,z` so a round trip restores them.
//!
//! Reader: classic TIFF in either byte order; strips or tiles; planar configuration 1 or 2;
//! compression none, LZW, Deflate (8 and 32946) and PackBits; predictors 2 (horizontal) and
//! 3 (floating point); 8/16/32-bit unsigned or signed integers, 16/32/64-bit floats; photometric
//! min-is-white, min-is-black, RGB and palette; any number of samples per pixel. Only the first
//! image (IFD) is read.
//!
//! One concept per file: `write` lays out and writes the file; `ifd` is bounds-checked access
//! to the header and tags; `read` is the decode pipeline; `codec` holds the compressions and
//! predictors; `samples` turns stored samples into floats; `photometric` names channels and
//! interprets colour (alpha, palette, white-is-zero).

mod codec;
mod ifd;
mod photometric;
mod read;
mod samples;
mod tiles;
mod write;

pub(crate) use read::read_tiff;
pub use write::TiffRows;
pub(crate) use write::{write_tiff, write_tiff_tiled};

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

#[cfg(test)]
mod tests;
