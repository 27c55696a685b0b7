//! Where a test finds what the repository does not hold: the read-only `../shared` folder beside
//! the checkout (the real-world RIB corpus, the Aqsis regression suite, the reference chapter),
//! external programs (`oiiotool`, `exrenvmap`, …) and binaries built by another `cargo build`.
//!
//! One rule for all of them, so that a green run means the tests ran: when an input is missing, a
//! test *skips loudly* (a message on stderr naming the test, what is missing and how to get it)
//! on a developer's machine, and *fails* under `CI=true`, where `.ci/run` installs every tool
//! and CI lays `shared/` beside the clone. A test that needs an input asks for it here and
//! returns when it gets `None`:
//!
//! ```no_run
//! let Some(corpus) = illume_testenv::shared_dir("corpus") else { return };
//! let Some(oiiotool) = illume_testenv::require_tool("oiiotool") else { return };
//! # let _ = (corpus, oiiotool);
//! ```
//!
//! This crate is a dev-dependency only; nothing in a shipped binary depends on it.

use std::path::{Path, PathBuf};

mod run;
pub use run::{render_in, scratch_dir};

/// True when the environment says this is a CI run (`CI` set to anything but empty, `0` or
/// `false`; CI systems set `CI=true`, and `.ci/run` exports it for local runs too).
pub fn in_ci() -> bool {
    means_ci(std::env::var("CI").ok().as_deref())
}

fn means_ci(value: Option<&str>) -> bool {
    value.is_some_and(|v| !matches!(v.trim().to_ascii_lowercase().as_str(), "" | "0" | "false"))
}

/// Reports a missing input: panics under CI (so the run is red), otherwise prints a loud skip
/// message naming the running test. `what` says what is missing, `fix` how to provide it.
/// Callers return from the test after this; prefer the `shared_*`/`require_*` functions, which
/// call it.
pub fn missing(what: &str, fix: &str) {
    let test = std::thread::current()
        .name()
        .unwrap_or("<unnamed test>")
        .to_string();
    match verdict(in_ci(), &test, what, fix) {
        Err(failure) => panic!("{failure}"),
        Ok(skip) => {
            // Written to the stderr handle, not with `eprintln!`: the test harness captures the
            // print macros of passing tests, and a skip must show in a plain `cargo test`.
            use std::io::Write;
            let _ = writeln!(std::io::stderr(), "\n{skip}\n");
        }
    }
}

/// The skip message (`Ok`) or, under CI, the failure (`Err`) for `test` missing `what`.
fn verdict(ci: bool, test: &str, what: &str, fix: &str) -> Result<String, String> {
    if ci {
        return Err(format!(
            "CI=true: {test} cannot run: {what} ({fix}). CI must not skip tests."
        ));
    }
    Ok(format!(
        "******** SKIPPED {test}: {what} ({fix}); under CI=true this is a failure ********"
    ))
}

/// `shared/<name>` (a directory such as `corpus`, `aqsis-regression`, `reference`), or `None`
/// after [`missing`]. Looked up as [`shared_path`] does; `$ILLUME_CORPUS` still names the
/// corpus itself.
pub fn shared_dir(name: &str) -> Option<PathBuf> {
    if name == "corpus" {
        if let Some(p) = std::env::var_os("ILLUME_CORPUS") {
            return found_or_missing(PathBuf::from(p), Path::is_dir, "$ILLUME_CORPUS");
        }
    }
    let p = shared_path(name);
    found_or_missing(
        p,
        Path::is_dir,
        "../shared beside the checkout, or $ILLUME_SHARED",
    )
}

/// A file under `shared/` (`rel` such as `reference/advanced-renderman-ch9-….txt` or
/// `corpus/aqsis2001/disp_test.rib`), or `None` after [`missing`].
pub fn shared_file(rel: &str) -> Option<PathBuf> {
    let p = match rel.strip_prefix("corpus/") {
        Some(in_corpus) => match std::env::var_os("ILLUME_CORPUS") {
            Some(c) => PathBuf::from(c).join(in_corpus),
            None => shared_path(rel),
        },
        None => shared_path(rel),
    };
    found_or_missing(
        p,
        Path::is_file,
        "../shared beside the checkout, or $ILLUME_SHARED",
    )
}

/// Where `shared/<rel>` is, whether or not it exists: under `$ILLUME_SHARED` when set, else
/// the first `shared/` folder found walking up from this workspace (for a checkout at
/// `/work/main` that is `/work/shared`, i.e. `../shared`). When none is found, the path
/// beside the workspace root, for the message.
pub fn shared_path(rel: &str) -> PathBuf {
    if let Some(root) = std::env::var_os("ILLUME_SHARED") {
        return PathBuf::from(root).join(rel);
    }
    let workspace = workspace_root();
    workspace
        .ancestors()
        .map(|a| a.join("shared"))
        .find(|s| s.is_dir())
        .unwrap_or_else(|| workspace.join("../shared"))
        .join(rel)
}

/// The workspace root: this crate lives at `<root>/crates/testenv`.
fn workspace_root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors().nth(2).unwrap_or(here).to_path_buf()
}

fn found_or_missing(p: PathBuf, exists: fn(&Path) -> bool, fix: &str) -> Option<PathBuf> {
    if exists(&p) {
        return Some(p);
    }
    missing(&format!("{} not found", p.display()), fix);
    None
}

/// The full path of the external program `name` found on `$PATH`, or `None` after
/// [`missing`] (with the Debian package that provides it).
pub fn require_tool(name: &str) -> Option<PathBuf> {
    if let Some(p) = find_on_path(name) {
        return Some(p);
    }
    missing(
        &format!("`{name}` is not installed"),
        &format!("apt-get install {}; .ci/run installs it", package_of(name)),
    );
    None
}

/// A program of this workspace built by `cargo build -p <name>` into the same profile
/// directory as the running test (`target/debug/<name>`), or the path in `$<var>` (`RENDER`,
/// `TXMAKE`). Tests of the root package need this: only a package's own binaries get
/// `CARGO_BIN_EXE_*`. `None` after [`missing`].
pub fn require_built(name: &str, var: &str) -> Option<PathBuf> {
    if let Some(p) = std::env::var_os(var) {
        return found_or_missing(PathBuf::from(p), Path::is_file, &format!("${var}"));
    }
    // A test binary runs from <profile>/deps/<test>-<hash>.
    let exe = std::env::current_exe().ok();
    let profile = exe.as_deref().and_then(Path::parent).and_then(Path::parent);
    let Some(profile) = profile else {
        missing("the test's own path is unknown", "set $RENDER/$TXMAKE");
        return None;
    };
    found_or_missing(
        profile.join(name),
        Path::is_file,
        &format!("cargo build -p {name}, or set ${var}"),
    )
}

/// An executable regular file called `name` in a `$PATH` directory.
fn find_on_path(name: &str) -> Option<PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(name))
        .find(|p| {
            p.metadata()
                .is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        })
}

/// The Debian package that installs `tool`, for the skip message.
fn package_of(tool: &str) -> &'static str {
    match tool {
        "oiiotool" | "iinfo" | "maketx" | "idiff" => "openimageio-tools",
        "exrheader" | "exrenvmap" | "exrmaketiled" => "openexr",
        "python3" => "python3",
        "munged" | "munge" => "munge",
        "sbatch" | "squeue" | "scontrol" | "sacct" | "slurmctld" | "slurmd" | "srun" => "slurm-wlm",
        _ => "the package that provides it",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_program_everyone_has_is_found_with_its_full_path() {
        let sh = find_on_path("sh").expect("sh on PATH");
        assert!(sh.is_absolute() && sh.ends_with("sh"), "{}", sh.display());
        assert!(find_on_path("illume-no-such-tool-0xdead").is_none());
    }

    #[test]
    fn the_shared_folder_is_looked_up_beside_the_workspace() {
        let root = workspace_root();
        assert!(root.join("Cargo.toml").is_file(), "{}", root.display());
        assert!(shared_path("corpus").ends_with("shared/corpus"));
    }

    #[test]
    fn a_missing_input_fails_under_ci_and_only_skips_outside() {
        let failure = verdict(true, "t", "thing", "get it").expect_err("CI=true must fail");
        assert!(
            failure.contains("t cannot run: thing (get it)"),
            "{failure}"
        );
        assert!(failure.contains("CI must not skip"), "{failure}");
        let skip = verdict(false, "t", "thing", "get it").expect("a skip outside CI");
        assert!(skip.contains("SKIPPED t: thing (get it)"), "{skip}");
    }

    #[test]
    fn what_counts_as_ci() {
        for (v, ci) in [
            (Some("true"), true),
            (Some("1"), true),
            (Some("yes"), true),
            (Some(""), false),
            (Some("0"), false),
            (Some("false"), false),
            (Some("FALSE"), false),
            (None, false),
        ] {
            assert_eq!(means_ci(v), ci, "{v:?}");
        }
    }
}
