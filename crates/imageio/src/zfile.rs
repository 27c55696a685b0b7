//! PRMan zfile: the `zfile` display and its reader (the input of `txmake -shadow`/`MakeShadow`).
//!
//! Layout (DESIGN.md "Files"): int32 magic `0x2f0867ab`, uint16 xres, uint16 yres,
//! float32[16] `Np` (world → screen), float32[16] `Nl` (world → camera), then xres·yres float32
//! depths, top row first. Matrices are in RIB (row-vector) order. The writer uses the host's
//! native byte order like PRMan did; the reader detects the order from the magic.

use crate::atomic_write::write_atomically;
use crate::raster_limits::check_size;
use crate::{format_error, io_error, DepthMatrices, Image, ImageError};
use std::io::Write;
use std::path::Path;

/// The zfile magic number.
pub const ZFILE_MAGIC: u32 = 0x2f08_67ab;

/// Header size in bytes: magic, two resolutions, two 4×4 float matrices.
const HEADER: usize = 4 + 2 + 2 + 64 + 64;

pub(crate) fn is_zfile_magic(b: &[u8]) -> bool {
    let m = [b[0], b[1], b[2], b[3]];
    u32::from_le_bytes(m) == ZFILE_MAGIC || u32::from_be_bytes(m) == ZFILE_MAGIC
}

/// Writes the `z` channel of `image` (or its only channel) as a zfile in native byte order.
pub fn write_zfile(path: &Path, image: &Image, depth: &DepthMatrices) -> Result<(), ImageError> {
    write_zfile_with_order(path, image, depth, cfg!(target_endian = "big"))
}

/// [`write_zfile`] with an explicit byte order (`big_endian`), for files meant for other hosts.
pub fn write_zfile_with_order(
    path: &Path,
    image: &Image,
    depth: &DepthMatrices,
    big_endian: bool,
) -> Result<(), ImageError> {
    let c = match (image.channel_index("z"), image.channels.len()) {
        (Some(c), _) => c,
        (None, 1) => 0,
        _ => {
            return Err(format_error(
                path,
                format!(
                    "zfile display expected a `z` channel, found channels {:?}",
                    image.channels
                ),
            ))
        }
    };
    if image.width > u16::MAX as u32 || image.height > u16::MAX as u32 {
        return Err(format_error(
            path,
            format!(
                "zfile expected at most 65535×65535 pixels, found {}×{}",
                image.width, image.height
            ),
        ));
    }
    let nc = image.channels.len();
    let f32b = |v: f32| {
        if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let mut bytes = Vec::with_capacity(HEADER + image.data.len() / nc * 4);
    let magic = if big_endian {
        ZFILE_MAGIC.to_be_bytes()
    } else {
        ZFILE_MAGIC.to_le_bytes()
    };
    bytes.extend(magic);
    for r in [image.width as u16, image.height as u16] {
        bytes.extend(if big_endian {
            r.to_be_bytes()
        } else {
            r.to_le_bytes()
        });
    }
    for m in depth.world_to_screen.iter().chain(&depth.world_to_camera) {
        bytes.extend(f32b(*m));
    }
    for px in image.data.chunks_exact(nc) {
        bytes.extend(f32b(px[c]));
    }
    write_atomically(path, |w| w.write_all(&bytes).map_err(|e| io_error(path, e)))
}

/// Reads a zfile: a one-channel (`z`) image and the camera matrices it was rendered with.
pub fn read_zfile(path: &Path) -> Result<(Image, DepthMatrices), ImageError> {
    let data = std::fs::read(path).map_err(|e| io_error(path, e))?;
    if data.len() < HEADER {
        return Err(format_error(
            path,
            format!(
                "truncated zfile: expected a {HEADER}-byte header, found {} bytes",
                data.len()
            ),
        ));
    }
    let big_endian = if u32::from_le_bytes([data[0], data[1], data[2], data[3]]) == ZFILE_MAGIC {
        false
    } else if u32::from_be_bytes([data[0], data[1], data[2], data[3]]) == ZFILE_MAGIC {
        true
    } else {
        return Err(format_error(
            path,
            format!(
                "expected the zfile magic 0x2f0867ab, found bytes {:02x?}",
                &data[..4]
            ),
        ));
    };
    let u16_at = |i: usize| {
        let b = [data[i], data[i + 1]];
        if big_endian {
            u16::from_be_bytes(b)
        } else {
            u16::from_le_bytes(b)
        }
    };
    let f32_at = |i: usize| {
        let b = [data[i], data[i + 1], data[i + 2], data[i + 3]];
        if big_endian {
            f32::from_be_bytes(b)
        } else {
            f32::from_le_bytes(b)
        }
    };
    let (w, h) = (u16_at(4) as u32, u16_at(6) as u32);
    check_size(path, w as u64, h as u64, 1)?;
    let mut matrices = DepthMatrices {
        world_to_screen: [0.0; 16],
        world_to_camera: [0.0; 16],
    };
    for i in 0..16 {
        matrices.world_to_screen[i] = f32_at(8 + 4 * i);
        matrices.world_to_camera[i] = f32_at(8 + 64 + 4 * i);
    }
    let n = w as usize * h as usize;
    let expected = HEADER + 4 * n;
    if data.len() < expected {
        return Err(format_error(
            path,
            format!(
                "truncated zfile: expected {expected} bytes for {w}×{h} depths, found {}",
                data.len()
            ),
        ));
    }
    let depths = (0..n).map(|i| f32_at(HEADER + 4 * i)).collect();
    Ok((
        Image {
            width: w,
            height: h,
            channels: vec!["z".into()],
            data: depths,
        },
        matrices,
    ))
}
