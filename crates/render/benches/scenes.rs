//! Time per example scene and micropolygons per second: `cargo bench -p illume-render`.
//! Renders every `rib/*.rib` of the workspace (displays are not written) three times and
//! prints the best wall time.
use illume_render::{render, RenderSettings};
use illume_ri::{from_rib_diagnostic, Ri};
use std::time::Instant;

fn main() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../rib");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|rd| {
            rd.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "rib"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    println!(
        "{:<24} {:>10} {:>14} {:>16}",
        "scene", "best s", "micropolygons", "micropolygons/s"
    );
    for f in files {
        let mut ri = Ri::new();
        let Ok(parser) = illume_rib::open(&f) else {
            continue;
        };
        for item in parser {
            match item {
                Ok(r) => ri.request(r),
                Err(d) => ri.report(from_rib_diagnostic(d)),
            }
        }
        ri.finish();
        for frame in ri.take_frames() {
            let mut best = f64::INFINITY;
            let mut mps = 0;
            for _ in 0..3 {
                let t = Instant::now();
                let r = render(&frame, &RenderSettings::default());
                best = best.min(t.elapsed().as_secs_f64());
                mps = r.stats.micropolygons;
            }
            let name = f.file_name().unwrap_or_default().to_string_lossy();
            println!(
                "{name:<24} {best:>10.3} {mps:>14} {:>16.0}",
                mps as f64 / best
            );
        }
    }
}
