//! The cache seen through `illume_texture::TextureLookup`: what the built-in shaders call.

use illume_imageio::Image;
use illume_texture::{make_texture, MakeOptions, TextureCache};
use illume_texture::{TextureLookup, TextureOptions};

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

#[test]
fn textureinfo_describes_made_textures_and_shadow_maps() {
    use illume_imageio::DepthMatrices;
    use illume_texture::InfoValue;
    let dir = std::env::temp_dir().join(format!("illume-texinfo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A 3-channel 32×8 texture made by `make_texture`.
    let tex = dir.join("flat.tx");
    let image = Image {
        width: 32,
        height: 8,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data: vec![0.5; 32 * 8 * 3],
    };
    make_texture(&image, &tex, &MakeOptions::default()).unwrap();
    // A 16×16 shadow map whose light camera is world translated by (5,6,7) (RIB row-vector
    // order: the translation in elements 12..14) and whose screen matrix is a projection.
    let mut wtc = [0.0f32; 16];
    for i in 0..4 {
        wtc[i * 5] = 1.0;
    }
    wtc[12..15].copy_from_slice(&[5.0, 6.0, 7.0]);
    let m = DepthMatrices {
        world_to_screen: [
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, -1.0, 0.0,
        ],
        world_to_camera: wtc,
    };
    let depth = Image {
        width: 16,
        height: 16,
        channels: vec!["z".into()],
        data: vec![3.0; 256],
    };
    let sm = dir.join("spot.sm");
    illume_texture::make_shadow(&depth, &m, &sm, &MakeOptions::default()).unwrap();

    let cache = TextureCache::new(1 << 20);
    let lookup: &dyn TextureLookup = &cache;
    let (t, s) = (tex.to_str().unwrap(), sm.to_str().unwrap());
    let floats = |v: Option<InfoValue>| match v {
        Some(InfoValue::Floats(f)) => f,
        other => panic!("{other:?}"),
    };
    assert_eq!(floats(lookup.textureinfo(t, "resolution")), vec![32.0, 8.0]);
    assert_eq!(floats(lookup.textureinfo(t, "channels")), vec![3.0]);
    assert_eq!(
        lookup.textureinfo(t, "type"),
        Some(InfoValue::String("texture".into()))
    );
    assert_eq!(lookup.textureinfo(t, "viewingmatrix"), None);
    assert_eq!(lookup.textureinfo(t, "nosuch"), None);
    assert_eq!(
        lookup.textureinfo(s, "type"),
        Some(InfoValue::String("shadow".into()))
    );
    assert_eq!(
        floats(lookup.textureinfo(s, "resolution")),
        vec![16.0, 16.0]
    );
    assert_eq!(floats(lookup.textureinfo(s, "viewingmatrix")), wtc.to_vec());
    assert_eq!(floats(lookup.textureinfo(s, "projectionmatrix")).len(), 16);
    assert_eq!(lookup.textureinfo("no/such/map.tx", "resolution"), None);
    let _ = std::fs::remove_dir_all(&dir);
}
