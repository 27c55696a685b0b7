//! Inputs the fuzz targets (`fuzz/`: read_tiff, read_png, read_exr, read_zfile) found to crash
//! a reader, kept as files in `tests/fuzz_crashes/`. Each must now be a clean error: no panic,
//! and a message that names the file. Files are named `<format>_<what was wrong>.bin`.
use std::path::PathBuf;

fn crash_files() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_crashes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    files.sort();
    files
}

#[test]
fn every_fuzz_crash_is_an_error_that_names_the_file() {
    let files = crash_files();
    assert!(
        !files.is_empty(),
        "the fuzz_crashes directory lost its files"
    );
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let result = std::panic::catch_unwind(|| {
            if name.starts_with("zfile_") {
                illume_imageio::read_zfile(&path).map(|(img, _)| img)
            } else {
                illume_imageio::read_image(&path)
            }
        });
        let result = result.unwrap_or_else(|_| panic!("{name}: the reader panicked"));
        match result {
            Ok(img) => panic!(
                "{name}: expected an error, read a {}×{} image",
                img.width, img.height
            ),
            Err(e) => assert!(
                e.to_string().contains(&name),
                "{name}: the error does not name the file: {e}"
            ),
        }
    }
}
