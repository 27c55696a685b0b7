//! `farm`: render a RIB's frames and tiles on a Slurm cluster and merge the tiles into the
//! frames' displays, bit-identical to a single-machine `render`.
//!
//! ```text
//! farm submit scene.rib [--frames 1-100] [--tiles 4x4] [--partition P] [--dry-run]
//!             [--allow-errors] ...
//! farm merge  scene.rib|scene.farm [--force]
//! farm status scene.rib|scene.farm
//! ```
//!
//! Exit codes: 0 clean; 1 merge refused an incomplete frame or a display failed; 2 usage,
//! unreadable scene, a scene with errors (without `--allow-errors`) or no Slurm (`sbatch`
//! missing or refusing the job; a job directory the failed submit created is removed).
#![forbid(unsafe_code)]

mod error;
mod jobdir;
mod merge;
mod plan;
mod scene;
mod script;
mod source_lines;
mod status;
mod submit;
mod tiles;

use clap::{Parser, Subcommand};
use error::FarmError;
use jobdir::{parse_frame_range, parse_grid, Config, JobDir};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "farm",
    about = "Render RIB frames and tiles on a Slurm cluster"
)]
struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write sbatch array jobs (passes, tiles, merge) into the job directory and submit them.
    Submit {
        scene: PathBuf,
        /// Beauty frames numbered a-b (or n); their passes come with them. Default: all.
        #[arg(long)]
        frames: Option<String>,
        /// Tiles per frame, columns x rows.
        #[arg(long, default_value = "4x4")]
        tiles: String,
        /// Slurm partition for every job.
        #[arg(long)]
        partition: Option<String>,
        /// Print the scripts and sbatch commands; write and submit nothing.
        #[arg(long)]
        dry_run: bool,
        /// Job directory (default: the scene's name with `.farm`, beside it).
        #[arg(long)]
        jobdir: Option<PathBuf>,
        /// Times a failed task is requeued before it gives up.
        #[arg(long, default_value_t = 2)]
        retries: u32,
        /// CPUs per task (render --threads).
        #[arg(long, default_value_t = 1)]
        cpus_per_task: u32,
        /// The cluster's MaxArraySize (`scontrol show config`): larger arrays are split.
        #[arg(long, default_value_t = 1001)]
        max_array_size: usize,
        /// The render binary the tasks run (default: `render` beside this farm binary, else
        /// on PATH). Must be reachable from every node.
        #[arg(long)]
        render: Option<PathBuf>,
        /// Redo every task even if its output is up to date.
        #[arg(long)]
        force: bool,
        /// Submit a scene whose RIB has errors (each task's render exits 1 and `farm status`
        /// lists it); without this, errors are printed and nothing is submitted.
        #[arg(long)]
        allow_errors: bool,
    },
    /// Assemble every frame whose tiles are complete into its displays; list missing tiles.
    Merge {
        /// The scene or its job directory.
        job: PathBuf,
        /// Merge frames even when their displays are newer than their tiles.
        #[arg(long)]
        force: bool,
    },
    /// Progress of a submitted job: tiles done, merged frames, Slurm states, retries, timings.
    Status {
        /// The scene or its job directory.
        job: PathBuf,
    },
}

fn absolute(p: &Path) -> Result<PathBuf, FarmError> {
    std::path::absolute(p).map_err(error::io_error(p))
}

/// `job` is a job directory, or a scene whose default job directory is meant.
fn job_dir(job: &Path) -> Result<JobDir, FarmError> {
    let job = absolute(job)?;
    Ok(if job.is_dir() {
        JobDir { root: job }
    } else {
        JobDir::beside(&job)
    })
}

/// `render` beside the running farm binary (cargo puts both in target/<profile>), else PATH.
fn default_render(farm: &Path) -> PathBuf {
    let beside = farm.with_file_name("render");
    if beside.is_file() {
        return beside;
    }
    std::env::var_os("PATH")
        .and_then(|p| {
            std::env::split_paths(&p)
                .map(|d| d.join("render"))
                .find(|c| c.is_file())
        })
        .unwrap_or_else(|| PathBuf::from("render"))
}

fn run(args: Args) -> Result<ExitCode, FarmError> {
    match args.command {
        Command::Submit {
            scene,
            frames,
            tiles,
            partition,
            dry_run,
            jobdir,
            retries,
            cpus_per_task,
            max_array_size,
            render,
            force,
            allow_errors,
        } => {
            let frames = match frames.as_deref() {
                Some(f) => Some(parse_frame_range(f).ok_or_else(|| {
                    FarmError::Usage(format!("--frames expects a-b or n, found {f:?}"))
                })?),
                None => None,
            };
            let tiles = parse_grid(&tiles).ok_or_else(|| {
                FarmError::Usage(format!(
                    "--tiles expects COLSxROWS (e.g. 4x4), found {tiles:?}"
                ))
            })?;
            let scene = absolute(&scene)?;
            if !scene.is_file() {
                return Err(FarmError::Usage(format!(
                    "{}: no such scene file",
                    scene.display()
                )));
            }
            let cwd = std::env::current_dir().map_err(error::io_error(Path::new(".")))?;
            let farm = std::env::current_exe().map_err(error::io_error(Path::new("farm")))?;
            let render = match render {
                Some(r) => absolute(&r)?,
                None => default_render(&farm),
            };
            let dir = match jobdir {
                Some(d) => JobDir {
                    root: absolute(&d)?,
                },
                None => JobDir::beside(&scene),
            };
            let name = scene
                .file_stem()
                .map_or("farm".into(), |s| s.to_string_lossy().into_owned());
            let ctx = script::ScriptContext {
                dir,
                scene: scene.clone(),
                cwd: cwd.clone(),
                render,
                farm,
                partition,
                retries,
                cpus_per_task: cpus_per_task.max(1),
                name,
            };
            let config = Config {
                scene,
                cwd,
                tiles,
                frames,
            };
            let opts = submit::SubmitOptions {
                dry_run,
                force,
                max_array: max_array_size,
                allow_errors,
            };
            let report = submit::submit(&ctx, &config, &opts)?;
            print!("{}", report.text);
            Ok(ExitCode::SUCCESS)
        }
        Command::Merge { job, force } => {
            let dir = job_dir(&job)?;
            let report = merge::merge(&dir, force)?;
            for (label, seconds) in &report.merged {
                println!("farm: merged {label} in {seconds:.3} s");
            }
            for label in &report.up_to_date {
                println!("farm: {label} is up to date");
            }
            for (label, missing) in &report.incomplete {
                eprintln!(
                    "farm: error: {label} not merged: {} missing tile(s): {}",
                    missing.len(),
                    missing.join(" ")
                );
            }
            for e in &report.errors {
                eprintln!("farm: error: {e}");
            }
            Ok(
                if report.incomplete.is_empty() && report.errors.is_empty() {
                    ExitCode::SUCCESS
                } else {
                    ExitCode::from(1)
                },
            )
        }
        Command::Status { job } => {
            print!("{}", status::status(&job_dir(&job)?)?);
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn main() -> ExitCode {
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match run(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("farm: error: {e}");
            ExitCode::from(2)
        }
    }
}
