//! `farm submit` failing fast and cleanly, without a cluster: a RIB with errors is refused
//! (each error printed with its line and a caret, exit 2) unless `--allow-errors`; a submit
//! that `sbatch` refuses removes the job directory it created, cancels what it did submit and
//! says what to set; `farm status` names the tasks that rendered with errors and their logs.
//! `sbatch`, `scancel`, `squeue` and `render` are stand-in shell scripts on PATH that record
//! how they were called, so every branch runs here; the real cluster is tests/farm/ci.sh.
#![cfg(unix)]

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("illume-farm-fail-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write_script(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).unwrap();
}

/// `farm ARGS` in `cwd` with `bin` first on PATH and `SLURM_CONF` as given.
fn farm(args: &[&str], cwd: &Path, bin: &Path, slurm_conf: Option<&Path>) -> Output {
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut c = Command::new(env!("CARGO_BIN_EXE_farm"));
    c.args(args).current_dir(cwd).env("PATH", path);
    match slurm_conf {
        Some(conf) => c.env("SLURM_CONF", conf),
        None => c.env_remove("SLURM_CONF"),
    };
    c.output().unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

const GOOD: &str = "Format 16 16 1\nDisplay \"g.tif\" \"tiff\" \"rgb\"\nWorldBegin\n\
    Translate 0 0 3\nSphere 1 -1 1 360\nWorldEnd\n";

#[test]
fn a_scene_with_errors_is_refused_with_file_line_col_and_a_caret() {
    let dir = temp_dir("parse");
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    // An unterminated string swallows the rest of the file.
    std::fs::write(
        dir.join("open.rib"),
        "Format 16 16 1\nDisplay \"g.tif \"tiff\" \"rgb\"\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n",
    )
    .unwrap();
    let out = farm(&["submit", "open.rib", "--dry-run"], &dir, &bin, None);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty(), "a refused scene printed scripts");
    // Line 2, column 27: the last quote opens a string that never closes.
    let caret = format!(
        "\n{}\n{}^",
        "Display \"g.tif \"tiff\" \"rgb\"",
        " ".repeat(26)
    );
    assert!(
        err.contains("open.rib:2:27: error:") && err.contains(&caret),
        "{err}"
    );
    assert!(err.contains("nothing submitted"), "{err}");
    assert!(!dir.join("open.farm").exists());

    // An error the RI state finds (not the parser) gets its line read back from the file.
    std::fs::write(
        dir.join("bad.rib"),
        format!("{GOOD}  WorldEnd\nSphre 1 -1 1 360\n"),
    )
    .unwrap();
    let out = farm(&["submit", "bad.rib", "--dry-run"], &dir, &bin, None);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bad.rib:7:3: error: WorldEnd:") && err.contains("\n  WorldEnd\n  ^"),
        "{err}"
    );
    // The misspelled request is a warning (render goes on without it), said once, with caret.
    assert!(
        err.contains("bad.rib:8:1: warning: Sphre: unknown request")
            && err.contains("\nSphre 1 -1 1 360\n^"),
        "{err}"
    );
    assert!(err.contains("1 error(s) in the RIB"), "{err}");

    // --allow-errors goes ahead (here a dry run) and says so.
    let out = farm(
        &["submit", "bad.rib", "--dry-run", "--allow-errors"],
        &dir,
        &bin,
        None,
    );
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("--allow-errors: submitting anyway"), "{err}");
    assert!(text(&out.stdout).contains("scripts/tiles.sh"));
    // A warning alone does not stop a submit.
    std::fs::write(dir.join("warn.rib"), format!("Sphre 1\n{GOOD}")).unwrap();
    let out = farm(&["submit", "warn.rib", "--dry-run"], &dir, &bin, None);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("warn.rib:1:1: warning: Sphre:"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A stand-in `sbatch`: accepts (prints a job id) its first `accept` calls, then refuses
/// with `message`; every call is appended to `calls`.
fn fake_sbatch(bin: &Path, accept: usize, message: &str) {
    write_script(
        &bin.join("sbatch"),
        &format!(
            "#!/bin/sh\necho \"$*\" >> '{calls}'\nn=$(wc -l < '{calls}')\n\
             if [ \"$n\" -le {accept} ]; then echo $((100 + n)); exit 0; fi\n\
             echo '{message}' >&2\nexit 1\n",
            calls = bin.join("calls").display()
        ),
    );
    write_script(
        &bin.join("scancel"),
        &format!(
            "#!/bin/sh\necho \"$*\" >> '{}'\n",
            bin.join("cancelled").display()
        ),
    );
}

#[test]
fn a_refused_submit_removes_the_job_directory_it_made_and_says_what_to_set() {
    let dir = temp_dir("sbatch");
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::write(dir.join("g.rib"), GOOD).unwrap();
    fake_sbatch(
        &bin,
        0,
        "sbatch: error: Could not establish a configuration source",
    );
    let missing = dir.join("no-such-slurm.conf");
    let out = farm(&["submit", "g.rib"], &dir, &bin, Some(&missing));
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("Could not establish a configuration source")
            && err.contains(&format!("SLURM_CONF={} is not a file", missing.display()))
            && err.contains("tests/farm/slurm_up.sh"),
        "{err}"
    );
    assert!(!dir.join("g.farm").exists(), "the job directory was left");

    // A partition the cluster lacks: the hint names --partition.
    let conf = dir.join("slurm.conf");
    std::fs::write(&conf, "# a stand-in\n").unwrap();
    std::fs::remove_file(bin.join("calls")).unwrap();
    fake_sbatch(
        &bin,
        0,
        "sbatch: error: Batch job submission failed: Invalid partition name specified",
    );
    let out = farm(
        &["submit", "g.rib", "--partition", "gpu"],
        &dir,
        &bin,
        Some(&conf),
    );
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--partition (`sinfo -s` lists them)"), "{err}");
    assert!(!dir.join("g.farm").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_submit_refused_halfway_cancels_its_jobs_and_leaves_an_older_job_directory_as_it_was() {
    let dir = temp_dir("halfway");
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::write(dir.join("g.rib"), GOOD).unwrap();
    let conf = dir.join("slurm.conf");
    std::fs::write(&conf, "# a stand-in\n").unwrap();
    // tiles accepted (job 101), merge refused.
    fake_sbatch(&bin, 1, "sbatch: error: QOSMaxSubmitJobPerUserLimit");
    let out = farm(&["submit", "g.rib"], &dir, &bin, Some(&conf));
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("QOSMaxSubmitJobPerUserLimit"), "{err}");
    assert_eq!(
        std::fs::read_to_string(bin.join("cancelled")).unwrap(),
        "101\n"
    );
    assert!(!dir.join("g.farm").exists());

    // A job directory from an earlier submit stays, with its jobs file unchanged.
    let job = dir.join("g.farm");
    std::fs::create_dir_all(&job).unwrap();
    std::fs::write(job.join("jobs"), "tiles 7 1.000 0\n").unwrap();
    std::fs::remove_file(bin.join("calls")).unwrap();
    std::fs::remove_file(bin.join("cancelled")).unwrap();
    let out = farm(&["submit", "g.rib"], &dir, &bin, Some(&conf));
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        std::fs::read_to_string(bin.join("cancelled")).unwrap(),
        "101\n"
    );
    assert_eq!(
        std::fs::read_to_string(job.join("jobs")).unwrap(),
        "tiles 7 1.000 0\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn status_names_the_tasks_that_rendered_with_errors_and_their_logs() {
    let dir = temp_dir("status");
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::write(dir.join("g.rib"), GOOD).unwrap();
    let conf = dir.join("slurm.conf");
    std::fs::write(&conf, "# a stand-in\n").unwrap();
    fake_sbatch(&bin, 10, "unused");
    write_script(&bin.join("squeue"), "#!/bin/sh\nexit 0\n");
    // A render that writes its tile and exits with $FAKE_RC (1: rendered with errors).
    let render = bin.join("fake-render");
    write_script(
        &render,
        "#!/bin/sh\nwhile [ $# -gt 0 ]; do [ \"$1\" = --tile-out ] && : > \"$2\"; shift; done\n\
         echo 'g.rib:5:1: error: Sphere: something' >&2\nexit \"${FAKE_RC:-1}\"\n",
    );
    let out = farm(
        &[
            "submit",
            "g.rib",
            "--tiles",
            "2x1",
            "--render",
            render.to_str().unwrap(),
        ],
        &dir,
        &bin,
        Some(&conf),
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let job = dir.join("g.farm");
    // Run the generated tiles script as Slurm would run array task 1 of job 101.
    let run_task = |task: &str, rc: &str| {
        let st = Command::new("bash")
            .arg(job.join("scripts/tiles.sh"))
            .current_dir(&dir)
            .env("SLURM_ARRAY_JOB_ID", "101")
            .env("SLURM_ARRAY_TASK_ID", task)
            .env("SLURM_JOB_ID", "102")
            .env("FAKE_RC", rc)
            .output()
            .unwrap();
        assert!(st.status.success(), "{}", text(&st.stdout));
        text(&st.stdout)
    };
    let log = run_task("1", "1");
    assert!(log.contains("farm: rendered with errors"), "{log}");
    let status = farm(&["status", "g.farm"], &dir, &bin, Some(&conf));
    let s = text(&status.stdout);
    let want = format!(
        "1 rendered with errors:\n          tiles 2x1/frame/x1y0: log {}\n",
        job.join("logs/tiles_101_1.out").display()
    );
    assert!(s.contains(&want), "{s}");
    // Rendered again cleanly (the tile removed, so the task is not skipped): no longer listed.
    std::fs::remove_file(job.join("tiles/2x1/frame/x1y0.tile")).unwrap();
    run_task("1", "0");
    let s = text(&farm(&["status", "g.farm"], &dir, &bin, Some(&conf)).stdout);
    assert!(s.contains(", 0 rendered with errors\n"), "{s}");
    std::fs::remove_dir_all(&dir).unwrap();
}
