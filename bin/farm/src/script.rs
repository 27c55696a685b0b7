//! The sbatch scripts: one per stage (setup, passes, tiles, merge), each an array job whose
//! task index selects a line of its `case` table, so the same script serves a first
//! submission and a resubmission of only the missing tasks.
//!
//! Retries: every script carries `#SBATCH --requeue` (Slurm restarts tasks whose node
//! fails) and runs `render` through `farm_run`, which on a failed render asks Slurm to requeue
//! the task itself (`scontrol requeue`) while `SLURM_RESTART_COUNT` is below the retry bound,
//! then gives up with render's exit code. A render that exits 1 rendered with errors: its
//! output is kept and noted in `errors/<task>` (which holds the task's log path, for
//! `farm status`), since running it again gives the same errors.
//! Outputs already newer than the scene are skipped, so a requeued or resubmitted task that
//! already finished costs nothing.

use crate::jobdir::JobDir;
use crate::plan::Plan;
use illume_rib::Request;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Everything a script needs to know about where things are.
#[derive(Clone, Debug)]
pub struct ScriptContext {
    pub dir: JobDir,
    pub scene: PathBuf,
    pub cwd: PathBuf,
    pub render: PathBuf,
    pub farm: PathBuf,
    pub partition: Option<String>,
    pub retries: u32,
    pub cpus_per_task: u32,
    /// Job name prefix (the scene's file stem).
    pub name: String,
}

/// `'…'` for the shell.
pub fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// A word as is when the shell would read it unchanged, else [`quote`]d.
pub fn quote_if_needed(s: &str) -> String {
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "_./=:,%+-@".contains(c));
    if plain {
        s.to_string()
    } else {
        quote(s)
    }
}

fn q(p: &Path) -> String {
    quote(&p.display().to_string())
}

fn frames_flag(n: Option<i32>) -> String {
    n.map_or(String::new(), |n| format!(" --frames {n}"))
}

/// The header and the shared `farm_run` function.
fn header(ctx: &ScriptContext, stage: &str, array: bool) -> String {
    let mut s = String::new();
    let log = ctx.dir.logs().join(if array {
        format!("{stage}_%A_%a.out")
    } else {
        format!("{stage}_%j.out")
    });
    let _ = writeln!(s, "#!/usr/bin/env bash");
    let _ = writeln!(s, "#SBATCH --job-name={}-{stage}", ctx.name);
    let _ = writeln!(s, "#SBATCH --requeue");
    // Append, so a requeued task's log keeps the failed attempt above the retry.
    let _ = writeln!(s, "#SBATCH --open-mode=append");
    let _ = writeln!(s, "#SBATCH --output={}", log.display());
    let _ = writeln!(s, "#SBATCH --chdir={}", ctx.cwd.display());
    let _ = writeln!(s, "#SBATCH --cpus-per-task={}", ctx.cpus_per_task);
    if let Some(p) = &ctx.partition {
        let _ = writeln!(s, "#SBATCH --partition={p}");
    }
    let _ = writeln!(
        s,
        "# Written by `farm submit`; array index = task number in the case table below."
    );
    let _ = writeln!(s, "set -u");
    let _ = writeln!(s, "SCENE={}", q(&ctx.scene));
    let _ = writeln!(s, "JOBDIR={}", q(&ctx.dir.root));
    let _ = writeln!(s, "RENDER={}", q(&ctx.render));
    let _ = writeln!(s, "FARM={}", q(&ctx.farm));
    let _ = writeln!(s, "RETRIES={}", ctx.retries);
    let _ = writeln!(s, "THREADS=${{SLURM_CPUS_PER_TASK:-{}}}", ctx.cpus_per_task);
    let _ = writeln!(s, "FARM_STAGE={stage}");
    let _ = writeln!(
        s,
        "i=$(( ${{FARM_OFFSET:-0}} + ${{SLURM_ARRAY_TASK_ID:-0}} ))"
    );
    let _ = writeln!(s, "attempt=$(( ${{SLURM_RESTART_COUNT:-0}} + 1 ))");
    // This task's log (the --output pattern above, expanded), named in errors/ markers.
    if array {
        let _ = writeln!(
            s,
            "LOG=\"$JOBDIR/logs/{stage}_${{SLURM_ARRAY_JOB_ID:-0}}_${{SLURM_ARRAY_TASK_ID:-0}}.out\""
        );
    } else {
        let _ = writeln!(s, "LOG=\"$JOBDIR/logs/{stage}_${{SLURM_JOB_ID:-0}}.out\"");
    }
    let _ = writeln!(s, "TASK={stage}");
    s.push_str(FARM_RUN);
    s
}

/// Runs one command with the retry policy. `ILLUME_FARM_KILL_TASK=stage:index` is a test hook:
/// that task's first attempt has its render killed mid-run (SIGKILL), as a crashed node would.
const FARM_RUN: &str = r#"echo "farm: $FARM_STAGE task $i attempt $attempt on $(hostname) start $EPOCHREALTIME"
RENDER_SECONDS=0
farm_run() {
  local t0=$EPOCHREALTIME
  "$@" &
  local pid=$!
  if [ "${ILLUME_FARM_KILL_TASK:-}" = "$FARM_STAGE:$i" ] && [ "$attempt" = 1 ]; then
    # No sleep by default: a tiny test render could finish before it ends.
    [ -n "${ILLUME_FARM_KILL_AFTER:-}" ] && sleep "$ILLUME_FARM_KILL_AFTER"
    echo "farm: test hook ILLUME_FARM_KILL_TASK: killing pid $pid mid-run"
    kill -9 "$pid" 2>/dev/null
  fi
  wait "$pid"
  local rc=$?
  RENDER_SECONDS=$(awk -v a="$t0" -v b="$EPOCHREALTIME" -v s="$RENDER_SECONDS" 'BEGIN { printf "%.3f", s + b - a }')
  # A task that runs again starts with a clean slate: an old errors/ marker goes.
  if [ -z "${FARM_CLEARED:-}" ]; then rm -f "$JOBDIR/errors/$TASK"; FARM_CLEARED=1; fi
  case $rc in
    0) return 0 ;;
    1) echo "farm: rendered with errors (output kept): $*"
       mkdir -p "$JOBDIR/errors" && echo "$LOG" >> "$JOBDIR/errors/$TASK"
       return 0 ;;
  esac
  echo "farm: exit $rc on attempt $attempt: $*"
  if [ "${SLURM_RESTART_COUNT:-0}" -lt "$RETRIES" ] && [ -n "${SLURM_JOB_ID:-}" ]; then
    echo "farm: requeueing (retry $attempt of $RETRIES)"
    # Slurm ends this run and starts the task again; wait for it here.
    scontrol requeue "$SLURM_JOB_ID" && sleep 3600
  fi
  echo "farm: giving up after $attempt attempt(s)"
  exit "$rc"
}
farm_done() {
  echo "farm: $FARM_STAGE task $i done $EPOCHREALTIME render_seconds $RENDER_SECONDS"
  exit 0
}
# `make`-style: skip when $1 exists and is at least as new as the scene.
farm_up_to_date() {
  [ -e "$1" ] && [ ! "$SCENE" -nt "$1" ]
}
farm_mark_done() {
  mkdir -p "$(dirname "$1")" && : > "$1.tmp.$$" && mv -f "$1.tmp.$$" "$1"
}
"#;

fn no_task() -> &'static str {
    "  *) echo \"farm: no task $i in this script\"; exit 2 ;;\nesac\n"
}

/// The `Make*` requests before the first frame, one job.
pub fn setup_script(ctx: &ScriptContext) -> String {
    let mut s = header(ctx, "setup", false);
    let marker = ctx.dir.done("setup", "all");
    let _ = writeln!(s, "farm_up_to_date {} && farm_done", q(&marker));
    let _ = writeln!(
        s,
        "farm_run \"$RENDER\" -q {}",
        q(&ctx.dir.make_rib("setup"))
    );
    let _ = writeln!(s, "farm_mark_done {}", q(&marker));
    s.push_str("farm_done\n");
    s
}

/// One task per group: its pass frames whole, then its `Make*` steps.
pub fn passes_script(ctx: &ScriptContext, plan: &Plan) -> String {
    let mut s = header(ctx, "passes", true);
    s.push_str("case $i in\n");
    for (i, task) in plan.passes.iter().enumerate() {
        let _ = writeln!(s, "  {i}) label={}", task.label);
        s.push_str("    passes() {\n");
        for f in &task.frames {
            let _ = writeln!(
                s,
                "      farm_run \"$RENDER\" -q --threads \"$THREADS\" --no-make{} \"$SCENE\"",
                frames_flag(*f)
            );
        }
        if !task.make.is_empty() {
            let _ = writeln!(
                s,
                "      farm_run \"$RENDER\" -q {}",
                q(&ctx.dir.make_rib(&task.label))
            );
        }
        s.push_str("      :\n    } ;;\n");
    }
    s.push_str(no_task());
    s.push_str("TASK=\"passes.$label\"\n");
    s.push_str("marker=\"$JOBDIR/done/passes.$label\"\n");
    s.push_str("farm_up_to_date \"$marker\" && farm_done\n");
    s.push_str("passes\nfarm_mark_done \"$marker\"\nfarm_done\n");
    s
}

/// One task per frame × tile: `render --crop` of the beauty frame into a tile file.
pub fn tiles_script(ctx: &ScriptContext, plan: &Plan) -> String {
    let mut s = header(ctx, "tiles", true);
    s.push_str("case $i in\n");
    for (i, t) in plan.tiles.iter().enumerate() {
        let [x0, x1, y0, y1] = t.window.ndc;
        let _ = writeln!(
            s,
            "  {i}) frames=\"{}\"; crop=\"{x0:?} {x1:?} {y0:?} {y1:?}\"; tile={} ;;",
            frames_flag(t.frame).trim_start(),
            t.file.display()
        );
    }
    s.push_str(no_task());
    // tiles/4x4/f0002/x1y1.tile -> tiles.4x4.f0002.x1y1
    s.push_str("TASK=${tile#tiles/}; TASK=${TASK%.tile}; TASK=\"tiles.${TASK//\\//.}\"\n");
    s.push_str("out=\"$JOBDIR/$tile\"\n");
    s.push_str("farm_up_to_date \"$out\" && farm_done\n");
    s.push_str("mkdir -p \"$(dirname \"$out\")\"\n");
    s.push_str("# shellcheck disable=SC2086 # $frames and $crop are word lists\n");
    s.push_str(
        "farm_run \"$RENDER\" -q --threads \"$THREADS\" --no-make $frames --crop $crop --tile-out \"$out\" \"$SCENE\"\n",
    );
    s.push_str("[ -e \"$out\" ] || { echo \"farm: render wrote no tile $out\"; exit 2; }\n");
    s.push_str("farm_done\n");
    s
}

/// Assembles every complete frame's tiles into its displays (`farm merge`).
pub fn merge_script(ctx: &ScriptContext) -> String {
    let mut s = header(ctx, "merge", false);
    s.push_str("\"$FARM\" merge \"$JOBDIR\"\nrc=$?\n");
    s.push_str("echo \"farm: merge task $i done $EPOCHREALTIME exit $rc\"\nexit $rc\n");
    s
}

/// A RIB holding only `Make*` requests (`render` runs them in order).
pub fn make_rib(requests: &[Request]) -> String {
    let mut s = String::from(
        "##RenderMan RIB\n# Written by farm submit: the Make* steps of one pass task.\n",
    );
    for r in requests {
        s.push_str(&illume_rib::to_ascii(r));
        s.push('\n');
    }
    s
}
