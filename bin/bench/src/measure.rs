//! Runs `render` as a child process and measures it: wall time (std `Instant`), CPU time
//! (the children's user + system time the kernel adds to our own `/proc/self/stat` once the
//! child is reaped), and the peak memory and micropolygon count `render --stats` prints.
//!
//! A subprocess rather than an in-process call: its wall time includes parsing, shadow-map and
//! cube-map building and file writing as a user sees them, its CPU time and peak RSS are its
//! own (an in-process run would share the bench's heap high-water mark and thread pool), and
//! no `unsafe` or libc binding is needed.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// What one render cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Cost {
    pub wall_seconds: f64,
    pub cpu_seconds: f64,
    /// Largest VmHWM `render --stats` reported over the file's frames, MB.
    pub peak_rss_mb: f64,
    /// Micropolygons summed over the file's frames (a shadow scene's depth pass included).
    pub micropolygons: u64,
}

/// `/proc` reports times in USER_HZ ticks, which Linux fixes at 100 for user space.
const USER_HZ: f64 = 100.0;

/// CPU seconds of our reaped children so far (fields 16 and 17, cutime + cstime, of
/// `/proc/self/stat`). `None` off Linux.
fn children_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) may hold spaces; fields after its closing ')' start at 3.
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let cutime: f64 = fields.get(16 - 3)?.parse().ok()?;
    let cstime: f64 = fields.get(17 - 3)?.parse().ok()?;
    Some((cutime + cstime) / USER_HZ)
}

/// Sums `micropolygons N` and takes the largest `peak X MB` over the frames of `--stats` output.
pub fn parse_stats(stderr: &str) -> (u64, f64) {
    let mut micropolygons = 0;
    let mut peak: f64 = 0.0;
    for line in stderr.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        for w in words.windows(2) {
            match w[0] {
                "micropolygons" => micropolygons += w[1].parse::<u64>().unwrap_or(0),
                "peak" => peak = peak.max(w[1].parse().unwrap_or(0.0)),
                _ => {}
            }
        }
    }
    (micropolygons, peak)
}

/// Renders `rib_file` in `dir` with `threads` workers. `Err` carries render's exit status and
/// its last lines of stderr when it fails (exit code 2; 1 — rendered with errors — is also a
/// failure here, because the image would not measure the knob).
pub fn run_render(
    render: &Path,
    dir: &Path,
    rib_file: &str,
    threads: usize,
) -> Result<Cost, String> {
    let cpu_before = children_cpu_seconds();
    let start = Instant::now();
    let out = Command::new(render)
        .args(["-q", "--stats", "--threads", &threads.to_string(), rib_file])
        .current_dir(dir)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", render.display()))?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let cpu_seconds = match (cpu_before, children_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        let tail: Vec<&str> = stderr.lines().rev().take(5).collect();
        return Err(format!(
            "render exited with {} in {}: {}",
            out.status,
            dir.display(),
            tail.into_iter().rev().collect::<Vec<_>>().join(" | ")
        ));
    }
    let (micropolygons, peak_rss_mb) = parse_stats(&stderr);
    Ok(Cost {
        wall_seconds,
        cpu_seconds,
        peak_rss_mb,
        micropolygons,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_two_frames_sum_micropolygons_and_keep_the_larger_peak() {
        let s = "render: stats for frame 1\n  counts    primitives 2  pieces 4  grids 3  micropolygons 1200  samples 9\n\
                 \x20 memory    peak 12.5 MB (VmHWM)\nrender: stats for frame 2\n\
                 \x20 counts    primitives 1  micropolygons 34  samples 4\n  memory    peak 20.0 MB (VmHWM)\n";
        assert_eq!(parse_stats(s), (1234, 20.0));
    }

    #[test]
    fn children_cpu_time_reads_on_linux() {
        if cfg!(target_os = "linux") {
            let t = children_cpu_seconds().expect("/proc/self/stat");
            assert!(t >= 0.0);
        }
    }
}
