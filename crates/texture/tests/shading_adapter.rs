//! The cache seen through `illume_shade::TextureLookup`: what the built-in shaders call.

use illume_imageio::Image;
use illume_shade::{TextureLookup, TextureOptions};
use illume_texture::{make_texture, MakeOptions, TextureCache};

#[test]
fn shader_lookup_reads_the_made_texture_and_misses_are_none() {
    let dir = std::env::temp_dir().join(format!("illume-adapter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("ramp.tx");
    // A horizontal ramp in red, constant green: the lookup at s must return s in red.
    let (w, h) = (64u32, 16u32);
    let mut data = Vec::new();
    for _y in 0..h {
        for x in 0..w {
            data.extend_from_slice(&[(x as f32 + 0.5) / w as f32, 0.25, 0.0]);
        }
    }
    let image = Image {
        width: w,
        height: h,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data,
    };
    make_texture(&image, &path, &MakeOptions::default()).unwrap();

    let cache = TextureCache::new(1 << 20);
    let lookup: &dyn TextureLookup = &cache;
    let name = path.to_str().unwrap();
    let (s, t, d) = (0.3f32, 0.5f32, 1.0 / 64.0);
    let st = [[s, t], [s + d, t], [s, t + d], [s + d, t + d]];
    let rgb = lookup
        .texture(name, 0, 3, st, &TextureOptions::default())
        .unwrap();
    let s_centre = s + d / 2.0;
    assert!(
        (rgb[0] - s_centre).abs() < 2.0 / 64.0,
        "red {} vs s {}",
        rgb[0],
        s_centre
    );
    assert!((rgb[1] - 0.25).abs() < 1e-3, "green {}", rgb[1]);
    // Channel offset: asking from channel 1 returns green first.
    let g = lookup
        .texture(name, 1, 1, st, &TextureOptions::default())
        .unwrap();
    assert!((g[0] - 0.25).abs() < 1e-3);

    assert!(lookup
        .texture("no/such/map.tx", 0, 3, st, &TextureOptions::default())
        .is_none());
    let _ = std::fs::remove_dir_all(&dir);
}
