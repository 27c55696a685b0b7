//! Inputs the `read_texture` fuzz target (`fuzz/src/texture.rs`) and its smoke pass found to
//! crash the `.tx`/`.sm` reader (an abort allocating a buffer sized by a corrupt offset table,
//! tile count or the offset after a tile's; a panic indexing a tile whose chunk was another
//! tile's). Each file in
//! `tests/fuzz_crashes/` is 8 lookup-parameter bytes and then the texture, decoded as the
//! target decodes them; the same lookups must now end in errors, not a panic or an abort.
use glam::Vec3;
use illume_texture::{corners_from_derivatives, LookupOptions, TextureCache};
use std::path::PathBuf;

/// Runs the fuzz target's lookups; returns how many of them (info included) were errors.
fn lookups(params: &[u8], name: &str) -> usize {
    let cache = TextureCache::new(64 << 10);
    if cache.info(name).is_err() {
        return 1;
    }
    let unit = |b: u8| b as f32 / 255.0;
    let opts = LookupOptions {
        blur: unit(params[4]) * 0.1,
        samples: 1 + (params[5] % 16) as u32,
        bias: unit(params[6]),
        max_anisotropy: 1 + (params[7] % 16) as u32,
        ..LookupOptions::default()
    };
    let (s, t) = (unit(params[0]) * 3.0 - 1.0, unit(params[1]) * 3.0 - 1.0);
    let d = unit(params[2]) * 0.5;
    let st = corners_from_derivatives(s, t, d, 0.0, 0.0, d);
    let first = (params[3] % 4) as usize;
    let dir = Vec3::new(s, t, 1.0 - s);
    let spread = Vec3::splat(d);
    let dirs = [dir, dir + spread, dir - spread, dir + spread * 2.0];
    [
        cache.texture(name, first, 3, st, &opts).is_err(),
        cache.environment(name, first, 3, dirs, &opts).is_err(),
        cache.shadow(name, dirs, &opts).is_err(),
    ]
    .iter()
    .filter(|&&e| e)
    .count()
}

#[test]
fn every_fuzz_crash_is_an_error() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_crashes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    files.sort();
    assert!(
        !files.is_empty(),
        "the fuzz_crashes directory lost its files"
    );
    for path in files {
        let bytes = std::fs::read(&path).expect("readable crash file");
        let (params, texture) = bytes.split_at(8);
        let label = path.file_name().unwrap().to_string_lossy().into_owned();
        let scratch = std::env::temp_dir().join(format!(
            "illume-texture-fuzz-{}-{label}.tx",
            std::process::id()
        ));
        std::fs::write(&scratch, texture).expect("temp dir is writable");
        let name = scratch.to_str().expect("utf-8 temp path").to_string();
        let errors = std::panic::catch_unwind(|| lookups(params, &name));
        let _ = std::fs::remove_file(&scratch);
        let errors = errors.unwrap_or_else(|_| panic!("{label}: a lookup panicked"));
        assert!(
            errors > 0,
            "{label}: expected the corrupt texture to be an error"
        );
    }
}
