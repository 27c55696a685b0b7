//! The texture cache: one per render, shared by every thread (`Sync`).
//!
//! Files are opened once (header and offset table only); tiles are read lazily the first time a
//! lookup touches them and kept in a sharded map bounded by `Option "limits" "texturememory"`.
//! Tiles stay in the file's precision (`half` for most `.tx` files: see `texels.rs`). The bound
//! is global: when the resident total exceeds it, the shard that just grew drops its least
//! recently used tiles (then the other shards theirs, if it has too few) down to a low-water
//! mark below the bound, so one sort pays for many evictions (a per-shard share of the bound made unevenly hashed shards thrash while others
//! sat half empty). Images that are not tiled
//! textures (plain TIFF/PNG/scan-line EXR) are read whole, mip-mapped in memory, and used with a
//! one-time warning. Failures (missing file, bad format) are remembered too, so a missing texture
//! costs one `open` per render, and the caller warns once.

use crate::build::image_to_level;
use crate::mipmap::{build_pyramid, Level, Resampler};
use crate::texels::Texels;
use crate::txfile::TiledExr;
use crate::wrapmode::{parse_wrapmodes, WrapMode};
use crate::{FilterKind, TextureError};
use glam::DMat4;
use std::collections::HashMap;
use std::path::Path;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, RwLock};

/// What a texture file holds (the `textureformat` attribute).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureKind {
    Plain,
    LatLong,
    Cube,
    Shadow,
}

impl TextureKind {
    pub fn name(self) -> &'static str {
        match self {
            TextureKind::Plain => "Plain Texture",
            TextureKind::LatLong => "LatLong Environment",
            TextureKind::Cube => "CubeFace Environment",
            TextureKind::Shadow => "Shadow",
        }
    }
}

/// Cache statistics for `render --stats`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CacheStats {
    /// Texture files opened (including in-memory fallbacks).
    pub files_opened: u64,
    /// Tiles decoded from disk.
    pub tiles_read: u64,
    /// Tile requests answered from memory.
    pub tile_hits: u64,
    /// Decoded bytes read from disk.
    pub bytes_read: u64,
    /// Bytes of tiles resident now.
    pub bytes_resident: u64,
    /// Most bytes ever resident.
    pub peak_bytes: u64,
    /// Tiles evicted to honour the memory limit.
    pub evictions: u64,
}

impl CacheStats {
    /// Fraction of tile requests served from memory.
    pub fn hit_rate(&self) -> f64 {
        let total = self.tile_hits + self.tiles_read;
        if total == 0 {
            1.0
        } else {
            self.tile_hits as f64 / total as f64
        }
    }
}

/// Summary of an opened texture.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureInfo {
    pub kind: TextureKind,
    pub width: usize,
    pub height: usize,
    /// Channel names in RenderMan order (R,G,B,A first).
    pub channels: Vec<String>,
    pub levels: usize,
    pub wrap: [WrapMode; 2],
    /// Whether the file was a tiled texture (false: mip-mapped in memory).
    pub tiled: bool,
}

pub(crate) enum Backing {
    Tiled(Box<TiledExr>),
    Memory(Vec<Level>),
}

/// An opened texture file.
pub(crate) struct TexFile {
    pub id: u64,
    pub path: String,
    pub kind: TextureKind,
    pub levels: Vec<(usize, usize)>,
    /// Channels per texel as stored.
    pub nch: usize,
    /// RenderMan channel index → stored channel index.
    pub order: Vec<usize>,
    pub names: Vec<String>,
    pub wrap: [WrapMode; 2],
    pub world_to_camera: Option<DMat4>,
    pub world_to_ndc: Option<DMat4>,
    /// Stored index of the `Zmax` channel of a shadow map's min/max pyramid.
    pub zmax: Option<usize>,
    pub backing: Backing,
}

/// A decoded tile: interleaved texels, stored channel order.
pub(crate) struct Tile {
    pub w: usize,
    pub data: Texels,
}

type TileKey = (u64, u32, u32, u32);

struct Shard {
    map: HashMap<TileKey, (Arc<Tile>, u64)>,
    bytes: usize,
}

const SHARDS: usize = 16;

/// Eviction frees down to `max − max / LOW_WATER_DIVISOR` (1/256 below the bound), so the sort
/// of a shard's tiles by age is paid once per many evicted tiles, not once per miss.
const LOW_WATER_DIVISOR: usize = 256;

/// An opened file, or why it could not be opened (remembered so failures cost one `open`).
type FileEntry = Result<Arc<TexFile>, Arc<TextureError>>;

/// The shared, bounded texture cache.
pub struct TextureCache {
    max_bytes: AtomicUsize,
    files: RwLock<HashMap<String, FileEntry>>,
    shards: Vec<Mutex<Shard>>,
    next_id: AtomicU64,
    clock: AtomicU64,
    resident: AtomicUsize,
    peak: AtomicUsize,
    tiles_read: AtomicU64,
    tile_hits: AtomicU64,
    bytes_read: AtomicU64,
    evictions: AtomicU64,
    files_opened: AtomicU64,
    /// `Option "searchpath" "texture"`: where relative names are looked for first.
    searchpath: Vec<String>,
}

impl std::fmt::Debug for TextureCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TextureCache")
            .field("stats", &self.stats())
            .finish()
    }
}

fn clone_error(e: &TextureError) -> TextureError {
    match e {
        TextureError::Io { path, source } => TextureError::Io {
            path: path.clone(),
            source: std::io::Error::new(source.kind(), source.to_string()),
        },
        TextureError::Missing { path } => TextureError::Missing { path: path.clone() },
        TextureError::Format { path, message } => TextureError::Format {
            path: path.clone(),
            message: message.clone(),
        },
        TextureError::WrongKind {
            path,
            expected,
            found,
        } => TextureError::WrongKind {
            path: path.clone(),
            expected,
            found,
        },
    }
}

impl TextureCache {
    /// A cache holding at most `max_bytes` of decoded tiles (`texturememory` is in KB: pass
    /// `kb * 1024`).
    pub fn new(max_bytes: usize) -> TextureCache {
        TextureCache {
            max_bytes: AtomicUsize::new(max_bytes.max(1)),
            files: RwLock::new(HashMap::new()),
            shards: (0..SHARDS)
                .map(|_| {
                    Mutex::new(Shard {
                        map: HashMap::new(),
                        bytes: 0,
                    })
                })
                .collect(),
            next_id: AtomicU64::new(1),
            clock: AtomicU64::new(0),
            resident: AtomicUsize::new(0),
            peak: AtomicUsize::new(0),
            tiles_read: AtomicU64::new(0),
            tile_hits: AtomicU64::new(0),
            bytes_read: AtomicU64::new(0),
            evictions: AtomicU64::new(0),
            files_opened: AtomicU64::new(0),
            searchpath: Vec::new(),
        }
    }

    /// The same cache, finding relative texture names on `searchpath` (`Option "searchpath"
    /// "texture"`) before the working directory.
    pub fn with_searchpath(mut self, searchpath: Vec<String>) -> TextureCache {
        self.searchpath = searchpath;
        self
    }

    /// Changes the memory bound (`Option "limits" "texturememory"`).
    pub fn set_max_bytes(&self, max_bytes: usize) {
        self.max_bytes.store(max_bytes.max(1), Ordering::Relaxed);
    }

    pub fn stats(&self) -> CacheStats {
        CacheStats {
            files_opened: self.files_opened.load(Ordering::Relaxed),
            tiles_read: self.tiles_read.load(Ordering::Relaxed),
            tile_hits: self.tile_hits.load(Ordering::Relaxed),
            bytes_read: self.bytes_read.load(Ordering::Relaxed),
            bytes_resident: self.resident.load(Ordering::Relaxed) as u64,
            peak_bytes: self.peak.load(Ordering::Relaxed) as u64,
            evictions: self.evictions.load(Ordering::Relaxed),
        }
    }

    /// Describes a texture (opening it if needed).
    pub fn info(&self, name: &str) -> Result<TextureInfo, TextureError> {
        let f = self.file(name)?;
        Ok(TextureInfo {
            kind: f.kind,
            width: f.levels[0].0,
            height: f.levels[0].1,
            channels: f.order.iter().map(|&i| f.names[i].clone()).collect(),
            levels: f.levels.len(),
            wrap: f.wrap,
            tiled: matches!(f.backing, Backing::Tiled(_)),
        })
    }

    pub(crate) fn file(&self, name: &str) -> Result<Arc<TexFile>, TextureError> {
        if let Ok(files) = self.files.read() {
            if let Some(r) = files.get(name) {
                return r.clone().map_err(|e| clone_error(&e));
            }
        }
        let opened = self.open(name).map(Arc::new).map_err(Arc::new);
        let mut files = self.files.write().unwrap_or_else(|p| p.into_inner());
        let entry = files.entry(name.to_string()).or_insert(opened);
        entry.clone().map_err(|e| clone_error(&e))
    }

    fn open(&self, name: &str) -> Result<TexFile, TextureError> {
        let found = illume_core::searchpath::find(name, &self.searchpath);
        let path = found.as_deref().unwrap_or(Path::new(name));
        if !path.exists() {
            return Err(TextureError::Missing {
                path: name.to_string(),
            });
        }
        self.files_opened.fetch_add(1, Ordering::Relaxed);
        let id = self.next_id.fetch_add(1, Ordering::Relaxed);
        if let Some(tx) = TiledExr::open(path)? {
            let names: Vec<String> = tx.channels.iter().map(|(n, _)| n.clone()).collect();
            let format = tx.text("textureformat").unwrap_or_default();
            let envmap = tx.envmap();
            let kind = if format.eq_ignore_ascii_case("Shadow") {
                TextureKind::Shadow
            } else if format.starts_with("CubeFace")
                || envmap == Some(exr::meta::attribute::EnvironmentMap::Cube)
            {
                TextureKind::Cube
            } else if format.starts_with("LatLong")
                || envmap == Some(exr::meta::attribute::EnvironmentMap::LatitudeLongitude)
            {
                TextureKind::LatLong
            } else {
                TextureKind::Plain
            };
            let wrap = tx
                .text("wrapmodes")
                .and_then(|w| parse_wrapmodes(&w))
                .unwrap_or([WrapMode::Black; 2]);
            let m = |n: &str| {
                tx.matrix(n)
                    .map(|a| DMat4::from_cols_array(&a.map(|v| v as f64)))
            };
            // OpenImageIO's `maketx --shadow` records the screen matrix as `worldToScreen`.
            let wtn = m("worldToNDC").or_else(|| {
                tx.matrix("worldToScreen").map(|a| {
                    let ndc = crate::build::screen_to_ndc(&a);
                    DMat4::from_cols_array(&ndc.map(|v| v as f64))
                })
            });
            let wtc = m("worldToCamera");
            if kind == TextureKind::Cube {
                let (w, h) = tx.levels[0];
                if h != 6 * w || !w.is_power_of_two() {
                    return Err(TextureError::Format {
                        path: name.to_string(),
                        message: format!("cube environment is {w}x{h}: expected n x 6n faces with n a power of two"),
                    });
                }
            }
            return Ok(TexFile {
                id,
                path: name.to_string(),
                kind,
                levels: tx.levels.clone(),
                nch: names.len(),
                order: renderman_order(&names),
                zmax: names.iter().position(|n| n == "Zmax"),
                names,
                wrap,
                world_to_camera: wtc,
                world_to_ndc: wtn,
                backing: Backing::Tiled(Box::new(tx)),
            });
        }
        // Not a tiled texture: read the whole image and mip-map it in memory.
        let image = read_plain_image(path)?;
        eprintln!("warning: {name}: not a tiled mip-mapped texture; building its pyramid in memory (run txmake)");
        let (level0, names) = image_to_level(&image, path)?;
        let r = Resampler {
            filter: FilterKind::Box,
            swidth: 1.0,
            twidth: 1.0,
            wrap: [WrapMode::Clamp; 2],
        };
        let levels = build_pyramid(level0, &r);
        Ok(TexFile {
            id,
            path: name.to_string(),
            kind: TextureKind::Plain,
            levels: levels.iter().map(|l| (l.width, l.height)).collect(),
            nch: names.len(),
            order: renderman_order(&names),
            names,
            wrap: [WrapMode::Black; 2],
            world_to_camera: None,
            world_to_ndc: None,
            zmax: None,
            backing: Backing::Memory(levels),
        })
    }

    /// Fetches a tile, reading it on a miss.
    pub(crate) fn tile(
        &self,
        f: &TexFile,
        tx: &TiledExr,
        level: usize,
        x: usize,
        y: usize,
    ) -> Result<Arc<Tile>, TextureError> {
        let key: TileKey = (f.id, level as u32, x as u32, y as u32);
        let shard_index = (key.0 as usize * 31 + level * 17 + x * 7 + y * 13) % SHARDS;
        let tick = self.clock.fetch_add(1, Ordering::Relaxed);
        {
            let mut shard = self.shards[shard_index]
                .lock()
                .unwrap_or_else(|p| p.into_inner());
            if let Some((t, last)) = shard.map.get_mut(&key) {
                *last = tick;
                self.tile_hits.fetch_add(1, Ordering::Relaxed);
                return Ok(t.clone());
            }
        }
        let (w, _h, data) = tx.read_tile(level, x, y)?;
        let bytes = data.bytes();
        let tile = Arc::new(Tile { w, data });
        self.tiles_read.fetch_add(1, Ordering::Relaxed);
        self.bytes_read.fetch_add(bytes as u64, Ordering::Relaxed);
        let mut shard = self.shards[shard_index]
            .lock()
            .unwrap_or_else(|p| p.into_inner());
        if let Some((t, _)) = shard.map.get(&key) {
            return Ok(t.clone());
        }
        shard.map.insert(key, (tile.clone(), tick));
        shard.bytes += bytes;
        let now = self.resident.fetch_add(bytes, Ordering::Relaxed) + bytes;
        self.peak.fetch_max(now, Ordering::Relaxed);
        let max = self.max_bytes.load(Ordering::Relaxed);
        if now > max {
            let target = max - max / LOW_WATER_DIVISOR;
            evict(self, &mut shard, Some(key), target);
            // A shard with nothing else to give: take from the others. `try_lock` only, since
            // this thread holds its own shard (two threads locking in opposite orders would
            // deadlock); a busy shard is skipped, the bound is met on a later miss.
            for k in 1..SHARDS {
                if self.resident.load(Ordering::Relaxed) <= target {
                    break;
                }
                if let Ok(mut other) = self.shards[(shard_index + k) % SHARDS].try_lock() {
                    evict(self, &mut other, None, target);
                }
            }
        }
        Ok(tile)
    }
}

/// Drops the least recently used tiles of `shard` (never `keep`, the tile being returned)
/// until `cache` holds at most `target` bytes or the shard has nothing else to give.
fn evict(cache: &TextureCache, shard: &mut Shard, keep: Option<TileKey>, target: usize) {
    let mut by_age: Vec<(u64, TileKey)> = shard
        .map
        .iter()
        .filter(|(k, _)| Some(**k) != keep)
        .map(|(k, (_, t))| (*t, *k))
        .collect();
    by_age.sort_unstable();
    for (_, k) in by_age {
        if cache.resident.load(Ordering::Relaxed) <= target {
            break;
        }
        if let Some((t, _)) = shard.map.remove(&k) {
            let b = t.data.bytes();
            shard.bytes -= b;
            cache.resident.fetch_sub(b, Ordering::Relaxed);
            cache.evictions.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// R, G, B, A first (RenderMan channel 0 is red), then the rest alphabetically.
fn renderman_order(names: &[String]) -> Vec<usize> {
    let mut order = Vec::with_capacity(names.len());
    for want in ["R", "G", "B", "A", "Y", "Z"] {
        if let Some(i) = names.iter().position(|n| n == want) {
            order.push(i);
        }
    }
    for i in 0..names.len() {
        if !order.contains(&i) {
            order.push(i);
        }
    }
    order
}

/// Reads a non-tiled image used directly as a texture (TIFF, PNG, JPEG, scan-line OpenEXR).
fn read_plain_image(path: &Path) -> Result<illume_imageio::Image, TextureError> {
    illume_imageio::read_image(path).map_err(|e| TextureError::Format {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}
