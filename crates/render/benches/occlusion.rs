//! The cost of ambient occlusion (issue 19: "occlusion at 16 samples within 4× the time of the
//! same frame without it"): `cargo bench -p illume-render --bench occlusion`.
//!
//! One frame (spheres on a ground plane, perspective, 256², shading rate 1) rendered with a
//! surface shader that multiplies its diffuse-like term by `1 − occlusion(P, Nf, 16)` and with
//! the same shader told to skip the call. Prints the best of five wall times of each on one
//! thread (the ratio is what the target is about; one thread keeps it stable on a shared
//! machine), their ratio, and occlusion rays per second (16 per shaded point, counted as the
//! frame's micropolygons: an estimate of the shaded points). On Linux it also prints the
//! mean CPU times and their ratio, steadier than wall times on a loaded machine.
use illume_render::{render, RenderSettings};
use illume_ri::{from_rib_diagnostic, Frame, Ri};
use std::time::Instant;

const SHADER: &str = "surface tao(float samples = 16; float useocc = 1) {
    normal Nf = faceforward(normalize(N), I);
    float o = 0;
    if (useocc > 0) {
        o = occlusion(P, Nf, samples);
    }
    float k = 0.2 + 0.8 * abs(Nf . normalize(I));
    Ci = Cs * k * (1 - o);
    Oi = 1;
}";

fn rib(dir: &std::path::Path, useocc: u32) -> String {
    let mut spheres = String::new();
    for k in 0..9 {
        let (x, z) = ((k % 3) as f64 * 2.4 - 2.4, (k / 3) as f64 * 2.4 + 8.0);
        spheres.push_str(&format!(
            "AttributeBegin\nTranslate {x} 0 {z}\nSphere 1 -1 1 360\nAttributeEnd\n"
        ));
    }
    format!(
        "Option \"searchpath\" \"shader\" [\"{}\"]\n\
         Format 256 256 1\nProjection \"perspective\" \"fov\" 45\nPixelSamples 2 2\n\
         ShadingRate 1\nWorldBegin\nTranslate 0 -1 0\n\
         Surface \"tao\" \"useocc\" [{useocc}]\nColor 0.8 0.7 0.6\n\
         Polygon \"P\" [-20 -1 0  20 -1 0  20 -1 40  -20 -1 40]\n{spheres}WorldEnd\n",
        dir.display()
    )
}

fn frame(text: &str) -> Frame {
    let mut ri = Ri::new();
    for item in illume_rib::Parser::new(text.as_bytes(), "occlusion.rib") {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    ri.take_frames().remove(0)
}

/// The process's CPU time (user + system) in seconds from `/proc/self/stat`, where there is
/// one: on a machine shared with other work the wall time swings with the load, the CPU time
/// much less.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name; utime and stime are the 12th and 13th.
    let rest = stat.rsplit_once(')')?.1;
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// Runs of each frame: the best wall time and the mean CPU time over them (the CPU clock
/// ticks every 10 ms, so one run of a 0.1 s frame would be ±10%).
const RUNS: u32 = 5;

/// Best wall time, mean CPU time (when known) and the frame's micropolygons.
fn time(frame: &Frame) -> (f64, Option<f64>, u64) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    let mut best = f64::INFINITY;
    let mut mps = 0;
    let c0 = cpu_seconds();
    for _ in 0..RUNS {
        let t = Instant::now();
        let r = pool.install(|| render(frame, &RenderSettings::default()));
        best = best.min(t.elapsed().as_secs_f64());
        mps = r.stats.micropolygons;
    }
    let cpu = match (c0, cpu_seconds()) {
        (Some(a), Some(b)) => Some((b - a) / f64::from(RUNS)),
        _ => None,
    };
    (best, cpu, mps)
}

fn main() {
    let dir = std::env::temp_dir().join(format!("illume-bench-occlusion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary shader directory");
    std::fs::write(dir.join("tao.sl"), SHADER).expect("the bench shader");
    let (without, without_cpu, mps) = time(&frame(&rib(&dir, 0)));
    let (with, with_cpu, _) = time(&frame(&rib(&dir, 1)));
    let rays = mps as f64 * 16.0;
    println!("occlusion(P, N, 16), 256x256, 1 thread, best of {RUNS} (CPU: mean)");
    println!("without occlusion  {without:>8.3} s");
    println!("with occlusion     {with:>8.3} s");
    println!("ratio              {:>8.2}x", with / without);
    if let (Some(a), Some(b)) = (without_cpu, with_cpu) {
        println!(
            "CPU time           {a:>8.2} s / {b:.2} s, ratio {:.2}x",
            b / a.max(0.01)
        );
    }
    println!(
        "occlusion rays/s   {:>8.3e}  ({rays:.0} rays over the extra time)",
        rays / (with - without).max(1e-9)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
