//! The markdown for the README: which settings reach which error at what time.

use crate::knob::Settings;
use crate::sweep::Point;

/// Error targets of the "fastest settings for a target error" table (RMSE, 1.0 = white).
pub const TARGETS: [f64; 5] = [3e-2, 1e-2, 3e-3, 1e-3, 3e-4];

/// "defaults" or the knob setting that differs from the defaults.
fn settings_name(p: &Point, defaults: &Settings) -> String {
    match p.knob {
        Some(_) if p.settings == *defaults => "defaults".into(),
        Some(k) => k.describe(p.value),
        None => "converged reference".into(),
    }
}

fn fmt_err(x: Option<f64>) -> String {
    x.map_or("—".into(), |e| format!("{e:.2e}"))
}

fn fmt_psnr(x: Option<f64>) -> String {
    x.map_or("—".into(), |e| {
        if e.is_finite() {
            format!("{e:.1}")
        } else {
            "∞".into()
        }
    })
}

/// Points with a setting that several knobs share listed once (first knob's name).
fn distinct(points: &[Point]) -> Vec<&Point> {
    let mut out: Vec<&Point> = Vec::new();
    for p in points.iter().filter(|p| p.knob.is_some()) {
        if !out.iter().any(|q| q.settings == p.settings) {
            out.push(p);
        }
    }
    out
}

/// The fastest measured point whose error is at most `target`, among the knobs that change
/// the image.
pub fn fastest_within(points: &[Point], target: f64) -> Option<&Point> {
    distinct(points)
        .into_iter()
        .filter(|p| p.knob.is_some_and(|k| k.changes_image()) && p.error() <= target)
        .min_by(|a, b| a.time().total_cmp(&b.time()))
}

/// The whole markdown: the target table, then per scene its defaults and Pareto front.
pub fn markdown(scenes: &[(String, Vec<Point>)], defaults: &Settings, heading: &str) -> String {
    let mut md = String::new();
    md.push_str(heading);
    md.push_str(
        "\n\nFastest measured setting whose RMSE is at most the target (one knob moved from the \
                 defaults, or PixelSamples and ShadingRate together), with its render CPU time:\n\n",
    );
    md.push_str("| scene (error vs) |");
    for t in TARGETS {
        md.push_str(&format!(" ≤ {t:.0e} |"));
    }
    md.push_str("\n|---|");
    md.push_str(&"---|".repeat(TARGETS.len()));
    md.push('\n');
    for (name, points) in scenes {
        let against = if points.iter().any(|p| p.against_closed_form()) {
            "closed form"
        } else {
            "converged"
        };
        md.push_str(&format!("| {name} ({against}) |"));
        for t in TARGETS {
            match fastest_within(points, t) {
                Some(p) => md.push_str(&format!(
                    " {}: {:.2} s |",
                    settings_name(p, defaults),
                    p.time()
                )),
                None => md.push_str(" not reached |"),
            }
        }
        md.push('\n');
    }
    for (name, points) in scenes {
        md.push_str(&format!("\n**{name}**"));
        let def = points
            .iter()
            .find(|p| p.knob.is_some() && p.settings == *defaults);
        if let Some(d) = def {
            md.push_str(&format!(
                ": defaults (PixelSamples {n} {n}, ShadingRate {r}) RMSE {e:.2e} in CPU {t:.2} s (wall {w:.3} s), {m} micropolygons",
                n = defaults.pixel_samples,
                r = defaults.shading_rate,
                e = d.error(),
                t = d.time(),
                w = d.cost.wall_seconds,
                m = d.cost.micropolygons
            ));
        }
        if let Some(c) = points.iter().find(|p| p.knob.is_none()) {
            md.push_str(&format!(
                "; converged reference CPU {:.2} s (wall {:.2} s)",
                c.time(),
                c.cost.wall_seconds
            ));
            if let Some(e) = c.vs_closed {
                md.push_str(&format!(", RMSE {:.2e} vs the closed form", e.rmse));
            }
        }
        let time_only: Vec<String> = points
            .iter()
            .filter(|p| p.knob.is_some_and(|k| !k.changes_image()))
            .filter_map(|p| {
                let k = p.knob?;
                Some(format!(
                    "{} wall {:.3} s / CPU {:.2} s",
                    k.describe(p.value),
                    p.cost.wall_seconds,
                    p.time()
                ))
            })
            .collect();
        if !time_only.is_empty() {
            md.push_str(&format!(
                "; time only (same image): {}",
                time_only.join(", ")
            ));
        }
        md.push_str(". Pareto front:\n\n");
        md.push_str("| setting | CPU (s) | wall (s) | peak RSS (MB) | micropolygons | RMSE vs converged | max | PSNR (dB) | RMSE vs closed form | max | PSNR (dB) |\n");
        md.push_str("|---|---|---|---|---|---|---|---|---|---|---|\n");
        let mut front: Vec<&Point> = points.iter().filter(|p| p.pareto).collect();
        front.sort_by(|a, b| a.time().total_cmp(&b.time()));
        for p in front {
            let c = p.vs_converged;
            let k = p.vs_closed;
            md.push_str(&format!(
                "| {} | {:.2} | {:.3} | {:.0} | {} | {} | {} | {} | {} | {} | {} |\n",
                settings_name(p, defaults),
                p.time(),
                p.cost.wall_seconds,
                p.cost.peak_rss_mb,
                p.cost.micropolygons,
                fmt_err(c.map(|e| e.rmse)),
                fmt_err(c.map(|e| e.max_abs)),
                fmt_psnr(c.map(|e| e.psnr)),
                fmt_err(k.map(|e| e.rmse)),
                fmt_err(k.map(|e| e.max_abs)),
                fmt_psnr(k.map(|e| e.psnr)),
            ));
        }
    }
    md
}
