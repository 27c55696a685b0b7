//! `farm` without a cluster: the scripts `submit --dry-run` prints (arrays, dependencies, crop
//! windows), the refusal to submit without `sbatch`, and `merge` — refusing an incomplete
//! frame, then writing displays bit-identical to a single full render from tiles rendered with
//! the exact crop windows the generated script would pass to `render`.
//! The same flow on a real (single-node) Slurm cluster is tests/farm/ci.sh, run by .ci/run.

use illume_ri::{Frame, Ri};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn farm(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_farm"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("illume-farm-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn turntable() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../rib/pipelines/farm/turntable.rib")
}

/// The text after `#### <path ending in name>` up to the next `####`.
fn section<'a>(dry: &'a str, name: &str) -> &'a str {
    let start = dry
        .find(&format!("{name}\n"))
        .unwrap_or_else(|| panic!("no section {name} in:\n{dry}"));
    let body = &dry[start + name.len() + 1..];
    &body[..body.find("\n####").map_or(body.len(), |e| e + 1)]
}

/// Tile table lines `  7) frames="--frames 1"; crop="0.25 0.5 0 0.25"; tile=tiles/... ;;`.
struct TileLine {
    index: usize,
    frame: Option<i32>,
    crop: [f32; 4],
    tile: String,
}

fn tile_lines(script: &str) -> Vec<TileLine> {
    script
        .lines()
        .filter_map(|l| {
            let (index, rest) = l.trim().split_once(") frames=\"")?;
            let (frames, rest) = rest.split_once("\"; crop=\"")?;
            let (crop, rest) = rest.split_once("\"; tile=")?;
            let tile = rest.trim_end_matches(";;").trim();
            let crop: Vec<f32> = crop.split(' ').map(|v| v.parse().unwrap()).collect();
            Some(TileLine {
                index: index.parse().ok()?,
                frame: frames.strip_prefix("--frames ").map(|n| n.parse().unwrap()),
                crop: [crop[0], crop[1], crop[2], crop[3]],
                tile: tile.to_string(),
            })
        })
        .collect()
}

fn sbatch_lines(dry: &str) -> Vec<String> {
    section(dry, "sbatch").lines().map(String::from).collect()
}

/// `Options::crop_pixels`: what `render --crop` makes of an NDC edge.
fn pixel(v: f32, res: u32) -> u32 {
    ((res as f32 * v).ceil().max(0.0) as u32).min(res)
}

#[test]
fn dry_run_prints_pass_tile_and_merge_arrays_with_afterok_dependencies() {
    let dir = temp_dir("dry");
    let job = dir.join("job");
    let out = farm(
        &[
            "submit",
            turntable().to_str().unwrap(),
            "--dry-run",
            "--jobdir",
            job.to_str().unwrap(),
        ],
        &dir,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dry = String::from_utf8(out.stdout).unwrap();
    assert!(!job.exists(), "a dry run wrote {}", job.display());
    let sb = sbatch_lines(&dry);
    assert_eq!(sb.len(), 3, "{sb:?}");
    assert!(
        sb[0].starts_with("passes_0=$(sbatch --parsable --array=0-2 "),
        "{}",
        sb[0]
    );
    assert!(!sb[0].contains("--dependency"));
    assert!(
        sb[1].starts_with(
            "tiles_0=$(sbatch --parsable --array=0-47 --dependency=afterok:$passes_0 "
        ),
        "{}",
        sb[1]
    );
    assert!(
        sb[2].starts_with("merge=$(sbatch --parsable --dependency=afterok:$tiles_0 "),
        "{}",
        sb[2]
    );

    // Each frame's depth pass renders whole (no Make*), then its own MakeShadow runs once.
    let passes = section(&dry, "scripts/passes.sh");
    assert!(passes.contains("#SBATCH --requeue"));
    for (n, depth) in [(1, 10), (2, 20), (3, 30)] {
        assert!(
            passes.contains(&format!("--no-make --frames {depth} \"$SCENE\"")),
            "pass {depth}"
        );
        let make = section(&dry, &format!("make/f000{n}.rib"));
        assert!(
            make.contains(&format!(
                "MakeShadow \"turntable_{n}.z\" \"turntable_{n}.sm\""
            )),
            "{make}"
        );
        assert_eq!(make.matches("\nMake").count(), 1, "{make}");
    }

    // 3 frames x 16 tiles whose crops, through render's own rounding, partition 128x96 once
    // per frame, and whose NDC edges cover [0,1]^2 exactly (first 0, last 1, shared inside).
    let tiles = section(&dry, "scripts/tiles.sh");
    assert!(tiles.contains("--no-make $frames --crop $crop --tile-out"));
    let lines = tile_lines(tiles);
    assert_eq!(lines.len(), 48);
    for frame in 1..=3 {
        let mine: Vec<&TileLine> = lines.iter().filter(|l| l.frame == Some(frame)).collect();
        assert_eq!(mine.len(), 16);
        let mut count = vec![0u32; 128 * 96];
        let mut area = 0.0f64;
        for l in &mine {
            let [x0, x1, y0, y1] = l.crop;
            area += f64::from(x1 - x0) * f64::from(y1 - y0);
            for y in pixel(y0, 96)..pixel(y1, 96) {
                for x in pixel(x0, 128)..pixel(x1, 128) {
                    count[(y * 128 + x) as usize] += 1;
                }
            }
        }
        assert!(
            count.iter().all(|&c| c == 1),
            "frame {frame}: a pixel is not in exactly one tile"
        );
        assert!(
            (area - 1.0).abs() < 1e-6,
            "frame {frame}: crops cover area {area}, not 1"
        );
        let xs: Vec<f32> = mine.iter().flat_map(|l| [l.crop[0], l.crop[1]]).collect();
        let ys: Vec<f32> = mine.iter().flat_map(|l| [l.crop[2], l.crop[3]]).collect();
        for v in [&xs, &ys] {
            assert_eq!(v.iter().cloned().fold(f32::MAX, f32::min), 0.0);
            assert_eq!(v.iter().cloned().fold(f32::MIN, f32::max), 1.0);
        }
    }
    // Indices are the array indices, 0..47 in order.
    assert!(lines.iter().enumerate().all(|(i, l)| l.index == i));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn big_arrays_split_at_max_array_size_and_resubmits_skip_finished_tiles() {
    let dir = temp_dir("split");
    let job = dir.join("job");
    // Tiles 0 and 1 of frame 1 already rendered (newer than the scene).
    for name in ["x0y0", "x1y0"] {
        let p = job.join("tiles/4x4/f0001").join(format!("{name}.tile"));
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, b"done").unwrap();
    }
    let out = farm(
        &[
            "submit",
            turntable().to_str().unwrap(),
            "--dry-run",
            "--jobdir",
            job.to_str().unwrap(),
            "--max-array-size",
            "20",
            "--frames",
            "1-3",
        ],
        &dir,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let sb = sbatch_lines(&String::from_utf8(out.stdout).unwrap());
    assert_eq!(sb.len(), 5, "{sb:?}");
    assert!(
        sb[1].starts_with(
            "tiles_0=$(sbatch --parsable --array=2-19 --dependency=afterok:$passes_0 "
        ),
        "{}",
        sb[1]
    );
    assert!(
        sb[2].starts_with("tiles_1=$(sbatch --parsable --array=0-19 --export=ALL,FARM_OFFSET=20 "),
        "{}",
        sb[2]
    );
    assert!(
        sb[3].starts_with("tiles_2=$(sbatch --parsable --array=0-7 --export=ALL,FARM_OFFSET=40 "),
        "{}",
        sb[3]
    );
    assert!(
        sb[4].contains("--dependency=afterok:$tiles_0:$tiles_1:$tiles_2 "),
        "{}",
        sb[4]
    );

    // A frame range selects beauty frames and brings their passes along.
    let out = farm(
        &[
            "submit",
            turntable().to_str().unwrap(),
            "--dry-run",
            "--jobdir",
            job.to_str().unwrap(),
            "--frames",
            "2",
        ],
        &dir,
    );
    let dry = String::from_utf8(out.stdout).unwrap();
    let sb = sbatch_lines(&dry);
    assert!(sb[0].contains("--array=0 "), "{}", sb[0]);
    assert!(sb[1].contains("--array=0-15 "), "{}", sb[1]);
    assert!(section(&dry, "scripts/passes.sh").contains("--frames 20 "));
    assert!(tile_lines(section(&dry, "scripts/tiles.sh"))
        .iter()
        .all(|l| l.frame == Some(2)));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn submit_without_sbatch_exits_2_and_writes_nothing() {
    let dir = temp_dir("nosbatch");
    let job = dir.join("job");
    let out = Command::new(env!("CARGO_BIN_EXE_farm"))
        .args([
            "submit",
            turntable().to_str().unwrap(),
            "--jobdir",
            job.to_str().unwrap(),
        ])
        .env("PATH", &dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("sbatch not found"), "{err}");
    assert!(!job.exists());
    let bad = farm(
        &[
            "submit",
            turntable().to_str().unwrap(),
            "--tiles",
            "4",
            "--dry-run",
        ],
        &dir,
    );
    assert_eq!(bad.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Two frames, a wide Gaussian filter (its margin crosses tile edges), 8-bit dithered TIFF and
/// float EXR with depth, and a float EXR of arbitrary output variables (issue 20): everything
/// that could differ between tiles and a full render.
const SCENE: &str = "FrameBegin 1\nFormat 45 31 1\nPixelSamples 2 2\nPixelFilter \"gaussian\" 3 3\n\
    Display \"a1.tif\" \"tiff\" \"rgba\"\nDisplay \"+a1.exr\" \"openexr\" \"rgbaz\"\n\
    Display \"+a1aov.exr\" \"openexr\" \"rgba,__diffuse,__specular,N,s\"\n\
    Projection \"perspective\" \"fov\" [40]\nWorldBegin\nTranslate 0 0 4\nSurface \"plastic\"\n\
    LightSource \"distantlight\" 1\nAttributeBegin Color [1 0.3 0.2] Sphere 1 -1 1 360 AttributeEnd\n\
    AttributeBegin Translate 1 0.5 1.5 Opacity [0.5 0.5 0.5] Sphere 0.6 -0.6 0.6 360 AttributeEnd\n\
    Polygon \"P\" [-3 -1 -1  3 -1 -1  3 -1 5  -3 -1 5]\nWorldEnd\nFrameEnd\n\
    FrameBegin 2\nFormat 45 31 1\nCropWindow 0.1 0.9 0.2 1\nDisplay \"a2.tif\" \"tiff\" \"rgb\"\n\
    Projection \"perspective\" \"fov\" [30]\nWorldBegin\nTranslate 0.2 0 4\nSurface \"matte\"\n\
    LightSource \"distantlight\" 1\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";

fn frames_of(scene: &Path, frame: Option<i32>, crop: Option<[f32; 4]>) -> Vec<Frame> {
    let mut ri = Ri::new();
    ri.set_crop_override(crop);
    ri.set_frame_range(frame.map(|n| (n, n)));
    for item in illume_rib::open(scene).unwrap() {
        ri.request(item.unwrap());
    }
    ri.finish();
    assert_eq!(ri.error_count(), 0);
    ri.take_frames()
}

#[test]
fn merge_refuses_incomplete_frames_then_matches_a_full_render_bit_for_bit() {
    let dir = temp_dir("merge");
    let scene = dir.join("scene.rib");
    std::fs::write(&scene, SCENE).unwrap();
    let job = dir.join("scene.farm");
    let out = farm(
        &["submit", "scene.rib", "--dry-run", "--tiles", "3x2"],
        &dir,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dry = String::from_utf8(out.stdout).unwrap();
    let lines = tile_lines(section(&dry, "scripts/tiles.sh"));
    assert_eq!(lines.len(), 12);
    // What `farm submit` records (a dry run writes nothing, and there is no sbatch here).
    std::fs::create_dir_all(&job).unwrap();
    std::fs::write(
        job.join("farm.conf"),
        format!(
            "scene={}\ncwd={}\ntiles=3x2\nframes=all\n",
            scene.display(),
            dir.display()
        ),
    )
    .unwrap();
    // Render every tile as the script's `render --crop ... --tile-out` would, except two of
    // frame 2.
    let render_tile = |l: &TileLine| {
        let f = &frames_of(&scene, l.frame, Some(l.crop))[0];
        let r = illume_render::render(f, &Default::default());
        let path = job.join(&l.tile);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        illume_render::write_tile(&path, &r, f.options.xres, f.options.yres).unwrap();
    };
    let (held, rendered): (Vec<&TileLine>, Vec<&TileLine>) = lines
        .iter()
        .partition(|l| l.tile.ends_with("f0002/x1y0.tile") || l.tile.ends_with("f0002/x2y1.tile"));
    assert_eq!(held.len(), 2);
    rendered.iter().for_each(|l| render_tile(l));
    let out = farm(&["merge", "scene.rib"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("f0002 not merged: 2 missing tile(s): x1y0 x2y1"),
        "{err}"
    );
    assert!(dir.join("a1.tif").exists() && !dir.join("a2.tif").exists());
    held.iter().for_each(|l| render_tile(l));
    let out = farm(&["merge", job.to_str().unwrap()], &dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("merged f0002"));

    // The reference: each frame rendered whole, displays written by the same drivers.
    let reference = dir.join("reference");
    std::fs::create_dir_all(&reference).unwrap();
    for mut f in frames_of(&scene, None, None) {
        let r = illume_render::render(&f, &Default::default());
        for d in &mut f.options.displays {
            d.name = reference.join(&d.name).display().to_string();
        }
        assert!(illume_render::write_displays(&f, &r)
            .iter()
            .all(|w| w.is_ok()));
    }
    for name in ["a1.tif", "a1.exr", "a1aov.exr", "a2.tif"] {
        let merged = std::fs::read(dir.join(name)).unwrap();
        let full = std::fs::read(reference.join(name)).unwrap();
        assert!(
            merged == full,
            "{name}: merged tiles differ from the full render"
        );
    }
    // The cropped frame 2 really is crop-sized (the CropWindow was tiled, not the frame).
    let img = illume_imageio::read_image(&dir.join("a2.tif")).unwrap();
    // x: ceil(45·0.1) = 5 .. ceil(45·0.9) = 41; y: ceil(31·0.2) = 7 .. 31.
    assert_eq!((img.width, img.height), (36, 24));
    // Up to date now: a second merge writes nothing.
    let out = farm(&["merge", "scene.rib"], &dir);
    assert!(String::from_utf8_lossy(&out.stdout).contains("f0001 is up to date"));
    std::fs::remove_dir_all(&dir).unwrap();
}
