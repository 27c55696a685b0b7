//! Fuzzes the `.tx`/`.sm` reader (the tiled OpenEXR container read tile by tile through the
//! texture cache): opening, `textureinfo`, and a texture, environment and shadow lookup whose
//! footprint and options come from the input's first bytes, so mutated headers, offset tables
//! and tiles are all reached through the code paths shaders use.
#![no_main]
use glam::Vec3;
use illume_texture::{corners_from_derivatives, LookupOptions, TextureCache};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // 8 bytes of lookup parameters, then the file.
    if data.len() < 8 || !data[8..].starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        return;
    }
    let (p, file) = data.split_at(8);
    let path = illume_fuzz::scratch_file("tx", file);
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
});
