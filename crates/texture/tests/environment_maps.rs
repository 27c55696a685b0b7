//! Cube-face environments: Table 9.1 orientation through txmake's builder, and seamlessness.

use glam::Vec3;
use illume_imageio::Image;
use illume_texture::cubeface::TABLE_9_1;
use illume_texture::{
    make_cube_face_environment, LookupOptions, MakeOptions, PixelFormat, TextureCache,
};
use std::path::PathBuf;

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-texture-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn image(w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) -> Image {
    let mut data = Vec::with_capacity((w * h * 3) as usize);
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

/// Face k of a Table 9.1 set: pixel (x, y) of a square 90° camera looks along
/// view + sx·right + sy·up with sx, sy the screen position of the pixel centre.
fn face_pixel_direction(k: usize, x: u32, y: u32, n: u32) -> Vec3 {
    let (view, up, right) = TABLE_9_1[k];
    let sx = (x as f32 + 0.5) / n as f32 * 2.0 - 1.0;
    let sy = 1.0 - (y as f32 + 0.5) / n as f32 * 2.0;
    view + right * sx + up * sy
}

fn point(d: Vec3) -> [Vec3; 4] {
    [d; 4]
}

fn solid_cube(path: &std::path::Path) {
    let faces: Vec<Image> = (0..6)
        .map(|k| {
            image(32, 32, |_, _| {
                [(k + 1) as f32 / 8.0, 0.25, 1.0 - k as f32 / 8.0]
            })
        })
        .collect();
    let refs: [&Image; 6] = std::array::from_fn(|k| &faces[k]);
    make_cube_face_environment(refs, path, &MakeOptions::default()).unwrap();
}

#[test]
fn axis_edge_and_corner_directions_return_the_table_9_1_face() {
    let path = temp("solid-cube.tx");
    solid_cube(&path);
    let cache = TextureCache::new(1 << 24);
    let opts = LookupOptions::default();
    // For every face: its axis, points near each of its 4 edges, and near its 4 corners.
    for (k, (view, up, right)) in TABLE_9_1.iter().enumerate() {
        let expect = (k + 1) as f32 / 8.0;
        let mut dirs = vec![*view];
        for (a, b) in [
            (0.9, 0.0),
            (-0.9, 0.0),
            (0.0, 0.9),
            (0.0, -0.9),
            (0.9, 0.9),
            (-0.9, 0.9),
            (0.9, -0.9),
            (-0.9, -0.9),
        ] {
            dirs.push(*view + *right * a + *up * b);
        }
        for d in dirs {
            let c = cache
                .environment(path.to_str().unwrap(), 0, 3, point(d), &opts)
                .unwrap();
            assert!(
                (c[0] - expect).abs() < 1e-3,
                "face {k} direction {d}: got {c:?}, expected red {expect}"
            );
            assert!(
                (c[2] - (1.0 - k as f32 / 8.0)).abs() < 1e-3,
                "face {k} direction {d}: {c:?}"
            );
        }
    }
}

#[test]
fn cube_lookup_reproduces_the_input_pixels_in_table_9_1_orientation() {
    // Each face encodes the screen position of its pixels: r = x/n, g = y/n, b = face index.
    let n = 64;
    let faces: Vec<Image> = (0..6)
        .map(|k| {
            image(n, n, |x, y| {
                [
                    (x as f32 + 0.5) / n as f32,
                    (y as f32 + 0.5) / n as f32,
                    k as f32 / 8.0,
                ]
            })
        })
        .collect();
    let refs: [&Image; 6] = std::array::from_fn(|k| &faces[k]);
    let path = temp("orient-cube.tx");
    let opts = MakeOptions {
        format: PixelFormat::Float,
        ..MakeOptions::default()
    };
    make_cube_face_environment(refs, &path, &opts).unwrap();
    let cache = TextureCache::new(1 << 24);
    for k in 0..6 {
        for &(x, y) in &[(5u32, 9u32), (32, 32), (50, 12), (10, 55)] {
            let d = face_pixel_direction(k, x, y, n);
            let c = cache
                .environment(
                    path.to_str().unwrap(),
                    0,
                    3,
                    point(d),
                    &LookupOptions::default(),
                )
                .unwrap();
            let want = [
                (x as f32 + 0.5) / n as f32,
                (y as f32 + 0.5) / n as f32,
                k as f32 / 8.0,
            ];
            for ch in 0..3 {
                assert!(
                    (c[ch] - want[ch]).abs() < 2e-2,
                    "face {k} pixel ({x},{y}): got {c:?}, want {want:?}"
                );
            }
        }
    }
}

/// A smooth function of direction rendered into six Table 9.1 faces.
fn gradient_cube(path: &std::path::Path, n: u32) {
    let f = |d: Vec3| {
        let d = d.normalize();
        [
            0.5 + 0.4 * d.x,
            0.5 + 0.3 * d.y + 0.1 * d.x * d.z,
            0.5 + 0.4 * d.z,
        ]
    };
    let faces: Vec<Image> = (0..6)
        .map(|k| image(n, n, |x, y| f(face_pixel_direction(k, x, y, n))))
        .collect();
    let refs: [&Image; 6] = std::array::from_fn(|k| &faces[k]);
    let opts = MakeOptions {
        format: PixelFormat::Float,
        ..MakeOptions::default()
    };
    make_cube_face_environment(refs, path, &opts).unwrap();
}

#[test]
fn gradient_environment_has_no_seam_across_any_edge_or_corner_at_any_blur() {
    let path = temp("gradient-cube.tx");
    gradient_cube(&path, 64);
    let cache = TextureCache::new(1 << 26);
    let name = path.to_str().unwrap();
    // Points on all 12 edges (two axes at ±1, the third varying) and at all 8 corners.
    let mut edge_points = Vec::new();
    for i in 0..3 {
        let (j, l) = ((i + 1) % 3, (i + 2) % 3);
        for sj in [-1.0f32, 1.0] {
            for sl in [-1.0f32, 1.0] {
                for v in [-0.6f32, 0.1, 0.77] {
                    let mut p = [0.0f32; 3];
                    p[j] = sj;
                    p[l] = sl;
                    p[i] = v;
                    edge_points.push(Vec3::from(p));
                }
            }
        }
    }
    for sx in [-1.0f32, 1.0] {
        for sy in [-1.0f32, 1.0] {
            for sz in [-1.0f32, 1.0] {
                edge_points.push(Vec3::new(sx, sy, sz));
            }
        }
    }
    let eps = 2e-4;
    let mut worst = 0.0f32;
    for blur in [0.0f32, 0.01, 0.05, 0.2, 0.6] {
        let opts = LookupOptions {
            blur,
            ..LookupOptions::default()
        };
        for p in &edge_points {
            let p = p.normalize();
            // Nudge into each neighbouring face: along every axis the point is extreme in.
            let mut values = Vec::new();
            for axis in 0..3 {
                for s in [-1.0f32, 1.0] {
                    let mut off = [0.0f32; 3];
                    off[axis] = s * eps;
                    let d = (p + Vec3::from(off)).normalize();
                    values.push(cache.environment(name, 0, 3, point(d), &opts).unwrap());
                }
            }
            for a in &values {
                for b in &values {
                    for c in 0..3 {
                        worst = worst.max((a[c] - b[c]).abs());
                        assert!(
                            (a[c] - b[c]).abs() < 1e-3,
                            "blur {blur} at {p}: {a:?} vs {b:?}"
                        );
                    }
                }
            }
        }
    }
    eprintln!("largest jump across cube edges/corners: {worst:e}");
}

#[test]
fn blurred_environment_lookup_approaches_the_mean_of_the_sphere() {
    // The gradient's mean over the sphere is 0.5 in every channel (odd terms vanish).
    let path = temp("gradient-cube-mean.tx");
    gradient_cube(&path, 32);
    let cache = TextureCache::new(1 << 24);
    let sharp = cache
        .environment(
            path.to_str().unwrap(),
            0,
            3,
            point(Vec3::X),
            &LookupOptions::default(),
        )
        .unwrap();
    assert!((sharp[0] - 0.9).abs() < 5e-3, "{sharp:?}");
    let wide = LookupOptions {
        blur: 2.0,
        ..LookupOptions::default()
    };
    let c = cache
        .environment(path.to_str().unwrap(), 0, 3, point(Vec3::X), &wide)
        .unwrap();
    assert!(
        c[0] < sharp[0] - 0.1,
        "blur must pull +x toward the mean: {c:?}"
    );
}

#[test]
fn missing_environment_is_a_missing_error() {
    let cache = TextureCache::new(1 << 20);
    let err = cache.environment(
        "/nonexistent/env.tx",
        0,
        3,
        point(Vec3::X),
        &LookupOptions::default(),
    );
    assert!(matches!(
        err,
        Err(illume_texture::TextureError::Missing { .. })
    ));
}

#[test]
fn faces_wider_than_90_degrees_use_their_margin_and_keep_orientation() {
    // Faces rendered with a 100° camera: pixel (x,y) looks along view + tan(50°)(sx·right + sy·up).
    let n = 48;
    let fov = 100.0f32;
    let k_tan = (0.5 * fov.to_radians()).tan();
    let f = |d: Vec3| {
        let d = d.normalize();
        [0.5 + 0.4 * d.x, 0.5 + 0.4 * d.y, 0.5 + 0.4 * d.z]
    };
    let faces: Vec<Image> = (0..6)
        .map(|k| {
            image(n, n, |x, y| {
                let (view, up, right) = TABLE_9_1[k];
                let sx = ((x as f32 + 0.5) / n as f32 * 2.0 - 1.0) * k_tan;
                let sy = (1.0 - (y as f32 + 0.5) / n as f32 * 2.0) * k_tan;
                f(view + right * sx + up * sy)
            })
        })
        .collect();
    let refs: [&Image; 6] = std::array::from_fn(|k| &faces[k]);
    let path = temp("wide-cube.tx");
    let opts = MakeOptions {
        format: PixelFormat::Float,
        fov,
        ..MakeOptions::default()
    };
    make_cube_face_environment(refs, &path, &opts).unwrap();
    let cache = TextureCache::new(1 << 24);
    for d in [
        Vec3::X,
        Vec3::new(1.0, 0.99, -0.98),
        Vec3::new(-0.3, 1.0, 0.999),
        Vec3::new(0.2, -0.7, -1.0),
        Vec3::new(1.0, 1.0, 1.0),
    ] {
        let c = cache
            .environment(
                path.to_str().unwrap(),
                0,
                3,
                point(d),
                &LookupOptions::default(),
            )
            .unwrap();
        let want = f(d);
        for ch in 0..3 {
            assert!(
                (c[ch] - want[ch]).abs() < 3e-3,
                "{d}: got {c:?}, want {want:?}"
            );
        }
    }
}

#[test]
fn latlong_environment_returns_the_pixel_of_each_direction() {
    use illume_texture::{latlong_direction, make_latlong_environment};
    let (w, h) = (128u32, 64u32);
    let f = |d: Vec3| [0.5 + 0.4 * d.x, 0.5 + 0.4 * d.y, 0.5 + 0.4 * d.z];
    let img = image(w, h, |x, y| {
        f(latlong_direction(
            (x as f32 + 0.5) / w as f32,
            (y as f32 + 0.5) / h as f32,
        ))
    });
    let path = temp("latlong.tx");
    let opts = MakeOptions {
        format: PixelFormat::Float,
        ..MakeOptions::default()
    };
    make_latlong_environment(&img, &path, &opts).unwrap();
    let cache = TextureCache::new(1 << 24);
    let info = cache.info(path.to_str().unwrap()).unwrap();
    assert_eq!(info.kind, illume_texture::TextureKind::LatLong);
    for d in [
        Vec3::X,
        Vec3::new(0.3, -0.8, 0.2),
        Vec3::new(-1.0, 0.01, -0.5),
        Vec3::new(0.1, 0.2, 0.9),
    ] {
        let c = cache
            .environment(
                path.to_str().unwrap(),
                0,
                3,
                point(d),
                &LookupOptions::default(),
            )
            .unwrap();
        let want = f(d.normalize());
        for ch in 0..3 {
            assert!(
                (c[ch] - want[ch]).abs() < 0.01,
                "{d}: got {c:?}, want {want:?}"
            );
        }
    }
}
