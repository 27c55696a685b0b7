//! `bench --threads`: how a bigger frame scales from 1 to N threads (issue 21 part 5). Each
//! scene (the teapot and a field of spheres, at `scale` × their `Format`) is rendered by the
//! real `render` binary with `--threads 1, 2, … N`, and a table (or CSV) of wall time, CPU
//! time, speedup (1-thread wall / N-thread wall) and efficiency (speedup / N) is printed.
//! Every thread count's float image is compared with the 1-thread one bit for bit: buckets
//! are independent, so the bits must not depend on how they were spread over threads.

use crate::measure::{run_render, Cost};
use std::fmt::Write as _;
use std::path::Path;

/// One scene at one thread count.
#[derive(Clone, Debug)]
pub struct ThreadRow {
    pub scene: String,
    pub pixels: u64,
    pub threads: usize,
    pub cost: Cost,
    /// Whether the float image equals the 1-thread render's bit for bit.
    pub identical: bool,
}

/// A field of `n × n` plastic spheres under two lights, 640×480 × `scale`: many small grids,
/// so every bucket has its own work and grids are shared along bucket borders.
pub fn spheres_rib(n: u32, scale: u32) -> String {
    let mut rib = format!(
        "Format {} {} 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 3 3\n\
         Display \"out.tif\" \"tiff\" \"rgba\"\nQuantize \"rgba\" 0 0 0 0\n\
         WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" [0.1]\n\
         LightSource \"distantlight\" 2 \"intensity\" [0.9] \"from\" [-1 2 -3] \"to\" [0 0 0]\n\
         Surface \"plastic\" \"roughness\" [0.1]\nTranslate 0 0 {}\n",
        640 * scale,
        480 * scale,
        1.5 * f64::from(n)
    );
    let half = f64::from(n - 1) / 2.0;
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (f64::from(i) - half, f64::from(j) - half);
            let c = [
                0.3 + 0.6 * f64::from(i) / f64::from(n),
                0.5,
                0.3 + 0.6 * f64::from(j) / f64::from(n),
            ];
            let _ = writeln!(
                rib,
                "AttributeBegin Color [{:.3} {:.3} {:.3}] Translate {x} {y} 0 Sphere 0.45 -0.45 0.45 360 AttributeEnd",
                c[0], c[1], c[2]
            );
        }
    }
    rib.push_str("WorldEnd\n");
    rib
}

/// A scene's text at `scale` × its `Format`, its one display replaced by a float TIFF
/// `out.tif`, and the pixel count. `Err` when there is no `Format` line.
pub fn scaled(rib: &str, scale: u32) -> Result<(String, u64), String> {
    let mut out = String::new();
    let mut pixels = None;
    for line in rib.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["Format", w, h, rest @ ..] => {
                let (format, n) = crate::scene::multiplied_format(line, w, h, rest, scale)?;
                pixels = Some(n);
                let _ = writeln!(out, "{format}");
            }
            ["Display", ..] => {
                out.push_str("Display \"out.tif\" \"tiff\" \"rgba\"\nQuantize \"rgba\" 0 0 0 0\n")
            }
            _ => {
                let _ = writeln!(out, "{line}");
            }
        }
    }
    Ok((out, pixels.ok_or("no Format line")?))
}

/// The fastest of `repeat` renders of `scene.rib` in `dir` (by wall time) and its image.
fn measure(
    render: &Path,
    dir: &Path,
    threads: usize,
    repeat: usize,
) -> Result<(Cost, Vec<u32>), String> {
    let mut best: Option<Cost> = None;
    for _ in 0..repeat.max(1) {
        let c = run_render(render, dir, "scene.rib", threads)?;
        if best.is_none_or(|b| c.wall_seconds < b.wall_seconds) {
            best = Some(c);
        }
    }
    let img = illume_imageio::read_image(&dir.join("out.tif")).map_err(|e| e.to_string())?;
    let bits = img.data.iter().map(|v| v.to_bits()).collect();
    Ok((best.unwrap_or_default(), bits))
}

/// The scenes: (name, RIB text, pixels).
pub fn scenes(rib_dir: &Path, scale: u32) -> Result<Vec<(String, String, u64)>, String> {
    let path = rib_dir.join("teapot.rib");
    let teapot = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let (teapot, px) = scaled(&teapot, scale).map_err(|e| format!("teapot.rib: {e}"))?;
    let spheres = spheres_rib(20, scale);
    let spheres_px = u64::from(640 * scale) * u64::from(480 * scale);
    Ok(vec![
        ("teapot".into(), teapot, px),
        ("spheres_400".into(), spheres, spheres_px),
    ])
}

/// Renders every scene at 1, 2, … `max_threads` threads.
pub fn run(
    render: &Path,
    rib_dir: &Path,
    scratch: &Path,
    scale: u32,
    max_threads: usize,
    repeat: usize,
) -> Result<Vec<ThreadRow>, String> {
    let mut rows = Vec::new();
    for (name, text, pixels) in scenes(rib_dir, scale)? {
        let dir = scratch.join(format!("threads_{name}"));
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let file = dir.join("scene.rib");
        std::fs::write(&file, &text).map_err(|e| format!("{}: {e}", file.display()))?;
        let mut first: Option<Vec<u32>> = None;
        for threads in 1..=max_threads.max(1) {
            let (cost, bits) = measure(render, &dir, threads, repeat)?;
            let identical = first.get_or_insert_with(|| bits.clone()) == &bits;
            eprintln!(
                "bench: {name} {threads} thread(s): {:.2} s wall, {:.2} s CPU{}",
                cost.wall_seconds,
                cost.cpu_seconds,
                if identical { "" } else { ", image DIFFERS" }
            );
            rows.push(ThreadRow {
                scene: name.clone(),
                pixels,
                threads,
                cost,
                identical,
            });
        }
    }
    Ok(rows)
}

/// Speedup (the scene's 1-thread wall over this row's) and efficiency (speedup / threads).
fn speedup(rows: &[ThreadRow], r: &ThreadRow) -> (f64, f64) {
    let one = rows
        .iter()
        .find(|q| q.scene == r.scene && q.threads == 1)
        .map_or(f64::NAN, |q| q.cost.wall_seconds);
    let s = one / r.cost.wall_seconds;
    (s, s / r.threads as f64)
}

/// The markdown table.
pub fn table(rows: &[ThreadRow]) -> String {
    let mut md = String::from(
        "| scene | pixels | threads | wall s | CPU s | CPU / wall | speedup | efficiency | \
         peak MB | same bits as 1 thread |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let (s, e) = speedup(rows, r);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.0}% | {:.0} | {} |",
            r.scene,
            r.pixels,
            r.threads,
            r.cost.wall_seconds,
            r.cost.cpu_seconds,
            r.cost.cpu_seconds / r.cost.wall_seconds,
            s,
            100.0 * e,
            r.cost.peak_rss_mb,
            if r.identical { "yes" } else { "NO" }
        );
    }
    md
}

/// The same rows as CSV (one header line).
pub fn csv(rows: &[ThreadRow]) -> String {
    let mut out = String::from(
        "scene,pixels,threads,wall_s,cpu_s,speedup,efficiency,peak_rss_mb,identical\n",
    );
    for r in rows {
        let (s, e) = speedup(rows, r);
        let _ = writeln!(
            out,
            "{},{},{},{:.4},{:.4},{:.4},{:.4},{:.1},{}",
            r.scene,
            r.pixels,
            r.threads,
            r.cost.wall_seconds,
            r.cost.cpu_seconds,
            s,
            e,
            r.cost.peak_rss_mb,
            r.identical
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_multiplies_the_format_and_replaces_the_display() {
        let rib = "Display \"t.tif\" \"tiff\" \"rgba\"\nFormat 480 360 1\nWorldBegin\nWorldEnd\n";
        let (text, px) = scaled(rib, 2).unwrap();
        assert_eq!(px, 960 * 720);
        assert!(text.contains("Format 960 720 1\n"));
        assert!(text.contains("Display \"out.tif\" \"tiff\" \"rgba\"\n"));
        assert!(!text.contains("\"t.tif\""));
        assert!(scaled("WorldBegin\n", 2).is_err());
        assert!(scaled("Format x 3 1\n", 2).is_err());
    }

    #[test]
    fn the_sphere_field_has_one_sphere_per_cell() {
        let rib = spheres_rib(3, 2);
        assert_eq!(rib.matches("Sphere 0.45").count(), 9);
        assert!(rib.contains("Format 1280 960 1\n"));
        assert!(rib.ends_with("WorldEnd\n"));
    }

    #[test]
    fn speedup_and_efficiency_are_against_one_thread() {
        let row = |threads: usize, wall: f64, identical: bool| ThreadRow {
            scene: "s".into(),
            pixels: 100,
            threads,
            cost: Cost {
                wall_seconds: wall,
                cpu_seconds: 2.0,
                peak_rss_mb: 30.0,
                micropolygons: 0,
            },
            identical,
        };
        let rows = [row(1, 2.0, true), row(2, 1.25, false)];
        let md = table(&rows);
        assert!(md.contains("| s | 100 | 1 | 2.00 | 2.00 | 1.00 | 1.00 | 100% | 30 | yes |"));
        assert!(md.contains("| s | 100 | 2 | 1.25 | 2.00 | 1.60 | 1.60 | 80% | 30 | NO |"));
        let csv = csv(&rows);
        assert_eq!(csv.lines().count(), 3);
        assert!(csv.contains("s,100,2,1.2500,2.0000,1.6000,0.8000,30.0,false\n"));
    }
}
