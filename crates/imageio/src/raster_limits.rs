//! Decoding limits: a hostile or corrupt header (say 4 000 000 000 × 4 000 000 000 pixels) must
//! return an error before anything is allocated, not abort the renderer on an allocation failure.

use crate::{format_error, ImageError};
use std::path::Path;

/// Largest width or height accepted (a 64K texture is far beyond any real scene's needs).
pub const MAX_DIMENSION: u32 = 1 << 16;
/// Largest `width·height·channels` accepted: 2^28 floats = 1 GiB of decoded samples.
pub const MAX_SAMPLES: u64 = 1 << 28;

/// Checks a decoded size before allocating for it.
pub(crate) fn check_size(
    path: &Path,
    width: u64,
    height: u64,
    channels: u64,
) -> Result<(), ImageError> {
    if width == 0 || height == 0 || channels == 0 {
        return Err(format_error(
            path,
            format!("expected a non-empty image, found {width}×{height} with {channels} channels"),
        ));
    }
    if width > MAX_DIMENSION as u64 || height > MAX_DIMENSION as u64 {
        return Err(format_error(
            path,
            format!("expected at most {MAX_DIMENSION} pixels per side, found {width}×{height}"),
        ));
    }
    let samples = width * height * channels;
    if samples > MAX_SAMPLES {
        return Err(format_error(
            path,
            format!(
                "expected at most {MAX_SAMPLES} samples, found {width}×{height}×{channels} = {samples}"
            ),
        ));
    }
    Ok(())
}
