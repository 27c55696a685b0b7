//! Fuzzes what `txmake` (and `MakeTexture`, `MakeLatLongEnvironment`, `MakeShadow`) does with
//! an input picture: the first byte picks the job and options (wrap modes, resize, filter,
//! pixel format), the rest is the picture file, read by `read_image` and built into a `.tx`,
//! an environment or a `.sm`, which is then opened again. Pictures over 64×64 are skipped to
//! keep each run short (the readers themselves are fuzzed by the read_* targets).
#![no_main]
use illume_texture::{
    make_latlong_environment, make_shadow, make_texture, FilterKind, MakeOptions, PixelFormat,
    Resize, TextureCache, WrapMode,
};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&op, picture)) = data.split_first() else {
        return;
    };
    let input = illume_fuzz::scratch_file("txmake-in", picture);
    let out = illume_fuzz::scratch_path("txmake-out.tx");
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
    let opts = MakeOptions {
        wrap: [wraps[(op % 3) as usize], wraps[(op / 3 % 3) as usize]],
        resize: resizes[(op >> 2 & 3) as usize],
        filter: filters[(op >> 4) as usize % filters.len()],
        format: if op & 0x80 != 0 {
            PixelFormat::Float
        } else {
            PixelFormat::Half
        },
        ..MakeOptions::default()
    };
    let _ = std::fs::remove_file(&out);
    let built = if picture.starts_with(&illume_imageio::ZFILE_MAGIC.to_le_bytes())
        || picture.starts_with(&illume_imageio::ZFILE_MAGIC.to_be_bytes())
    {
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
});
