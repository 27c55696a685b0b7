//! `farm status`: progress of a submitted job from the job directory (which outputs exist)
//! and Slurm (`squeue` states of the recorded job ids), plus timings parsed from the task logs:
//! the per-task overhead and merge time README's cluster section quotes.

use crate::error::FarmError;
use crate::jobdir::JobDir;
use crate::merge::is_merged;
use crate::plan::{plan, todo};
use crate::scene::read_scene;
use std::collections::BTreeMap;
use std::fmt::Write;
use std::process::Command;

/// One line of the `jobs` file.
#[derive(Clone, Debug, PartialEq)]
pub struct JobRecord {
    pub stage: String,
    pub id: String,
    pub submitted: f64,
}

pub fn read_jobs(dir: &JobDir) -> Vec<JobRecord> {
    let text = std::fs::read_to_string(dir.jobs_path()).unwrap_or_default();
    text.lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            Some(JobRecord {
                stage: w.next()?.to_string(),
                id: w.next()?.to_string(),
                submitted: w.next()?.parse().ok()?,
            })
        })
        .collect()
}

/// Task timings from the logs (`farm: <stage> task <i> attempt <a> on <host> start <t>`,
/// `farm: <stage> task <i> done <t> render_seconds <s>`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timings {
    /// Per finished task: (stage, start, done, render seconds), last attempt.
    pub tasks: Vec<(String, f64, f64, f64)>,
    pub attempts: usize,
    pub retried: usize,
    pub gave_up: usize,
}

pub fn parse_logs(texts: &[String]) -> Timings {
    let mut t = Timings::default();
    for text in texts {
        let mut start: Option<f64> = None;
        let mut attempts_here = 0;
        for line in text.lines() {
            let w: Vec<&str> = line.split_whitespace().collect();
            if w.len() >= 10
                && w[0] == "farm:"
                && w[2] == "task"
                && w[4] == "attempt"
                && w[8] == "start"
            {
                start = w[9].parse().ok();
                attempts_here += 1;
            } else if w.len() >= 8 && w[0] == "farm:" && w[2] == "task" && w[4] == "done" {
                if let (Some(s), Ok(d)) = (start, w[5].parse::<f64>()) {
                    let render = if w[6] == "render_seconds" {
                        w[7].parse().unwrap_or(0.0)
                    } else {
                        0.0
                    };
                    t.tasks.push((w[1].to_string(), s, d, render));
                }
            } else if line.starts_with("farm: giving up") {
                t.gave_up += 1;
            }
        }
        t.attempts += attempts_here;
        if attempts_here > 1 {
            t.retried += 1;
        }
    }
    t
}

fn read_logs(dir: &JobDir) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir.logs()) else {
        return Vec::new();
    };
    let mut paths: Vec<_> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    paths
        .iter()
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .collect()
}

/// The tasks whose render exited 1, from the `errors/` markers the scripts write
/// (`tiles.4x4.f0002.x1y1` holding the task's log paths): (`tiles 4x4/f0002/x1y1`, logs).
pub fn rendered_with_errors(dir: &JobDir) -> Vec<(String, Vec<String>)> {
    let Ok(entries) = std::fs::read_dir(dir.errors()) else {
        return Vec::new();
    };
    let mut out: Vec<(String, Vec<String>)> = entries
        .filter_map(|e| {
            let path = e.ok()?.path();
            let name = path.file_name()?.to_str()?.to_string();
            let task = match name.split_once('.') {
                Some((stage, rest)) => format!("{stage} {}", rest.replace('.', "/")),
                None => name,
            };
            let mut logs: Vec<String> = std::fs::read_to_string(&path)
                .unwrap_or_default()
                .lines()
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .map(String::from)
                .collect();
            logs.dedup();
            Some((task, logs))
        })
        .collect();
    out.sort();
    out
}

/// `squeue` states of the given job ids (array tasks counted per state); `None` without squeue.
fn slurm_states(ids: &[String]) -> Option<BTreeMap<String, BTreeMap<String, usize>>> {
    if ids.is_empty() {
        return Some(BTreeMap::new());
    }
    let out = Command::new("squeue")
        .args(["-h", "-r", "-o", "%F %T", "-j", &ids.join(",")])
        .output()
        .ok()?;
    let mut m: BTreeMap<String, BTreeMap<String, usize>> = BTreeMap::new();
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let mut w = line.split_whitespace();
        if let (Some(id), Some(state)) = (w.next(), w.next()) {
            *m.entry(id.to_string())
                .or_default()
                .entry(state.to_string())
                .or_default() += 1;
        }
    }
    Some(m)
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

pub fn status(dir: &JobDir) -> Result<String, FarmError> {
    let config = dir.read_config()?;
    let scene = read_scene(&config.scene)?;
    let plan = plan(&scene, config.tiles, config.frames);
    let todo = todo(&plan, dir, &config);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "scene   {} ({} frame(s), {}x{} tiles)",
        config.scene.display(),
        plan.frames.len(),
        config.tiles.0,
        config.tiles.1
    );
    if !plan.passes.is_empty() {
        let _ = writeln!(
            s,
            "passes  {}/{} done",
            plan.passes.len() - todo.passes.len(),
            plan.passes.len()
        );
    }
    let _ = write!(
        s,
        "tiles   {}/{} done",
        plan.tiles.len() - todo.tiles.len(),
        plan.tiles.len()
    );
    if !todo.tiles.is_empty() {
        let names: Vec<String> = todo
            .tiles
            .iter()
            .take(12)
            .map(|&t| format!("{}/{}", plan.tiles[t].label, plan.tiles[t].window.name()))
            .collect();
        let more = todo.tiles.len().saturating_sub(names.len());
        let _ = write!(
            s,
            "; missing {}{}",
            names.join(" "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        );
    }
    s.push('\n');
    let merged = (0..plan.frames.len())
        .filter(|&i| is_merged(dir, &config, &plan, i))
        .count();
    let _ = writeln!(s, "merged  {merged}/{} frame(s)", plan.frames.len());
    let jobs = read_jobs(dir);
    let ids: Vec<String> = jobs.iter().map(|j| j.id.clone()).collect();
    match slurm_states(&ids) {
        None => {
            let _ = writeln!(s, "slurm   squeue not found: queue states unknown");
        }
        Some(states) => {
            let active: Vec<String> = jobs
                .iter()
                .filter_map(|j| {
                    let st = states.get(&j.id)?;
                    let parts: Vec<String> = st.iter().map(|(k, n)| format!("{n} {k}")).collect();
                    Some(format!("{} {}: {}", j.stage, j.id, parts.join(", ")))
                })
                .collect();
            let _ = writeln!(
                s,
                "slurm   {}",
                if active.is_empty() {
                    "no recorded job is queued or running".to_string()
                } else {
                    active.join("; ")
                }
            );
        }
    }
    let errors = rendered_with_errors(dir);
    let timings = parse_logs(&read_logs(dir));
    let _ = writeln!(
        s,
        "tasks   {} attempt(s), {} task(s) retried, {} gave up, {} rendered with errors{}",
        timings.attempts,
        timings.retried,
        timings.gave_up,
        errors.len(),
        if errors.is_empty() { "" } else { ":" }
    );
    for (task, logs) in &errors {
        let _ = writeln!(
            s,
            "          {task}: log {}",
            if logs.is_empty() {
                "unknown (see logs/)".to_string()
            } else {
                logs.join(", ")
            }
        );
    }
    let tiles: Vec<&(String, f64, f64, f64)> =
        timings.tasks.iter().filter(|t| t.0 == "tiles").collect();
    if !tiles.is_empty() {
        let wall: Vec<f64> = tiles.iter().map(|t| t.2 - t.1).collect();
        let render: Vec<f64> = tiles.iter().map(|t| t.3).collect();
        let first = tiles.iter().map(|t| t.1).fold(f64::INFINITY, f64::min);
        let last = tiles.iter().map(|t| t.2).fold(0.0, f64::max);
        let submitted = jobs
            .iter()
            .filter(|j| j.stage == "tiles")
            .map(|j| j.submitted)
            .fold(f64::INFINITY, f64::min);
        let _ = writeln!(
            s,
            "timing  tiles: {} task(s), wall {:.3} s mean in the script (render {:.3} s), first start {:.2} s after sbatch, stage {:.2} s first start to last done",
            tiles.len(),
            mean(&wall),
            mean(&render),
            first - submitted,
            last - first
        );
    }
    let merges: Vec<f64> = timings
        .tasks
        .iter()
        .filter(|t| t.0 == "merge")
        .map(|t| t.2 - t.1)
        .collect();
    if !merges.is_empty() {
        let _ = writeln!(s, "timing  merge: {:.3} s per merge job", mean(&merges));
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logs_give_attempts_retries_and_task_times() {
        let a = "farm: tiles task 3 attempt 1 on n1 start 100.5\nfarm: exit 137 on attempt 1\nfarm: requeueing\n\
                 farm: tiles task 3 attempt 2 on n1 start 130.0\nfarm: tiles task 3 done 131.25 render_seconds 1.000\n";
        let b =
            "farm: tiles task 4 attempt 1 on n2 start 101.0\nfarm: giving up after 1 attempt(s)\n";
        let t = parse_logs(&[a.to_string(), b.to_string()]);
        assert_eq!(t.attempts, 3);
        assert_eq!(t.retried, 1);
        assert_eq!(t.gave_up, 1);
        assert_eq!(t.tasks, vec![("tiles".to_string(), 130.0, 131.25, 1.0)]);
    }
}
