//! Issue 23, part 5: the texture cache keeps tiles in the file's precision (half tiles cost
//! 2 bytes a sample, float tiles 4) and honours its bound globally; evicting never changes a
//! lookup's result.
use illume_imageio::Image;
use illume_texture::{make_texture, LookupOptions, MakeOptions, PixelFormat, TextureCache};

const SIDE: u32 = 256;
/// 64×64 RGB texels of one level-0 tile.
const TILE_SAMPLES: u64 = 64 * 64 * 3;

fn pattern_texture(format: PixelFormat, name: &str) -> String {
    let mut data = Vec::new();
    for y in 0..SIDE {
        for x in 0..SIDE {
            data.extend_from_slice(&[x as f32 / 255.0, y as f32 / 255.0, ((x ^ y) % 7) as f32]);
        }
    }
    let img = Image {
        width: SIDE,
        height: SIDE,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data,
    };
    let dir = std::env::temp_dir().join(format!("illume-cache-pressure-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let opts = MakeOptions {
        resize: illume_texture::Resize::None,
        format,
        ..MakeOptions::default()
    };
    make_texture(&img, &path, &opts).unwrap();
    path.to_str().unwrap().to_string()
}

/// Point lookups at every texel centre of a coarse lattice: level 0, every tile, in an order
/// that revisits tiles after others were read (a small cache must evict and re-read).
fn sweep(cache: &TextureCache, name: &str) -> Vec<[f32; 4]> {
    let mut out = Vec::new();
    for pass in 0..2 {
        for j in 0..16 {
            for i in 0..16 {
                let (x, y) = ((i * 16 + pass * 5) as f32 + 0.5, (j * 16 + 3) as f32 + 0.5);
                let st = [x / SIDE as f32, y / SIDE as f32];
                out.push(
                    cache
                        .texture(name, 0, 3, [st; 4], &LookupOptions::default())
                        .unwrap(),
                );
            }
        }
    }
    out
}

#[test]
fn half_tiles_cost_two_bytes_a_sample_and_float_tiles_four() {
    for (format, bytes, file) in [
        (PixelFormat::Half, 2, "half.tx"),
        (PixelFormat::Float, 4, "float.tx"),
    ] {
        let name = pattern_texture(format, file);
        let cache = TextureCache::new(1 << 30);
        sweep(&cache, &name);
        let st = cache.stats();
        // 256² at level 0 is 4×4 full tiles, each read once.
        assert_eq!(st.tiles_read, 16, "{st:?}");
        assert_eq!(
            st.bytes_resident,
            16 * TILE_SAMPLES * bytes,
            "{format:?}: {st:?}"
        );
        assert_eq!(st.evictions, 0);
    }
}

#[test]
fn a_cache_of_three_tiles_evicts_but_returns_the_same_texels() {
    let name = pattern_texture(PixelFormat::Half, "evict.tx");
    let big = TextureCache::new(1 << 30);
    let want = sweep(&big, &name);
    let tile_bytes = (TILE_SAMPLES * 2) as usize;
    let small = TextureCache::new(3 * tile_bytes);
    let got = sweep(&small, &name);
    assert_eq!(got, want, "eviction changed a result");
    let st = small.stats();
    assert!(st.evictions > 0 && st.tiles_read > 16, "{st:?}");
    // The bound is global (not a per-shard share): at most one tile over it at any time.
    assert!(st.peak_bytes as usize <= 4 * tile_bytes, "{st:?}");
    // The first lookup is texel (0, 3) (a texel centre: no bilinear blend): g = 3/255 to
    // half precision (relative 2⁻¹¹).
    assert!((want[0][1] - 3.0 / 255.0).abs() < 1e-5, "{:?}", want[0]);
}
