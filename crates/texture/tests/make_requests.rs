//! The RIB Make* requests produce the same kinds of files `txmake` does.

use illume_imageio::{write_display, write_zfile, DepthMatrices, Image, Quantize};
use illume_rib::Request;
use illume_texture::{make_from_request, TextureCache, TextureError, TextureKind, WrapMode};

fn dir() -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("illume-make-req-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &std::path::Path) -> String {
    p.to_str().unwrap().to_string()
}

#[test]
fn make_texture_request_keeps_wrap_modes_and_values() {
    let d = dir();
    let png = d.join("grey.png");
    let image = Image {
        width: 8,
        height: 8,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data: vec![0.5; 192],
    };
    write_display(
        &png,
        "png",
        &image,
        Quantize {
            dither: 0.0,
            ..Quantize::RGBA_DEFAULT
        },
        None,
    )
    .unwrap();
    let tx = d.join("grey.tx");
    let req = Request::MakeTexture {
        picture: s(&png),
        texture: s(&tx),
        swrap: "periodic".into(),
        twrap: "clamp".into(),
        filter: "gaussian".into(),
        swidth: 2.0,
        twidth: 2.0,
        params: vec![],
    };
    assert!(make_from_request(&req).unwrap().is_empty());
    let cache = TextureCache::new(1 << 20);
    let info = cache.info(tx.to_str().unwrap()).unwrap();
    assert_eq!(info.kind, TextureKind::Plain);
    assert_eq!(info.wrap, [WrapMode::Periodic, WrapMode::Clamp]);
    let st = [[0.4, 0.4], [0.5, 0.4], [0.4, 0.5], [0.5, 0.5]];
    let v = cache
        .texture(tx.to_str().unwrap(), 0, 3, st, &Default::default())
        .unwrap();
    // 8-bit PNG of 0.5 without dither rounds to 128/255.
    assert!((v[0] - 128.0 / 255.0).abs() < 2e-3, "{v:?}");
}

#[test]
fn make_shadow_request_reads_a_zfile_and_writes_a_shadow_map_even_in_place() {
    let d = dir();
    let z = d.join("depth.z");
    let image = Image {
        width: 16,
        height: 16,
        channels: vec!["z".into()],
        data: vec![3.0; 256],
    };
    let identity = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    let m = DepthMatrices {
        world_to_screen: identity,
        world_to_camera: identity,
    };
    write_zfile(&z, &image, &m).unwrap();
    let sm = d.join("depth.sm");
    let req = Request::MakeShadow {
        picture: s(&z),
        texture: s(&sm),
        params: vec![],
    };
    make_from_request(&req).unwrap();
    let cache = TextureCache::new(1 << 20);
    assert_eq!(
        cache.info(sm.to_str().unwrap()).unwrap().kind,
        TextureKind::Shadow
    );

    // Output named like the input (the aqsis corpus does this): the input is read first.
    let same = Request::MakeShadow {
        picture: s(&z),
        texture: s(&z),
        params: vec![],
    };
    make_from_request(&same).unwrap();
    assert_eq!(
        TextureCache::new(1 << 20)
            .info(z.to_str().unwrap())
            .unwrap()
            .kind,
        TextureKind::Shadow
    );
}

#[test]
fn missing_picture_is_a_missing_error_and_make_bump_warns() {
    let req = Request::MakeBump {
        picture: "no/such/file.tif".into(),
        texture: "never.tx".into(),
        swrap: "black".into(),
        twrap: "black".into(),
        filter: "box".into(),
        swidth: 1.0,
        twidth: 1.0,
        params: vec![],
    };
    assert!(matches!(
        make_from_request(&req),
        Err(TextureError::Missing { .. })
    ));
    assert!(!std::path::Path::new("never.tx").exists());
}
