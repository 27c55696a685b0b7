//! `speed_error.csv`: one row per measured point, every number the sweep recorded.

use crate::knob::{Knob, Settings};
use crate::measure::Cost;
use crate::metrics::ErrorStats;
use crate::sweep::Point;

/// The header row; columns are documented in the README's "Speed against error" section.
pub const HEADER: &str =
    "scene,knob,value,pixel_samples,shading_rate,smooth,shadow_samples,shadow_blur,\
shadow_map_size,filter_width,env_blur,bucket_size,threads,raytraced_shadows,wall_s,cpu_s,peak_rss_mb,micropolygons,\
rmse_converged,max_converged,psnr_converged,rmse_closed,max_closed,psnr_closed,pareto";

fn num(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else if x.is_infinite() {
        "inf".into()
    } else {
        format!("{x}")
    }
}

fn stats(e: Option<ErrorStats>) -> String {
    match e {
        Some(e) => format!("{:.6e},{:.6e},{:.3}", e.rmse, e.max_abs, e.psnr),
        None => ",,".into(),
    }
}

/// The CSV text of `points`. The converged reference rows have knob `converged`.
pub fn to_csv(points: &[Point]) -> String {
    let mut out = String::from(HEADER);
    out.push('\n');
    for p in points {
        let s = &p.settings;
        let c = &p.cost;
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.6},{},{:.1},{},{},{},{}\n",
            p.scene,
            p.knob.map_or("converged", |k| k.name()),
            num(p.value),
            s.pixel_samples,
            s.shading_rate,
            u8::from(s.smooth),
            s.shadow_samples,
            s.shadow_blur,
            s.shadow_map_size,
            s.filter_width,
            s.env_blur,
            s.bucket_size,
            s.threads,
            u8::from(s.raytraced_shadows),
            c.wall_seconds,
            // CPU time is whole 10 ms ticks: three decimals hold it exactly.
            num((c.cpu_seconds * 1000.0).round() / 1000.0),
            c.peak_rss_mb,
            c.micropolygons,
            stats(p.vs_converged),
            stats(p.vs_closed),
            u8::from(p.pareto),
        ));
    }
    out
}

/// Reads [`to_csv`]'s text back (to redraw the plot and tables without measuring again,
/// `bench --from-csv`). Pixel counts are not stored and read as 0.
pub fn from_csv(text: &str) -> Result<Vec<Point>, String> {
    let mut lines = text.lines().enumerate();
    let header: Vec<&str> = match lines.next() {
        Some((_, h)) => h.split(',').collect(),
        None => return Err("empty CSV".into()),
    };
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or_else(|| format!("CSV has no column {name}"))
    };
    let names = [
        "scene",
        "knob",
        "value",
        "pixel_samples",
        "shading_rate",
        "smooth",
        "shadow_samples",
        "shadow_blur",
        "shadow_map_size",
        "filter_width",
        "env_blur",
        "bucket_size",
        "threads",
        "wall_s",
        "cpu_s",
        "peak_rss_mb",
        "micropolygons",
        "rmse_converged",
        "max_converged",
        "psnr_converged",
        "rmse_closed",
        "max_closed",
        "psnr_closed",
        "pareto",
    ];
    let idx: Vec<usize> = names.iter().map(|n| col(n)).collect::<Result<_, _>>()?;
    // Added with the ray-traced shadow knob: CSVs written before it have map shadows only.
    let raytraced_col = col("raytraced_shadows").ok();
    let mut points = Vec::new();
    for (n, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        let field = |k: usize| f.get(idx[k]).copied().unwrap_or("");
        let float = |k: usize| -> Result<f64, String> {
            match field(k) {
                "" => Ok(f64::NAN),
                "inf" => Ok(f64::INFINITY),
                v => v.parse().map_err(|_| {
                    format!(
                        "line {}: {}: expected a number, found {v:?}",
                        n + 1,
                        names[k]
                    )
                }),
            }
        };
        let stats = |k: usize| -> Result<Option<ErrorStats>, String> {
            let rmse = float(k)?;
            Ok((!rmse.is_nan()).then_some(ErrorStats {
                rmse,
                max_abs: float(k + 1)?,
                psnr: float(k + 2)?,
                pixels: 0,
            }))
        };
        let knob = match field(1) {
            "converged" => None,
            name => Some(
                Knob::from_name(name)
                    .ok_or_else(|| format!("line {}: unknown knob {name:?}", n + 1))?,
            ),
        };
        points.push(Point {
            scene: field(0).to_string(),
            knob,
            value: float(2)?,
            settings: Settings {
                pixel_samples: float(3)? as u32,
                shading_rate: float(4)?,
                smooth: float(5)? > 0.5,
                shadow_samples: float(6)? as u32,
                shadow_blur: float(7)?,
                shadow_map_size: float(8)? as u32,
                raytraced_shadows: raytraced_col.and_then(|c| f.get(c)) == Some(&"1"),
                filter_width: float(9)?,
                env_blur: float(10)?,
                bucket_size: float(11)? as u32,
                threads: float(12)? as usize,
            },
            cost: Cost {
                wall_seconds: float(13)?,
                cpu_seconds: float(14)?,
                peak_rss_mb: float(15)?,
                micropolygons: float(16)? as u64,
            },
            vs_converged: stats(17)?,
            vs_closed: stats(20)?,
            pareto: field(23) == "1",
        });
    }
    Ok(points)
}

/// The data rows of a CSV text whose first line must be `header` and whose rows must have
/// `fields` comma-separated fields, each with its 0-based line index (blank lines skipped).
/// Shared by the `--peer` and `--scaling` readers, which differ only in how fields are typed.
pub fn records<'a>(
    text: &'a str,
    header: &str,
    fields: usize,
) -> Result<Vec<(usize, Vec<&'a str>)>, String> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == header => {}
        _ => return Err(format!("line 1: expected the header {header:?}")),
    }
    lines
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(n, line)| {
            let f: Vec<&str> = line.split(',').collect();
            if f.len() == fields {
                Ok((n, f))
            } else {
                Err(format!(
                    "line {}: expected {fields} fields, found {}",
                    n + 1,
                    f.len()
                ))
            }
        })
        .collect()
}
