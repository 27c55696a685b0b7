//! `farm merge`: paste each frame's tiles into one float image and write the frame's
//! displays through the same `write_displays` a single-machine `render` uses, so the files
//! are bit-identical to it. A frame with a missing or stale tile is refused, and its missing
//! tiles are listed; the complete frames are still merged.

use crate::error::FarmError;
use crate::jobdir::{up_to_date, Config, JobDir};
use crate::plan::{plan, todo, Plan};
use crate::scene::read_scene;
use illume_render::{Rendered, Tile};
use illume_ri::{from_rib_diagnostic, Ri};
use std::time::Instant;

/// What one `farm merge` did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MergeReport {
    /// Frame label and seconds to read, paste and write it.
    pub merged: Vec<(String, f64)>,
    /// Frame label and the names of its missing tiles (`x1y3`).
    pub incomplete: Vec<(String, Vec<String>)>,
    pub up_to_date: Vec<String>,
    /// Display or tile errors, one line each.
    pub errors: Vec<String>,
}

/// Pastes `tiles` into the crop region `region` (pixels x0, x1, y0, y1). Every pixel must be
/// covered by exactly one tile of a `xres × yres` frame.
pub fn assemble(
    xres: u32,
    yres: u32,
    region: [u32; 4],
    tiles: &[Tile],
) -> Result<Rendered, String> {
    let [rx0, rx1, ry0, ry1] = region;
    let (w, h) = (rx1.saturating_sub(rx0), ry1.saturating_sub(ry0));
    let n = w as usize * h as usize;
    let mut rgba = vec![0.0f32; n * 4];
    let mut z = vec![f32::MAX; n];
    let mut covered = vec![0u8; n];
    // Every tile of a frame carries the same output variables (the same scene rendered them).
    let aov_layout = tiles
        .first()
        .map(|t| t.aov_layout.clone())
        .unwrap_or_default();
    let stride = aov_layout.stride;
    let mut aov = vec![0.0f32; n * stride];
    for t in tiles {
        if t.aov_layout != aov_layout {
            return Err(format!(
                "tile at ({}, {}) carries other output variables than the frame's first tile",
                t.x0, t.y0
            ));
        }
        if (t.xres, t.yres) != (xres, yres) {
            return Err(format!(
                "tile at ({}, {}) is from a {}x{} frame, not {xres}x{yres}",
                t.x0, t.y0, t.xres, t.yres
            ));
        }
        if t.x0 < rx0 || t.y0 < ry0 || t.x0 + t.width > rx1 || t.y0 + t.height > ry1 {
            return Err(format!(
                "tile {}x{} at ({}, {}) lies outside the frame's crop region",
                t.width, t.height, t.x0, t.y0
            ));
        }
        for y in 0..t.height {
            for x in 0..t.width {
                let src = (y * t.width + x) as usize;
                let dst = ((t.y0 - ry0 + y) * w + (t.x0 - rx0 + x)) as usize;
                covered[dst] = covered[dst].saturating_add(1);
                rgba[dst * 4..dst * 4 + 4].copy_from_slice(&t.rgba[src * 4..src * 4 + 4]);
                z[dst] = t.z[src];
                aov[dst * stride..(dst + 1) * stride]
                    .copy_from_slice(&t.aov[src * stride..(src + 1) * stride]);
            }
        }
    }
    if let Some(i) = covered.iter().position(|&c| c != 1) {
        let (x, y) = (rx0 + i as u32 % w.max(1), ry0 + i as u32 / w.max(1));
        return Err(format!(
            "pixel ({x}, {y}) is covered by {} tiles, expected exactly 1",
            covered[i]
        ));
    }
    Ok(Rendered {
        x0: rx0,
        y0: ry0,
        width: w,
        height: h,
        rgba,
        z,
        aov_layout,
        aov,
        stats: Default::default(),
        warnings: Vec::new(),
    })
}

/// Merges every selected frame whose tiles are all present and newer than the scene.
pub fn merge(dir: &JobDir, force: bool) -> Result<MergeReport, FarmError> {
    let config = dir.read_config()?;
    let scene = read_scene(&config.scene)?;
    let plan = plan(&scene, config.tiles, config.frames);
    let todo = todo(&plan, dir, &config);
    let mut report = MergeReport::default();
    let mut wanted = Vec::new();
    for (i, f) in plan.frames.iter().enumerate() {
        let missing: Vec<String> = f
            .tiles
            .iter()
            .filter(|&&t| todo.tiles.contains(&t))
            .map(|&t| plan.tiles[t].window.name())
            .collect();
        if !missing.is_empty() {
            report.incomplete.push((f.label.clone(), missing));
        } else if force || todo.merges.contains(&i) {
            wanted.push(i);
        } else {
            report.up_to_date.push(f.label.clone());
        }
    }
    if !wanted.is_empty() {
        write_frames(dir, &config, &plan, &wanted, &mut report)?;
    }
    Ok(report)
}

/// Streams the scene through `Ri` once (each frame is dropped as soon as it is written) and
/// writes the displays of the frames in `wanted` (indices into `plan.frames`).
fn write_frames(
    dir: &JobDir,
    config: &Config,
    plan: &Plan,
    wanted: &[usize],
    report: &mut MergeReport,
) -> Result<(), FarmError> {
    let parser = illume_rib::open(&config.scene).map_err(crate::error::io_error(&config.scene))?;
    let mut ri = Ri::new();
    ri.set_texture_maker(Box::new(|_, _| Ok(())));
    let single = plan.frames.len() == 1 && plan.frames[0].beauty.number.is_none();
    let handle = |frame: illume_ri::Frame, report: &mut MergeReport| {
        let Some(&i) = wanted.iter().find(|&&i| {
            single || plan.frames[i].beauty.number == frame.number && frame.number.is_some()
        }) else {
            return;
        };
        let f = &plan.frames[i];
        let t0 = Instant::now();
        let tiles: Result<Vec<Tile>, String> = f
            .tiles
            .iter()
            .map(|&t| {
                illume_render::read_tile(&dir.root.join(&plan.tiles[t].file))
                    .map_err(|e| e.to_string())
            })
            .collect();
        let merged =
            tiles.and_then(|tiles| assemble(f.beauty.xres, f.beauty.yres, f.beauty.crop, &tiles));
        let rendered = match merged {
            Ok(r) => r,
            Err(e) => {
                report.errors.push(format!("{}: {e}", f.label));
                return;
            }
        };
        let frame = displays_under(frame, &config.cwd);
        let mut ok = true;
        for result in illume_render::write_displays(&frame, &rendered) {
            if let Err(e) = result {
                report.errors.push(format!("{}: {e}", f.label));
                ok = false;
            }
        }
        if ok {
            let marker = dir.done("merge", &f.label);
            match crate::jobdir::write_atomically(&marker, b"") {
                Ok(()) => report
                    .merged
                    .push((f.label.clone(), t0.elapsed().as_secs_f64())),
                Err(e) => report.errors.push(e.to_string()),
            }
        }
    };
    for item in parser {
        match item {
            Ok(req) => ri.request(req),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
        ri.drain_diagnostics();
        for frame in ri.take_frames() {
            handle(frame, report);
        }
    }
    ri.finish();
    for frame in ri.take_frames() {
        handle(frame, report);
    }
    Ok(())
}

/// Display names in a RIB are relative to where `render` runs (the submit directory): make
/// them absolute, and spell out the default `ri.tif` display, so merge may run anywhere.
fn displays_under(mut frame: illume_ri::Frame, cwd: &std::path::Path) -> illume_ri::Frame {
    if frame.options.displays.is_empty() {
        frame.options.displays.push(illume_ri::DisplaySpec {
            name: "ri.tif".into(),
            kind: "tiff".into(),
            mode: "rgba".into(),
            ..Default::default()
        });
    }
    for d in &mut frame.options.displays {
        d.name = cwd.join(&d.name).display().to_string();
    }
    frame
}

/// Whether the frame's merged displays are newer than its tiles (for `farm status`).
pub fn is_merged(dir: &JobDir, config: &Config, plan: &Plan, frame: usize) -> bool {
    let f = &plan.frames[frame];
    let files: Vec<std::path::PathBuf> = f
        .tiles
        .iter()
        .map(|&t| dir.root.join(&plan.tiles[t].file))
        .collect();
    let mut inputs: Vec<&std::path::Path> = files.iter().map(|p| p.as_path()).collect();
    inputs.push(&config.scene);
    up_to_date(&dir.done("merge", &f.label), &inputs)
}
