//! Running a pipeline example the way users do: from its own directory, through the real
//! `render`/`txmake` binaries (`.ci/run` builds them first), in both forms.
use std::path::{Path, PathBuf};
use std::process::Command;

pub fn example_dir(pipeline: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("rib/pipelines")
        .join(pipeline)
}

/// A fresh scratch directory per test (tests run in parallel in one process).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("illume-pipelines-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// File names a pipeline's RIB mentions: quoted words ending in one of these extensions.
const FILE_EXTENSIONS: [&str; 8] = ["tif", "rib", "env", "tx", "exr", "sm", "z", "png"];

/// Copies every file of `pipeline`'s example directory into `dir`.
pub fn copy_example(pipeline: &str, dir: &Path) {
    for entry in std::fs::read_dir(example_dir(pipeline)).unwrap() {
        let path = entry.unwrap().path();
        if path.is_file() {
            std::fs::copy(&path, dir.join(path.file_name().unwrap())).unwrap();
        }
    }
}

/// `pipeline`'s RIB `file` with every quoted file name (`"room.rib"`, `"px.tif"`, …) made a
/// path inside `dir` (where [`copy_example`] put the inputs), so it renders in-process without changing the working directory.
pub fn rib_in(pipeline: &str, file: &str, dir: &Path) -> String {
    let text = std::fs::read_to_string(example_dir(pipeline).join(file)).unwrap();
    text.split('"')
        .enumerate()
        .map(|(k, piece)| {
            let is_file = k % 2 == 1
                && !piece.contains(char::is_whitespace)
                && piece
                    .rsplit_once('.')
                    .is_some_and(|(stem, ext)| !stem.is_empty() && FILE_EXTENSIONS.contains(&ext));
            if is_file {
                dir.join(piece).display().to_string()
            } else {
                piece.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\"")
}

/// `render` and `txmake` next to this test's profile directory, or named by `$RENDER`/`$TXMAKE`;
/// `None` when not built (skipped loudly; a failure under `CI=true`).
pub fn binaries() -> Option<(PathBuf, PathBuf)> {
    Some((
        illume_testenv::require_built("render", "RENDER")?,
        illume_testenv::require_built("txmake", "TXMAKE")?,
    ))
}

/// Copies `pipeline`'s example into a scratch directory, runs `sh script` there and
/// `render -q single` there, and returns the pairs of images they wrote (`outputs`: the
/// single-RIB form's file, the script's file). `None` (with a loud skip message) when the
/// binaries are not built.
pub fn run_both_forms(
    pipeline: &str,
    single: &str,
    script: &str,
    outputs: &[[&str; 2]],
) -> Option<Vec<[illume_imageio::Image; 2]>> {
    let (render_bin, txmake_bin) = binaries()?;
    let dir = scratch(&format!("{pipeline}-forms"));
    copy_example(pipeline, &dir);
    let status = Command::new("sh")
        .arg(dir.join(script))
        .env("RENDER", &render_bin)
        .env("TXMAKE", &txmake_bin)
        .status()
        .unwrap();
    assert!(status.success(), "{script}: {status}");
    let status = Command::new(&render_bin)
        .arg("-q")
        .arg(single)
        .current_dir(&dir)
        .status()
        .unwrap();
    assert!(status.success(), "render {single}: {status}");
    let read = |f: &str| illume_imageio::read_image(&dir.join(f)).unwrap();
    let images = outputs.iter().map(|[a, b]| [read(a), read(b)]).collect();
    let _ = std::fs::remove_dir_all(&dir);
    Some(images)
}

/// Asserts two images are the same bits, reporting how many values differ (not the images).
pub fn assert_same_image(a: &illume_imageio::Image, b: &illume_imageio::Image, what: &str) {
    assert_eq!(
        (a.width, a.height, &a.channels),
        (b.width, b.height, &b.channels),
        "{what}"
    );
    let diff: Vec<usize> = (0..a.data.len())
        .filter(|&i| a.data[i].to_bits() != b.data[i].to_bits())
        .collect();
    if let Some(&first) = diff.first() {
        let nc = a.channels.len();
        let (x, y) = (
            (first / nc) % a.width as usize,
            first / nc / a.width as usize,
        );
        panic!(
            "{what}: {} of {} values differ; first at pixel ({x}, {y}): {} vs {}",
            diff.len(),
            a.data.len(),
            a.data[first],
            b.data[first]
        );
    }
}
