//! Issue 24: texture files made while rendering are the same bytes on every run. One RIB makes
//! every kind the `Make*` requests and `Display "shadow"` write; `render` runs it five times,
//! each in its own process and directory (the `exr` crate's attribute map is seeded per process),
//! and every texture file must equal the first run's.
use std::path::{Path, PathBuf};
use std::process::Command;

const RUNS: usize = 5;

/// A small depth pass and colour frame (its image is the `Make*` input), the `Make*` requests
/// between frames (frames render in file order), and a frame whose display is a shadow map.
const SCENE: &str = r#"
FrameBegin 1
  Format 32 24 1
  Display "depth.z" "zfile" "z"
  Display "+picture.tif" "tiff" "rgb"
  Projection "perspective" "fov" [40]
  Translate 0 0 4
  WorldBegin
    LightSource "ambientlight" 1 "intensity" [1]
    Surface "matte"
    Color [0.9 0.4 0.2]
    Sphere 1 -1 1 360
    Color [0.2 0.5 0.9]
    Polygon "P" [-3 -3 1  3 -3 1  3 3 1  -3 3 1]
  WorldEnd
FrameEnd
MakeShadow "depth.z" "made.sm"
MakeTexture "picture.tif" "made.tx" "periodic" "clamp" "gaussian" 2 2
MakeLatLongEnvironment "picture.tif" "latlong.tx" "box" 1 1
MakeCubeFaceEnvironment "picture.tif" "picture.tif" "picture.tif" "picture.tif" "picture.tif" "picture.tif" "cube.tx" 95 "triangle" 2 2
FrameBegin 2
  Format 24 24 1
  Display "direct.sm" "shadow" "z"
  Projection "perspective" "fov" [50]
  Translate 0 0 4
  WorldBegin
    Sphere 1 -1 1 360
    Polygon "P" [-3 -3 1  3 -3 1  3 3 1  -3 3 1]
  WorldEnd
FrameEnd
"#;

const MADE: [&str; 5] = ["made.sm", "made.tx", "latlong.tx", "cube.tx", "direct.sm"];

fn run(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("scene.rib"), SCENE).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_render"))
        .args(["-q", "scene.rib"])
        .current_dir(dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}

#[test]
fn make_requests_and_shadow_displays_write_the_same_bytes_every_run() {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("render-same-bytes");
    let _ = std::fs::remove_dir_all(&root);
    let dirs: Vec<PathBuf> = (0..RUNS).map(|k| root.join(format!("run{k}"))).collect();
    for d in &dirs {
        run(d);
    }
    let mut differing = Vec::new();
    for name in MADE {
        let first = std::fs::read(dirs[0].join(name)).unwrap();
        assert!(
            first.windows(13).any(|w| w == b"textureformat"),
            "{name}: no textureformat attribute"
        );
        for (k, d) in dirs.iter().enumerate().skip(1) {
            if std::fs::read(d.join(name)).unwrap() != first {
                differing.push(format!("{name} (run {k})"));
            }
        }
    }
    assert!(differing.is_empty(), "different bytes: {differing:?}");
    let _ = std::fs::remove_dir_all(&root);
}
