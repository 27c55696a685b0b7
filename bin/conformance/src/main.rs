//! `conformance`: renders every job of a peer's regression suite (Aqsis's layout) with `render`
//! and reports how far each image is from the peer's reference.
//!
//! Exit codes: 0 every job ran and each one above the MAE threshold is explained in
//! `explanations.toml`; 1 a crash, timeout or unexplained divergence; 2 usage or setup error.
#![forbid(unsafe_code)]

use clap::Parser;
use conformance::run::RunConfig;
use conformance::{contact, explanations, report, run_jobs, suite, JobResult, Verdict, MAX_MAE};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

#[derive(Parser)]
#[command(
    name = "conformance",
    about = "Render a RenderMan regression suite (Aqsis jobs.cfg layout) and compare with its references"
)]
struct Args {
    /// The suite root (holds RIBs/ and reference/). Default: $ILLUME_AQSIS_REGRESSION, else
    /// the first shared/aqsis-regression found walking up from the current directory.
    #[arg(long)]
    suite: Option<PathBuf>,
    /// The render binary. Default: `render` beside this program (the same target folder).
    #[arg(long)]
    render: Option<PathBuf>,
    /// Output folder for report.md, results.csv, the contact sheet, images and logs.
    /// Default: $CARGO_TARGET_DIR/conformance, else target/conformance.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Jobs rendered at once.
    #[arg(short = 'j', long, default_value_t = 1)]
    jobs: usize,
    /// Threads of each render. Default: the cores divided among the parallel jobs.
    #[arg(long)]
    threads: Option<usize>,
    /// Only jobs whose `category/.../name` contains PATTERN (case-insensitive; repeatable).
    #[arg(long, value_name = "PATTERN")]
    only: Vec<String>,
    /// Seconds before a job is killed.
    #[arg(long, default_value_t = 120)]
    timeout: u64,
    /// The verdict threshold on mean absolute error over RGB (0..1).
    #[arg(long, default_value_t = MAX_MAE)]
    max_mae: f64,
    /// Divergence explanations (job → class and reason).
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/explanations.toml"))]
    explanations: PathBuf,
    /// Keep each job's scratch copy of the suite (out/scratch/<job>).
    #[arg(long)]
    keep_scratch: bool,
    /// List the jobs and exit.
    #[arg(long)]
    list: bool,
}

fn default_suite() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("ILLUME_AQSIS_REGRESSION") {
        return Some(p.into());
    }
    let mut dir = std::env::current_dir().ok()?;
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

fn default_render() -> Option<PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let p = exe
        .parent()?
        .join(format!("render{}", std::env::consts::EXE_SUFFIX));
    p.is_file().then_some(p)
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("conformance: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(args: Args) -> Result<ExitCode, String> {
    let suite_dir = args
        .suite
        .clone()
        .or_else(default_suite)
        .ok_or("no suite: pass --suite or set ILLUME_AQSIS_REGRESSION")?;
    let mut jobs = suite::load(&suite_dir)?;
    let patterns: Vec<String> = args.only.iter().map(|p| p.to_lowercase()).collect();
    if !patterns.is_empty() {
        jobs.retain(|j| {
            let name = j.path_name().to_lowercase();
            patterns.iter().any(|p| name.contains(p))
        });
    }
    if args.list {
        for j in &jobs {
            println!(
                "{}\t{}",
                j.path_name(),
                j.workdir().join(&j.spec.rib).display()
            );
        }
        return Ok(ExitCode::SUCCESS);
    }
    if jobs.is_empty() {
        return Err(format!("no jobs in {} match", suite_dir.display()));
    }
    let render =
        args.render.clone().or_else(default_render).ok_or(
            "no render binary: build it (cargo build --release -p render) or pass --render",
        )?;
    let render =
        std::fs::canonicalize(&render).map_err(|e| format!("{}: {e}", render.display()))?;
    let out = args.out.clone().unwrap_or_else(|| {
        std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("target"))
            .join("conformance")
    });
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let out = std::fs::canonicalize(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let suite_dir =
        std::fs::canonicalize(&suite_dir).map_err(|e| format!("{}: {e}", suite_dir.display()))?;
    let explanations = explanations::load(&args.explanations)?;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let workers = args.jobs.max(1);
    let cfg = RunConfig {
        suite: suite_dir,
        render,
        out: out.clone(),
        timeout: Duration::from_secs(args.timeout),
        threads: args.threads.unwrap_or((cores / workers).max(1)),
        keep_scratch: args.keep_scratch,
    };
    eprintln!(
        "conformance: {} jobs, {workers} at a time, {} render threads each, output in {}",
        jobs.len(),
        cfg.threads,
        out.display()
    );
    let total = jobs.len();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let progress = |r: &JobResult| {
        let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        let mae = r
            .metrics
            .as_ref()
            .map_or("–".to_string(), |m| format!("{:.4}", m.mae));
        eprintln!(
            "[{k}/{total}] {:<40} {:>6.1} s  MAE {mae:>7}  {}",
            r.job.path_name(),
            r.seconds,
            r.verdict(args.max_mae).as_str()
        );
    };
    let results = run_jobs(&cfg, &jobs, workers, &progress);
    write_outputs(&args, &out, &results, &explanations)?;
    let (pass, n) = report::pass_count(&results, args.max_mae);
    eprintln!(
        "conformance: {pass}/{n} within MAE {}; report: {}",
        args.max_mae,
        out.join("report.md").display()
    );
    let bad = results.iter().filter(|r| {
        let v = r.verdict(args.max_mae);
        matches!(v, Verdict::Crash | Verdict::Timeout)
            || (v != Verdict::Pass && !explanations.contains_key(&r.job.name))
    });
    let bad: Vec<&str> = bad.map(|r| r.job.name.as_str()).collect();
    if bad.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        eprintln!(
            "conformance: crashed, timed out or unexplained: {}",
            bad.join(", ")
        );
        Ok(ExitCode::from(1))
    }
}

fn write_outputs(
    args: &Args,
    out: &Path,
    results: &[JobResult],
    explanations: &explanations::Explanations,
) -> Result<(), String> {
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let sheet_name = "contact_sheet.png";
    let sheet = contact::write_sheet(
        results,
        args.max_mae,
        3,
        &out.join(sheet_name),
        Some(&out.join("triptychs")),
    );
    if let Err(e) = &sheet {
        eprintln!("conformance: contact sheet: {e}");
    }
    let info = report::ReportInfo {
        command: &command,
        max_mae: args.max_mae,
        explanations,
        contact_sheet: sheet.is_ok().then_some(sheet_name),
    };
    let write = |name: &str, text: String| {
        let p = out.join(name);
        std::fs::write(&p, text).map_err(|e| format!("{}: {e}", p.display()))
    };
    write("report.md", report::markdown(results, &info))?;
    write("results.csv", report::csv(results, &info))
}
