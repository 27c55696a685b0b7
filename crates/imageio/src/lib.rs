//! Display drivers and image readers.
//!
//! # Contract
//! * The hider hands a display a float [`Image`] (after pixel filter and `Exposure`), plus the
//!   `Quantize` settings; this crate quantizes, dithers (deterministically per pixel), and writes
//!   the file through a temporary name and a rename, so an interrupted render never leaves a
//!   half-written image under the real name.
//! * [`read_image`] reads any supported file into float RGBA-ish channels for `txmake` and
//!   textures used directly.
#![forbid(unsafe_code)]

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

/// `Quantize "rgba" one min max dither`: `one == 0` means float output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantize {
    pub one: i32,
    pub min: i32,
    pub max: i32,
    pub dither: f32,
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
    #[error("{path}: unsupported display type `{kind}`")]
    UnsupportedDisplay { path: String, kind: String },
    #[error("{path}: {message}")]
    Format { path: String, message: String },
}

/// Writes one display (`Display "name" "type" "mode"`): `kind` is the display type
/// (`tiff`/`file`, `png`, `openexr`/`exr`, `zfile`, `framebuffer`, …).
pub fn write_display(
    path: &Path,
    kind: &str,
    image: &Image,
    quantize: Quantize,
    depth: Option<&DepthMatrices>,
) -> Result<(), ImageError> {
    let _ = (image, quantize, depth);
    Err(ImageError::UnsupportedDisplay {
        path: path.display().to_string(),
        kind: kind.to_string(),
    })
}

/// Reads TIFF, PNG, JPEG, OpenEXR or PRMan zfile into a float image.
pub fn read_image(path: &Path) -> Result<Image, ImageError> {
    Err(ImageError::Format {
        path: path.display().to_string(),
        message: "not implemented".into(),
    })
}
