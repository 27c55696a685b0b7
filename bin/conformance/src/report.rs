//! `report.md` (summary, divergence classes, one table row per job) and `results.csv`.
use crate::explanations::Explanations;
use crate::run::Outcome;
use crate::{JobResult, Verdict};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// What the report needs besides the results.
pub struct ReportInfo<'a> {
    pub command: &'a str,
    pub max_mae: f64,
    pub explanations: &'a Explanations,
    /// The contact sheet's file name, when one was written.
    pub contact_sheet: Option<&'a str>,
}

/// The exit column: the code, or what happened instead.
pub fn exit_text(o: &Outcome) -> String {
    match o {
        Outcome::Exited(c) => c.to_string(),
        Outcome::Signalled => "signal".to_string(),
        Outcome::TimedOut => "killed".to_string(),
        Outcome::NotRun(_) => "not run".to_string(),
    }
}

/// The reason column: the explanation (class: reason), else what the runner saw.
pub fn reason(r: &JobResult, explanations: &Explanations) -> String {
    if let Some(e) = explanations.get(&r.job.name) {
        return match (e.class.is_empty(), e.reason.is_empty()) {
            (false, false) => format!("{}: {}", e.class, e.reason),
            (false, true) => e.class.clone(),
            _ => e.reason.clone(),
        };
    }
    if let Outcome::NotRun(why) = &r.outcome {
        return why.clone();
    }
    if let Some(panic) = panic_line(r) {
        return panic;
    }
    match &r.metrics {
        Err(e) => e.clone(),
        Ok(_) => String::new(),
    }
}

/// The renderer's panic message from its log, if it panicked.
fn panic_line(r: &JobResult) -> Option<String> {
    let log = std::fs::read_to_string(&r.log).ok()?;
    log.lines()
        .find(|l| l.contains("panicked"))
        .map(|l| l.trim().to_string())
}

/// The pass count as `X/N`.
pub fn pass_count(results: &[JobResult], max_mae: f64) -> (usize, usize) {
    let pass = results
        .iter()
        .filter(|r| r.verdict(max_mae) == Verdict::Pass)
        .count();
    (pass, results.len())
}

fn metric_cells(r: &JobResult) -> (String, String) {
    match &r.metrics {
        Ok(m) => (format!("{:.4}", m.mae), format!("{:.1}", m.within * 100.0)),
        Err(_) => ("–".to_string(), "–".to_string()),
    }
}

/// The markdown report.
pub fn markdown(results: &[JobResult], info: &ReportInfo) -> String {
    let mut s = String::new();
    let (pass, n) = pass_count(results, info.max_mae);
    let _ = writeln!(s, "# Conformance: Aqsis regression suite\n");
    let _ = writeln!(s, "Command: `{}`\n", info.command);
    let _ = writeln!(
        s,
        "**{pass}/{n} jobs within MAE {}** (mean absolute error over RGB in 0..1 against \
         Aqsis's reference image; \"within\" is the share of pixels whose channels are all \
         within 8/255).\n",
        info.max_mae
    );
    let mut verdicts: BTreeMap<Verdict, usize> = BTreeMap::new();
    for r in results {
        *verdicts.entry(r.verdict(info.max_mae)).or_default() += 1;
    }
    let counts: Vec<String> = verdicts
        .iter()
        .map(|(v, c)| format!("{} {c}", v.as_str()))
        .collect();
    let _ = writeln!(s, "Verdicts: {}.\n", counts.join(", "));

    // Divergence classes of the jobs that do not pass.
    let mut classes: BTreeMap<String, Vec<&str>> = BTreeMap::new();
    for r in results
        .iter()
        .filter(|r| r.verdict(info.max_mae) != Verdict::Pass)
    {
        let class = info
            .explanations
            .get(&r.job.name)
            .map(|e| e.class.clone())
            .filter(|c| !c.is_empty())
            .unwrap_or_else(|| "unexplained".to_string());
        classes.entry(class).or_default().push(&r.job.name);
    }
    if !classes.is_empty() {
        let _ = writeln!(
            s,
            "## Divergence classes (jobs above MAE {})\n",
            info.max_mae
        );
        let _ = writeln!(s, "| class | jobs | which |\n|---|---|---|");
        let mut by_size: Vec<_> = classes.into_iter().collect();
        by_size.sort_by(|a, b| b.1.len().cmp(&a.1.len()).then(a.0.cmp(&b.0)));
        for (class, jobs) in by_size {
            let _ = writeln!(
                s,
                "| {} | {} | {} |",
                cell(&class),
                jobs.len(),
                jobs.join(", ")
            );
        }
        s.push('\n');
    }

    let mut slowest: Vec<&JobResult> = results.iter().collect();
    slowest.sort_by(|a, b| b.seconds.total_cmp(&a.seconds));
    let slow: Vec<String> = slowest
        .iter()
        .take(5)
        .map(|r| format!("{} {:.1} s", r.job.name, r.seconds))
        .collect();
    let total: f64 = results.iter().map(|r| r.seconds).sum();
    let _ = writeln!(
        s,
        "Slowest: {}. Total render time {total:.0} s.\n",
        slow.join(", ")
    );
    if let Some(sheet) = info.contact_sheet {
        let _ = writeln!(
            s,
            "Contact sheet: [{sheet}]({sheet}), jobs in table order, three per row, each \
             ours | reference | difference ×4 (a green bar under a pass, red otherwise).\n"
        );
    }

    let _ = writeln!(s, "## Jobs\n");
    let _ = writeln!(
        s,
        "| job | exit | time (s) | MAE | within 8/255 (%) | verdict | reason |\n|---|---|---|---|---|---|---|"
    );
    for r in results {
        let (mae, within) = metric_cells(r);
        let _ = writeln!(
            s,
            "| {} | {} | {:.1} | {mae} | {within} | {} | {} |",
            cell(&r.job.path_name()),
            exit_text(&r.outcome),
            r.seconds,
            r.verdict(info.max_mae).as_str(),
            cell(&reason(r, info.explanations)),
        );
    }
    s
}

/// Text safe inside a markdown table cell.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// `results.csv`: one row per job, RFC 4180 quoting.
pub fn csv(results: &[JobResult], info: &ReportInfo) -> String {
    let mut s = String::from("job,path,exit,seconds,mae,within,verdict,class,reason\n");
    for r in results {
        let (mae, within) = match &r.metrics {
            Ok(m) => (format!("{:.6}", m.mae), format!("{:.6}", m.within)),
            Err(_) => (String::new(), String::new()),
        };
        let class = info
            .explanations
            .get(&r.job.name)
            .map(|e| e.class.as_str())
            .unwrap_or("");
        let row = [
            r.job.name.clone(),
            r.job.path_name(),
            exit_text(&r.outcome),
            format!("{:.2}", r.seconds),
            mae,
            within,
            r.verdict(info.max_mae).as_str().to_string(),
            class.to_string(),
            reason(r, info.explanations),
        ];
        let quoted: Vec<String> = row.iter().map(|f| csv_field(f)).collect();
        s.push_str(&quoted.join(","));
        s.push('\n');
    }
    s
}

fn csv_field(f: &str) -> String {
    if f.contains([',', '"', '\n']) {
        format!("\"{}\"", f.replace('"', "\"\""))
    } else {
        f.to_string()
    }
}
