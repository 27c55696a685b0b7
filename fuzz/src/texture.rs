//! The texture targets: the `.tx`/`.sm` reader through the texture cache, and what `txmake`
//! (and `MakeTexture`, `MakeLatLongEnvironment`, `MakeShadow`) does with an input picture.
use super::{scratch_file, scratch_path};
use glam::Vec3;
use illume_texture::{
    corners_from_derivatives, make_latlong_environment, make_shadow, make_texture, FilterKind,
    LookupOptions, MakeOptions, PixelFormat, Resize, TextureCache, WrapMode,
};

/// The tiled OpenEXR container read tile by tile through the texture cache: opening,
/// `textureinfo`, and a texture, environment and shadow lookup whose footprint and options come
/// from the input's first 8 bytes (the file follows), so mutated headers, offset tables and
/// tiles are all reached through the code paths shaders use.
pub fn read_texture(data: &[u8]) {
    if data.len() < 8 || !data[8..].starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        return;
    }
    let (p, file) = data.split_at(8);
    let path = scratch_file("tx", file);
    let name = path.to_str().expect("utf-8 scratch path");
    // A small cache, so eviction runs too.
    let cache = TextureCache::new(64 << 10);
    if cache.info(name).is_err() {
        return;
    }
    let unit = |b: u8| b as f32 / 255.0;
    let opts = LookupOptions {
        blur: unit(p[4]) * 0.1,
        samples: 1 + (p[5] % 16) as u32,
        bias: unit(p[6]),
        max_anisotropy: 1 + (p[7] % 16) as u32,
        ..LookupOptions::default()
    };
    let (s, t) = (unit(p[0]) * 3.0 - 1.0, unit(p[1]) * 3.0 - 1.0);
    let d = unit(p[2]) * 0.5;
    let st = corners_from_derivatives(s, t, d, 0.0, 0.0, d);
    let first = (p[3] % 4) as usize;
    let _ = cache.texture(name, first, 3, st, &opts);
    let dir = Vec3::new(s, t, 1.0 - s);
    let spread = Vec3::splat(d);
    let dirs = [dir, dir + spread, dir - spread, dir + spread * 2.0];
    let _ = cache.environment(name, first, 3, dirs, &opts);
    let _ = cache.shadow(name, dirs, &opts);
}

/// The build options the first byte picks: wrap modes, resize, filter, pixel format (bit 6
/// picks the latlong environment instead of a texture).
fn make_options(op: u8) -> MakeOptions {
    let wraps = [WrapMode::Black, WrapMode::Clamp, WrapMode::Periodic];
    let filters = [
        FilterKind::Box,
        FilterKind::Triangle,
        FilterKind::Gaussian,
        FilterKind::CatmullRom,
        FilterKind::Lanczos,
        FilterKind::Mitchell,
        FilterKind::Sinc,
    ];
    let resizes = [Resize::None, Resize::Up, Resize::Down, Resize::Round];
    MakeOptions {
        wrap: [wraps[(op % 3) as usize], wraps[(op / 3 % 3) as usize]],
        resize: resizes[(op >> 2 & 3) as usize],
        filter: filters[(op >> 4) as usize % filters.len()],
        format: if op & 0x80 != 0 {
            PixelFormat::Float
        } else {
            PixelFormat::Half
        },
        ..MakeOptions::default()
    }
}

/// One option byte, then a picture: read by `read_image`/`read_zfile`, built into a `.tx`, a
/// latlong environment or a `.sm`, which must then open again. Pictures over 64×64 are skipped
/// to keep each run short (the readers themselves have their own targets).
pub fn txmake(data: &[u8]) {
    let Some((&op, picture)) = data.split_first() else {
        return;
    };
    let input = scratch_file("txmake-in", picture);
    let out = scratch_path("txmake-out.tx");
    let opts = make_options(op);
    let _ = std::fs::remove_file(&out);
    let magic = illume_imageio::ZFILE_MAGIC;
    let built =
        if picture.starts_with(&magic.to_le_bytes()) || picture.starts_with(&magic.to_be_bytes()) {
            let Ok((depth, matrices)) = illume_imageio::read_zfile(&input) else {
                return;
            };
            if depth.width > 64 || depth.height > 64 {
                return;
            }
            make_shadow(&depth, &matrices, &out, &opts)
        } else {
            let Ok(img) = illume_imageio::read_image(&input) else {
                return;
            };
            if img.width > 64 || img.height > 64 {
                return;
            }
            if op & 0x40 != 0 {
                make_latlong_environment(&img, &out, &opts)
            } else {
                make_texture(&img, &out, &opts)
            }
        };
    if built.is_ok() {
        // What txmake wrote must open again.
        let cache = TextureCache::new(1 << 20);
        let name = out.to_str().expect("utf-8 scratch path");
        if let Err(e) = cache.info(name) {
            panic!("txmake wrote a texture that does not open: {e}");
        }
    }
}
