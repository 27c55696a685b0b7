//! Tile files: one crop of a frame's filtered float image and depth, exactly as the hider left
//! them, for render farms (`render --tile-out`, `farm merge`).
//!
//! A tile holds the floats *before* any display driver quantizes, dithers or encodes them, so
//! pasting tiles into one [`Rendered`] and running [`crate::write_displays`] once writes every
//! display of the frame bit for bit as a single-machine render would (the hider already renders
//! each crop's pixel-filter margin, and dither is keyed on full-frame pixel positions).
//!
//! Layout, little-endian: the 8 bytes `ILMTILE1`, then u32 full-frame xres, yres, the tile's
//! x0, y0, width, height (raster pixels), then width·height·4 f32 premultiplied RGBA (top row
//! first), then width·height f32 depths. Written under a temporary name and renamed.
//!
//! A frame with arbitrary output variables writes `ILMTILE2`: the same, then u32 channel
//! count, per channel u32 name length, the UTF-8 name, u8 components, u8 flags (1: colour,
//! 2: premultiplied), then width·height·stride f32 AOV values (the hider's records).

use crate::Rendered;
use illume_imageio::{write_atomically, ImageError, MAX_DIMENSION};
use illume_reyes::{AovChannel, AovLayout};
use std::io::Write;
use std::path::Path;

const MAGIC: &[u8; 8] = b"ILMTILE1";
const MAGIC_AOV: &[u8; 8] = b"ILMTILE2";
const HEADER_BYTES: usize = 8 + 6 * 4;

/// A tile read back: where it sits in which frame size, and its pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Tile {
    /// Full-frame resolution the tile was cut from (`Format`).
    pub xres: u32,
    pub yres: u32,
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
    /// Premultiplied RGBA, top row first.
    pub rgba: Vec<f32>,
    pub z: Vec<f32>,
    /// The arbitrary output variables (`aov_layout.stride` floats per pixel).
    pub aov_layout: AovLayout,
    pub aov: Vec<f32>,
}

fn format_error(path: &Path, message: impl Into<String>) -> ImageError {
    ImageError::Format {
        path: path.display().to_string(),
        message: message.into(),
    }
}

/// Writes the crop `r` of a frame of `xres × yres` pixels to `path`, atomically.
pub fn write_tile(path: &Path, r: &Rendered, xres: u32, yres: u32) -> Result<(), ImageError> {
    let pixels = (r.width as usize) * (r.height as usize);
    if r.rgba.len() != pixels * 4
        || r.z.len() != pixels
        || r.aov.len() != pixels * r.aov_layout.stride
    {
        return Err(format_error(path, "tile buffers do not match its size"));
    }
    let with_aov = r.aov_layout.stride > 0;
    write_atomically(path, |w| {
        let io = |e| ImageError::Io {
            path: path.display().to_string(),
            source: e,
        };
        w.write_all(if with_aov { MAGIC_AOV } else { MAGIC })
            .map_err(io)?;
        for v in [xres, yres, r.x0, r.y0, r.width, r.height] {
            w.write_all(&v.to_le_bytes()).map_err(io)?;
        }
        for v in r.rgba.iter().chain(&r.z) {
            w.write_all(&v.to_le_bytes()).map_err(io)?;
        }
        if with_aov {
            let channels = &r.aov_layout.channels;
            w.write_all(&(channels.len() as u32).to_le_bytes())
                .map_err(io)?;
            for c in channels {
                w.write_all(&(c.name.len() as u32).to_le_bytes())
                    .map_err(io)?;
                w.write_all(c.name.as_bytes()).map_err(io)?;
                let flags = u8::from(c.colour) | (u8::from(c.premultiplied) << 1);
                w.write_all(&[c.components as u8, flags]).map_err(io)?;
            }
            for v in &r.aov {
                w.write_all(&v.to_le_bytes()).map_err(io)?;
            }
        }
        Ok(())
    })
}

/// Reads a tile file; a truncated, foreign or inconsistent file is an error, never a panic.
pub fn read_tile(path: &Path) -> Result<Tile, ImageError> {
    let bytes = std::fs::read(path).map_err(|e| ImageError::Io {
        path: path.display().to_string(),
        source: e,
    })?;
    let with_aov = bytes.len() >= 8 && &bytes[..8] == MAGIC_AOV;
    if bytes.len() < HEADER_BYTES || (&bytes[..8] != MAGIC && !with_aov) {
        return Err(format_error(
            path,
            "not an Illume tile file (no ILMTILE1 header)",
        ));
    }
    let word = |i: usize| {
        let at = 8 + 4 * i;
        u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
    };
    let [xres, yres, x0, y0, width, height] = [0, 1, 2, 3, 4, 5].map(word);
    let inside = |start: u32, len: u32, res: u32| start.checked_add(len).is_some_and(|e| e <= res);
    if xres > MAX_DIMENSION
        || yres > MAX_DIMENSION
        || !inside(x0, width, xres)
        || !inside(y0, height, yres)
    {
        return Err(format_error(
            path,
            format!("tile {width}x{height} at ({x0}, {y0}) does not fit a {xres}x{yres} frame"),
        ));
    }
    let pixels = width as usize * height as usize;
    let base = HEADER_BYTES + pixels * 5 * 4;
    let (aov_layout, aov) = if with_aov && bytes.len() >= base {
        read_aov(path, &bytes[base..], pixels)?
    } else {
        (AovLayout::default(), Vec::new())
    };
    let aov_bytes = if with_aov {
        bytes.len().saturating_sub(base)
    } else {
        0
    };
    if bytes.len() != base + aov_bytes || (with_aov && aov_layout.stride == 0) {
        return Err(format_error(
            path,
            format!(
                "truncated tile: {} bytes, expected {}",
                bytes.len(),
                HEADER_BYTES + pixels * 20
            ),
        ));
    }
    let floats: Vec<f32> = bytes[HEADER_BYTES..base]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let (rgba, z) = floats.split_at(pixels * 4);
    Ok(Tile {
        xres,
        yres,
        x0,
        y0,
        width,
        height,
        rgba: rgba.to_vec(),
        z: z.to_vec(),
        aov_layout,
        aov,
    })
}

/// The AOV part of an `ILMTILE2` tile: its channels and exactly `pixels · stride` floats.
fn read_aov(path: &Path, b: &[u8], pixels: usize) -> Result<(AovLayout, Vec<f32>), ImageError> {
    let bad = |what: &str| format_error(path, format!("tile AOV section: {what}"));
    let mut at = 0usize;
    let mut take = |n: usize| -> Result<&[u8], ImageError> {
        let s = b.get(at..at + n).ok_or_else(|| bad("truncated"))?;
        at += n;
        Ok(s)
    };
    let word = |s: &[u8]| u32::from_le_bytes([s[0], s[1], s[2], s[3]]) as usize;
    let count = word(take(4)?);
    if count > 4096 {
        return Err(bad("more than 4096 channels"));
    }
    let mut channels = Vec::with_capacity(count);
    for _ in 0..count {
        let len = word(take(4)?);
        if len > 4096 {
            return Err(bad("a channel name over 4096 bytes"));
        }
        let name = String::from_utf8(take(len)?.to_vec()).map_err(|_| bad("name not UTF-8"))?;
        let meta = take(2)?;
        if !(meta[0] == 1 || meta[0] == 3) {
            return Err(bad("expected 1 or 3 components"));
        }
        channels.push(AovChannel {
            name,
            components: meta[0] as usize,
            colour: meta[1] & 1 != 0,
            premultiplied: meta[1] & 2 != 0,
            filter: None,
        });
    }
    let layout = AovLayout::new(channels);
    let rest = &b[at..];
    if rest.len() != pixels * layout.stride * 4 {
        return Err(bad(&format!(
            "expected {} bytes of values, found {}",
            pixels * layout.stride * 4,
            rest.len()
        )));
    }
    let values = rest
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Ok((layout, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rendered(x0: u32, y0: u32, width: u32, height: u32) -> Rendered {
        let n = (width * height) as usize;
        Rendered {
            x0,
            y0,
            width,
            height,
            rgba: (0..n * 4).map(|i| i as f32 * 0.37 - 1.0).collect(),
            z: (0..n)
                .map(|i| if i % 3 == 0 { f32::MAX } else { i as f32 })
                .collect(),
            aov_layout: AovLayout::default(),
            aov: Vec::new(),
            stats: Default::default(),
            warnings: Vec::new(),
        }
    }

    #[test]
    fn tile_round_trips_every_bit() {
        let dir = std::env::temp_dir().join(format!("illume-tile-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.tile");
        let r = rendered(3, 5, 7, 4);
        write_tile(&path, &r, 16, 9).unwrap();
        let t = read_tile(&path).unwrap();
        assert_eq!(
            (t.xres, t.yres, t.x0, t.y0, t.width, t.height),
            (16, 9, 3, 5, 7, 4)
        );
        let bits = |v: &[f32]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&t.rgba), bits(&r.rgba));
        assert_eq!(bits(&t.z), bits(&r.z));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_tile_with_aovs_round_trips_every_bit_and_rejects_a_cut() {
        let dir = std::env::temp_dir().join(format!("illume-tile-aov-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.tile");
        let mut r = rendered(2, 1, 5, 3);
        r.aov_layout = AovLayout::new(vec![
            AovChannel {
                name: "N".into(),
                components: 3,
                colour: false,
                premultiplied: false,
                filter: None,
            },
            AovChannel {
                name: "__diffuse".into(),
                components: 3,
                colour: true,
                premultiplied: true,
                filter: None,
            },
        ]);
        r.aov = (0..15 * 6).map(|i| (i as f32).sin()).collect();
        write_tile(&path, &r, 9, 6).unwrap();
        let t = read_tile(&path).unwrap();
        let bits = |v: &[f32]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
        assert_eq!(t.aov_layout, r.aov_layout);
        assert_eq!(bits(&t.aov), bits(&r.aov));
        assert_eq!(bits(&t.rgba), bits(&r.rgba));
        let good = std::fs::read(&path).unwrap();
        for cut in [HEADER_BYTES + 15 * 20 + 2, good.len() - 4] {
            std::fs::write(&path, &good[..cut]).unwrap();
            assert!(read_tile(&path).is_err(), "cut at {cut} accepted");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn truncated_or_foreign_tiles_are_errors() {
        let dir = std::env::temp_dir().join(format!("illume-tile-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.tile");
        write_tile(&path, &rendered(0, 0, 4, 4), 4, 4).unwrap();
        let good = std::fs::read(&path).unwrap();
        for cut in [0, 7, HEADER_BYTES, good.len() - 1] {
            std::fs::write(&path, &good[..cut]).unwrap();
            assert!(read_tile(&path).is_err(), "cut at {cut} accepted");
        }
        // A tile that claims to lie outside its frame.
        let mut outside = good.clone();
        outside[8 + 8..8 + 12].copy_from_slice(&1u32.to_le_bytes());
        std::fs::write(&path, &outside).unwrap();
        assert!(read_tile(&path).is_err());
        std::fs::write(&path, b"II*\0 not a tile").unwrap();
        assert!(read_tile(&path).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
