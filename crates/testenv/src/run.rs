//! Running a built binary of the workspace from a test: a fresh scratch directory and one
//! `render` run with its exit code and stderr (the preamble the limit and kill tests shared).
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh, empty directory under the system's temporary directory, named after `group`,
/// `name` and this process (parallel test runs do not share it).
pub fn scratch_dir(group: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("illume-{group}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d)
        .unwrap_or_else(|e| panic!("cannot create the scratch directory {}: {e}", d.display()));
    d
}

/// Runs `render -q --threads 1 file` in `dir` (`bin` from [`crate::require_built`]); returns
/// its exit code and stderr. Panics when it could not start or a signal ended it: the tests
/// that use it expect the renderer to exit by itself.
pub fn render_in(bin: &Path, dir: &Path, file: &str) -> (i32, String) {
    let out = Command::new(bin)
        .current_dir(dir)
        .args(["-q", "--threads", "1", file])
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", bin.display()));
    let code = out
        .status
        .code()
        .expect("render exited by itself, not by a signal");
    (code, String::from_utf8_lossy(&out.stderr).into_owned())
}
