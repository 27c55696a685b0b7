//! Interoperability with OpenImageIO (`iinfo`) and OpenEXR (`exrenvmap`): skipped loudly when the
//! tools are not installed (Debian `openimageio-tools`, `openexr`), and failed under `CI=true`.

use glam::Vec3;
use illume_imageio::{DepthMatrices, Image};
use illume_texture::cubeface::TABLE_9_1;
use illume_texture::{
    make_cube_face_environment, make_shadow, make_texture, LookupOptions, MakeOptions, PixelFormat,
    TextureCache, WrapMode,
};
use std::path::{Path, PathBuf};
use std::process::Command;

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-texture-interop-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Whether `name` is installed; when not, the test skips loudly (a failure under `CI=true`).
fn tool(name: &str) -> bool {
    illume_testenv::require_tool(name).is_some()
}

fn iinfo(path: &Path) -> String {
    let out = Command::new("iinfo").arg("-v").arg(path).output().unwrap();
    assert!(
        out.status.success(),
        "iinfo failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn rgb(w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) -> Image {
    let mut data = Vec::new();
    for y in 0..h {
        for x in 0..w {
            data.extend_from_slice(&f(x, y));
        }
    }
    Image {
        width: w,
        height: h,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data,
    }
}

#[test]
fn iinfo_reads_our_texture_and_shadow_attributes() {
    if !tool("iinfo") {
        return;
    }
    let tx = temp("iinfo.tx");
    let opts = MakeOptions {
        wrap: [WrapMode::Periodic, WrapMode::Clamp],
        source: "checker.tif".into(),
        ..MakeOptions::default()
    };
    make_texture(
        &rgb(256, 128, |x, y| [((x + y) % 2) as f32, 0.5, 0.25]),
        &tx,
        &opts,
    )
    .unwrap();
    let text = iinfo(&tx);
    for want in [
        "256 x  128, 3 channel, half openexr",
        "MIP-map levels: 256x128 128x64 64x32 32x16 16x8 8x4 4x2 2x1 1x1",
        "tile size: 64 x 64",
        "textureformat: \"Plain Texture\"",
        "wrapmodes: \"periodic,clamp\"",
        "filter: \"box 1 1\"",
        "source: \"checker.tif\"",
    ] {
        assert!(text.contains(want), "iinfo -v lacks `{want}`:\n{text}");
    }
    let sm = temp("iinfo.sm");
    let mut m = [0.0f32; 16];
    for i in 0..4 {
        m[i * 5] = 2.0;
    }
    m[15] = 1.0;
    let depth = Image {
        width: 32,
        height: 32,
        channels: vec!["z".into()],
        data: (0..1024).map(|i| 1.0 + i as f32 / 1024.0).collect(),
    };
    let matrices = DepthMatrices {
        world_to_screen: m,
        world_to_camera: m,
    };
    make_shadow(&depth, &matrices, &sm, &MakeOptions::default()).unwrap();
    let text = iinfo(&sm);
    for want in [
        "32 x   32, 2 channel, float openexr",
        "channel list: Z, Zmax",
        "textureformat: \"Shadow\"",
        "worldToCamera: 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1",
        "worldToNDC: 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 2, 0, 0.5, 0.5, 0, 1",
    ] {
        assert!(text.contains(want), "iinfo -v lacks `{want}`:\n{text}");
    }
}

fn face_pixel_direction(k: usize, x: u32, y: u32, n: u32) -> Vec3 {
    let (view, up, right) = TABLE_9_1[k];
    let sx = (x as f32 + 0.5) / n as f32 * 2.0 - 1.0;
    let sy = 1.0 - (y as f32 + 0.5) / n as f32 * 2.0;
    view + right * sx + up * sy
}

#[test]
fn exrenvmap_latlong_of_our_cube_agrees_with_our_lookups() {
    if !tool("exrenvmap") {
        return;
    }
    let n = 64;
    // Smooth and asymmetric in every axis, so any face flip or rotation shows.
    let f = |d: Vec3| {
        let d = d.normalize();
        [
            0.5 + 0.4 * d.x,
            0.5 + 0.3 * d.y + 0.1 * d.z,
            0.5 + 0.35 * d.z - 0.05 * d.x,
        ]
    };
    let faces: Vec<Image> = (0..6)
        .map(|k| rgb(n, n, |x, y| f(face_pixel_direction(k, x, y, n))))
        .collect();
    let refs: [&Image; 6] = std::array::from_fn(|k| &faces[k]);
    let cube = temp("interop-cube.tx");
    make_cube_face_environment(
        refs,
        &cube,
        &MakeOptions {
            format: PixelFormat::Float,
            ..MakeOptions::default()
        },
    )
    .unwrap();
    let ll = temp("interop-latlong.exr");
    let out = Command::new("exrenvmap")
        .args(["-l", "-w", "128"])
        .arg(&cube)
        .arg(&ll)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "exrenvmap failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    // exrenvmap copies our header's chunkCount (a tiled-file count) into its scan-line output,
    // which strict readers reject; when oiiotool is present, re-save through it first.
    let clean = temp("interop-latlong-clean.exr");
    let img = match illume_imageio::read_image(&ll) {
        Ok(img) => img,
        Err(e) => {
            eprintln!("exrenvmap output unreadable ({e}): cleaning it with oiiotool");
            if !tool("oiiotool") {
                return;
            }
            let st = Command::new("oiiotool")
                .arg(&ll)
                .args(["-d", "float", "--eraseattrib", "openexr:chunkCount", "-o"])
                .arg(&clean)
                .status()
                .unwrap();
            assert!(st.success());
            illume_imageio::read_image(&clean).unwrap()
        }
    };
    let (w, h) = (img.width as usize, img.height as usize);
    let chan = |name: &str| img.channels.iter().position(|c| c == name).unwrap();
    let (cr, cg, cb) = (chan("r"), chan("g"), chan("b"));
    let cache = TextureCache::new(1 << 24);
    let mut worst = 0.0f32;
    for y in 0..h {
        for x in 0..w {
            // OpenEXR LatLongMap::direction for pixel (x, y).
            let lat = -std::f32::consts::PI * (y as f32 / (h - 1) as f32 - 0.5);
            let lon = -2.0 * std::f32::consts::PI * (x as f32 / (w - 1) as f32 - 0.5);
            let d = Vec3::new(lon.sin() * lat.cos(), lat.sin(), lon.cos() * lat.cos());
            let ours = cache
                .environment(
                    cube.to_str().unwrap(),
                    0,
                    3,
                    [d; 4],
                    &LookupOptions::default(),
                )
                .unwrap();
            let i = (y * w + x) * img.channels.len();
            let theirs = [img.data[i + cr], img.data[i + cg], img.data[i + cb]];
            for c in 0..3 {
                worst = worst.max((ours[c] - theirs[c]).abs());
            }
        }
    }
    eprintln!("largest |ours - exrenvmap| = {worst:e}");
    assert!(
        worst <= 1.0 / 255.0,
        "largest difference {worst} exceeds 1/255"
    );
}

#[test]
fn maketx_shadow_of_our_zfile_gives_the_same_shadows_as_our_shadow_map() {
    if !tool("maketx") {
        return;
    }
    // Light at the origin looking down +z, 90° frustum; an occluder square in front of a floor.
    let n = 64u32;
    let screen = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, -1.0, 0.0,
    ];
    let mut identity = [0.0f32; 16];
    for i in 0..4 {
        identity[i * 5] = 1.0;
    }
    let matrices = DepthMatrices {
        world_to_screen: screen,
        world_to_camera: identity,
    };
    let data = (0..n * n)
        .map(|i| {
            let sx = ((i % n) as f32 + 0.5) / n as f32 * 2.0 - 1.0;
            let sy = 1.0 - ((i / n) as f32 + 0.5) / n as f32 * 2.0;
            if sx.abs() < 0.3 && sy.abs() < 0.3 {
                2.0
            } else {
                8.0
            }
        })
        .collect();
    let depth = Image {
        width: n,
        height: n,
        channels: vec!["z".into()],
        data,
    };
    let z = temp("maketx.z");
    illume_imageio::write_zfile(&z, &depth, &matrices).unwrap();
    let theirs = temp("maketx-shadow.exr");
    let out = Command::new("maketx")
        .arg("--shadow")
        .arg(&z)
        .arg("-o")
        .arg(&theirs)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "maketx --shadow failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (img, m) = illume_imageio::read_zfile(&z).unwrap();
    let ours = temp("ours-shadow.sm");
    make_shadow(&img, &m, &ours, &MakeOptions::default()).unwrap();
    let cache = TextureCache::new(1 << 24);
    let opts = LookupOptions {
        bias: 0.05,
        blur: 0.05,
        samples: 64,
        ..LookupOptions::default()
    };
    for &(sx, sy) in &[
        (0.0f32, 0.0f32),
        (0.5, 0.5),
        (0.3, 0.0),
        (-0.31, 0.2),
        (0.9, -0.9),
    ] {
        let p = Vec3::new(sx * 8.0, sy * 8.0, 8.0);
        let a = cache.shadow(ours.to_str().unwrap(), [p; 4], &opts).unwrap();
        let b = cache
            .shadow(theirs.to_str().unwrap(), [p; 4], &opts)
            .unwrap();
        assert!((a - b).abs() < 1e-6, "({sx},{sy}): ours {a}, maketx {b}");
    }
    let centre = Vec3::new(0.0, 0.0, 8.0);
    assert_eq!(
        cache
            .shadow(theirs.to_str().unwrap(), [centre; 4], &opts)
            .unwrap(),
        1.0
    );
}

#[test]
fn textures_made_by_maketx_are_read() {
    if !tool("maketx") {
        return;
    }
    // 4×4-texel checker, 64×32: a tiled EXR and a tiled TIFF from maketx, and our own .tx.
    let img = rgb(64, 32, |x, y| {
        if (x / 4 + y / 4) % 2 == 0 {
            [1.0, 0.5, 0.0]
        } else {
            [0.0, 0.25, 1.0]
        }
    });
    let src = temp("maketx-src.exr");
    illume_imageio::write_display(
        &src,
        "exr",
        &img,
        illume_imageio::Quantize {
            one: 0,
            min: 0,
            max: 0,
            dither: 0.0,
        },
        None,
    )
    .unwrap();
    let ours = temp("maketx-ours.tx");
    make_texture(&img, &ours, &MakeOptions::default()).unwrap();
    let cache = TextureCache::new(1 << 24);
    for ext in ["exr", "tx"] {
        let theirs = temp(&format!("maketx-out.{ext}"));
        let out = Command::new("maketx")
            .arg(&src)
            .arg("-o")
            .arg(&theirs)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "maketx failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        for &(s, t) in &[(0.03f32, 0.05f32), (0.5, 0.5), (0.77, 0.9)] {
            let a = cache
                .texture(
                    ours.to_str().unwrap(),
                    0,
                    3,
                    [[s, t]; 4],
                    &LookupOptions::default(),
                )
                .unwrap();
            let b = cache
                .texture(
                    theirs.to_str().unwrap(),
                    0,
                    3,
                    [[s, t]; 4],
                    &LookupOptions::default(),
                )
                .unwrap();
            for c in 0..3 {
                assert!(
                    (a[c] - b[c]).abs() < 1.0 / 255.0,
                    "{ext} at ({s},{t}): ours {a:?}, maketx {b:?}"
                );
            }
        }
        // Minified to one texel per checker period: both pyramids hold the average.
        let wide = [
            [0.4, 0.4],
            [0.4 + 8.0 / 64.0, 0.4],
            [0.4, 0.4 + 8.0 / 32.0],
            [0.4 + 8.0 / 64.0, 0.4 + 8.0 / 32.0],
        ];
        let b = cache
            .texture(
                theirs.to_str().unwrap(),
                0,
                3,
                wide,
                &LookupOptions::default(),
            )
            .unwrap();
        assert!(
            (b[0] - 0.5).abs() < 0.03 && (b[2] - 0.5).abs() < 0.03,
            "{ext}: {b:?}"
        );
    }
}
