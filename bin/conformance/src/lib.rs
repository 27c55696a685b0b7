//! The conformance runner: renders every job of a RenderMan regression suite laid out as
//! Aqsis's `testing/regression/` (`RIBs/**/jobs.cfg`, `reference/<image>.tif`, `shaders/`,
//! `maps/`) with Illume's `render`, and compares each image with its reference.
//!
//! The `conformance` binary wraps this; the integration test calls [`run_jobs`] directly.
#![forbid(unsafe_code)]

pub mod compare;
pub mod contact;
pub mod explanations;
pub mod jobs_cfg;
pub mod report;
pub mod run;
pub mod suite;

use compare::Metrics;
use run::{Outcome, RunConfig};
use std::path::PathBuf;
use std::sync::Mutex;
use suite::Job;

/// The verdict threshold: mean absolute error over RGB at most this (issue 18's acceptance).
pub const MAX_MAE: f64 = 0.02;

/// What one job came to.
#[derive(Debug, Clone)]
pub struct JobResult {
    pub job: Job,
    pub outcome: Outcome,
    pub seconds: f64,
    /// Our image (copied to the output folder), when written.
    pub image: Option<PathBuf>,
    pub reference: PathBuf,
    /// The comparison, or why there is none (no image, size mismatch, unreadable file).
    pub metrics: Result<Metrics, String>,
    pub log: PathBuf,
}

/// The verdict classes of the report.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verdict {
    Pass,
    Fail,
    /// The renderer panicked or died by a signal.
    Crash,
    Timeout,
    /// It ended without writing the image.
    NoImage,
}

impl Verdict {
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Pass => "pass",
            Verdict::Fail => "fail",
            Verdict::Crash => "crash",
            Verdict::Timeout => "timeout",
            Verdict::NoImage => "no image",
        }
    }
}

impl JobResult {
    /// Pass when the image is within `max_mae`; a crash (signal, or Rust's panic exit code
    /// 101) or a timeout outranks the image comparison.
    pub fn verdict(&self, max_mae: f64) -> Verdict {
        match self.outcome {
            Outcome::TimedOut => return Verdict::Timeout,
            Outcome::Signalled | Outcome::Exited(101) => return Verdict::Crash,
            _ => {}
        }
        match (&self.image, &self.metrics) {
            (None, _) => Verdict::NoImage,
            (Some(_), Ok(m)) if m.mae <= max_mae => Verdict::Pass,
            _ => Verdict::Fail,
        }
    }
}

/// Renders `jobs` with `workers` jobs at a time and compares each image with
/// `suite/reference/<image>`; results come back in job order whatever the parallelism.
/// `progress` is called as each job ends.
pub fn run_jobs(
    cfg: &RunConfig,
    jobs: &[Job],
    workers: usize,
    progress: &(dyn Fn(&JobResult) + Sync),
) -> Vec<JobResult> {
    let next = Mutex::new(0usize);
    let results: Mutex<Vec<Option<JobResult>>> = Mutex::new(vec![None; jobs.len()]);
    std::thread::scope(|s| {
        for _ in 0..workers.clamp(1, jobs.len().max(1)) {
            s.spawn(|| loop {
                let k = {
                    let Ok(mut n) = next.lock() else { return };
                    let k = *n;
                    *n += 1;
                    k
                };
                let Some(job) = jobs.get(k) else { return };
                let r = run_one(cfg, job);
                progress(&r);
                if let Ok(mut all) = results.lock() {
                    all[k] = Some(r);
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap_or_default()
        .into_iter()
        .flatten()
        .collect()
}

/// Renders one job and compares its image (the job's first image is `job.name`'s).
fn run_one(cfg: &RunConfig, job: &Job) -> JobResult {
    let rendered = run::render_job(cfg, job);
    let k = job
        .images
        .iter()
        .position(|i| {
            std::path::Path::new(i)
                .file_stem()
                .is_some_and(|s| s.to_string_lossy() == job.name)
        })
        .unwrap_or(0);
    let image = rendered.images.get(k).cloned().flatten();
    let reference_name = std::path::Path::new(&job.images[k])
        .file_name()
        .map(|f| f.to_os_string())
        .unwrap_or_default();
    let reference = cfg.suite.join("reference").join(reference_name);
    let metrics = match &image {
        None => Err("no output image".to_string()),
        Some(ours) => compare::load_rgb(ours).and_then(|ours| {
            let theirs = compare::load_rgb(&reference)?;
            compare::compare(&ours, &theirs)
        }),
    };
    JobResult {
        job: job.clone(),
        outcome: rendered.outcome,
        seconds: rendered.seconds,
        image,
        reference,
        metrics,
        log: rendered.log,
    }
}
