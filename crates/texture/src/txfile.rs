//! The `.tx`/`.sm` container: a tiled (64×64), round-down mip-mapped, single-part OpenEXR file.
//!
//! Writing goes through the `exr` crate's image API (parallel compression) into memory, puts the
//! header's attributes in name order (so the same input gives the same bytes), then writes a
//! temporary name and renames it, so an interrupted `txmake` never leaves a half-written texture. Reading is
//! tile-granular: the header and offset table are parsed once, and each tile is fetched with one
//! positioned read and decompressed on demand, so a lookup touches only the tiles it needs.

use crate::texels::Texels;
use crate::TextureError;
use exr::block::chunk::Chunk;
use exr::block::UncompressedBlock;
use exr::image::{AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, Levels};
use exr::math::{RoundingMode, Vec2};
use exr::meta::attribute::{AttributeValue, SampleType, Text};
use exr::meta::header::LayerAttributes;
use exr::meta::{BlockDescription, MetaData};
use exr::prelude::{Blocks, Compression, LineOrder, SmallVec};
use half::f16;
use std::collections::HashMap;
use std::fs::File;
use std::io::{Cursor, Read};
use std::os::unix::fs::FileExt;
use std::path::Path;

use crate::mipmap::Level;

/// Texel storage in the written file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelFormat {
    Half,
    Float,
}

/// Tile edge length of every file we write (DESIGN.md, "Files").
pub const TILE: usize = 64;

/// Parses `-compression` names: none, rle, zips, zip, piz, pxr24, b44, b44a.
pub fn parse_compression(name: &str) -> Option<Compression> {
    Some(match name.to_ascii_lowercase().as_str() {
        "none" | "uncompressed" => Compression::Uncompressed,
        "rle" => Compression::RLE,
        "zips" => Compression::ZIP1,
        "zip" | "deflate" | "lossless" => Compression::ZIP16,
        "piz" => Compression::PIZ,
        "pxr24" => Compression::PXR24,
        "b44" => Compression::B44,
        "b44a" => Compression::B44A,
        _ => return None,
    })
}

/// Writes `levels` (level 0 first, all with the same channel count) as a tiled mip-mapped EXR.
pub(crate) fn write_tx(
    path: &Path,
    channel_names: &[String],
    levels: &[Level],
    format: PixelFormat,
    compression: Compression,
    attributes: Vec<(&str, AttributeValue)>,
) -> Result<(), TextureError> {
    let (w, h) = (levels[0].width, levels[0].height);
    let nch = channel_names.len();
    let mut list: SmallVec<[AnyChannel<Levels<FlatSamples>>; 4]> = SmallVec::new();
    for (c, name) in channel_names.iter().enumerate() {
        // Depth channels stay 32-bit: a shadow test compares depths, half would move them.
        let as_float = format == PixelFormat::Float || name.starts_with('Z');
        let level_data: Vec<FlatSamples> = levels
            .iter()
            .map(|l| {
                let it = l.data.iter().skip(c).step_by(nch).copied();
                if as_float {
                    FlatSamples::F32(it.collect())
                } else {
                    FlatSamples::F16(it.map(f16::from_f32).collect())
                }
            })
            .collect();
        list.push(AnyChannel::new(
            name.as_str(),
            Levels::Mip {
                rounding_mode: RoundingMode::Down,
                level_data,
            },
        ));
    }
    let mut layer_attributes = LayerAttributes {
        software_name: Some(Text::from("illume txmake")),
        ..LayerAttributes::default()
    };
    for (name, value) in attributes {
        // OpenEXR's standard attributes have their own fields in the `exr` crate.
        match (name, value) {
            ("envmap", AttributeValue::EnvironmentMap(e)) => {
                layer_attributes.environment_map = Some(e)
            }
            ("wrapmodes", AttributeValue::Text(t)) => layer_attributes.wrap_mode_name = Some(t),
            ("worldToCamera", AttributeValue::Matrix4x4(m)) => {
                layer_attributes.world_to_camera = Some(m)
            }
            ("worldToNDC", AttributeValue::Matrix4x4(m)) => {
                layer_attributes.world_to_normalized_device = Some(m)
            }
            (name, value) => {
                layer_attributes.other.insert(Text::from(name), value);
            }
        }
    }
    let layer = Layer::new(
        (w, h),
        layer_attributes,
        Encoding {
            compression,
            blocks: Blocks::Tiles(Vec2(TILE, TILE)),
            line_order: LineOrder::Increasing,
        },
        AnyChannels::sort(list),
    );
    let image = Image::from_layer(layer);
    // Encoded in memory first: the header's attributes are put in a fixed order before any
    // byte reaches the file (header_order.rs says why).
    use exr::image::write::WritableImage;
    let format_error = |message: String| TextureError::Format {
        path: path.display().to_string(),
        message,
    };
    let mut bytes = Vec::new();
    image
        .write()
        .to_buffered(Cursor::new(&mut bytes))
        .map_err(|e| format_error(format!("cannot write OpenEXR texture: {e}")))?;
    crate::header_order::sort_header_attributes(&mut bytes)
        .map_err(|e| format_error(format!("cannot order the OpenEXR header: {e}")))?;
    let tmp = temp_name(path);
    std::fs::write(&tmp, &bytes).map_err(|source| {
        let _ = std::fs::remove_file(&tmp);
        TextureError::Io {
            path: tmp.display().to_string(),
            source,
        }
    })?;
    std::fs::rename(&tmp, path).map_err(|source| TextureError::Io {
        path: path.display().to_string(),
        source,
    })
}

fn temp_name(path: &Path) -> std::path::PathBuf {
    let mut name = path
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(format!(".tmp{}", std::process::id()));
    path.with_file_name(name)
}

/// An opened tiled EXR: header, per-level sizes, and where every tile's chunk lies.
pub(crate) struct TiledExr {
    file: File,
    path: String,
    meta: MetaData,
    /// Channel names in file (alphabetical) order and their sample types.
    pub channels: Vec<(String, SampleType)>,
    pub tile: (usize, usize),
    /// `(width, height)` of each mip level.
    pub levels: Vec<(usize, usize)>,
    /// `(offset, length)` per chunk, indexed by `chunk_index[level][ty * ntx + tx]`.
    chunks: Vec<Vec<(u64, usize)>>,
    pub attributes: HashMap<String, AttributeValue>,
}

impl TiledExr {
    /// Opens `path` if it is a single-part tiled OpenEXR; `Ok(None)` when it is some other image.
    pub fn open(path: &Path) -> Result<Option<TiledExr>, TextureError> {
        let p = path.display().to_string();
        let io = |source| TextureError::Io {
            path: p.clone(),
            source,
        };
        let file = File::open(path).map_err(io)?;
        let len = file.metadata().map_err(io)?.len();
        let mut magic = [0u8; 4];
        if file.read_at(&mut magic, 0).map_err(io)? < 4 || magic != [0x76, 0x2f, 0x31, 0x01] {
            return Ok(None);
        }
        let fmt = |message: String| TextureError::Format {
            path: p.clone(),
            message,
        };
        let meta = MetaData::read_from_buffered(
            std::io::BufReader::new(File::open(path).map_err(io)?),
            false,
        )
        .map_err(|e| fmt(format!("bad OpenEXR header: {e}")))?;
        if meta.headers.len() != 1 {
            return Err(fmt("multi-part OpenEXR textures are not supported".into()));
        }
        let header = &meta.headers[0];
        let desc = match header.blocks {
            BlockDescription::Tiles(t) => t,
            BlockDescription::ScanLines => return Ok(None),
        };
        if header.deep {
            return Err(fmt("deep OpenEXR cannot be a texture".into()));
        }
        let table_start = header_end(&file, len).map_err(fmt)?;
        let count = header.chunk_count;
        // Textures keep to the image readers' per-side limit (issue 23: limits on read).
        let (w, h) = (header.layer_size.0, header.layer_size.1);
        let max = illume_imageio::MAX_DIMENSION as usize;
        if w > max || h > max {
            return Err(fmt(format!(
                "expected at most {max} texels per side, found {w}×{h}"
            )));
        }
        // The header's tile count sizes the offset table: check it against the file before
        // allocating, so a corrupt size is an error rather than an abort.
        let table_len = count
            .checked_mul(8)
            .filter(|&n| table_start.saturating_add(n as u64) <= len)
            .ok_or_else(|| {
                fmt(format!(
                    "the offset table of {count} tiles runs past the end of the file ({len} bytes)"
                ))
            })?;
        let mut raw = vec![0u8; table_len];
        file.read_exact_at(&mut raw, table_start).map_err(io)?;
        let offsets: Vec<u64> = raw
            .chunks_exact(8)
            .map(|b| u64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
            .collect();
        let mut sorted = offsets.clone();
        sorted.sort_unstable();
        sorted.push(len);
        // A chunk runs to the next chunk or the end of the file, whichever comes first (the
        // next offset of a corrupt table may lie far past the end); an offset past the end has
        // no bytes, so it reads as a missing tile instead of a huge buffer.
        let length_of = |o: u64| -> usize {
            if o >= len {
                return 0;
            }
            let i = sorted.partition_point(|&x| x <= o);
            (sorted[i.min(sorted.len() - 1)].min(len) - o) as usize
        };
        let tile = (desc.tile_size.0, desc.tile_size.1);
        let nlevels = match desc.level_mode {
            exr::meta::attribute::LevelMode::Singular => 1,
            exr::meta::attribute::LevelMode::MipMap => {
                exr::meta::compute_level_count(desc.rounding_mode, w.max(h))
            }
            exr::meta::attribute::LevelMode::RipMap => {
                return Err(fmt("rip-mapped textures are not supported".into()))
            }
        };
        let levels: Vec<(usize, usize)> = (0..nlevels)
            .map(|l| {
                (
                    exr::meta::compute_level_size(desc.rounding_mode, w, l),
                    exr::meta::compute_level_size(desc.rounding_mode, h, l),
                )
            })
            .collect();
        let mut chunks: Vec<Vec<(u64, usize)>> = levels
            .iter()
            .map(|&(lw, lh)| vec![(0, 0); lw.div_ceil(tile.0) * lh.div_ceil(tile.1)])
            .collect();
        for (i, t) in header.blocks_increasing_y_order().enumerate() {
            let l = t.location.level_index.0;
            if t.location.level_index.0 != t.location.level_index.1
                || l >= levels.len()
                || i >= offsets.len()
            {
                continue;
            }
            let ntx = levels[l].0.div_ceil(tile.0);
            let idx = t.location.tile_index.1 * ntx + t.location.tile_index.0;
            if let Some(slot) = chunks[l].get_mut(idx) {
                *slot = (offsets[i], length_of(offsets[i]));
            }
        }
        let channels = header
            .channels
            .list
            .iter()
            .map(|c| (c.name.to_string(), c.sample_type))
            .collect();
        let mut attributes: HashMap<String, AttributeValue> = HashMap::new();
        for (k, v) in header
            .shared_attributes
            .other
            .iter()
            .chain(header.own_attributes.other.iter())
        {
            attributes.insert(k.to_string(), v.clone());
        }
        let own = &header.own_attributes;
        if let Some(e) = own.environment_map {
            attributes.insert("envmap".into(), AttributeValue::EnvironmentMap(e));
        }
        if let Some(w) = &own.wrap_mode_name {
            attributes.insert("wrapmodes".into(), AttributeValue::Text(w.clone()));
        }
        if let Some(m) = own.world_to_camera {
            attributes.insert("worldToCamera".into(), AttributeValue::Matrix4x4(m));
        }
        if let Some(m) = own.world_to_normalized_device {
            attributes.insert("worldToNDC".into(), AttributeValue::Matrix4x4(m));
        }
        Ok(Some(TiledExr {
            file,
            path: p.clone(),
            meta: meta.clone(),
            channels,
            tile,
            levels,
            chunks,
            attributes,
        }))
    }

    /// Text attribute value, if present.
    pub fn text(&self, name: &str) -> Option<String> {
        match self.attributes.get(name) {
            Some(AttributeValue::Text(t)) => Some(t.to_string()),
            _ => None,
        }
    }

    pub fn matrix(&self, name: &str) -> Option<[f32; 16]> {
        match self.attributes.get(name) {
            Some(AttributeValue::Matrix4x4(m)) => Some(*m),
            _ => None,
        }
    }

    pub fn envmap(&self) -> Option<exr::meta::attribute::EnvironmentMap> {
        match self.attributes.get("envmap") {
            Some(AttributeValue::EnvironmentMap(e)) => Some(*e),
            _ => None,
        }
    }

    /// Number of tiles across level `l`.
    pub fn tiles_across(&self, l: usize) -> usize {
        self.levels[l].0.div_ceil(self.tile.0)
    }

    /// Reads and decodes one tile: interleaved texels in file channel order, `tw·th` texels where
    /// `(tw, th)` is the tile's real (possibly clipped) size; kept as `half` when every channel
    /// is `half` (see [`Texels`]).
    pub fn read_tile(
        &self,
        level: usize,
        tx: usize,
        ty: usize,
    ) -> Result<(usize, usize, Texels), TextureError> {
        let fmt = |message: String| TextureError::Format {
            path: self.path.clone(),
            message,
        };
        let ntx = self.tiles_across(level);
        let &(offset, length) = self.chunks[level]
            .get(ty * ntx + tx)
            .ok_or_else(|| fmt(format!("tile ({tx},{ty}) of level {level} out of range")))?;
        if length == 0 {
            return Err(fmt(format!(
                "tile ({tx},{ty}) of level {level} missing from the offset table"
            )));
        }
        let mut bytes = vec![0u8; length];
        self.file
            .read_exact_at(&mut bytes, offset)
            .map_err(|source| TextureError::Io {
                path: self.path.clone(),
                source,
            })?;
        let chunk = Chunk::read(&mut Cursor::new(bytes), &self.meta)
            .map_err(|e| fmt(format!("bad tile ({tx},{ty}) level {level}: {e}")))?;
        // The exr crate's decoders can panic on corrupt data (B44 under overflow checks).
        let block = std::panic::catch_unwind(|| {
            UncompressedBlock::decompress_chunk(chunk, &self.meta, false)
        })
        .unwrap_or_else(|_| Err(exr::error::Error::Invalid("corrupt compressed data".into())))
        .map_err(|e| {
            fmt(format!(
                "cannot decompress tile ({tx},{ty}) level {level}: {e}"
            ))
        })?;
        let (tw, th) = (block.index.pixel_size.0, block.index.pixel_size.1);
        // The chunk names its own tile: a corrupt table can point at another tile's chunk,
        // whose size the cache (which indexes by the requested tile) would misread.
        let (lw, lh) = self.levels[level];
        let expected = (
            self.tile.0.min(lw.saturating_sub(tx * self.tile.0)),
            self.tile.1.min(lh.saturating_sub(ty * self.tile.1)),
        );
        if (tw, th) != expected {
            return Err(fmt(format!(
                "tile ({tx},{ty}) of level {level}: expected {}×{} texels, the chunk holds {tw}×{th}",
                expected.0, expected.1
            )));
        }
        let nch = self.channels.len();
        let short = || fmt("short tile".into());
        let all_half = self
            .channels
            .iter()
            .all(|(_, t)| matches!(t, SampleType::F16));
        let data = &block.data;
        // The tile's size comes from the header: check the texels it claims against the bytes
        // the tile holds before allocating them (a corrupt tile size aborted here).
        let texel_bytes: usize = self
            .channels
            .iter()
            .map(|(_, t)| t.bytes_per_sample())
            .sum();
        tw.checked_mul(th)
            .and_then(|n| n.checked_mul(texel_bytes))
            .filter(|&n| texel_bytes > 0 && n <= data.len())
            .ok_or_else(short)?;
        if all_half {
            // Scan lines hold each channel's row in turn; the cache wants texels interleaved.
            let mut out = vec![f16::ZERO; tw * th * nch];
            let mut rows = data.chunks_exact(2);
            for y in 0..th {
                for c in 0..nch {
                    for x in 0..tw {
                        let b = rows.next().ok_or_else(short)?;
                        out[(y * tw + x) * nch + c] = f16::from_ne_bytes([b[0], b[1]]);
                    }
                }
            }
            return Ok((tw, th, Texels::Half(out)));
        }
        let mut out = vec![0.0f32; tw * th * nch];
        let mut pos = 0usize;
        for y in 0..th {
            for (c, (_, ty)) in self.channels.iter().enumerate() {
                for x in 0..tw {
                    let v = match ty {
                        SampleType::F16 => {
                            let b = data.get(pos..pos + 2).ok_or_else(short)?;
                            pos += 2;
                            f16::from_ne_bytes([b[0], b[1]]).to_f32()
                        }
                        SampleType::F32 => {
                            let b = data.get(pos..pos + 4).ok_or_else(short)?;
                            pos += 4;
                            f32::from_ne_bytes([b[0], b[1], b[2], b[3]])
                        }
                        SampleType::U32 => {
                            let b = data.get(pos..pos + 4).ok_or_else(short)?;
                            pos += 4;
                            u32::from_ne_bytes([b[0], b[1], b[2], b[3]]) as f32
                        }
                    };
                    out[(y * tw + x) * nch + c] = v;
                }
            }
        }
        Ok((tw, th, Texels::Float(out)))
    }
}

/// Byte position just after a single-part header (magic, version, attributes, terminating 0):
/// where the offset table starts.
fn header_end(file: &File, len: u64) -> Result<u64, String> {
    let mut buf = vec![0u8; (len.min(1 << 20)) as usize];
    let n = file.read_at(&mut buf, 0).map_err(|e| e.to_string())?;
    buf.truncate(n);
    let mut r = Cursor::new(&buf[..]);
    let mut skip8 = [0u8; 8];
    r.read_exact(&mut skip8).map_err(|e| e.to_string())?;
    let cstr = |r: &mut Cursor<&[u8]>| -> Result<Vec<u8>, String> {
        let mut s = Vec::new();
        loop {
            let mut b = [0u8; 1];
            r.read_exact(&mut b)
                .map_err(|_| "header runs past the end of the file".to_string())?;
            if b[0] == 0 {
                return Ok(s);
            }
            s.push(b[0]);
        }
    };
    loop {
        let name = cstr(&mut r)?;
        if name.is_empty() {
            return Ok(r.position());
        }
        let _kind = cstr(&mut r)?;
        let mut size = [0u8; 4];
        r.read_exact(&mut size)
            .map_err(|_| "truncated attribute".to_string())?;
        let size = i32::from_le_bytes(size);
        if size < 0 {
            return Err("negative attribute size".into());
        }
        r.set_position(r.position() + size as u64);
    }
}
