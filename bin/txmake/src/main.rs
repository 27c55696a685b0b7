//! `txmake`: PRMan-style texture maker over `illume_texture::build`.
//!
//! ```text
//! txmake [options] in out
//! txmake -envcube px nx py ny pz nz out
//! txmake -envlatl in out
//! txmake -shadow in.z out.sm
//! ```
//! PRMan's options are single-dash words (`-smode`, `-filterwidth`), which derive-style parsers
//! mistake for clusters of short flags, so the arguments are read by a small explicit loop.
//! Exit status: 0 done (or skipped by `-newer`), 1 the build failed, 2 usage error.
#![forbid(unsafe_code)]

use illume_texture::{
    make_cube_face_environment, make_latlong_environment, make_shadow, make_texture, FilterKind,
    MakeOptions, PixelFormat, Resize, WrapMode,
};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

const USAGE: &str = "usage: txmake [options] in out
       txmake [options] -envcube px nx py ny pz nz out
       txmake [options] -envlatl in out
       txmake [options] -shadow in.z out.sm
options:
  -mode|-smode|-tmode black|clamp|periodic   wrap modes (default black)
  -resize up|down|round|none (or up- down- round- none-)   default up
  -filter box|triangle|gaussian|catmull-rom|lanczos|mitchell|sinc   (default box)
  -filterwidth w | -sfilterwidth w | -tfilterwidth w
  -float | -half | -short | -byte      texel type (OpenEXR stores half or float)
  -fov degrees                         cube face field of view (default 90)
  -compression none|rle|zips|zip|piz|pxr24|b44|b44a   (default zip)
  -newer                               skip when the output is newer than every input
  -v                                   say what is done
  -q                                   no progress spinner (there is none when stderr is not a terminal)";

#[derive(Debug, PartialEq)]
enum Job {
    Plain { input: PathBuf, out: PathBuf },
    Cube { faces: [PathBuf; 6], out: PathBuf },
    LatLong { input: PathBuf, out: PathBuf },
    Shadow { input: PathBuf, out: PathBuf },
}

#[derive(Debug)]
struct Args {
    job: Job,
    opts: MakeOptions,
    newer: bool,
    verbose: bool,
    quiet: bool,
}

fn parse(args: &[String]) -> Result<Args, String> {
    let mut opts = MakeOptions::default();
    let mut newer = false;
    let mut verbose = false;
    let mut quiet = false;
    let mut mode: Option<&str> = None;
    let mut files: Vec<PathBuf> = Vec::new();
    let mut i = 0;
    let value = |i: &mut usize, flag: &str| -> Result<String, String> {
        *i += 1;
        args.get(*i)
            .cloned()
            .ok_or_else(|| format!("{flag} expects a value"))
    };
    let number = |text: String, flag: &str| -> Result<f32, String> {
        text.parse::<f32>()
            .ok()
            .filter(|v| v.is_finite() && *v > 0.0)
            .ok_or_else(|| format!("{flag} expects a positive number, found `{text}`"))
    };
    let wrap = |text: String, flag: &str| -> Result<WrapMode, String> {
        WrapMode::parse(&text)
            .ok_or_else(|| format!("{flag} expects black, clamp or periodic, found `{text}`"))
    };
    while i < args.len() {
        let a = args[i].as_str();
        match a {
            "-envcube" | "-envlatl" | "-shadow" => {
                if mode.is_some() {
                    return Err(format!("{a}: only one of -envcube, -envlatl, -shadow"));
                }
                mode = Some(&args[i]);
            }
            "-mode" => {
                let m = wrap(value(&mut i, a)?, a)?;
                opts.wrap = [m, m];
            }
            "-smode" => opts.wrap[0] = wrap(value(&mut i, a)?, a)?,
            "-tmode" => opts.wrap[1] = wrap(value(&mut i, a)?, a)?,
            "-resize" => {
                let v = value(&mut i, a)?;
                opts.resize = Resize::parse(&v).ok_or_else(|| {
                    format!("-resize expects up, down, round or none, found `{v}`")
                })?;
            }
            "-filter" => {
                let v = value(&mut i, a)?;
                opts.filter = FilterKind::parse(&v).ok_or_else(|| {
                    format!(
                        "-filter expects one of {}, found `{v}`",
                        illume_texture::filter::filter_names_list()
                    )
                })?;
            }
            "-filterwidth" => {
                let w = number(value(&mut i, a)?, a)?;
                opts.swidth = Some(w);
                opts.twidth = Some(w);
            }
            "-sfilterwidth" => opts.swidth = Some(number(value(&mut i, a)?, a)?),
            "-tfilterwidth" => opts.twidth = Some(number(value(&mut i, a)?, a)?),
            "-float" => opts.format = PixelFormat::Float,
            "-half" => opts.format = PixelFormat::Half,
            "-short" | "-byte" => {
                eprintln!(
                    "txmake: warning: {a}: OpenEXR textures hold half or float; writing half"
                );
                opts.format = PixelFormat::Half;
            }
            "-fov" => {
                let v = value(&mut i, a)?;
                opts.fov = v
                    .parse::<f32>()
                    .ok()
                    .filter(|f| *f >= 90.0 && *f < 179.0)
                    .ok_or_else(|| format!("-fov expects degrees in [90, 179), found `{v}`"))?;
            }
            "-compression" => {
                let v = value(&mut i, a)?;
                if illume_texture::txfile::parse_compression(&v).is_none() {
                    return Err(format!("-compression expects none, rle, zips, zip, piz, pxr24, b44 or b44a, found `{v}`"));
                }
                opts.compression = v;
            }
            "-newer" => newer = true,
            "-v" | "-verbose" => verbose = true,
            "-q" | "-quiet" => quiet = true,
            "-h" | "-help" | "--help" => return Err(String::new()),
            _ if a.starts_with('-') && a.len() > 1 => return Err(format!("unknown option `{a}`")),
            _ => files.push(PathBuf::from(a)),
        }
        i += 1;
    }
    let count = |n: usize, what: &str| -> Result<(), String> {
        if files.len() == n {
            Ok(())
        } else {
            Err(format!(
                "{what} expects {n} file names, found {}",
                files.len()
            ))
        }
    };
    let job = match mode {
        Some("-envcube") => {
            count(7, "-envcube")?;
            let out = files[6].clone();
            Job::Cube {
                faces: std::array::from_fn(|k| files[k].clone()),
                out,
            }
        }
        Some("-envlatl") => {
            count(2, "-envlatl")?;
            Job::LatLong {
                input: files[0].clone(),
                out: files[1].clone(),
            }
        }
        Some(_) => {
            count(2, "-shadow")?;
            Job::Shadow {
                input: files[0].clone(),
                out: files[1].clone(),
            }
        }
        None => {
            count(2, "txmake")?;
            Job::Plain {
                input: files[0].clone(),
                out: files[1].clone(),
            }
        }
    };
    Ok(Args {
        job,
        opts,
        newer,
        verbose,
        quiet,
    })
}

fn inputs_and_output(job: &Job) -> (Vec<&Path>, &Path) {
    match job {
        Job::Plain { input, out } | Job::LatLong { input, out } | Job::Shadow { input, out } => {
            (vec![input.as_path()], out)
        }
        Job::Cube { faces, out } => (faces.iter().map(|p| p.as_path()).collect(), out),
    }
}

/// `-newer`: the output exists and is at least as new as every input.
fn up_to_date(job: &Job) -> bool {
    let (inputs, out) = inputs_and_output(job);
    let Ok(out_time) = std::fs::metadata(out).and_then(|m| m.modified()) else {
        return false;
    };
    inputs.iter().all(|p| {
        std::fs::metadata(p)
            .and_then(|m| m.modified())
            .map(|t| t <= out_time)
            .unwrap_or(false)
    })
}

fn read(path: &Path) -> Result<illume_imageio::Image, String> {
    illume_imageio::read_image(path).map_err(|e| e.to_string())
}

fn run(args: &Args) -> Result<(), String> {
    let (inputs, out) = inputs_and_output(&args.job);
    let mut opts = args.opts.clone();
    opts.source = inputs
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(" ");
    let progress = (!args.quiet && std::io::stderr().is_terminal()).then(|| {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        bar
    });
    let stage = |what: String| {
        if let Some(bar) = &progress {
            bar.set_message(what);
        }
    };
    let start = Instant::now();
    stage(format!("reading {}", opts.source));
    let pixels: u64 = match &args.job {
        Job::Plain { input, out } => {
            let img = read(input)?;
            stage(format!("filtering {}x{}", img.width, img.height));
            make_texture(&img, out, &opts).map_err(|e| e.to_string())?;
            img.width as u64 * img.height as u64
        }
        Job::LatLong { input, out } => {
            let img = read(input)?;
            stage(format!("filtering {}x{}", img.width, img.height));
            make_latlong_environment(&img, out, &opts).map_err(|e| e.to_string())?;
            img.width as u64 * img.height as u64
        }
        Job::Cube { faces, out } => {
            let imgs = faces
                .iter()
                .map(|p| read(p))
                .collect::<Result<Vec<_>, _>>()?;
            stage("filtering cube faces".into());
            let refs: [&illume_imageio::Image; 6] = std::array::from_fn(|k| &imgs[k]);
            make_cube_face_environment(refs, out, &opts).map_err(|e| e.to_string())?;
            imgs.iter().map(|i| i.width as u64 * i.height as u64).sum()
        }
        Job::Shadow { input, out } => {
            let (img, matrices) = illume_imageio::read_zfile(input).map_err(|e| e.to_string())?;
            stage("building min/max depth pyramid".into());
            make_shadow(&img, &matrices, out, &opts).map_err(|e| e.to_string())?;
            img.width as u64 * img.height as u64
        }
    };
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    if args.verbose {
        let secs = start.elapsed().as_secs_f64();
        eprintln!(
            "txmake: wrote {} from {} ({:.2} Mpixel in {:.3} s, {:.1} Mpixel/s)",
            out.display(),
            opts.source,
            pixels as f64 / 1e6,
            secs,
            pixels as f64 / 1e6 / secs.max(1e-9)
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = match parse(&argv) {
        Ok(a) => a,
        Err(message) => {
            if !message.is_empty() {
                eprintln!("txmake: {message}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    if args.newer && up_to_date(&args.job) {
        if args.verbose {
            eprintln!(
                "txmake: {} is up to date",
                inputs_and_output(&args.job).1.display()
            );
        }
        return ExitCode::SUCCESS;
    }
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("txmake: error: {e}");
            ExitCode::from(1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn argv(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn every_name_of_the_shared_filter_table_is_accepted() {
        // The same table PixelFilter and MakeTexture use (illume_core::filter).
        for &(name, kind) in illume_texture::filter::FILTER_NAMES {
            let a = parse(&argv(&format!("-filter {name} in.tif out.tx"))).unwrap();
            assert_eq!(a.opts.filter, kind, "-filter {name}");
        }
        let e = parse(&argv("-filter bogus in.tif out.tx")).err().unwrap();
        assert!(e.contains("catrom") && e.contains("bogus"), "{e}");
    }

    #[test]
    fn prman_style_single_dash_options_parse() {
        let a = parse(&argv("-smode periodic -tmode clamp -filter catmull-rom -sfilterwidth 3 -float -resize up- in.tif out.tx")).unwrap();
        assert_eq!(a.opts.wrap, [WrapMode::Periodic, WrapMode::Clamp]);
        assert_eq!(a.opts.filter, FilterKind::CatmullRom);
        assert_eq!(a.opts.swidth, Some(3.0));
        assert_eq!(a.opts.format, PixelFormat::Float);
        assert_eq!(a.opts.resize, Resize::Up);
        assert_eq!(
            a.job,
            Job::Plain {
                input: "in.tif".into(),
                out: "out.tx".into()
            }
        );
        let a = parse(&argv("-envcube px nx py ny pz nz env.tx -fov 95")).unwrap();
        assert!(matches!(a.job, Job::Cube { .. }));
        assert_eq!(a.opts.fov, 95.0);
        let a = parse(&argv("-shadow shadow.z shadow.sm")).unwrap();
        assert!(matches!(a.job, Job::Shadow { .. }));
        assert!(!a.quiet);
        assert!(parse(&argv("-q in.tif out.tx")).unwrap().quiet);
    }

    #[test]
    fn usage_errors_are_reported_not_guessed() {
        assert!(parse(&argv("-mode wobble a b"))
            .unwrap_err()
            .contains("wobble"));
        assert!(parse(&argv("-envcube a b c out"))
            .unwrap_err()
            .contains("7 file names"));
        assert!(parse(&argv("-filterwidth"))
            .unwrap_err()
            .contains("expects a value"));
        assert!(parse(&argv("-bogus a b")).unwrap_err().contains("-bogus"));
        assert!(parse(&argv("-fov 45 -envcube a b c d e f g")).is_err());
    }
}
