//! Helpers shared by the fuzz targets: the readers under test take paths, so each input is
//! written to a scratch file first (in `/dev/shm` when it exists, so no disk I/O per run).
use std::path::PathBuf;

/// A scratch path unique to this process and `tag` (libFuzzer runs inputs one at a time in a
/// process, so one file per target and process is enough; `-jobs`/`-fork` get their own pids).
pub fn scratch_path(tag: &str) -> PathBuf {
    let dir = if std::path::Path::new("/dev/shm").is_dir() {
        PathBuf::from("/dev/shm")
    } else {
        std::env::temp_dir()
    };
    dir.join(format!("illume-fuzz-{}-{tag}", std::process::id()))
}

/// Writes `data` to [`scratch_path`]`(tag)` and returns the path.
pub fn scratch_file(tag: &str, data: &[u8]) -> PathBuf {
    let path = scratch_path(tag);
    std::fs::write(&path, data).expect("scratch file is writable");
    path
}

/// Reads one image through `read_image` (the decoder is chosen from the bytes), after checking
/// that `data` starts with one of `magics` so each target stays on its own decoder. Errors are
/// fine; panics, hangs and huge allocations are the bugs.
pub fn read_image_if(data: &[u8], magics: &[&[u8]], tag: &str) -> Option<illume_imageio::Image> {
    if !magics.iter().any(|m| data.starts_with(m)) {
        return None;
    }
    let path = scratch_file(tag, data);
    let image = illume_imageio::read_image(&path).ok();
    if let Some(img) = &image {
        // Every reader promises width × height × channels samples.
        assert_eq!(
            img.data.len(),
            img.width as usize * img.height as usize * img.channels.len()
        );
    }
    image
}
