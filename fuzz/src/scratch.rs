//! Scratch files: the readers under test take paths, so each input is written to a file first
//! (in `/dev/shm` when it exists, so no disk I/O per run).
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Every tag the bodies use, for [`remove_scratch_files`].
const TAGS: &[&str] = &[
    "tiff",
    "png",
    "exr",
    "zfile",
    "tx",
    "txmake-in",
    "txmake-out.tx",
];

/// A scratch path unique to this process, thread and `tag`: libFuzzer runs inputs one at a
/// time on one thread (`-jobs`/`-fork` get their own pids); the smoke test runs its targets on
/// parallel test threads, and one thread's cleanup must not remove another's files.
pub fn scratch_path(tag: &str) -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    thread_local! {
        static THREAD: usize = NEXT.fetch_add(1, Ordering::Relaxed);
    }
    let dir = if std::path::Path::new("/dev/shm").is_dir() {
        PathBuf::from("/dev/shm")
    } else {
        std::env::temp_dir()
    };
    let thread = THREAD.with(|t| *t);
    dir.join(format!("illume-fuzz-{}-{thread}-{tag}", std::process::id()))
}

/// Writes `data` to [`scratch_path`]`(tag)` and returns the path.
pub fn scratch_file(tag: &str, data: &[u8]) -> PathBuf {
    let path = scratch_path(tag);
    std::fs::write(&path, data).expect("scratch file is writable");
    path
}

/// Removes this thread's scratch files (the fuzz binaries leave theirs; the smoke test cleans
/// up).
pub fn remove_scratch_files() {
    for tag in TAGS {
        let _ = std::fs::remove_file(scratch_path(tag));
    }
}
