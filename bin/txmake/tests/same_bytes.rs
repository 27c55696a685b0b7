//! Issue 24: the same input gives the same bytes. Each kind of texture file is made five times,
//! each by its own `txmake` process (the `exr` crate's attribute map is seeded per process, so
//! runs inside one process would not show a varying order), and every file must equal the first.
//! Before the header order was fixed, five `-shadow` runs gave three different files.

use illume_imageio::{DepthMatrices, Image, Quantize};
use std::path::{Path, PathBuf};
use std::process::Command;

const RUNS: usize = 5;

fn scratch(kind: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("same-bytes-{kind}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A smooth, asymmetric colour image, so every mip level has distinct data.
fn write_png(path: &Path, w: u32, h: u32, tint: f32) {
    let data = (0..h)
        .flat_map(|y| (0..w).flat_map(move |x| [x as f32 / w as f32, y as f32 / h as f32, tint]))
        .collect();
    let img = Image {
        width: w,
        height: h,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data,
    };
    let q = Quantize {
        one: 255,
        min: 0,
        max: 255,
        dither: 0.0,
    };
    illume_imageio::write_display(path, "png", &img, q, None).unwrap();
}

/// Runs `txmake args… <dir>/out<k>.tx` RUNS times and asserts the outputs are byte-identical.
fn assert_same_bytes(kind: &str, dir: &Path, args: &[String]) {
    let mut first: Option<Vec<u8>> = None;
    for k in 0..RUNS {
        let out = dir.join(format!("out{k}.tx"));
        let o = Command::new(env!("CARGO_BIN_EXE_txmake"))
            .args(args)
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{kind}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let bytes = std::fs::read(&out).unwrap();
        // The custom attributes are in the header: the test means nothing without them.
        assert!(
            bytes.windows(13).any(|w| w == b"textureformat"),
            "{kind}: no textureformat attribute"
        );
        match &first {
            None => first = Some(bytes),
            Some(f) => {
                let at = f.iter().zip(&bytes).position(|(a, b)| a != b);
                assert!(
                    *f == bytes,
                    "{kind}: run {k} wrote different bytes (lengths {} and {}, first difference at {at:?})",
                    f.len(),
                    bytes.len()
                );
            }
        }
    }
}

fn path_string(p: PathBuf) -> String {
    p.to_str().unwrap().to_string()
}

#[test]
fn plain_texture_is_the_same_bytes_every_run() {
    let dir = scratch("plain");
    write_png(&dir.join("in.png"), 40, 24, 0.3);
    let args = ["-smode", "periodic", "-filter", "gaussian"].map(String::from);
    let mut args = args.to_vec();
    args.push(path_string(dir.join("in.png")));
    assert_same_bytes("plain", &dir, &args);
}

#[test]
fn cube_environment_is_the_same_bytes_every_run() {
    let dir = scratch("envcube");
    let mut args = vec!["-envcube".to_string()];
    for (k, face) in ["px", "nx", "py", "ny", "pz", "nz"].iter().enumerate() {
        let p = dir.join(format!("{face}.png"));
        write_png(&p, 16, 16, k as f32 / 5.0);
        args.push(path_string(p));
    }
    assert_same_bytes("envcube", &dir, &args);
}

#[test]
fn latlong_environment_is_the_same_bytes_every_run() {
    let dir = scratch("envlatl");
    write_png(&dir.join("sky.png"), 64, 32, 0.8);
    let args = ["-envlatl".to_string(), path_string(dir.join("sky.png"))];
    assert_same_bytes("envlatl", &dir, &args);
}

#[test]
fn shadow_map_is_the_same_bytes_every_run() {
    let dir = scratch("shadow");
    let identity: [f32; 16] = std::array::from_fn(|i| if i % 5 == 0 { 1.0 } else { 0.0 });
    let depth = Image {
        width: 24,
        height: 16,
        channels: vec!["z".into()],
        data: (0..24 * 16).map(|i| 2.0 + (i % 7) as f32).collect(),
    };
    let z = dir.join("depth.z");
    let matrices = DepthMatrices {
        world_to_screen: identity,
        world_to_camera: identity,
    };
    illume_imageio::write_zfile(&z, &depth, &matrices).unwrap();
    let args = ["-shadow".to_string(), path_string(z)];
    assert_same_bytes("shadow", &dir, &args);
}
