//! Shared by the C binding tests (tests/c_binding.rs, tests/c_library.rs): building C programs
//! against include/ri.h and libillume.a, and running them.
#![allow(dead_code)] // each test binary uses its own subset
use std::path::{Path, PathBuf};
use std::process::Command;

pub struct Tools {
    pub cc: PathBuf,
    pub lib: PathBuf,
    pub render: PathBuf,
    pub catrib: PathBuf,
}

pub fn tools() -> Option<Tools> {
    let lib = illume_testenv::require_built("libillume.a", "LIBILLUME")?;
    if let Some(newer) = newer_source(&lib) {
        panic!(
            "{} is older than {}: run `cargo build -p libillume` (cargo test does not rebuild \
             the C library, and a stale one fails these tests with confusing differences)",
            lib.display(),
            newer.display()
        );
    }
    Some(Tools {
        cc: illume_testenv::require_tool("cc")?,
        lib,
        render: illume_testenv::require_built("render", "RENDER")?,
        catrib: illume_testenv::require_built("catrib", "CATRIB")?,
    })
}

/// A source file of this workspace that went into `lib` (cargo's dep-info beside it,
/// `libillume.d`) and was modified after `lib` was written; `None` when the library is up to
/// date or there is no dep-info to judge by. Dep-info paths are those of the checkout that
/// built it: each is taken relative to its `crates/` folder in this checkout.
pub fn newer_source(lib: &Path) -> Option<PathBuf> {
    let built = std::fs::metadata(lib).and_then(|m| m.modified()).ok()?;
    let info = std::fs::read_to_string(lib.with_extension("d")).ok()?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    info.lines()
        .filter_map(|l| l.split_once(": ").map(|(_, deps)| deps))
        .flat_map(str::split_whitespace)
        .filter_map(|dep| dep.find("/crates/").map(|i| root.join(&dep[i + 1..])))
        .find(|src| {
            std::fs::metadata(src)
                .and_then(|m| m.modified())
                .is_ok_and(|t| t > built)
        })
}

pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("c_binding")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Compiles `source` against ri.h and libillume into `dir/prog`.
pub fn compile(t: &Tools, dir: &Path, source: &str) -> PathBuf {
    let c = dir.join("prog.c");
    std::fs::write(&c, source).unwrap();
    let exe = dir.join("prog");
    let include = Path::new(env!("CARGO_MANIFEST_DIR")).join("include");
    let out = Command::new(&t.cc)
        .args(["-Wall", "-Werror", "-o"])
        .arg(&exe)
        .arg(&c)
        .arg("-I")
        .arg(include)
        .arg("-L")
        .arg(t.lib.parent().unwrap())
        .args(["-lillume", "-lm"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "cc: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

pub fn run(exe: &Path, dir: &Path, env: &[(&str, &str)]) -> String {
    let out = Command::new(exe)
        .current_dir(dir)
        .envs(env.iter().copied())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{} failed: {}",
        exe.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}
