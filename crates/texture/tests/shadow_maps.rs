//! Shadow maps: zfile → `.sm` → percentage-closer lookups against closed-form scenes.

use glam::Vec3;
use illume_imageio::{DepthMatrices, Image};
use illume_texture::{make_shadow, LookupOptions, MakeOptions, TextureCache};
use std::path::PathBuf;

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-texture-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Light at the world origin looking down +z with a 90° square frustum: world = camera,
/// screen = (x/z, y/z) (RIB row-vector order: w' = z).
fn matrices() -> DepthMatrices {
    let mut identity = [0.0f32; 16];
    for i in 0..4 {
        identity[i * 5] = 1.0;
    }
    DepthMatrices {
        world_to_screen: [
            1.0, 0.0, 0.0, 0.0, //
            0.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, 1.0, 1.0, //
            0.0, 0.0, -1.0, 0.0,
        ],
        world_to_camera: identity,
    }
}

/// Renders a depth map of `depth(sx, sy)` (screen coordinates, y up) through a zfile round trip.
fn shadow_map(name: &str, n: u32, depth: impl Fn(f32, f32) -> f32) -> PathBuf {
    let mut data = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let sx = (i as f32 + 0.5) / n as f32 * 2.0 - 1.0;
            let sy = 1.0 - (j as f32 + 0.5) / n as f32 * 2.0;
            data.push(depth(sx, sy));
        }
    }
    let img = Image {
        width: n,
        height: n,
        channels: vec!["z".into()],
        data,
    };
    let z = temp(&format!("{name}.z"));
    illume_imageio::write_zfile(&z, &img, &matrices()).unwrap();
    let (img, m) = illume_imageio::read_zfile(&z).unwrap();
    let sm = temp(&format!("{name}.sm"));
    make_shadow(&img, &m, &sm, &MakeOptions::default()).unwrap();
    sm
}

fn on_screen(sx: f32, sy: f32, z: f32) -> Vec3 {
    Vec3::new(sx * z, sy * z, z)
}

#[test]
fn plane_with_equal_depths_and_bias_is_fully_lit() {
    let sm = shadow_map("flat", 64, |_, _| 5.0);
    let cache = TextureCache::new(1 << 24);
    let name = sm.to_str().unwrap();
    let lit = LookupOptions {
        bias: 0.01,
        blur: 0.05,
        samples: 16,
        ..LookupOptions::default()
    };
    let inside = LookupOptions { bias: -0.01, ..lit };
    for &(sx, sy) in &[(0.0, 0.0), (0.5, -0.3), (-0.8, 0.8), (0.21, 0.33)] {
        let p = on_screen(sx, sy, 5.0);
        assert_eq!(
            cache.shadow(name, [p; 4], &lit).unwrap(),
            0.0,
            "({sx},{sy})"
        );
        // Pushed behind its own depth it is fully shadowed: the comparison is live.
        assert_eq!(
            cache.shadow(name, [p; 4], &inside).unwrap(),
            1.0,
            "({sx},{sy})"
        );
    }
}

#[test]
fn tilted_plane_needs_bias_to_escape_self_shadowing() {
    // z = 5 + 0.05·x in world space, seen at screen x: z = 5 / (1 - 0.05 sx).
    let sm = shadow_map("tilted", 64, |sx, _| 5.0 / (1.0 - 0.05 * sx));
    let cache = TextureCache::new(1 << 24);
    let name = sm.to_str().unwrap();
    let (mut with_bias, mut without) = (0.0f32, 0.0f32);
    let count = 200;
    for k in 0..count {
        let sx = ((k * 37) % count) as f32 / count as f32 * 1.6 - 0.8;
        let sy = ((k * 91) % count) as f32 / count as f32 * 1.6 - 0.8;
        let p = on_screen(sx, sy, 5.0 / (1.0 - 0.05 * sx));
        with_bias += cache
            .shadow(
                name,
                [p; 4],
                &LookupOptions {
                    bias: 0.01,
                    ..LookupOptions::default()
                },
            )
            .unwrap();
        without += cache
            .shadow(
                name,
                [p; 4],
                &LookupOptions {
                    bias: 0.0,
                    ..LookupOptions::default()
                },
            )
            .unwrap();
    }
    assert_eq!(with_bias, 0.0);
    assert!(
        without / count as f32 > 0.2,
        "unbiased self-shadowing expected, got {}",
        without / count as f32
    );
}

#[test]
fn occluder_shadow_matches_the_covered_fraction_of_the_footprint() {
    // Occluder square at depth 2 covering screen |x|,|y| < 0.2, floor at depth 8 elsewhere.
    let sm = shadow_map("occluder", 128, |sx, sy| {
        if sx.abs() < 0.2 && sy.abs() < 0.2 {
            2.0
        } else {
            8.0
        }
    });
    let cache = TextureCache::new(1 << 24);
    let name = sm.to_str().unwrap();
    let floor = |sx: f32, sy: f32| on_screen(sx, sy, 8.0);
    let opts = LookupOptions {
        bias: 0.05,
        ..LookupOptions::default()
    };
    assert_eq!(
        cache.shadow(name, [floor(0.0, 0.0); 4], &opts).unwrap(),
        1.0
    );
    assert_eq!(
        cache.shadow(name, [floor(0.6, 0.1); 4], &opts).unwrap(),
        0.0
    );
    // Blurred lookups across the occluder's right edge (screen x = 0.2 → NDC s = 0.6):
    // the footprint is an NDC box of width `blur`; the covered fraction is its part left of 0.6.
    let blur = 0.1f32;
    let wide = LookupOptions {
        blur,
        samples: 256,
        ..opts
    };
    for &s_centre in &[0.57f32, 0.6, 0.63, 0.52, 0.68] {
        let sx = 2.0 * s_centre - 1.0;
        let got = cache.shadow(name, [floor(sx, 0.0); 4], &wide).unwrap();
        // Occluder in NDC: s in (0.4, 0.6); texel-quantised edge at 0.6 exactly (128 texels).
        let covered = ((0.6 - (s_centre - blur / 2.0)) / blur).clamp(0.0, 1.0);
        assert!(
            (got - covered).abs() < 0.07,
            "s={s_centre}: got {got}, covered fraction {covered}"
        );
    }
    // Deterministic: the same lookup twice gives the same bits.
    let a = cache.shadow(name, [floor(0.2, 0.05); 4], &wide).unwrap();
    let b = cache.shadow(name, [floor(0.2, 0.05); 4], &wide).unwrap();
    assert_eq!(a.to_bits(), b.to_bits());
}

#[test]
fn shadow_lookup_on_a_plain_texture_is_a_kind_error() {
    let img = Image {
        width: 4,
        height: 4,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data: vec![0.5; 48],
    };
    let path = temp("not-a-shadow.tx");
    illume_texture::make_texture(&img, &path, &MakeOptions::default()).unwrap();
    let cache = TextureCache::new(1 << 20);
    let r = cache.shadow(
        path.to_str().unwrap(),
        [Vec3::Z; 4],
        &LookupOptions::default(),
    );
    assert!(
        matches!(r, Err(illume_texture::TextureError::WrongKind { .. })),
        "{r:?}"
    );
}

#[test]
fn disc_occluder_shadows_exactly_the_points_behind_it() {
    let sm = shadow_map("disc", 512, |sx, sy| {
        let r2 = sx * sx + sy * sy;
        if r2 < 0.25 {
            4.0 - (0.25 - r2).sqrt()
        } else {
            10.0
        }
    });
    let cache = TextureCache::new(64 * 1024); // tiny: evictions all the time

    let name = sm.to_str().unwrap();
    let opts = LookupOptions {
        bias: 0.01,
        ..LookupOptions::default()
    };
    let mut wrong = Vec::new();
    for j in 0..41 {
        for i in 0..41 {
            let (sx, sy) = (i as f32 / 20.0 - 1.0, j as f32 / 20.0 - 1.0);
            let r = (sx * sx + sy * sy).sqrt();
            if (r - 0.5).abs() < 0.02 || sx.abs() > 0.99 || sy.abs() > 0.99 {
                continue; // on the silhouette or the map's edge texels
            }
            let got = cache
                .shadow(name, [on_screen(sx, sy, 10.0); 4], &opts)
                .unwrap();
            let want = if r < 0.5 { 1.0 } else { 0.0 };
            if got != want {
                wrong.push((sx, sy, got));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "{} wrong, e.g. {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(8)]
    );
}
