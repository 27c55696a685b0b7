//! `bench --motion`: what motion blur costs against the same frame still, and how that grows
//! with the pixel count (issue 21 part 2). The `rib/bench` blur scenes are rendered at 1×, 2×
//! and 4× their `Format`, each with its shutter open (moving) and closed (`Shutter 0 0`: the
//! first key, a still frame of the same geometry and shading), and a table of the times is
//! printed. Targets: moving ≤ 2× still, and time per pixel flat across the scales.

use crate::measure::{run_render, Cost};
use std::fmt::Write as _;
use std::path::Path;

/// The blur scenes, as (name, file under `rib/`).
pub const SCENES: [(&str, &str); 2] = [
    ("camera_blur", "bench/camera_blur.rib"),
    ("transform_blur", "bench/transform_blur.rib"),
];

/// One scene at one scale, still and moving.
#[derive(Clone, Debug)]
pub struct MotionRow {
    pub scene: String,
    pub scale: u32,
    pub pixels: u64,
    pub still: Cost,
    pub moving: Cost,
}

/// The scene text at `scale` × its `Format`, writing `out.tif`, with the shutter closed when
/// `still`. `Err` when the text has no `Format` or no `Shutter` line to change.
pub fn variant(rib: &str, scale: u32, still: bool) -> Result<(String, u64), String> {
    let mut out = String::new();
    let (mut pixels, mut shutter) = (None, false);
    for line in rib.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["Format", w, h, rest @ ..] => {
                let (format, n) = crate::scene::multiplied_format(line, w, h, rest, scale)?;
                pixels = Some(n);
                let _ = writeln!(out, "{format}");
            }
            ["Shutter", ..] if still => {
                shutter = true;
                out.push_str("Shutter 0 0\n");
            }
            ["Shutter", ..] => {
                shutter = true;
                let _ = writeln!(out, "{line}");
            }
            ["Display", ..] => out.push_str("Display \"out.tif\" \"file\" \"rgba\"\n"),
            _ => {
                let _ = writeln!(out, "{line}");
            }
        }
    }
    let pixels = pixels.ok_or("no Format line")?;
    if !shutter {
        return Err("no Shutter line".into());
    }
    Ok((out, pixels))
}

/// The fastest of `repeat` renders of `text` in `dir` (by wall time).
fn measure(
    render: &Path,
    dir: &Path,
    text: &str,
    threads: usize,
    repeat: usize,
) -> Result<Cost, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let file = dir.join("scene.rib");
    std::fs::write(&file, text).map_err(|e| format!("{}: {e}", file.display()))?;
    let mut best: Option<Cost> = None;
    for _ in 0..repeat.max(1) {
        let c = run_render(render, dir, "scene.rib", threads)?;
        if best.is_none_or(|b| c.wall_seconds < b.wall_seconds) {
            best = Some(c);
        }
    }
    Ok(best.unwrap_or_default())
}

/// Renders every scene at every scale, still and moving.
pub fn run(
    render: &Path,
    rib_dir: &Path,
    scratch: &Path,
    scales: &[u32],
    threads: usize,
    repeat: usize,
) -> Result<Vec<MotionRow>, String> {
    let mut rows = Vec::new();
    for (name, file) in SCENES {
        let path = rib_dir.join(file);
        let rib = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        for &scale in scales {
            let mut cost = [Cost::default(); 2];
            let mut pixels = 0;
            for (k, still) in [true, false].into_iter().enumerate() {
                let (text, px) = variant(&rib, scale, still).map_err(|e| format!("{file}: {e}"))?;
                pixels = px;
                let dir = scratch.join(format!("{name}_{scale}x_{k}"));
                cost[k] = measure(render, &dir, &text, threads, repeat)?;
                eprintln!(
                    "bench: {name} {scale}x {}: {:.2} s wall, {:.2} s CPU",
                    if still { "still" } else { "moving" },
                    cost[k].wall_seconds,
                    cost[k].cpu_seconds
                );
            }
            rows.push(MotionRow {
                scene: name.into(),
                scale,
                pixels,
                still: cost[0],
                moving: cost[1],
            });
        }
    }
    Ok(rows)
}

/// The markdown table: per scene and scale the still and moving times, their ratio, and the
/// moving CPU time per megapixel relative to the scene's smallest scale (1.0 = linear).
pub fn table(rows: &[MotionRow]) -> String {
    let mut md = String::from(
        "| scene | scale | pixels | still wall s | still CPU s | moving wall s | moving CPU s | \
         moving/still CPU | moving CPU per pixel vs 1st scale | peak MB moving |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let first = rows.iter().find(|q| q.scene == r.scene).unwrap_or(r);
        let per_px = |c: &Cost, px: u64| c.cpu_seconds / px.max(1) as f64;
        let growth = per_px(&r.moving, r.pixels) / per_px(&first.moving, first.pixels);
        let _ = writeln!(
            md,
            "| {} | {}× | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.0} |",
            r.scene,
            r.scale,
            r.pixels,
            r.still.wall_seconds,
            r.still.cpu_seconds,
            r.moving.wall_seconds,
            r.moving.cpu_seconds,
            r.moving.cpu_seconds / r.still.cpu_seconds,
            growth,
            r.moving.peak_rss_mb
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    const RIB: &str = "Display \"x.tif\" \"tiff\" \"rgb\"\nFormat 320 240 1\nShutter 0 1\n\
                       WorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";

    #[test]
    fn variants_scale_the_format_and_close_the_shutter() {
        let (moving, px) = variant(RIB, 2, false).unwrap();
        assert_eq!(px, 640 * 480);
        assert!(moving.contains("Format 640 480 1\n"));
        assert!(moving.contains("Shutter 0 1\n"));
        assert!(moving.contains("Display \"out.tif\" \"file\" \"rgba\"\n"));
        assert!(!moving.contains("x.tif"));
        let (still, _) = variant(RIB, 4, true).unwrap();
        assert!(still.contains("Format 1280 960 1\n") && still.contains("Shutter 0 0\n"));
        assert!(still.contains("Sphere 1 -1 1 360\n"));
    }

    #[test]
    fn a_scene_without_format_or_shutter_is_an_error() {
        assert!(variant("Shutter 0 1\n", 1, true).is_err());
        assert!(variant("Format 10 10 1\n", 1, true).is_err());
        assert!(variant("Format ten 10 1\nShutter 0 1\n", 1, true).is_err());
    }

    #[test]
    fn the_table_reports_ratio_and_growth() {
        let c = |cpu: f64| Cost {
            wall_seconds: cpu,
            cpu_seconds: cpu,
            peak_rss_mb: 10.0,
            micropolygons: 0,
        };
        let rows = [
            MotionRow {
                scene: "s".into(),
                scale: 1,
                pixels: 100,
                still: c(1.0),
                moving: c(1.5),
            },
            MotionRow {
                scene: "s".into(),
                scale: 2,
                pixels: 400,
                still: c(4.0),
                moving: c(9.0),
            },
        ];
        let md = table(&rows);
        assert!(md.contains("| s | 1× | 100 | 1.00 | 1.00 | 1.50 | 1.50 | 1.50 | 1.00 | 10 |"));
        assert!(md.contains("| s | 2× | 400 | 4.00 | 4.00 | 9.00 | 9.00 | 2.25 | 1.50 | 10 |"));
    }
}
