//! Measures any command (our `render` or a peer renderer) as the kernel accounts it: wall
//! time, user + system CPU time and peak resident set size of that one process.
//!
//! The peak RSS of one child needs its own rusage. `getrusage(RUSAGE_CHILDREN)` reports the
//! largest peak of *all* reaped children so far, so after a big render a smaller one would be
//! invisible; and `wait4` is not in std and would need `unsafe`. So `bench` runs each measured
//! command under a fresh copy of itself (`bench --rusage-child PROGRAM ARGS…`), whose only
//! child is the command: its `RUSAGE_CHILDREN` is exactly that command's. The copy passes the
//! command's stdout/stderr through and appends one line, [`MARK`], with the numbers.

use std::path::Path;
use std::process::{Command, ExitCode};
use std::time::Instant;

/// The argument that turns `bench` into the measuring wrapper.
pub const WRAPPER_FLAG: &str = "--rusage-child";

/// Start of the wrapper's last stderr line: `MARK exit maxrss_kb user_s sys_s`.
pub const MARK: &str = "bench-rusage:";

/// What one command cost.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Usage {
    pub wall_seconds: f64,
    pub cpu_seconds: f64,
    pub peak_rss_mb: f64,
    /// The command's exit code (-1 when killed by a signal).
    pub exit_code: i32,
    /// The command's stderr without the wrapper's line.
    pub stderr: String,
}

/// The wrapper's line for these numbers.
pub fn mark_line(exit_code: i32, max_rss_kb: f64, user: f64, sys: f64) -> String {
    format!("{MARK} {exit_code} {max_rss_kb} {user:.6} {sys:.6}")
}

/// Splits the wrapper's stderr into the command's own text and (exit, peak MB, CPU s).
pub fn parse_mark(stderr: &str) -> Option<(String, i32, f64, f64)> {
    let at = stderr.rfind(MARK)?;
    let words: Vec<&str> = stderr[at + MARK.len()..].split_whitespace().collect();
    let [exit, rss, user, sys] = words.as_slice() else {
        return None;
    };
    let exit: i32 = exit.parse().ok()?;
    let rss_kb: f64 = rss.parse().ok()?;
    let cpu = user.parse::<f64>().ok()? + sys.parse::<f64>().ok()?;
    Some((stderr[..at].to_string(), exit, rss_kb / 1024.0, cpu))
}

/// The wrapper's body: runs `args[0]` with `args[1..]`, waits, prints [`mark_line`] to stderr
/// and exits with the command's code.
pub fn wrapper_main(args: &[String]) -> ExitCode {
    let Some((program, rest)) = args.split_first() else {
        eprintln!("bench {WRAPPER_FLAG}: no command");
        return ExitCode::from(2);
    };
    let status = match Command::new(program).args(rest).status() {
        Ok(s) => s,
        Err(e) => {
            eprintln!("bench {WRAPPER_FLAG}: cannot run {program}: {e}");
            return ExitCode::from(2);
        }
    };
    let code = status.code().unwrap_or(-1);
    let (rss, user, sys) = children_usage();
    eprintln!("{}", mark_line(code, rss, user, sys));
    ExitCode::from(u8::try_from(code).unwrap_or(2))
}

/// Peak RSS (kB, Linux's unit) and user, system seconds of the reaped children (NaN when
/// unknown).
#[cfg(unix)]
fn children_usage() -> (f64, f64, f64) {
    use nix::sys::resource::{getrusage, UsageWho};
    match getrusage(UsageWho::RUSAGE_CHILDREN) {
        Ok(u) => {
            let secs = |t: nix::sys::time::TimeVal| t.tv_sec() as f64 + t.tv_usec() as f64 * 1e-6;
            (
                u.max_rss() as f64,
                secs(u.user_time()),
                secs(u.system_time()),
            )
        }
        Err(_) => (f64::NAN, f64::NAN, f64::NAN),
    }
}

#[cfg(not(unix))]
fn children_usage() -> (f64, f64, f64) {
    (f64::NAN, f64::NAN, f64::NAN)
}

/// Runs `program args` in `dir` under the wrapper (this executable) and measures it.
/// `Err` when the wrapper cannot start or its line is missing; a failing command is `Ok`
/// with its `exit_code`, for the caller to judge.
pub fn run_measured(program: &Path, args: &[String], dir: &Path) -> Result<Usage, String> {
    let me = std::env::current_exe().map_err(|e| format!("cannot find bench itself: {e}"))?;
    let start = Instant::now();
    let out = Command::new(me)
        .arg(WRAPPER_FLAG)
        .arg(program)
        .args(args)
        .current_dir(dir)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", program.display()))?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let (text, exit_code, peak_rss_mb, cpu_seconds) = parse_mark(&stderr).ok_or_else(|| {
        format!(
            "{} in {}: no measurement ({})",
            program.display(),
            dir.display(),
            stderr.lines().last().unwrap_or("")
        )
    })?;
    Ok(Usage {
        wall_seconds,
        cpu_seconds,
        peak_rss_mb,
        exit_code,
        stderr: text,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mark_line_parses_back_and_keeps_the_commands_own_stderr() {
        let text = format!("warning: x\n{}\n", mark_line(1, 204_800.0, 1.25, 0.125));
        let (own, exit, mb, cpu) = parse_mark(&text).unwrap();
        assert_eq!(own, "warning: x\n");
        assert_eq!(exit, 1);
        assert_eq!(mb, 200.0);
        assert!((cpu - 1.375).abs() < 1e-12);
        assert!(parse_mark("no mark here").is_none());
        assert!(parse_mark(&format!("{MARK} 0 12")).is_none());
    }
}
