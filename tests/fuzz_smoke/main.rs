//! The fuzz targets' smoke pass, for CI (issue 23: "CI runs a short smoke pass of each
//! target"; the instrumented nightly build is too slow for CI). Each target's body from
//! `fuzz/src` (the same functions the libFuzzer binaries call) runs over every committed crash
//! input and a few hundred to a few thousand deterministic mutations of small seeds. A body
//! that panics is a failure; its input is saved under the test's scratch directory and named
//! in the message, so it can be replayed by the fuzz binary or minimised with `cargo fuzz tmin`.
//! An abort (a failed allocation) cannot be caught: the input in hand is then left as
//! `<target>-last.bin` in the same directory.
//!
//! This is not fuzzing (no coverage feedback): it keeps the targets compiling on stable, keeps
//! the fixed crashes fixed, and catches gross regressions in the readers' error paths.
#[path = "../../fuzz/src/lib.rs"]
mod illume_fuzz;
mod mutate;
mod seeds;
mod slow_render;

use seeds::{Pictures, Seed};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Committed crash inputs of `crate_dir/tests/fuzz_crashes` whose names start with `prefix`.
fn regressions(crate_dir: &str, prefix: &str) -> Vec<Seed> {
    inputs_in(
        &seeds::repo().join(crate_dir).join("tests/fuzz_crashes"),
        prefix,
    )
}

/// The files of `dir` whose names start with `prefix`, sorted; at least one.
fn inputs_in(dir: &Path, prefix: &str) -> Vec<Seed> {
    let mut out: Vec<Seed> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with(prefix))
        })
        .map(|p| {
            let bytes = std::fs::read(&p).expect("readable crash input");
            (p.to_string_lossy().into_owned(), bytes)
        })
        .collect();
    out.sort();
    assert!(!out.is_empty(), "{}: no `{prefix}*` inputs", dir.display());
    out
}

/// Runs `body` on `regressions` and `seeds` as they are, then on `mutations` mutations of the
/// seeds (cycled); panics listing every input that made the body panic.
fn smoke(target: &str, body: fn(&[u8]), seeds: &[Seed], regressions: &[Seed], mutations: u64) {
    if let Some(dir) = std::env::var_os("ILLUME_FUZZ_SEEDS") {
        write_corpus(&Path::new(&dir).join(target), seeds, regressions);
    }
    let start = Instant::now();
    let failed_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz_smoke/failed");
    let mut failures: Vec<String> = Vec::new();
    std::fs::create_dir_all(&failed_dir).expect("scratch dir");
    // An abort (a failed allocation) cannot be caught: the input in hand is kept here.
    let last = failed_dir.join(format!("{target}-last.bin"));
    let mut run = |label: &str, input: &[u8]| {
        std::fs::write(&last, input).expect("scratch dir is writable");
        if std::panic::catch_unwind(|| body(input)).is_err() {
            let path: PathBuf = failed_dir.join(format!("{target}-{}.bin", failures.len()));
            std::fs::write(&path, input).expect("scratch dir is writable");
            failures.push(format!("{label} (input saved as {})", path.display()));
        }
    };
    for (name, bytes) in regressions.iter().chain(seeds) {
        run(name, bytes);
    }
    for i in 0..mutations {
        let (name, seed) = &seeds[i as usize % seeds.len()];
        run(&format!("{name}, mutation {i}"), &mutate::mutate(seed, i));
    }
    illume_fuzz::remove_scratch_files();
    let _ = std::fs::remove_file(&last);
    eprintln!(
        "{target}: {} inputs in {:.2} s",
        regressions.len() + seeds.len() + mutations as usize,
        start.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{target} panicked on {} inputs:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// `ILLUME_FUZZ_SEEDS=fuzz/corpus cargo test --test fuzz_smoke` also writes each target's
/// seeds and crash inputs as a libFuzzer corpus, `<dir>/<target>/<n>`, for `cargo fuzz run`.
fn write_corpus(dir: &Path, seeds: &[Seed], regressions: &[Seed]) {
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for (n, (_, bytes)) in regressions.iter().chain(seeds).enumerate() {
        let path = dir.join(format!("seed-{n:03}"));
        std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}

#[test]
fn parse_rib() {
    let mut seeds = seeds::ribs(4 << 10);
    let extra: Vec<Seed> = seeds
        .iter()
        .take(6)
        .flat_map(|(name, text)| {
            [
                (format!("{name} (binary)"), seeds::binary_rib(text)),
                (format!("{name} (gzip)"), seeds::gzip_stored(text)),
            ]
        })
        .collect();
    seeds.extend(extra);
    // The third runs' finding: a `##` comment of invalid UTF-8 near the 4096-byte cap grew
    // past it when printed (each bad byte a 3-byte U+FFFD) and read back shorter.
    let crashes = regressions("crates/rib", "parse_rib_");
    smoke("parse_rib", illume_fuzz::parse_rib, &seeds, &crashes, 4000);
}

#[test]
fn render_rib() {
    let seeds = seeds::ribs(2 << 10);
    // The target's own bug, found by render_rib: `Format 0 …` (the device default, 640×480)
    // slipped past a `min(24)` clamp and tripped the frame-size assertion.
    let format_zero = (
        "Format 0".to_string(),
        b"Format 0 240 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n".to_vec(),
    );
    // Crash inputs of the renderer (`fuzz/regressions/render_rib_crash_*.rib`): a torus around
    // the eye with depth of field, whose far-off blurred boxes overflowed `i32` in
    // `reyes::motion::buffer_pixels`.
    let mut crashes = inputs_in(&seeds::repo().join("fuzz/regressions"), "render_rib_crash_");
    crashes.push(format_zero);
    smoke("render_rib", illume_fuzz::render_rib, &seeds, &crashes, 300);
}

#[test]
fn read_tiff() {
    let seeds = Pictures::new("tiff").tiffs();
    let crashes = regressions("crates/imageio", "tiff_");
    smoke("read_tiff", illume_fuzz::read_tiff, &seeds, &crashes, 3000);
}

#[test]
fn read_png() {
    let seeds = Pictures::new("png").pngs();
    smoke("read_png", illume_fuzz::read_png, &seeds, &[], 2000);
}

#[test]
fn read_exr() {
    let seeds = Pictures::new("exr").exrs();
    let crashes = regressions("crates/imageio", "exr_");
    smoke("read_exr", illume_fuzz::read_exr, &seeds, &crashes, 2000);
}

#[test]
fn read_zfile() {
    let seeds = Pictures::new("zfile").zfiles();
    smoke("read_zfile", illume_fuzz::read_zfile, &seeds, &[], 2000);
}

/// Lookup parameters for the `.tx` seeds: a mid-texture footprint, some blur and samples.
const LOOKUP: [u8; 8] = [100, 140, 30, 0, 20, 3, 0, 2];

#[test]
fn read_texture() {
    let seeds: Vec<Seed> = Pictures::new("tx")
        .textures()
        .into_iter()
        .map(|(name, tx)| (name, [&LOOKUP[..], &tx].concat()))
        .collect();
    let crashes = regressions("crates/texture", "tx_");
    smoke(
        "read_texture",
        illume_fuzz::read_texture,
        &seeds,
        &crashes,
        1500,
    );
}

#[test]
fn txmake() {
    let pictures = Pictures::new("txmake");
    let mut inputs = pictures.tiffs();
    inputs.truncate(3);
    inputs.extend(pictures.pngs());
    inputs.extend(pictures.exrs());
    inputs.extend(pictures.zfiles());
    // Option bytes: texture/half/box, latlong, float/periodic/gaussian, resize down/sinc.
    let ops = [0x00, 0x40, 0xa5, 0x68];
    let seeds: Vec<Seed> = inputs
        .iter()
        .zip(ops.iter().cycle())
        .map(|((name, bytes), &op)| (format!("{op:#04x} {name}"), [&[op][..], bytes].concat()))
        .collect();
    let mut pictures = regressions("crates/imageio", "tiff_");
    pictures.extend(regressions("crates/imageio", "exr_"));
    let crashes: Vec<Seed> = pictures
        .into_iter()
        .map(|(name, bytes)| (name, [&[0][..], &bytes].concat()))
        .collect();
    smoke("txmake", illume_fuzz::txmake, &seeds, &crashes, 600);
}

#[test]
fn sl_preprocess() {
    let seeds = seeds::shaders(1 << 10);
    smoke(
        "sl_preprocess",
        illume_fuzz::sl_preprocess,
        &seeds,
        &[],
        3000,
    );
}

#[test]
fn sl_parse() {
    let seeds = seeds::shaders(1 << 10);
    smoke("sl_parse", illume_fuzz::sl_parse, &seeds, &[], 2000);
}

#[test]
fn sl_compile() {
    let seeds = seeds::shaders(1 << 10);
    smoke("sl_compile", illume_fuzz::sl_compile, &seeds, &[], 2000);
}
