//! `bench`: sweeps the renderer's quality knobs over closed-form and gallery scenes and writes
//! `speed_error.csv`, `speed_error.png` and `speed_error.md` (issue 8).
//!
//! Exit codes: 0 every point measured, 1 some points or scenes failed (the rest written) or,
//! with `--threads` alone, some thread count's image differed from 1 thread's, 2 usage error
//! or nothing could be measured.
#![forbid(unsafe_code)]

use bench::knob::Settings;
use bench::scene::{Scene, SceneKind};
use bench::sweep::{sweep_scene, SweepConfig};
use clap::Parser;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Parser)]
#[command(
    name = "bench",
    about = "Speed against error of Illume's quality knobs"
)]
struct Args {
    /// Small images and fewer points (under 2 minutes on 2 cores; what CI runs).
    #[arg(long)]
    quick: bool,
    /// Directory for speed_error.csv, speed_error.png and speed_error.md.
    #[arg(long, default_value = ".")]
    out: PathBuf,
    /// The `render` binary (default: next to this program).
    #[arg(long)]
    render: Option<PathBuf>,
    /// The gallery scenes' directory (default: the repository's rib/).
    #[arg(long)]
    rib_dir: Option<PathBuf>,
    /// Scratch directory for scenes and renders (default: a new one under the temp dir,
    /// removed afterwards).
    #[arg(long)]
    scratch: Option<PathBuf>,
    /// Renders per point, the fastest kept (default 1 with --quick, else 2).
    #[arg(long)]
    repeat: Option<usize>,
    /// `--threads N`: threads of every point except the thread-count sweep (default: all
    /// cores). `--threads` alone: the thread-scaling table instead of the sweep: the teapot and
    /// 400 spheres at --scales × their Format (default 4) rendered with 1, 2, … --max-threads
    /// threads, wall, CPU, speedup, efficiency and whether the bits match 1 thread (issue 21).
    #[arg(long, num_args = 0..=1)]
    threads: Option<Option<usize>>,
    /// The largest thread count of `--threads` alone (default: all cores).
    #[arg(long)]
    max_threads: Option<usize>,
    /// Print `--threads`' table as CSV instead of markdown.
    #[arg(long)]
    csv: bool,
    /// Motion blur against the still frame: render rib/bench's blur scenes shutter open and
    /// closed at each of --scales × their Format and print the times (issue 21), no sweep.
    #[arg(long)]
    motion: bool,
    /// Image scales of --motion (default 1,2,4); with `--threads` alone, the one scale used
    /// (default 4).
    #[arg(long, value_delimiter = ',')]
    scales: Vec<u32>,
    /// Time and peak RSS against image size, sphere count (instanced and unique), pixel samples
    /// and AOV count: writes scaling.csv, scaling.png and scaling.md to --out (issue 21).
    #[arg(long)]
    scaling: bool,
    /// Largest sphere count of --scaling (10⁶ takes minutes; default 10⁵, 10⁴ with --quick).
    #[arg(long, default_value_t = 100_000)]
    max_prims: usize,
    /// Side by side with a peer renderer: this command line (the scene file appended), run on
    /// the 14-scene set at --peer-scale × Format per axis; writes peer.csv and peer.md.
    #[arg(long, allow_hyphen_values = true)]
    peer: Option<String>,
    /// Per-axis scale of --peer's scenes (2: 4× the pixels).
    #[arg(long, default_value_t = 2)]
    peer_scale: u32,
    /// Only these scenes of --peer (comma-separated names).
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Redraw speed_error.png and speed_error.md from this speed_error.csv, measuring nothing.
    #[arg(long)]
    from_csv: Option<PathBuf>,
}

/// `--from-csv`: the points of a previous run, grouped by scene in file order.
fn redraw(csv: &Path, out: &Path) -> ExitCode {
    let points = match std::fs::read_to_string(csv)
        .map_err(|e| e.to_string())
        .and_then(|t| bench::csv::from_csv(&t))
    {
        Ok(p) => p,
        Err(e) => {
            eprintln!("bench: {}: {e}", csv.display());
            return ExitCode::from(2);
        }
    };
    let mut results: Vec<(String, Vec<bench::sweep::Point>)> = Vec::new();
    for p in points {
        match results.iter_mut().find(|(name, _)| *name == p.scene) {
            Some((_, v)) => v.push(p),
            None => results.push((p.scene.clone(), vec![p])),
        }
    }
    for (_, v) in &mut results {
        bench::sweep::mark_pareto(v);
    }
    // The defaults are the settings of the defaults' own point (knob PIXELSAMPLES at 2).
    let defaults = results
        .iter()
        .flat_map(|(_, v)| v.iter())
        .find(|p| p.knob == Some(bench::knob::Knob::PixelSamples) && p.value == 2.0)
        .map_or(Settings::defaults(256, 2), |p| p.settings);
    let heading = format!("Redrawn by `bench --from-csv {}`.", csv.display());
    match write_outputs(out, &results, &defaults, &heading) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bench: {e}");
            ExitCode::from(2)
        }
    }
}

fn default_render() -> Option<PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let p = exe
        .parent()?
        .join(format!("render{}", std::env::consts::EXE_SUFFIX));
    p.exists().then_some(p)
}

fn scenes(quick: bool, rib_dir: &Path) -> Vec<Scene> {
    let res = if quick { 48 } else { 224 };
    let mut v = vec![
        Scene {
            name: "matte_sphere".into(),
            kind: SceneKind::MatteSphere,
            res,
        },
        Scene {
            name: "disk_shadow".into(),
            kind: SceneKind::DiskShadow,
            res,
        },
        Scene {
            name: "mirror_sphere".into(),
            kind: SceneKind::MirrorSphere,
            res,
        },
    ];
    let gallery: &[(&str, &str)] = if quick {
        &[("sphere", "sphere.rib")]
    } else {
        &[
            ("sphere", "sphere.rib"),
            ("teapot", "teapot.rib"),
            ("fig9_2_vase", "ch9/fig9_2_vase.rib"),
            ("fig9_8_ward", "ch9/fig9_8_ward.rib"),
        ]
    };
    let scale = if quick { 0.25 } else { 0.75 };
    for (name, file) in gallery {
        let path = rib_dir.join(file);
        if path.exists() {
            v.push(Scene {
                name: (*name).into(),
                kind: SceneKind::Gallery { path, scale },
                res,
            });
        } else {
            eprintln!(
                "bench: warning: {} not found; gallery scene {name} skipped",
                path.display()
            );
        }
    }
    v
}

fn write_outputs(
    out: &Path,
    results: &[(String, Vec<bench::sweep::Point>)],
    defaults: &Settings,
    heading: &str,
) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let all: Vec<_> = results
        .iter()
        .flat_map(|(_, p)| p.iter().cloned())
        .collect();
    let files = [
        ("speed_error.csv", bench::csv::to_csv(&all).into_bytes()),
        ("speed_error.png", bench::plot::plot_png(results)?),
        (
            "speed_error.md",
            bench::table::markdown(results, defaults, heading).into_bytes(),
        ),
    ];
    for (name, bytes) in files {
        let path = out.join(name);
        // Temporary sibling + rename (the displays' writer): a reader never sees half a file.
        illume_imageio::write_atomically(&path, |w| {
            w.write_all(&bytes)
                .map_err(|source| illume_imageio::ImageError::Io {
                    path: path.display().to_string(),
                    source,
                })
        })
        .map_err(|e| e.to_string())?;
        eprintln!("bench: wrote {}", path.display());
    }
    Ok(())
}

/// Writes `files` (name, bytes) under `out`, each atomically.
fn write_files(out: &Path, files: &[(&str, Vec<u8>)]) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (name, bytes) in files {
        let path = out.join(name);
        illume_imageio::write_atomically(&path, |w| {
            w.write_all(bytes)
                .map_err(|source| illume_imageio::ImageError::Io {
                    path: path.display().to_string(),
                    source,
                })
        })
        .map_err(|e| e.to_string())?;
        eprintln!("bench: wrote {}", path.display());
    }
    Ok(())
}

/// `--scaling`: every point of the plan, then the CSV, plot and summary.
fn scaling(args: &Args, render: &Path, scratch: &Path, threads: usize) -> Result<(), String> {
    let max_prims = if args.quick {
        args.max_prims.min(10_000)
    } else {
        args.max_prims
    };
    let plan = bench::scaling::plan(args.quick, max_prims);
    let repeat = args.repeat.unwrap_or(1);
    let start = Instant::now();
    let rows = bench::scaling::run(render, scratch, &plan, threads, repeat)?;
    let heading = format!(
        "Measured by `bench --scaling{}` in {:.0} s ({threads} threads, the smallest of {repeat} runs per number; \
         wall, user + system CPU and peak RSS of the render process).",
        if args.quick { " --quick" } else { "" },
        start.elapsed().as_secs_f64()
    );
    write_files(
        &args.out,
        &[
            ("scaling.csv", bench::scaling::to_csv(&rows).into_bytes()),
            ("scaling.png", bench::scaling_plot::plot_png(&rows)?),
            (
                "scaling.md",
                bench::scaling::markdown(&rows, &heading).into_bytes(),
            ),
        ],
    )
}

/// `--peer CMD`: the side-by-side table. `Ok(failures)`.
fn peer(
    args: &Args,
    cmd: &str,
    render: &Path,
    scratch: &Path,
    threads: usize,
) -> Result<usize, String> {
    let peer: Vec<String> = cmd.split_whitespace().map(str::to_string).collect();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let repeat = args.repeat.unwrap_or(1);
    let cfg = bench::peer::PeerConfig {
        render,
        peer: &peer,
        repo: &repo,
        scratch,
        scale: args.peer_scale,
        threads,
        repeat,
    };
    let (rows, failures) = bench::peer::run(&cfg, &args.only)?;
    if rows.is_empty() {
        return Err("no scene measured".into());
    }
    let heading = format!(
        "Measured by `bench --peer '{cmd}'`: {} scenes at {}× their Format per axis, ours with {threads} threads, \
         the renderers alternating scene by scene, the smallest of {repeat} runs per number; wall, user + system CPU \
         and peak RSS of each renderer's process. Speed-up = peer / ours (above 1: we are faster); RSS ratio = ours / peer.",
        rows.len(),
        args.peer_scale
    );
    write_files(
        &args.out,
        &[
            ("peer.csv", bench::peer::to_csv(&rows).into_bytes()),
            (
                "peer.md",
                bench::peer::markdown(&rows, &heading).into_bytes(),
            ),
        ],
    )?;
    println!("{}", bench::peer::markdown(&rows, &heading));
    Ok(failures)
}

fn main() -> ExitCode {
    // The measuring wrapper (`bench::child`): bench runs each measured command under a copy of
    // itself so that the command's peak RSS is that copy's only child's.
    let argv: Vec<String> = std::env::args().collect();
    if argv.get(1).map(String::as_str) == Some(bench::child::WRAPPER_FLAG) {
        return bench::child::wrapper_main(&argv[2..]);
    }
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    if let Some(csv) = &args.from_csv {
        return redraw(csv, &args.out);
    }
    let Some(render) = args.render.clone().or_else(default_render) else {
        eprintln!("bench: no render binary next to bench; build it (cargo build --release -p render) or pass --render");
        return ExitCode::from(2);
    };
    // The renders run in per-scene scratch directories: relative paths would not resolve there.
    let render = match std::fs::canonicalize(&render) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("bench: {}: {e}", render.display());
            return ExitCode::from(2);
        }
    };
    let rib_dir = args
        .rib_dir
        .clone()
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../rib"));
    let own_scratch = args.scratch.is_none();
    let scratch = args.scratch.clone().unwrap_or_else(|| {
        std::env::temp_dir().join(format!("illume-bench-{}", std::process::id()))
    });
    let scratch =
        match std::fs::create_dir_all(&scratch).and_then(|()| std::fs::canonicalize(&scratch)) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("bench: {}: {e}", scratch.display());
                return ExitCode::from(2);
            }
        };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = args.threads.flatten().unwrap_or(cores);
    if matches!(args.threads, Some(None)) || args.max_threads.is_some() {
        let scale = args.scales.last().copied().unwrap_or(4);
        let max_threads = args.max_threads.unwrap_or(cores);
        let repeat = args.repeat.unwrap_or(2);
        let rows = bench::threads::run(&render, &rib_dir, &scratch, scale, max_threads, repeat);
        if own_scratch {
            let _ = std::fs::remove_dir_all(&scratch);
        }
        return match rows {
            Ok(rows) if args.csv => {
                print!("{}", bench::threads::csv(&rows));
                ExitCode::from(u8::from(rows.iter().any(|r| !r.identical)))
            }
            Ok(rows) => {
                println!("{}", bench::threads::table(&rows));
                ExitCode::from(u8::from(rows.iter().any(|r| !r.identical)))
            }
            Err(e) => {
                eprintln!("bench: {e}");
                ExitCode::from(2)
            }
        };
    }
    if args.scaling || args.peer.is_some() {
        let result = match &args.peer {
            Some(cmd) => peer(
                &args,
                cmd,
                &render,
                &scratch,
                args.threads.flatten().unwrap_or(2),
            ),
            None => scaling(&args, &render, &scratch, threads).map(|()| 0),
        };
        if own_scratch {
            let _ = std::fs::remove_dir_all(&scratch);
        }
        return match result {
            Ok(failures) => ExitCode::from(u8::from(failures > 0)),
            Err(e) => {
                eprintln!("bench: {e}");
                ExitCode::from(2)
            }
        };
    }
    if args.motion {
        let repeat = args.repeat.unwrap_or(1);
        let scales = if args.scales.is_empty() {
            vec![1, 2, 4]
        } else {
            args.scales.clone()
        };
        let rows = bench::motion::run(&render, &rib_dir, &scratch, &scales, threads, repeat);
        if own_scratch {
            let _ = std::fs::remove_dir_all(&scratch);
        }
        return match rows {
            Ok(rows) => {
                println!("{}", bench::motion::table(&rows));
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("bench: {e}");
                ExitCode::from(2)
            }
        };
    }
    sweep_all(&args, &render, &rib_dir, &scratch, threads, own_scratch)
}

/// The default mode: every scene's quality-knob sweep, written as CSV, plots and a table.
fn sweep_all(
    args: &Args,
    render: &Path,
    rib_dir: &Path,
    scratch: &Path,
    threads: usize,
    own_scratch: bool,
) -> ExitCode {
    let defaults = Settings::defaults(256, threads);
    let cfg = SweepConfig {
        render,
        scratch,
        quick: args.quick,
        repeat: args.repeat.unwrap_or(if args.quick { 1 } else { 2 }),
        defaults,
    };
    let start = Instant::now();
    let mut results = Vec::new();
    let mut failures = 0;
    for scene in scenes(args.quick, rib_dir) {
        match sweep_scene(&scene, &cfg) {
            Ok(points) => results.push((scene.name.clone(), points)),
            Err(e) => {
                eprintln!("bench: {}: {e}", scene.name);
                failures += 1;
            }
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    let points: usize = results.iter().map(|(_, p)| p.len()).sum();
    eprintln!(
        "bench: {points} points over {} scenes in {elapsed:.1} s",
        results.len()
    );
    if own_scratch {
        let _ = std::fs::remove_dir_all(scratch);
    }
    if results.is_empty() {
        eprintln!("bench: nothing measured");
        return ExitCode::from(2);
    }
    let heading = format!(
        "Measured by `bench{}` in {elapsed:.0} s ({} threads, the smallest wall and CPU time of {} runs per point).",
        if args.quick { " --quick" } else { "" },
        threads,
        cfg.repeat.max(1)
    );
    if let Err(e) = write_outputs(&args.out, &results, &defaults, &heading) {
        eprintln!("bench: {e}");
        return ExitCode::from(2);
    }
    ExitCode::from(u8::from(failures > 0))
}
