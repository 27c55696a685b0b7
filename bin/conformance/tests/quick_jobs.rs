//! The fast subset of the conformance suite that `cargo test` runs: a few small Aqsis
//! regression jobs that match Aqsis's reference images today, rendered by the real `render`
//! binary the way the runner renders every job, with their mean absolute error over RGB
//! bounded (the full-suite verdict threshold is 0.02; each bound here sits two to three times
//! above what the job measured, so a drift shows before it fails the suite).
//!
//! Needs `../shared/aqsis-regression` (or `$ILLUME_AQSIS_REGRESSION`) and a built `render`
//! (`cargo build -p render`, or `$RENDER`). Without them the test skips loudly, except under
//! `CI=true`, where it fails.
use conformance::run::{Outcome, RunConfig};
use conformance::{run_jobs, suite, Verdict, MAX_MAE};
use std::path::PathBuf;
use std::time::Duration;

/// (job, MAE bound): ScreenWindow, a surface shader compiled from the job's `.sl` with
/// ReverseOrientation, DelayedReadArchive, `spline()` over a color array, TextureCoordinates,
/// and RunProgram through a Python helper that imports `cgkit.ri` (the runner's `pyshim/`).
/// The release render measured 0.0004, 0.0030, 0.0005, 0.0016, 0.0037 and 0.0004.
const QUICK: [(&str, f64); 6] = [
    ("Bug1113859", 0.005),
    ("reverseorientation", 0.008),
    ("delayedproc", 0.005),
    ("Bug1379411", 0.005),
    ("mod_st_test", 0.01),
    ("runsphereproc", 0.005),
];

fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// Skips (prints why) or, under CI, fails.
fn missing(what: &str) {
    assert!(!in_ci(), "CI=true but {what}");
    eprintln!("SKIPPED: {what}");
}

fn suite_dir() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("ILLUME_AQSIS_REGRESSION") {
        return Some(p.into());
    }
    let mut dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    loop {
        let c = dir.join("shared/aqsis-regression");
        if c.is_dir() {
            return Some(c);
        }
        if !dir.pop() {
            return None;
        }
    }
}

/// `$RENDER`, else `render` in this test's target folder (target/debug/deps/.. /render).
fn render_bin() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("RENDER") {
        return Some(p.into());
    }
    let p = std::env::current_exe()
        .ok()?
        .parent()?
        .parent()?
        .join(format!("render{}", std::env::consts::EXE_SUFFIX));
    p.is_file().then_some(p)
}

/// Every job of the shared suite parses and has its reference image.
#[test]
fn every_job_has_a_reference() {
    let Some(root) = suite_dir() else {
        return missing("shared/aqsis-regression not found (set ILLUME_AQSIS_REGRESSION)");
    };
    let jobs = suite::load(&root).unwrap();
    assert!(
        jobs.len() >= 90,
        "only {} jobs in {}",
        jobs.len(),
        root.display()
    );
    for j in &jobs {
        let rib = root.join(j.workdir()).join(&j.spec.rib);
        assert!(
            rib.is_file(),
            "{}: {} missing",
            j.path_name(),
            rib.display()
        );
        let reference = root.join("reference").join(format!("{}.tif", j.name));
        assert!(reference.is_file(), "{}: no reference", j.path_name());
    }
}

#[test]
fn quick_jobs_match_aqsis_references() {
    let Some(root) = suite_dir() else {
        return missing("shared/aqsis-regression not found (set ILLUME_AQSIS_REGRESSION)");
    };
    let Some(render) = render_bin() else {
        return missing("render binary not built (cargo build -p render, or set RENDER)");
    };
    let jobs: Vec<_> = suite::load(&root)
        .unwrap()
        .into_iter()
        .filter(|j| QUICK.iter().any(|(n, _)| *n == j.name))
        .collect();
    assert_eq!(jobs.len(), QUICK.len(), "quick jobs missing from the suite");
    let out = std::env::temp_dir().join(format!("illume-conformance-{}", std::process::id()));
    let cfg = RunConfig {
        suite: root,
        render,
        out: out.clone(),
        timeout: Duration::from_secs(120),
        threads: 2,
        keep_scratch: false,
    };
    let results = run_jobs(&cfg, &jobs, 2, &|_| {});
    for r in &results {
        let log = std::fs::read_to_string(&r.log).unwrap_or_default();
        assert_eq!(r.outcome, Outcome::Exited(0), "{}: {log}", r.job.name);
        let m = r
            .metrics
            .as_ref()
            .unwrap_or_else(|e| panic!("{}: {e}", r.job.name));
        let bound = QUICK.iter().find(|(n, _)| *n == r.job.name).unwrap().1;
        assert!(
            m.mae <= bound,
            "{}: MAE {:.4} above {bound} (within 8/255: {:.1}%)",
            r.job.name,
            m.mae,
            m.within * 100.0
        );
        assert!(bound <= MAX_MAE);
        assert_eq!(r.verdict(MAX_MAE), Verdict::Pass);
    }
    std::fs::remove_dir_all(&out).unwrap();
}
