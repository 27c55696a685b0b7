//! `farm submit`: write the scripts and `Make*` RIBs into the job directory and submit the
//! stages that still have work, each depending (`afterok`) on the stage before it:
//! setup → passes → tiles → merge. Arrays larger than the cluster's `MaxArraySize` are split
//! into several array jobs (`FARM_OFFSET` shifts their indices).

use crate::error::{io_error, FarmError};
use crate::jobdir::{write_atomically, Config, JobDir};
use crate::plan::{plan, todo, Plan, Todo};
use crate::scene::read_scene_checked;
use crate::script::{self, ScriptContext};
use std::path::{Path, PathBuf};
use std::process::Command;

/// One `sbatch` call.
#[derive(Clone, Debug, PartialEq)]
pub struct Submission {
    /// Shell variable the job id is kept in (`tiles_0`).
    pub var: String,
    pub stage: String,
    pub script: PathBuf,
    /// Array indices spec (`0-15,17`), `None` for a plain job.
    pub array: Option<String>,
    pub offset: usize,
    /// Variables of the jobs this one waits for.
    pub after: Vec<String>,
}

impl Submission {
    /// The sbatch arguments, with `after` already resolved to job ids.
    pub fn args(&self, after_ids: &[String]) -> Vec<String> {
        let mut a = vec!["--parsable".to_string()];
        if let Some(spec) = &self.array {
            a.push(format!("--array={spec}"));
        }
        if self.offset > 0 {
            a.push(format!("--export=ALL,FARM_OFFSET={}", self.offset));
        }
        if !after_ids.is_empty() {
            a.push(format!("--dependency=afterok:{}", after_ids.join(":")));
            // A stage that gave up cancels the stages after it instead of leaving them
            // pending forever (DependencyNeverSatisfied).
            a.push("--kill-on-invalid-dep=yes".into());
        }
        a.push(self.script.display().to_string());
        a
    }
}

/// `0-3,5,7-8` from sorted, distinct indices.
pub fn array_spec(indices: &[usize]) -> String {
    let mut parts = Vec::new();
    let mut i = 0;
    while i < indices.len() {
        let mut j = i;
        while j + 1 < indices.len() && indices[j + 1] == indices[j] + 1 {
            j += 1;
        }
        parts.push(if i == j {
            indices[i].to_string()
        } else {
            format!("{}-{}", indices[i], indices[j])
        });
        i = j + 1;
    }
    parts.join(",")
}

/// Splits indices into chunks whose array indices (index − offset) stay below `max_array`.
fn chunks(indices: &[usize], max_array: usize) -> Vec<(usize, Vec<usize>)> {
    let max_array = max_array.max(1);
    let mut out: Vec<(usize, Vec<usize>)> = Vec::new();
    for &i in indices {
        let offset = i / max_array * max_array;
        match out.last_mut() {
            Some((o, v)) if *o == offset => v.push(i - offset),
            _ => out.push((offset, vec![i - offset])),
        }
    }
    out
}

/// The sbatch calls for the tasks in `todo`, in dependency order.
pub fn submissions(dir: &JobDir, todo: &Todo, max_array: usize) -> Vec<Submission> {
    let mut subs = Vec::new();
    let mut previous: Vec<String> = Vec::new();
    if todo.setup {
        subs.push(Submission {
            var: "setup".into(),
            stage: "setup".into(),
            script: dir.script("setup"),
            array: None,
            offset: 0,
            after: Vec::new(),
        });
        previous = vec!["setup".into()];
    }
    for (stage, indices) in [("passes", &todo.passes), ("tiles", &todo.tiles)] {
        if indices.is_empty() {
            continue;
        }
        let mut vars = Vec::new();
        for (k, (offset, local)) in chunks(indices, max_array).into_iter().enumerate() {
            let var = format!("{stage}_{k}");
            subs.push(Submission {
                var: var.clone(),
                stage: stage.into(),
                script: dir.script(stage),
                array: Some(array_spec(&local)),
                offset,
                after: previous.clone(),
            });
            vars.push(var);
        }
        previous = vars;
    }
    if !todo.merges.is_empty() || !todo.tiles.is_empty() {
        subs.push(Submission {
            var: "merge".into(),
            stage: "merge".into(),
            script: dir.script("merge"),
            array: None,
            offset: 0,
            after: previous,
        });
    }
    subs
}

/// Scripts and RIBs to write: (path, text).
pub fn files(ctx: &ScriptContext, plan: &Plan) -> Vec<(PathBuf, String)> {
    let dir = &ctx.dir;
    let mut out = Vec::new();
    if !plan.setup.is_empty() {
        out.push((dir.make_rib("setup"), script::make_rib(&plan.setup)));
        out.push((dir.script("setup"), script::setup_script(ctx)));
    }
    for p in &plan.passes {
        if !p.make.is_empty() {
            out.push((dir.make_rib(&p.label), script::make_rib(&p.make)));
        }
    }
    if !plan.passes.is_empty() {
        out.push((dir.script("passes"), script::passes_script(ctx, plan)));
    }
    out.push((dir.script("tiles"), script::tiles_script(ctx, plan)));
    out.push((dir.script("merge"), script::merge_script(ctx)));
    out
}

/// Options of `farm submit` beyond the config.
#[derive(Clone, Debug)]
pub struct SubmitOptions {
    pub dry_run: bool,
    pub force: bool,
    pub max_array: usize,
    /// Submit even when the RIB has errors.
    pub allow_errors: bool,
}

/// The printed form of a dry run: every file, then the sbatch lines as a runnable script.
pub fn dry_run_text(files: &[(PathBuf, String)], subs: &[Submission]) -> String {
    let mut s = String::from("# farm submit --dry-run: nothing written, nothing submitted\n");
    for (path, text) in files {
        s.push_str(&format!("#### {}\n{text}", path.display()));
    }
    s.push_str("#### sbatch\n");
    for sub in subs {
        let after: Vec<String> = sub.after.iter().map(|v| format!("${v}")).collect();
        // The dependency names our own shell variables; everything else is quoted if needed.
        let args: Vec<String> = sub
            .args(&after)
            .iter()
            .map(|a| {
                if a.starts_with("--dependency=") {
                    a.clone()
                } else {
                    script::quote_if_needed(a)
                }
            })
            .collect();
        s.push_str(&format!("{}=$(sbatch {})\n", sub.var, args.join(" ")));
    }
    if subs.is_empty() {
        s.push_str("# everything is up to date\n");
    }
    s
}

fn find_on_path(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(name))
        .find(|p| p.is_file())
}

fn sbatch(args: &[String]) -> Result<String, FarmError> {
    let out = Command::new("sbatch")
        .args(args)
        .output()
        .map_err(|e| FarmError::Slurm(format!("sbatch: {e}")))?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        return Err(FarmError::Slurm(format!(
            "sbatch {} failed: {}\nfarm: {}",
            args.join(" "),
            stderr.trim(),
            slurm_hint(&stderr, std::env::var_os("SLURM_CONF").as_deref())
        )));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    // --parsable prints `id` or `id;cluster`.
    let id = text.trim().split(';').next().unwrap_or("").to_string();
    if id.is_empty() || !id.chars().all(|c| c.is_ascii_digit()) {
        return Err(FarmError::Slurm(format!(
            "sbatch printed no job id: {text:?}"
        )));
    }
    Ok(id)
}

/// What to set when `sbatch` refuses: the usual causes are no cluster configuration on this
/// host, a partition the cluster does not have, or controllers that cannot be reached.
fn slurm_hint(stderr: &str, slurm_conf: Option<&std::ffi::OsStr>) -> String {
    let lower = stderr.to_ascii_lowercase();
    let test_cluster = "for the test cluster: eval \"$(tests/farm/slurm_up.sh DIR)\"";
    match slurm_conf {
        Some(conf) if !Path::new(conf).is_file() => format!(
            "SLURM_CONF={} is not a file: point it at your cluster's slurm.conf ({test_cluster})",
            Path::new(conf).display()
        ),
        None if ["/etc/slurm/slurm.conf", "/etc/slurm-llnl/slurm.conf"]
            .iter()
            .all(|p| !Path::new(p).is_file()) =>
        {
            format!(
                "this host has no Slurm configuration: set SLURM_CONF to your cluster's slurm.conf ({test_cluster}), or submit from a login node"
            )
        }
        _ if lower.contains("partition") => {
            "choose an existing partition with --partition (`sinfo -s` lists them)".to_string()
        }
        _ => format!(
            "check that `sinfo` works on this host (SLURM_CONF={}; the controller must be up and reachable)",
            slurm_conf.map_or("unset".into(), |c| Path::new(c).display().to_string())
        ),
    }
}

fn now_seconds() -> f64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

/// What a submit did, for the summary line.
pub struct SubmitReport {
    pub text: String,
}

pub fn submit(
    ctx: &ScriptContext,
    config: &Config,
    opts: &SubmitOptions,
) -> Result<SubmitReport, FarmError> {
    let read = read_scene_checked(&config.scene);
    // What `render` would say about the RIB, said once here instead of once per task.
    for d in &read.diagnostics {
        eprintln!("{d}");
    }
    let errors = read.error_count();
    if errors > 0 && !opts.allow_errors {
        return Err(FarmError::SceneErrors {
            scene: config.scene.display().to_string(),
            count: errors,
        });
    }
    if errors > 0 {
        eprintln!(
            "farm: warning: {}: {errors} error(s); --allow-errors: submitting anyway (`farm status` lists the tasks that render with errors)",
            config.scene.display()
        );
    }
    let scene = read.scene?;
    let plan = plan(&scene, config.tiles, config.frames);
    if plan.frames.is_empty() && plan.passes.is_empty() {
        return Err(FarmError::Usage(format!(
            "{}: no frames in the range asked for",
            config.scene.display()
        )));
    }
    let dir = &ctx.dir;
    let todo = if opts.force {
        Todo {
            setup: !plan.setup.is_empty(),
            passes: (0..plan.passes.len()).collect(),
            tiles: (0..plan.tiles.len()).collect(),
            merges: (0..plan.frames.len()).collect(),
        }
    } else {
        todo(&plan, dir, config)
    };
    let files = files(ctx, &plan);
    let subs = submissions(dir, &todo, opts.max_array);
    if opts.dry_run {
        return Ok(SubmitReport {
            text: dry_run_text(&files, &subs),
        });
    }
    if !subs.is_empty() && find_on_path("sbatch").is_none() {
        return Err(FarmError::Slurm(
            "sbatch not found on PATH: run farm submit on a Slurm submit host (Debian: apt-get install slurm-wlm), or use --dry-run to see the scripts".into(),
        ));
    }
    if opts.force {
        for f in plan.frames.iter().map(|f| dir.done("merge", &f.label)) {
            let _ = std::fs::remove_file(f);
        }
        for t in &plan.tiles {
            let _ = std::fs::remove_file(dir.root.join(&t.file));
        }
        for p in &plan.passes {
            let _ = std::fs::remove_file(dir.done("passes", &p.label));
        }
        let _ = std::fs::remove_file(dir.done("setup", "all"));
    }
    // A submit that fails leaves things as they were: no job directory it created, no jobs.
    let created = !dir.root.exists();
    let previous_jobs = std::fs::read_to_string(dir.jobs_path()).ok();
    let mut submitted = Vec::new();
    let result = write_and_submit(ctx, config, &files, &subs, &mut submitted);
    if let Err(e) = result {
        undo(dir, created, previous_jobs.as_deref(), &submitted);
        return Err(e);
    }
    let text = if submitted.is_empty() {
        format!(
            "farm: {} is up to date; nothing submitted\n",
            config.scene.display()
        )
    } else {
        let list: Vec<String> = submitted
            .iter()
            .map(|(s, id)| format!("{s} {id}"))
            .collect();
        format!(
            "farm: submitted {} ({} pass task(s), {} tile task(s), {} frame(s) to merge); job dir {}\n",
            list.join(", "),
            todo.passes.len(),
            todo.tiles.len(),
            plan.frames.len(),
            dir.root.display()
        )
    };
    Ok(SubmitReport { text })
}

/// Writes the job directory's files and submits `subs` in order; `submitted` gets each
/// (stage, job id) as soon as sbatch accepts it, so a failure later can cancel them.
fn write_and_submit(
    ctx: &ScriptContext,
    config: &Config,
    files: &[(PathBuf, String)],
    subs: &[Submission],
    submitted: &mut Vec<(String, String)>,
) -> Result<(), FarmError> {
    let dir = &ctx.dir;
    dir.write_config(config)?;
    std::fs::create_dir_all(dir.logs()).map_err(io_error(&dir.logs()))?;
    for (path, text) in files {
        write_atomically(path, text.as_bytes())?;
        make_executable(path)?;
    }
    let mut ids: std::collections::HashMap<String, String> = Default::default();
    let mut jobs = std::fs::read_to_string(dir.jobs_path()).unwrap_or_default();
    for sub in subs {
        let after: Vec<String> = sub
            .after
            .iter()
            .filter_map(|v| ids.get(v).cloned())
            .collect();
        let t = now_seconds();
        let id = sbatch(&sub.args(&after))?;
        jobs.push_str(&format!(
            "{} {id} {t:.3} {}\n",
            sub.stage,
            sub.array.as_deref().unwrap_or("-")
        ));
        // Record as we go: a later sbatch failing must not lose the ids of submitted jobs.
        write_atomically(&dir.jobs_path(), jobs.as_bytes())?;
        ids.insert(sub.var.clone(), id.clone());
        submitted.push((sub.stage.clone(), id));
    }
    Ok(())
}

/// After a failed submit: cancels the jobs it did submit (their scripts are about to go),
/// then removes the job directory if this submit created it, else restores its `jobs` file.
fn undo(dir: &JobDir, created: bool, previous_jobs: Option<&str>, submitted: &[(String, String)]) {
    if !submitted.is_empty() {
        let ids: Vec<&str> = submitted.iter().map(|(_, id)| id.as_str()).collect();
        let cancelled = Command::new("scancel").args(&ids).status();
        if !cancelled.is_ok_and(|s| s.success()) {
            eprintln!(
                "farm: warning: could not cancel the jobs already submitted: scancel {}",
                ids.join(" ")
            );
        }
    }
    if created {
        if let Err(e) = std::fs::remove_dir_all(&dir.root) {
            eprintln!(
                "farm: warning: could not remove {}: {e}",
                dir.root.display()
            );
        }
    } else {
        let restored = match previous_jobs {
            Some(text) => write_atomically(&dir.jobs_path(), text.as_bytes()),
            None => std::fs::remove_file(dir.jobs_path()).or(Ok(())),
        };
        if let Err(e) = restored {
            eprintln!("farm: warning: {e}");
        }
    }
}

#[cfg(unix)]
fn make_executable(path: &Path) -> Result<(), FarmError> {
    use std::os::unix::fs::PermissionsExt;
    if path.extension().is_some_and(|e| e == "sh") {
        std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755))
            .map_err(io_error(path))?;
    }
    Ok(())
}

#[cfg(not(unix))]
fn make_executable(_: &Path) -> Result<(), FarmError> {
    Ok(())
}
