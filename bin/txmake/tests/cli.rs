//! `txmake` as users type it.

use illume_imageio::{DepthMatrices, Image, Quantize};
use illume_texture::{LookupOptions, TextureCache, TextureKind};
use std::path::PathBuf;
use std::process::Command;

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-txmake-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn txmake(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_txmake"))
        .args(args)
        .output()
        .unwrap()
}

fn png(name: &str, w: u32, h: u32, value: [f32; 3]) -> String {
    let img = Image {
        width: w,
        height: h,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data: (0..w * h).flat_map(|_| value).collect(),
    };
    let p = temp(name);
    let q = Quantize {
        one: 255,
        min: 0,
        max: 255,
        dither: 0.0,
    };
    illume_imageio::write_display(&p, "png", &img, q, None).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn plain_texture_from_png_with_prman_options() {
    let input = png("in.png", 48, 20, [1.0, 0.5, 0.0]);
    let out = temp("in.tx");
    let o = txmake(&[
        "-smode",
        "periodic",
        "-tmode",
        "clamp",
        "-filter",
        "gaussian",
        "-filterwidth",
        "2",
        "-resize",
        "up-",
        &input,
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cache = TextureCache::new(1 << 20);
    let info = cache.info(out.to_str().unwrap()).unwrap();
    assert_eq!(
        (info.kind, info.width, info.height),
        (TextureKind::Plain, 64, 32)
    );
    let c = cache
        .texture(
            out.to_str().unwrap(),
            0,
            3,
            [[0.3, 0.6]; 4],
            &LookupOptions::default(),
        )
        .unwrap();
    assert!(
        (c[0] - 1.0).abs() < 2e-3 && (c[1] - 128.0 / 255.0).abs() < 3e-3 && c[2].abs() < 1e-3,
        "{c:?}"
    );
}

#[test]
fn envcube_from_six_faces_and_newer_skips_up_to_date_output() {
    let names = ["px", "nx", "py", "ny", "pz", "nz"];
    let faces: Vec<String> = names
        .iter()
        .enumerate()
        .map(|(k, n)| png(&format!("{n}.png"), 16, 16, [k as f32 / 5.0, 0.5, 0.5]))
        .collect();
    let out = temp("env.tx");
    let mut args: Vec<&str> = vec!["-envcube"];
    args.extend(faces.iter().map(|s| s.as_str()));
    args.push(out.to_str().unwrap());
    let o = txmake(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cache = TextureCache::new(1 << 20);
    assert_eq!(
        cache.info(out.to_str().unwrap()).unwrap().kind,
        TextureKind::Cube
    );
    let c = cache
        .environment(
            out.to_str().unwrap(),
            0,
            1,
            [glam::Vec3::NEG_Y; 4],
            &LookupOptions::default(),
        )
        .unwrap();
    assert!((c[0] - 0.6).abs() < 3e-3, "ny face is the 4th: {c:?}");
    // -newer: output is newer than the inputs → nothing is rewritten.
    let before = std::fs::metadata(&out).unwrap().modified().unwrap();
    let mut newer = vec!["-newer", "-v"];
    newer.extend(args.iter());
    let o = txmake(&newer);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("up to date"));
    assert_eq!(std::fs::metadata(&out).unwrap().modified().unwrap(), before);
}

#[test]
fn shadow_from_zfile() {
    let mut m = [0.0f32; 16];
    for i in 0..4 {
        m[i * 5] = 1.0;
    }
    let depth = Image {
        width: 8,
        height: 8,
        channels: vec!["z".into()],
        data: vec![3.0; 64],
    };
    let z = temp("shadow.z");
    illume_imageio::write_zfile(
        &z,
        &depth,
        &DepthMatrices {
            world_to_screen: m,
            world_to_camera: m,
        },
    )
    .unwrap();
    let sm = temp("shadow.sm");
    let o = txmake(&["-shadow", z.to_str().unwrap(), sm.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cache = TextureCache::new(1 << 20);
    assert_eq!(
        cache.info(sm.to_str().unwrap()).unwrap().kind,
        TextureKind::Shadow
    );
    let behind = glam::Vec3::new(0.1, 0.1, 4.0);
    let opts = LookupOptions {
        bias: 0.01,
        ..LookupOptions::default()
    };
    assert_eq!(
        cache
            .shadow(sm.to_str().unwrap(), [behind; 4], &opts)
            .unwrap(),
        1.0
    );
    let front = glam::Vec3::new(0.1, 0.1, 2.0);
    assert_eq!(
        cache
            .shadow(sm.to_str().unwrap(), [front; 4], &opts)
            .unwrap(),
        0.0
    );
}

#[test]
fn usage_errors_exit_2_and_build_errors_exit_1() {
    assert_eq!(txmake(&[]).status.code(), Some(2));
    assert_eq!(
        txmake(&["-mode", "sideways", "a", "b"]).status.code(),
        Some(2)
    );
    assert_eq!(txmake(&["-envcube", "a", "b"]).status.code(), Some(2));
    let o = txmake(&["/no/such/input.tif", temp("never.tx").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("/no/such/input.tif"));
}
