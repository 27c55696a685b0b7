//! `speed_error.csv`: one row per measured point, every number the sweep recorded.

use crate::metrics::ErrorStats;
use crate::sweep::Point;

/// The header row; columns are documented in the README's "Speed against error" section.
pub const HEADER: &str = "scene,knob,value,pixel_samples,shading_rate,smooth,shadow_samples,shadow_blur,\
shadow_map_size,filter_width,env_blur,bucket_size,threads,wall_s,cpu_s,peak_rss_mb,micropolygons,\
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
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4},{},{:.1},{},{},{},{}\n",
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
            c.wall_seconds,
            num(c.cpu_seconds),
            c.peak_rss_mb,
            c.micropolygons,
            stats(p.vs_converged),
            stats(p.vs_closed),
            u8::from(p.pareto),
        ));
    }
    out
}
