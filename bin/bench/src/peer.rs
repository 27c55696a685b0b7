//! `bench --peer CMD`: our `render` and a peer renderer side by side on the same 14 gallery
//! scenes at 4× their pixels (2× their `Format` per axis), each measured as the kernel
//! accounts it (wall, user + system CPU, peak RSS of that process, [`crate::child`]), the two
//! renderers alternating scene by scene so that the machine's load hits both alike (issue 21
//! part 6 and its acceptance table).
//!
//! The scenes are the `rib/` gallery that Aqsis 1.8.4 (the peer this was written against)
//! renders with its own standard shaders. Where a scene uses a shader only we have or a
//! parameter the peer does not declare, the *same* edit is made for both renderers
//! ([`SCENES`]' substitutions), so both render one scene text. Each renderer works in its own
//! copy of `rib/` and `textures/`, because the shadow maps and textures a scene makes
//! (`MakeShadow`, `MakeTexture`) are each renderer's own file format.

use crate::child::{run_measured, Usage};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One scene of the set: its name, its file under `rib/`, and textual edits applied to its
/// text for both renderers, with the reason.
pub struct PeerScene {
    pub name: &'static str,
    pub file: &'static str,
    pub edits: &'static [(&'static str, &'static str)],
    pub note: &'static str,
}

/// Aqsis 1.8.4 reports shader parameters that its RIB parser has no declaration for as
/// "undeclared token" and drops the whole request; an inline declaration means the same to
/// both renderers.
const DECLARE_SHADOWNAME: (&str, &str) = ("\"shadowname\"", "\"string shadowname\"");
/// The other `shadowspot` parameters Aqsis 1.8.4 does not declare. Its `shadowspot` has no
/// `bias` (it takes `Option "shadow" "bias"`): declared inline, the peer ignores it with a
/// warning.
const DECLARE_SHADOW_FLOATS: [(&str, &str); 3] = [
    ("\"samples\" [", "\"float samples\" ["),
    ("\"blur\" [", "\"float blur\" ["),
    ("\"bias\" [", "\"float bias\" ["),
];
const DECLARE_SHADOW: [(&str, &str); 4] = [
    DECLARE_SHADOWNAME,
    DECLARE_SHADOW_FLOATS[0],
    DECLARE_SHADOW_FLOATS[1],
    DECLARE_SHADOW_FLOATS[2],
];

/// The 14-scene set.
pub const SCENES: [PeerScene; 14] = [
    PeerScene { name: "sphere", file: "sphere.rib", edits: &[], note: "" },
    PeerScene { name: "teapot", file: "teapot.rib", edits: &[], note: "" },
    PeerScene { name: "geometry", file: "geometry.rib", edits: &[], note: "" },
    PeerScene { name: "blobby", file: "blobby.rib", edits: &[], note: "" },
    PeerScene { name: "csg", file: "csg.rib", edits: &[], note: "" },
    PeerScene { name: "motion", file: "motion.rib", edits: &[], note: "" },
    PeerScene {
        name: "displacement",
        file: "displacement.rib",
        edits: &[("\"ripple\"", "\"dented\""), ("\"frequency\"", "\"float frequency\"")],
        note: "`ripple` (ours only) replaced by `dented`; `frequency` declared inline",
    },
    PeerScene { name: "camera_blur", file: "bench/camera_blur.rib", edits: &[], note: "" },
    PeerScene { name: "transform_blur", file: "bench/transform_blur.rib", edits: &[], note: "" },
    PeerScene { name: "specular_models", file: "ch9/specular_models.rib", edits: &[], note: "" },
    PeerScene {
        name: "vase",
        file: "ch9/fig9_2_vase.rib",
        edits: &[("\"roughmetal\"", "\"metal\"")],
        note: "`roughmetal` (ours only) replaced by `metal`",
    },
    PeerScene {
        name: "shadow",
        file: "pipelines/shadow/shadow_single.rib",
        edits: &DECLARE_SHADOW,
        note: "depth pass, MakeShadow, beauty; `shadowname`, `samples`, `blur`, `bias` declared inline",
    },
    PeerScene {
        name: "turntable",
        file: "pipelines/farm/turntable.rib",
        edits: &DECLARE_SHADOW,
        note: "3 frames of depth pass, MakeShadow, beauty; `shadowname`, `samples`, `blur`, `bias` declared inline",
    },
    PeerScene {
        name: "flatmirror",
        file: "pipelines/flatmirror/flatmirror_single.rib",
        edits: &[
            ("\"envname\"", "\"string envname\""),
            ("\"envspace\"", "\"string envspace\""),
        ],
        note: "mirror pass, MakeTexture, beauty; the peer's `shinymetal` has no `envname`, so its mirror stays dark",
    },
];

/// The scene text with `edits` applied and every `Format` scaled by `scale` per axis, and
/// the pixel count of its last `Format` (the beauty frame's). `Err` when there is no `Format`.
pub fn variant(rib: &str, edits: &[(&str, &str)], scale: u32) -> Result<(String, u64), String> {
    let mut text = rib.to_string();
    for (from, to) in edits {
        text = text.replace(from, to);
    }
    let mut out = String::with_capacity(text.len());
    let mut pixels = None;
    for (n, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if let ["Format", w, h, rest @ ..] = words.as_slice() {
            let (format, count) = crate::scene::multiplied_format(line, w, h, rest, scale)
                .map_err(|e| format!("line {}: {e}", n + 1))?;
            pixels = Some(count);
            let indent = &line[..line.len() - line.trim_start().len()];
            let _ = writeln!(out, "{indent}{format}");
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok((out, pixels.ok_or("no Format line")?))
}

/// One scene's measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct PeerRow {
    pub scene: String,
    pub pixels: u64,
    pub ours: Cost,
    pub peer: Cost,
}

/// The three numbers compared.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Cost {
    pub wall_seconds: f64,
    pub cpu_seconds: f64,
    pub peak_rss_mb: f64,
}

impl PeerRow {
    /// Peer wall / our wall: above 1 we are faster.
    pub fn wall_speedup(&self) -> f64 {
        self.peer.wall_seconds / self.ours.wall_seconds
    }
    /// Peer CPU / our CPU: above 1 we do the frame in fewer CPU seconds.
    pub fn cpu_speedup(&self) -> f64 {
        self.peer.cpu_seconds / self.ours.cpu_seconds
    }
    /// Our peak RSS / the peer's: at most 1 is the target.
    pub fn rss_ratio(&self) -> f64 {
        self.ours.peak_rss_mb / self.peer.peak_rss_mb
    }
}

/// Geometric mean of the positive finite values (NaN when there are none).
pub fn geomean(values: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut n) = (0.0, 0u32);
    for v in values.filter(|v| v.is_finite() && *v > 0.0) {
        sum += v.ln();
        n += 1;
    }
    if n == 0 {
        f64::NAN
    } else {
        (sum / f64::from(n)).exp()
    }
}

/// The CSV's header.
pub const HEADER: &str = "scene,pixels,ours_wall_s,ours_cpu_s,ours_rss_mb,peer_wall_s,peer_cpu_s,peer_rss_mb,wall_speedup,cpu_speedup,rss_ratio";

/// The CSV text of `rows` (ratios included for spreadsheets; [`from_csv`] recomputes them).
pub fn to_csv(rows: &[PeerRow]) -> String {
    let mut s = format!("{HEADER}\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{:.4},{:.4},{:.4}",
            r.scene,
            r.pixels,
            r.ours.wall_seconds,
            r.ours.cpu_seconds,
            r.ours.peak_rss_mb,
            r.peer.wall_seconds,
            r.peer.cpu_seconds,
            r.peer.peak_rss_mb,
            r.wall_speedup(),
            r.cpu_speedup(),
            r.rss_ratio()
        );
    }
    s
}

/// Reads [`to_csv`]'s text back.
pub fn from_csv(text: &str) -> Result<Vec<PeerRow>, String> {
    let mut rows = Vec::new();
    for (n, f) in crate::csv::records(text, HEADER, 11)? {
        let num = |k: usize| -> Result<f64, String> {
            f[k].parse().map_err(|_| {
                format!(
                    "line {}: field {}: expected a number, found {:?}",
                    n + 1,
                    k + 1,
                    f[k]
                )
            })
        };
        let cost = |k: usize| -> Result<Cost, String> {
            Ok(Cost {
                wall_seconds: num(k)?,
                cpu_seconds: num(k + 1)?,
                peak_rss_mb: num(k + 2)?,
            })
        };
        rows.push(PeerRow {
            scene: f[0].to_string(),
            pixels: num(1)? as u64,
            ours: cost(2)?,
            peer: cost(5)?,
        });
    }
    Ok(rows)
}

/// The markdown table with the geometric means and the scene edits.
pub fn markdown(rows: &[PeerRow], heading: &str) -> String {
    let mut md = format!("{heading}\n\n");
    md.push_str(
        "| scene | pixels | ours wall s | peer wall s | wall speed-up | ours CPU s | peer CPU s | \
         CPU speed-up | ours peak MB | peer peak MB | RSS ours/peer |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {:.2} | {:.2} | {:.2}× | {:.2} | {:.2} | {:.2}× | {:.0} | {:.0} | {:.2} |",
            r.scene,
            r.pixels,
            r.ours.wall_seconds,
            r.peer.wall_seconds,
            r.wall_speedup(),
            r.ours.cpu_seconds,
            r.peer.cpu_seconds,
            r.cpu_speedup(),
            r.ours.peak_rss_mb,
            r.peer.peak_rss_mb,
            r.rss_ratio()
        );
    }
    let g = |f: fn(&PeerRow) -> f64| geomean(rows.iter().map(f));
    let _ = writeln!(
        md,
        "| **geometric mean** | | | | **{:.2}×** | | | **{:.2}×** | | | **{:.2}** |",
        g(PeerRow::wall_speedup),
        g(PeerRow::cpu_speedup),
        g(PeerRow::rss_ratio)
    );
    let edited: Vec<String> = SCENES
        .iter()
        .filter(|s| !s.note.is_empty() && rows.iter().any(|r| r.scene == s.name))
        .map(|s| format!("{} ({})", s.name, s.note))
        .collect();
    if !edited.is_empty() {
        let _ = writeln!(
            md,
            "\nEdited for both renderers alike: {}.",
            edited.join("; ")
        );
    }
    md
}

/// How a side-by-side run goes.
pub struct PeerConfig<'a> {
    pub render: &'a Path,
    /// The peer's command line, the scene file appended.
    pub peer: &'a [String],
    pub repo: &'a Path,
    pub scratch: &'a Path,
    pub scale: u32,
    pub threads: usize,
    /// Renders per scene and renderer; the smallest of each number is kept.
    pub repeat: usize,
}

/// Copies `from` into `to` recursively.
fn copy_tree(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::create_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
    let entries = std::fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", from.display()))?;
        let (src, dst) = (entry.path(), to.join(entry.file_name()));
        if src.is_dir() {
            copy_tree(&src, &dst)?;
        } else {
            std::fs::copy(&src, &dst).map_err(|e| format!("{}: {e}", src.display()))?;
        }
    }
    Ok(())
}

/// Each renderer's own copy of `rib/` and `textures/` under `scratch/<who>`.
fn prepare(cfg: &PeerConfig, who: &str) -> Result<PathBuf, String> {
    let root = cfg.scratch.join(who);
    for d in ["rib", "textures"] {
        let src = cfg.repo.join(d);
        if src.is_dir() {
            copy_tree(&src, &root.join(d))?;
        }
    }
    Ok(root.join("rib"))
}

/// The smaller of each number.
fn keep_best(best: &mut Option<Cost>, u: &Usage) {
    let c = Cost {
        wall_seconds: u.wall_seconds,
        cpu_seconds: u.cpu_seconds,
        peak_rss_mb: u.peak_rss_mb,
    };
    *best = Some(match *best {
        None => c,
        Some(b) => Cost {
            wall_seconds: b.wall_seconds.min(c.wall_seconds),
            cpu_seconds: b.cpu_seconds.min(c.cpu_seconds),
            peak_rss_mb: b.peak_rss_mb.min(c.peak_rss_mb),
        },
    });
}

/// A peer's stderr lines that report errors (Aqsis: `ERROR:`); a scene the peer rendered
/// with errors measures a different scene, so it is a failure.
fn peer_errors(stderr: &str) -> Vec<&str> {
    stderr.lines().filter(|l| l.contains("ERROR")).collect()
}

/// Runs one scene on both renderers `repeat` times, alternating.
fn run_scene(cfg: &PeerConfig, s: &PeerScene, ours: &Path, peer: &Path) -> Result<PeerRow, String> {
    let rib = std::fs::read_to_string(ours.join(s.file)).map_err(|e| format!("{}: {e}", s.file))?;
    let (text, pixels) =
        variant(&rib, s.edits, cfg.scale).map_err(|e| format!("{}: {e}", s.file))?;
    let rel = Path::new(s.file);
    let dir_of = |root: &Path| root.join(rel.parent().unwrap_or(Path::new("")));
    let name = format!("{}_bench.rib", s.name);
    for root in [ours, peer] {
        let f = dir_of(root).join(&name);
        std::fs::write(&f, &text).map_err(|e| format!("{}: {e}", f.display()))?;
    }
    let ours_args = [
        "-q".to_string(),
        "--threads".into(),
        cfg.threads.to_string(),
        name.clone(),
    ];
    let mut peer_args: Vec<String> = cfg.peer[1..].to_vec();
    peer_args.push(name.clone());
    let peer_prog = program_path(&cfg.peer[0]);
    let (mut best_ours, mut best_peer) = (None, None);
    for _ in 0..cfg.repeat.max(1) {
        let u = run_measured(cfg.render, &ours_args, &dir_of(ours))?;
        if u.exit_code != 0 {
            let tail: Vec<&str> = u.stderr.lines().rev().take(3).collect();
            return Err(format!(
                "render exited with {}: {}",
                u.exit_code,
                tail.join(" | ")
            ));
        }
        keep_best(&mut best_ours, &u);
        let u = run_measured(&peer_prog, &peer_args, &dir_of(peer))?;
        let errors = peer_errors(&u.stderr);
        if u.exit_code != 0 || !errors.is_empty() {
            return Err(format!(
                "peer exited with {}: {}",
                u.exit_code,
                errors.join(" | ")
            ));
        }
        keep_best(&mut best_peer, &u);
    }
    let (ours_cost, peer_cost) = (best_ours.unwrap_or_default(), best_peer.unwrap_or_default());
    eprintln!(
        "bench: {}: ours {:.2} s wall {:.2} s CPU {:.0} MB, peer {:.2} s wall {:.2} s CPU {:.0} MB",
        s.name,
        ours_cost.wall_seconds,
        ours_cost.cpu_seconds,
        ours_cost.peak_rss_mb,
        peer_cost.wall_seconds,
        peer_cost.cpu_seconds,
        peer_cost.peak_rss_mb
    );
    Ok(PeerRow {
        scene: s.name.into(),
        pixels,
        ours: ours_cost,
        peer: peer_cost,
    })
}

/// The peer's program as a path that still names it from the scene's scratch folder, where it
/// runs: a relative path with a folder in it (`../shared/tools/aqsis-render`, as the README
/// writes it) is made absolute from the current folder; a bare name is left to `PATH`.
fn program_path(program: &str) -> PathBuf {
    let path = Path::new(program);
    if path.is_relative() && path.components().count() > 1 {
        std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
    } else {
        path.to_path_buf()
    }
}

/// Runs the set (or the scenes named in `only`); scenes that fail are reported and skipped.
pub fn run(cfg: &PeerConfig, only: &[String]) -> Result<(Vec<PeerRow>, usize), String> {
    if cfg.peer.is_empty() {
        return Err("--peer needs a command".into());
    }
    let ours = prepare(cfg, "ours")?;
    let peer = prepare(cfg, "peer")?;
    let mut rows = Vec::new();
    let mut failures = 0;
    for s in SCENES
        .iter()
        .filter(|s| only.is_empty() || only.iter().any(|o| o == s.name))
    {
        match run_scene(cfg, s, &ours, &peer) {
            Ok(r) => rows.push(r),
            Err(e) => {
                eprintln!("bench: {}: {e}", s.name);
                failures += 1;
            }
        }
    }
    Ok((rows, failures))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_relative_peer_path_is_taken_from_the_current_folder() {
        let here = std::env::current_dir().unwrap();
        let p = program_path("../tools/aqsis-render");
        assert!(p.is_absolute(), "{}", p.display());
        assert!(
            p.starts_with(&here),
            "{} not under {}",
            p.display(),
            here.display()
        );
        assert!(p.ends_with("tools/aqsis-render"));
        assert_eq!(program_path("aqsis"), PathBuf::from("aqsis"));
        assert_eq!(program_path("/opt/x/aqsis"), PathBuf::from("/opt/x/aqsis"));
    }

    #[test]
    fn variants_scale_every_format_and_apply_the_edits() {
        let rib = "FrameBegin 1\n  Format 128 96 1\n  LightSource \"shadowspot\" 2 \"shadowname\" [\"a.sm\"]\nFrameEnd\n\
                   Format 320 240 1.5\nSurface \"roughmetal\"\n";
        let (text, pixels) = variant(
            rib,
            &[DECLARE_SHADOWNAME, ("\"roughmetal\"", "\"metal\"")],
            2,
        )
        .unwrap();
        assert_eq!(pixels, 640 * 480);
        assert!(text.contains("  Format 256 192 1\n"));
        assert!(text.contains("Format 640 480 1.5\n"));
        assert!(text.contains("\"string shadowname\" [\"a.sm\"]"));
        assert!(text.contains("Surface \"metal\"\n"));
        assert!(variant("Sphere 1 -1 1 360\n", &[], 2).is_err());
        assert!(variant("Format x 2 1\n", &[], 2).is_err());
    }

    #[test]
    fn the_csv_round_trips_and_ratios_follow() {
        let c = |w: f64, cpu: f64, m: f64| Cost {
            wall_seconds: w,
            cpu_seconds: cpu,
            peak_rss_mb: m,
        };
        let rows = vec![
            PeerRow {
                scene: "a".into(),
                pixels: 1200,
                ours: c(0.5, 0.875, 20.5),
                peer: c(2.0, 1.75, 41.0),
            },
            PeerRow {
                scene: "b".into(),
                pixels: 7,
                ours: c(1.0, 2.0, 10.0),
                peer: c(8.0, 2.0, 5.0),
            },
        ];
        let back = from_csv(&to_csv(&rows)).unwrap();
        assert_eq!(back, rows);
        assert_eq!(back[0].wall_speedup(), 4.0);
        assert_eq!(back[0].cpu_speedup(), 2.0);
        assert_eq!(back[0].rss_ratio(), 0.5);
        // Geometric mean of 4 and 8 is sqrt(32).
        let g = geomean(back.iter().map(PeerRow::wall_speedup));
        assert!((g - 32f64.sqrt()).abs() < 1e-12);
        let md = markdown(&back, "h");
        assert!(md.contains("| a | 1200 | 0.50 | 2.00 | 4.00× |"));
        assert!(md.contains(&format!("**{:.2}×**", 32f64.sqrt())));
        assert!(from_csv("scene\n").is_err());
        assert!(from_csv(&format!("{HEADER}\na,1,2\n")).is_err());
    }

    #[test]
    fn every_scene_of_the_set_exists_and_has_a_format() {
        let rib_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../rib");
        for s in &SCENES {
            let text = std::fs::read_to_string(rib_dir.join(s.file)).unwrap();
            for (from, _) in s.edits {
                assert!(
                    text.contains(from),
                    "{}: edit {from} matches nothing",
                    s.name
                );
            }
            let (_, px) = variant(&text, s.edits, 2).unwrap();
            assert!(px > 0);
        }
    }
}
