//! `render`: RIB files in, images out. A thin layer over `illume-ri` and `illume-render`.
//!
//! Exit codes: 0 clean, 1 rendered with errors, 2 usage error or fatal, 130 interrupted
//! (SIGINT, SIGTERM or SIGHUP: displays being written are removed, none is left half written).
#![forbid(unsafe_code)]

use clap::Parser;
use illume_ri::{Ri, Severity};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Parser)]
#[command(
    name = "render",
    about = "Render RenderMan RIB files with the Illume REYES hider"
)]
struct Args {
    /// No progress bar.
    #[arg(short)]
    q: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Print time per stage, counts and peak memory.
    #[arg(long)]
    stats: bool,
    /// Crop window xmin xmax ymin ymax in NDC, overriding the file's CropWindow.
    #[arg(long, num_args = 4, allow_negative_numbers = true)]
    crop: Option<Vec<f32>>,
    /// Only frames numbered a-b (or a single n).
    #[arg(long)]
    frames: Option<String>,
    /// Skip MakeTexture/MakeShadow/Make*Environment requests (render farms run them once, in
    /// the pass job, not in every tile).
    #[arg(long)]
    no_make: bool,
    /// Write the frame's float image and depth to this tile file instead of its displays
    /// (`farm merge` assembles tiles into the displays). One frame only: use with --frames.
    #[arg(long, value_name = "FILE")]
    tile_out: Option<PathBuf>,
    /// RIB files; `-` reads stdin.
    #[arg(required = true)]
    files: Vec<PathBuf>,
}

fn parse_frames(s: &str) -> Option<(i32, i32)> {
    match s.split_once('-') {
        Some((a, b)) => Some((a.trim().parse().ok()?, b.trim().parse().ok()?)),
        None => s.trim().parse().ok().map(|n| (n, n)),
    }
}

/// Peak resident memory from /proc/self/status (Linux), in kB.
fn peak_memory_kb() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Stops the process on SIGINT/SIGTERM/SIGHUP without leaving a half-written display: every
/// display goes through a temporary file renamed when complete, and the handler removes the
/// temporary files still open (the frame being rendered is lost, earlier frames are kept).
fn install_interrupt_handler() {
    let installed = ctrlc::set_handler(|| {
        let n = illume_imageio::remove_temporary_files();
        eprintln!("render: interrupted; {n} partly written display(s) removed");
        std::process::exit(130);
    });
    if let Err(e) = installed {
        eprintln!("render: warning: no interrupt handler ({e}); an interrupted write may leave a temporary file");
    }
}

fn main() -> ExitCode {
    install_interrupt_handler();
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    let frames = match args.frames.as_deref().map(parse_frames) {
        Some(None) => {
            eprintln!("render: --frames expects a-b or n");
            return ExitCode::from(2);
        }
        Some(r) => r,
        None => None,
    };
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.threads {
        builder = builder.num_threads(n.max(1));
    }
    let pool = match builder.build() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("render: {e}");
            return ExitCode::from(2);
        }
    };
    let show_progress = !args.q && std::io::stderr().is_terminal();
    let mut errors = 0usize;
    let mut fatal = false;
    let output = match &args.tile_out {
        Some(path) => Output::Tile {
            path,
            written: std::cell::Cell::new(false),
        },
        None => Output::Displays,
    };
    for file in &args.files {
        let parser = match illume_rib::open(file) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("render: {}: {e}", file.display());
                fatal = true;
                continue;
            }
        };
        let mut ri = Ri::new();
        ri.set_frame_range(frames);
        if args.no_make {
            ri.set_texture_maker(Box::new(|_, _| Ok(())));
        } else {
            ri.set_texture_maker(illume_render::texture_maker(|request, warning| {
                eprintln!("render: warning: {request}: {warning}")
            }));
        }
        if let Some(c) = &args.crop {
            ri.set_crop_override(Some([c[0], c[1], c[2], c[3]]));
        }
        // Parse time of a frame: from the end of the previous frame's render (or the start).
        let mut since_last_frame = Instant::now();
        illume_render::render_frames_in_order(
            &mut ri,
            parser,
            |d| eprintln!("{d}"),
            |frame| {
                let parse_seconds = since_last_frame.elapsed().as_secs_f64();
                errors += render_frame(
                    &pool,
                    &frame,
                    &output,
                    show_progress,
                    args.stats,
                    parse_seconds,
                );
                since_last_frame = Instant::now();
            },
        );
        errors += ri.error_count();
    }
    if fatal {
        ExitCode::from(2)
    } else if errors > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// Where a rendered frame goes.
enum Output<'a> {
    /// The frame's `Display`s.
    Displays,
    /// One tile file (`--tile-out`); `written` catches a second frame that would overwrite it.
    Tile {
        path: &'a std::path::Path,
        written: std::cell::Cell<bool>,
    },
}

/// Renders and writes one frame; returns the number of errors.
fn render_frame(
    pool: &rayon::ThreadPool,
    frame: &illume_ri::Frame,
    output: &Output,
    show_progress: bool,
    stats: bool,
    parse_seconds: f64,
) -> usize {
    let bar = show_progress.then(|| {
        let b = indicatif::ProgressBar::new(1);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "{msg} [{bar:40}] {pos}/{len} buckets, ETA {eta}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b.set_message(match frame.number {
            Some(n) => format!("frame {n}"),
            None => "frame".to_string(),
        });
        b
    });
    let progress = |done: usize, total: usize| {
        if let Some(b) = &bar {
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    };
    // `limits texturememory` is in kilobytes.
    let cache = illume_texture::TextureCache::new(frame.options.texture_memory as usize * 1024)
        .with_searchpath(frame.options.texture_path.clone());
    let settings = illume_render::RenderSettings {
        progress: Some(&progress),
        textures: Some(&cache),
    };
    let t = Instant::now();
    // Displays are written while the frame renders (streaming output); a tile file holds the
    // whole crop, so `--tile-out` renders into memory.
    let (rendered, written) = match output {
        Output::Displays => {
            let (r, written) = pool.install(|| illume_render::render_to_displays(frame, &settings));
            (r, Some(written))
        }
        Output::Tile { .. } => (
            pool.install(|| illume_render::render(frame, &settings)),
            None,
        ),
    };
    let render_seconds = t.elapsed().as_secs_f64();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let mut errors = 0;
    for w in &rendered.warnings {
        eprintln!("{w}");
        errors += usize::from(w.severity == Severity::Error);
    }
    let t = Instant::now();
    if let Output::Tile { path, written } = output {
        if written.replace(true) {
            eprintln!(
                "render: error: --tile-out {} holds one frame; select it with --frames (frame {} not written)",
                path.display(),
                frame.number.map_or("-".into(), |n| n.to_string())
            );
            return errors + 1;
        }
        let (xres, yres) = (frame.options.xres, frame.options.yres);
        if let Err(e) = illume_render::write_tile(path, &rendered, xres, yres) {
            eprintln!("render: error: {e}");
            errors += 1;
        }
        return errors;
    }
    for result in written.into_iter().flatten() {
        match result {
            Ok(w) if w.framebuffer => {
                eprintln!(
                    "render: framebuffer display written to {}",
                    w.path.display()
                )
            }
            Ok(_) => {}
            Err(e) => {
                eprintln!("render: error: {e}");
                errors += 1;
            }
        }
    }
    let write_seconds = t.elapsed().as_secs_f64();
    if stats {
        let s = &rendered.stats;
        eprintln!(
            "render: stats for frame {}",
            frame.number.map_or("-".into(), |n| n.to_string())
        );
        eprintln!("  time (s)  parse {parse_seconds:.3}  split {:.3}  dice {:.3}*  shade {:.3}*  sample {:.3}*  filter {:.3}*  write {write_seconds:.3}  render wall {render_seconds:.3}", s.split_seconds, s.dice_seconds, s.shade_seconds, s.sample_seconds, s.filter_seconds);
        eprintln!("            (* CPU seconds summed over threads)");
        eprintln!(
            "  counts    primitives {}  pieces {}  grids {}  micropolygons {}  samples {}  culled pieces {}  occluded grids {}  non-finite shaded points {}",
            s.primitives, s.pieces, s.grids, s.micropolygons, s.samples, s.culled_pieces, s.occluded_grids, s.nonfinite
        );
        eprintln!(
            "  live      peak pieces {}  peak grids {}",
            s.peak_live_pieces, s.peak_live_grids
        );
        if render_seconds > 0.0 {
            eprintln!(
                "  rate      {:.0} micropolygons/s",
                s.micropolygons as f64 / render_seconds
            );
        }
        let names: Vec<&str> = rendered
            .aov_layout
            .channels
            .iter()
            .map(|c| c.name.as_str())
            .collect();
        eprintln!(
            "  aov       {} variables ({} floats per visible point){}  largest bucket store {:.2} MB  images {:.2} MB",
            names.len(),
            s.aov_stride,
            if names.is_empty() { String::new() } else { format!(": {}", names.join(",")) },
            s.aov_bucket_peak_bytes as f64 / 1048576.0,
            s.aov_image_bytes as f64 / 1048576.0
        );
        if let Some(kb) = peak_memory_kb() {
            eprintln!("  memory    peak {:.1} MB (VmHWM)", kb as f64 / 1024.0);
        }
    }
    errors
}
