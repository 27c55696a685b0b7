//! `slc` end to end: exit codes 0 / 1 / 2, diagnostics on stderr, `-I` and `-D`, `--emit`.

use std::path::{Path, PathBuf};
use std::process::Command;

fn slc() -> Command {
    Command::new(env!("CARGO_BIN_EXE_slc"))
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slc-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn clean_file_exits_zero_and_prints_nothing() {
    let d = scratch("clean");
    let f = write(&d, "matte.sl", "surface matte (float Kd = 1;) { Oi = Os; Ci = Os * Cs * Kd * diffuse(faceforward(normalize(N), I)); }\n");
    let out = slc().arg(&f).output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn errors_exit_one_with_file_line_col_on_stderr() {
    let d = scratch("errors");
    let f = write(
        &d,
        "bad.sl",
        "surface bad () {\n  Ci = Kq;\n  Oi = Cs + P;\n}\n",
    );
    let out = slc().arg(&f).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    let path = f.display();
    assert_eq!(
        err,
        format!(
            "{path}:2:8: error: undeclared variable 'Kq'\n{path}:3:11: error: operator '+' cannot combine color and point\n"
        )
    );
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn include_dirs_and_defines_reach_the_preprocessor() {
    let d = scratch("include");
    let inc = d.join("inc");
    std::fs::create_dir_all(&inc).unwrap();
    write(&inc, "k.h", "#define KD_DEFAULT 0.8\n");
    let f = write(
        &d,
        "uses.sl",
        "#include \"k.h\"\n#ifndef WANT\n#error WANT is not defined\n#endif\nsurface uses (float Kd = KD_DEFAULT;) { Ci = Kd; }\n",
    );
    let out = slc()
        .arg("-I")
        .arg(&inc)
        .arg("-D")
        .arg("WANT")
        .arg("--emit")
        .arg("summary")
        .arg(&f)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("surface uses\n  param uniform float Kd (inferred uniform)\n"),
        "{summary}"
    );
    // Without -I the include is missing; without -D the #error fires: both are source errors.
    let out = slc().arg(&f).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(":1:10: error: cannot find include file 'k.h'"),
        "{err}"
    );
    assert!(
        err.contains(":3:2: error: #error WANT is not defined"),
        "{err}"
    );
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn usage_errors_exit_two() {
    assert_eq!(slc().output().unwrap().status.code(), Some(2));
    assert_eq!(
        slc()
            .arg("--emit")
            .arg("bogus")
            .arg("x.sl")
            .output()
            .unwrap()
            .status
            .code(),
        Some(2)
    );
}

#[test]
fn a_missing_file_is_a_source_error() {
    let out = slc().arg("/nonexistent/dir/none.sl").output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr)
        .starts_with("/nonexistent/dir/none.sl:1:1: error: cannot read"));
}

#[test]
fn latin1_bytes_in_comments_do_not_stop_compilation() {
    let d = scratch("latin1");
    let p = d.join("old.sl");
    let mut bytes = b"/* (c) 1991 Fran\xe7ois \xa9 */\nsurface old () { Ci = Cs; }\n".to_vec();
    bytes.extend_from_slice(b"/* tail \xff */\n");
    std::fs::write(&p, bytes).unwrap();
    let out = slc().arg(&p).output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::remove_dir_all(&d).ok();
}
