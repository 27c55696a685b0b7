//! Running one job the way Aqsis's `rendertester.py` did: in a scratch copy of the whole suite
//! (so `../../shaders/x.sl` and `../../maps/y.tif` resolve), its shaders copied beside the RIB,
//! `render` started in the working directory with a time limit.
use crate::suite::Job;
use std::fs::File;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// How to run the jobs.
#[derive(Debug, Clone)]
pub struct RunConfig {
    /// The suite root (the folder holding `RIBs/` and `reference/`).
    pub suite: PathBuf,
    /// The `render` binary.
    pub render: PathBuf,
    /// Where scratch copies, logs and output images go.
    pub out: PathBuf,
    pub timeout: Duration,
    /// `render --threads` for each job.
    pub threads: usize,
    /// Keep the scratch copy after the job (for debugging a job by hand).
    pub keep_scratch: bool,
}

/// How the render ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// The process exited with this code.
    Exited(i32),
    /// Killed by a signal (a crash such as SIGSEGV/SIGABRT).
    Signalled,
    /// Killed by the runner after the time limit.
    TimedOut,
    /// The runner could not set the job up or start it.
    NotRun(String),
}

/// The result of rendering one job.
#[derive(Debug, Clone)]
pub struct Rendered {
    pub outcome: Outcome,
    pub seconds: f64,
    /// The output images copied out of the scratch folder (`None`: not written).
    pub images: Vec<Option<PathBuf>>,
    /// stderr (and for programs, the generator's stderr) of the run.
    pub log: PathBuf,
}

/// Renders `job` and copies its output images to `out/images/<name>.<ext>`.
pub fn render_job(cfg: &RunConfig, job: &Job) -> Rendered {
    let logs = cfg.out.join("logs");
    let images_dir = cfg.out.join("images");
    let log = logs.join(format!("{}.log", job.name));
    let scratch = cfg.out.join("scratch").join(&job.name);
    let not_run = |why: String| Rendered {
        outcome: Outcome::NotRun(why),
        seconds: 0.0,
        images: vec![None; job.images.len()],
        log: log.clone(),
    };
    if let Err(e) = std::fs::create_dir_all(&logs).and(std::fs::create_dir_all(&images_dir)) {
        return not_run(format!("{}: {e}", cfg.out.display()));
    }
    let _ = std::fs::remove_dir_all(&scratch);
    if let Err(e) = copy_tree(&cfg.suite, &scratch) {
        return not_run(format!("copying the suite to {}: {e}", scratch.display()));
    }
    let workdir = scratch.join(job.workdir());
    // A listed shader the suite does not hold (`pointlight.sl`: Aqsis took its standard
    // shaders from its own install) is noted in the log; the renderer's built-in stands in.
    let mut notes = String::new();
    for shader in &job.spec.shaders {
        let from = workdir.join(shader);
        let Some(file_name) = from.file_name() else {
            continue;
        };
        let to = workdir.join(file_name);
        if !from.is_file() {
            notes.push_str(&format!(
                "conformance: listed shader {shader} is not in the suite\n"
            ));
        } else if from != to {
            if let Err(e) = std::fs::copy(&from, &to) {
                return not_run(format!("shader {shader}: {e}"));
            }
        }
    }
    let start = Instant::now();
    let outcome = match spawn(cfg, job, &workdir, &log, &notes) {
        Ok(children) => wait_all(children, cfg.timeout),
        Err(e) => Outcome::NotRun(e),
    };
    let seconds = start.elapsed().as_secs_f64();
    let images = job
        .images
        .iter()
        .map(|image| {
            let from = workdir.join(image);
            let ext = from.extension().and_then(|e| e.to_str()).unwrap_or("tif");
            let to = images_dir.join(format!("{}.{ext}", job.name));
            let _ = std::fs::remove_file(&to);
            (from.is_file() && std::fs::copy(&from, &to).is_ok()).then_some(to)
        })
        .collect();
    if !cfg.keep_scratch {
        let _ = std::fs::remove_dir_all(&scratch);
    }
    Rendered {
        outcome,
        seconds,
        images,
        log,
    }
}

/// Starts `render RIB`, or `python3 PROGRAM | render -` for a RIB-generating program; every
/// process writes its stderr (and render its stdout) to `log`.
fn spawn(
    cfg: &RunConfig,
    job: &Job,
    workdir: &Path,
    log: &Path,
    notes: &str,
) -> Result<Vec<Child>, String> {
    let mut first = File::create(log).map_err(|e| format!("{}: {e}", log.display()))?;
    first
        .write_all(notes.as_bytes())
        .map_err(|e| format!("{}: {e}", log.display()))?;
    let second = first.try_clone().map_err(|e| e.to_string())?;
    let mut render = Command::new(&cfg.render);
    render
        .current_dir(workdir)
        .env("PYTHONPATH", python_path())
        .arg("-q")
        .arg("--threads")
        .arg(cfg.threads.to_string())
        .stdout(Stdio::from(first))
        .stderr(Stdio::from(second));
    let start_err = |what: &Path, e: std::io::Error| format!("starting {}: {e}", what.display());
    if !job.is_program() {
        let child = render
            .arg(&job.spec.rib)
            .spawn()
            .map_err(|e| start_err(&cfg.render, e))?;
        return Ok(vec![child]);
    }
    let mut generator = Command::new("python3")
        .current_dir(workdir)
        .env("PYTHONPATH", python_path())
        .arg(&job.spec.rib)
        .stdout(Stdio::piped())
        .stderr(Stdio::from(log_file_append(log)?))
        .spawn()
        .map_err(|e| start_err(Path::new("python3"), e))?;
    let Some(rib) = generator.stdout.take() else {
        let _ = generator.kill();
        return Err("python3 gave no stdout".to_string());
    };
    match render.arg("-").stdin(Stdio::from(rib)).spawn() {
        Ok(child) => Ok(vec![generator, child]),
        Err(e) => {
            let _ = generator.kill();
            let _ = generator.wait();
            Err(start_err(&cfg.render, e))
        }
    }
}

/// `PYTHONPATH` for a job's processes: `pyshim/` (stand-ins for the Python 2-era `cgkit.ri`
/// and old PIL modules that the suite's RunProgram helpers import; see its README) before
/// whatever the caller had.
fn python_path() -> std::ffi::OsString {
    let shim = Path::new(env!("CARGO_MANIFEST_DIR")).join("pyshim");
    let mut paths = vec![shim];
    if let Some(old) = std::env::var_os("PYTHONPATH") {
        paths.extend(std::env::split_paths(&old));
    }
    std::env::join_paths(paths).unwrap_or_default()
}

fn log_file_append(log: &Path) -> Result<File, String> {
    std::fs::OpenOptions::new()
        .append(true)
        .open(log)
        .map_err(|e| format!("{}: {e}", log.display()))
}

/// Waits for every process; kills them all once `timeout` has passed. The outcome is the last
/// process's (the renderer's), unless it was killed.
fn wait_all(mut children: Vec<Child>, timeout: Duration) -> Outcome {
    let start = Instant::now();
    let mut status: Vec<Option<ExitStatus>> = vec![None; children.len()];
    loop {
        for (child, s) in children.iter_mut().zip(status.iter_mut()) {
            if s.is_none() {
                *s = child.try_wait().ok().flatten();
            }
        }
        if status.iter().all(Option::is_some) {
            break;
        }
        if start.elapsed() > timeout {
            for child in &mut children {
                let _ = child.kill();
                let _ = child.wait();
            }
            return Outcome::TimedOut;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    match status.last().copied().flatten().map(|s| s.code()) {
        Some(Some(code)) => Outcome::Exited(code),
        _ => Outcome::Signalled,
    }
}

/// Copies the suite to `to`, leaving out `reference/` (a job must not see the answers).
fn copy_tree(from: &Path, to: &Path) -> std::io::Result<()> {
    for entry in walkdir::WalkDir::new(from).min_depth(1) {
        let entry = entry.map_err(std::io::Error::other)?;
        let rel = entry
            .path()
            .strip_prefix(from)
            .map_err(std::io::Error::other)?;
        if rel.starts_with("reference") {
            continue;
        }
        let dest = to.join(rel);
        if entry.file_type().is_dir() {
            std::fs::create_dir_all(&dest)?;
        } else if entry.file_type().is_file() {
            if let Some(parent) = dest.parent() {
                std::fs::create_dir_all(parent)?;
            }
            std::fs::copy(entry.path(), &dest)?;
            // The shared suite is read-only; jobs overwrite their own files (shadow maps).
            let mut perms = std::fs::metadata(&dest)?.permissions();
            if perms.readonly() {
                #[allow(clippy::permissions_set_readonly_false)] // the copy is ours alone
                perms.set_readonly(false);
                std::fs::set_permissions(&dest, perms)?;
            }
        }
    }
    Ok(())
}
