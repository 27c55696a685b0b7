//! The shaders of *The RenderMan Companion* (Upstill, 1989) and *Advanced RenderMan*
//! (Apodaca & Gritz, 1999) compile with our front end, and each renders a lit sphere under the
//! `render` binary (surface on the sphere, light shining on it, displacement on it, volume as
//! its atmosphere) without an error, a fallback to a built-in shader or a non-finite value.
//!
//! The collections are copyrighted and stay outside this repository. They are the books' own
//! auxiliary files as kept by the RenderMan Repository (renderman.org, snapshot at
//! `github.com/tlanc007/RenderMan_Repository`): `RMR/Publications/arman/shaders/` (the 32
//! shaders and headers of Advanced RenderMan's materials, `arman-shaders.tar.gz`) and every
//! `.sl` under `RMR/Publications/rc/` (the Companion's listings: chapters 12, 13, 16, 17, and
//! `ch16/modern/`, renderman.org's RI 3.1 update of chapter 16 with `normal`/`vector` types).
//!
//! Where: `$ILLUME_SHADER_BOOKS`, a checkout of that repository or its git directory (read with
//! `git archive`, never written); without it, the fetched mirror at [`MIRROR`]. When neither
//! exists it says so and exits with status 2: an opt-in check, an example rather than a test,
//! so that no test passes without its data (CI carries no copy). When the variable is set but
//! holds no collection, it fails.
//!
//! Run: `cargo build -p render && ILLUME_SHADER_BOOKS=… cargo run -p illume-slvm --example
//! library_books` (the table of counts goes to stderr).
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Where this project's helper machines fetch the repository (`fetch github:tlanc007/…`).
const MIRROR: &str = "/work/.mirror/tlanc007+RenderMan_Repository/repo";

/// Each collection: its name, directory in the repository, whether `.sl` files are searched in
/// subdirectories, and how many shaders it holds.
const COLLECTIONS: [(&str, &str, bool, usize); 2] = [
    (
        "Advanced RenderMan",
        "RMR/Publications/arman/shaders",
        false,
        32,
    ),
    ("RenderMan Companion", "RMR/Publications/rc", true, 81),
];

/// The repository root holding the collections, extracted into a temporary directory when the
/// source is a git directory; `None` (after saying why) when there is none.
fn books(scratch: &Path) -> Option<PathBuf> {
    let (source, from_env) = match std::env::var_os("ILLUME_SHADER_BOOKS") {
        Some(p) if !p.is_empty() => (PathBuf::from(p), true),
        Some(_) => panic!("$ILLUME_SHADER_BOOKS is set but empty"),
        None => (PathBuf::from(MIRROR), false),
    };
    if !source.exists() {
        assert!(
            !from_env,
            "$ILLUME_SHADER_BOOKS={} does not exist",
            source.display()
        );
        say(&format!(
            "******** SKIPPED library_books: the book shader collections are not here ({MIRROR} \
             absent, $ILLUME_SHADER_BOOKS unset); set it to a checkout of \
             github.com/tlanc007/RenderMan_Repository to run this check ********"
        ));
        return None;
    }
    if !source.join("HEAD").is_file() || !source.join("objects").is_dir() {
        return Some(source);
    }
    let root = scratch.join("repository");
    std::fs::create_dir_all(&root).unwrap();
    let mut archive = Command::new("git")
        .arg("--git-dir")
        .arg(&source)
        .args(["archive", "--format=tar", "HEAD"])
        .args(COLLECTIONS.map(|c| c.1))
        .stdout(Stdio::piped())
        // The mirror lacks files of 4 MiB and more elsewhere in the tree; git names them.
        .stderr(Stdio::null())
        .spawn()
        .expect("git runs");
    let untar = Command::new("tar")
        .arg("-x")
        .arg("-C")
        .arg(&root)
        .stdin(archive.stdout.take().unwrap())
        .status()
        .expect("tar runs");
    let archived = archive.wait().expect("git archive finishes");
    assert!(
        archived.success() && untar.success(),
        "git archive of {} failed",
        source.display()
    );
    Some(root)
}

/// Writes a line to the real stderr (the harness captures `eprintln!` of passing tests).
fn say(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// The `.sl` files under `dir` (and its subdirectories when `deep`), sorted.
fn shaders_in(dir: &Path, deep: bool) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return found;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() && deep {
            found.extend(shaders_in(&p, true));
        } else if p.extension().is_some_and(|x| x == "sl") {
            found.push(p);
        }
    }
    found.sort();
    found
}

/// The test scene: a sphere under an ambient and a distant light, with the shader under test
/// in the role its kind gives it (a light shines from the camera side, in its shader space
/// looking down +z at the sphere).
fn scene(kind: &str, name: &str, searchpath: &str) -> String {
    let mut lights = "LightSource \"ambientlight\" 1 \"intensity\" [0.1]\n".to_string();
    let (mut surface, mut extra, mut outside) = ("Surface \"plastic\"".to_string(), "", "");
    match kind {
        "surface" => surface = format!("Surface \"{name}\""),
        "light" => {
            lights +=
                &format!("TransformBegin Translate 0 0 -3 LightSource \"{name}\" 2 TransformEnd\n")
        }
        "displacement" => extra = "Attribute \"displacementbound\" \"sphere\" [0.5]\n",
        "volume" => outside = "Atmosphere",
        _ => outside = "Imager",
    }
    if kind != "light" {
        lights += "LightSource \"distantlight\" 2 \"intensity\" [0.9] \"from\" [-4 5 -6] \"to\" [0 0 0]\n";
    }
    let displacement = if kind == "displacement" {
        format!("Displacement \"{name}\"")
    } else {
        String::new()
    };
    let outside = if outside.is_empty() {
        String::new()
    } else {
        format!("{outside} \"{name}\"")
    };
    format!(
        "Option \"searchpath\" \"shader\" [\"{searchpath}\"]\nDisplay \"out.tif\" \"file\" \"rgba\"\n\
         Format 32 32 1\nPixelSamples 1 1\nProjection \"perspective\" \"fov\" [40]\n\
         Translate 0 0 4\nWorldBegin\n{lights}{outside}\nAttributeBegin\nColor [0.8 0.6 0.4]\n\
         {surface}\n{extra}{displacement}\nSphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n"
    )
}

/// Warnings the scene may give without the shader being at fault: the books' texture and
/// shadow files are not part of the shader collections, and the generic scene's
/// `displacementbound` is smaller than a few displacements (re-rendered correctly).
fn expected_warning(line: &str) -> bool {
    line.contains("not found; black") || line.contains("\"displacementbound\"")
}

/// Renders `file` (a `kind` shader called `name`) on the test sphere: `Err` says why not.
fn render_one(
    render: &Path,
    file: &Path,
    kind: &str,
    name: &str,
    dir: &Path,
) -> Result<(), String> {
    std::fs::create_dir_all(dir).unwrap();
    // Copied under the shader's own name (the Companion's `plastic.sl` defines `RCPlastic`);
    // its includes are still found next to the original on the searchpath.
    std::fs::copy(file, dir.join(format!("{name}.sl"))).unwrap();
    let searchpath = format!("{}:{}:&", dir.display(), file.parent().unwrap().display());
    std::fs::write(dir.join("scene.rib"), scene(kind, name, &searchpath)).unwrap();
    let log = std::fs::File::create(dir.join("render.log")).unwrap();
    let mut child = Command::new(render)
        .args(["-q", "--stats", "scene.rib"])
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(log)
        .spawn()
        .map_err(|e| format!("render did not run: {e}"))?;
    let status = wait_at_most(&mut child, std::time::Duration::from_secs(120))?;
    let stderr = std::fs::read_to_string(dir.join("render.log")).unwrap_or_default();
    if !status.success() {
        return Err(format!("render exited with {status}: {stderr}"));
    }
    let bad: Vec<&str> = stderr
        .lines()
        .filter(|l| {
            let lower = l.to_ascii_lowercase();
            (lower.contains("warning") || lower.contains("error")) && !expected_warning(l)
        })
        .collect();
    if !bad.is_empty() {
        return Err(bad.join(" | "));
    }
    let nonfinite = stderr
        .split("non-finite shaded points ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse::<u64>().ok());
    match nonfinite {
        Some(0) => {}
        other => return Err(format!("non-finite shaded points: {other:?}")),
    }
    match std::fs::metadata(dir.join("out.tif")) {
        Ok(m) if m.len() > 0 => Ok(()),
        _ => Err("no image written".into()),
    }
}

/// Waits for `child` up to `limit` (the 120 s per job), killing it after that: a
/// shader loop that never ends must fail the test, not hang it.
fn wait_at_most(
    child: &mut std::process::Child,
    limit: std::time::Duration,
) -> Result<std::process::ExitStatus, String> {
    let start = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            return Ok(status);
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("render took over {} s", limit.as_secs()));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Compiles and renders every shader of the two books; exits non-zero (a panic) on any
/// failure, and with status 2 when the collections or the `render` binary are not here.
fn main() {
    let scratch = std::env::temp_dir().join(format!("illume-books-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&scratch);
    let Some(root) = books(&scratch) else {
        std::process::exit(2)
    };
    let Some(render) = illume_testenv::require_built("render", "RENDER") else {
        std::process::exit(2)
    };
    let mut failures = Vec::new();
    for (collection, rel, deep, expected) in COLLECTIONS {
        let dir = root.join(rel);
        let files = shaders_in(&dir, deep);
        assert!(
            !files.is_empty(),
            "no .sl files in {} ({collection}): is {} the RenderMan Repository?",
            dir.display(),
            root.display()
        );
        let (mut compiled, mut rendered) = (0, 0);
        for file in &files {
            let shown = file
                .strip_prefix(&dir)
                .unwrap_or(file)
                .display()
                .to_string();
            let opts = illume_sl::PpOptions {
                include_dirs: vec![file.parent().unwrap().to_path_buf()],
                defines: Vec::new(),
            };
            let out = illume_sl::compile_file(file, &opts);
            let Some(shader) = out.program.shaders.first().filter(|_| !out.has_errors()) else {
                failures.push(format!(
                    "{collection} {shown}: {}",
                    out.render_diagnostics()
                ));
                continue;
            };
            compiled += 1;
            let (kind, name) = (shader.kind.to_string(), shader.name.clone());
            let case = scratch.join(shown.replace(['/', '.'], "_"));
            match render_one(&render, file, &kind, &name, &case) {
                Ok(()) => rendered += 1,
                Err(why) => failures.push(format!("{collection} {shown} ({kind} {name}): {why}")),
            }
        }
        let total = files.len();
        say(&format!(
            "{collection} ({rel}): compiled {compiled}/{total}, rendered {rendered}/{total}"
        ));
        assert_eq!(
            total,
            expected,
            "{collection}: {total} shaders in {}",
            dir.display()
        );
    }
    let _ = std::fs::remove_dir_all(&scratch);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
