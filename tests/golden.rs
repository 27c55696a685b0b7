//! Whole-image references (`tests/golden/`, ../shared/DESIGN.md "tests/"): each scene listed in
//! `tests/golden/golden.toml` is rendered and compared with its accepted 16-bit PNG by the
//! metric stated there: per channel (R, G, B, A), the maximum and the mean absolute difference
//! over all pixels, with the render clamped to [0, 1] as the PNG stores it. Each entry also
//! carries the proof that its thresholds can fail: `catch_max` and `catch_mean` edit the scene
//! (a find/replace in the RIB) and their renders must exceed the max and the mean threshold
//! respectively; `tolerate` is an edit of the kind the thresholds exist to allow, whose render
//! must pass. `tests/golden/update.sh` re-makes the PNGs after a deliberate change.
mod support;

use illume_render::{render, RenderSettings};
use std::path::{Path, PathBuf};
use toml_edit::{DocumentMut, Item, Table};

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// One entry of golden.toml.
struct Golden {
    name: String,
    scene: String,
    image: String,
    max: f64,
    mean: f64,
    catch_max: Edit,
    catch_mean: Edit,
    tolerate: Edit,
}

/// A find/replace on the scene's RIB text, and what it means.
struct Edit {
    find: String,
    replace: String,
    why: String,
}

fn text(t: &Table, key: &str, entry: &str) -> String {
    t.get(key)
        .and_then(Item::as_str)
        .unwrap_or_else(|| panic!("golden.toml [{entry}]: `{key}` must be a string"))
        .to_string()
}

fn number(t: &Table, key: &str, entry: &str) -> f64 {
    let v = t.get(key).and_then(Item::as_value);
    v.and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64)))
        .unwrap_or_else(|| panic!("golden.toml [{entry}]: `{key}` must be a number"))
}

fn edit(t: &Table, key: &str, entry: &str) -> Edit {
    let e = t
        .get(key)
        .and_then(|i| i.as_inline_table())
        .unwrap_or_else(|| {
            panic!("golden.toml [{entry}]: `{key}` must be {{ find, replace, why }}")
        });
    let field = |f: &str| {
        e.get(f)
            .and_then(|v| v.as_str())
            .unwrap_or_else(|| panic!("golden.toml [{entry}].{key}: `{f}` must be a string"))
            .to_string()
    };
    Edit {
        find: field("find"),
        replace: field("replace"),
        why: field("why"),
    }
}

fn goldens() -> Vec<Golden> {
    let toml = std::fs::read_to_string(golden_dir().join("golden.toml")).unwrap();
    let doc: DocumentMut = toml.parse().unwrap_or_else(|e| panic!("golden.toml: {e}"));
    doc.iter()
        .map(|(name, item)| {
            let t = item
                .as_table()
                .unwrap_or_else(|| panic!("golden.toml: `{name}` must be a table"));
            Golden {
                name: name.to_string(),
                scene: text(t, "scene", name),
                image: text(t, "image", name),
                max: number(t, "max", name),
                mean: number(t, "mean", name),
                catch_max: edit(t, "catch_max", name),
                catch_mean: edit(t, "catch_mean", name),
                tolerate: edit(t, "tolerate", name),
            }
        })
        .collect()
}

/// Per channel (R, G, B, A): (max, mean) of |render − reference|.
type Metric = [(f64, f64); 4];

fn render_rib(rib: &str) -> illume_render::Rendered {
    let frames = support::frames(rib, None);
    assert_eq!(frames.len(), 1, "a golden scene is one frame");
    render(&frames[0], &RenderSettings::default())
}

fn compare(r: &illume_render::Rendered, reference: &illume_imageio::Image, what: &str) -> Metric {
    assert_eq!(
        (r.width, r.height, reference.channels.len()),
        (reference.width, reference.height, 4),
        "{what}: size or channels differ from the reference"
    );
    let mut m = [(0.0f64, 0.0f64); 4];
    for (p, q) in r.rgba.chunks_exact(4).zip(reference.data.chunks_exact(4)) {
        for c in 0..4 {
            let d = (f64::from(p[c].clamp(0.0, 1.0)) - f64::from(q[c])).abs();
            m[c].0 = m[c].0.max(d);
            m[c].1 += d;
        }
    }
    let n = (r.width * r.height) as f64;
    m.map(|(max, sum)| (max, sum / n))
}

fn edited(rib: &str, e: &Edit, what: &str) -> String {
    assert_eq!(
        rib.matches(&e.find).count(),
        1,
        "{what}: `{}` must occur exactly once in the scene",
        e.find
    );
    rib.replace(&e.find, &e.replace)
}

/// `R (max, mean) G (…) …` in short exponent form, for messages.
fn show(m: &Metric) -> String {
    let names = ["R", "G", "B", "A"];
    let parts: Vec<String> = names
        .iter()
        .zip(m)
        .map(|(n, (x, y))| format!("{n} ({x:.2e}, {y:.2e})"))
        .collect();
    parts.join(" ")
}

fn worst(m: &Metric) -> (f64, f64) {
    m.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (f64::max(a, x), f64::max(b, y))
    })
}

#[test]
fn every_golden_scene_renders_within_its_thresholds() {
    let dir = golden_dir();
    let goldens = goldens();
    assert!(goldens.len() >= 4, "golden.toml lists {}", goldens.len());
    let mut failures = Vec::new();
    for g in &goldens {
        let rib = std::fs::read_to_string(dir.join(&g.scene)).unwrap();
        // update.sh runs `render` on the scene: its display must be the reference file.
        assert!(
            rib.contains(&format!("Display \"{}\" \"png\"", g.image)),
            "{}: {} must display to {}",
            g.name,
            g.scene,
            g.image
        );
        let reference = illume_imageio::read_image(&dir.join(&g.image))
            .unwrap_or_else(|e| panic!("{}: {e} (make it with tests/golden/update.sh)", g.name));
        let within = |m: &Metric| m.iter().all(|&(x, y)| x <= g.max && y <= g.mean);

        let m = compare(&render_rib(&rib), &reference, &g.name);
        eprintln!("{}: per-channel (max, mean) {}", g.name, show(&m));
        if !within(&m) {
            failures.push(format!(
                "{}: per-channel (max, mean) {} exceeds max {} / mean {}",
                g.name,
                show(&m),
                g.max,
                g.mean
            ));
        }

        let t = compare(
            &render_rib(&edited(&rib, &g.tolerate, &g.name)),
            &reference,
            &g.name,
        );
        eprintln!("{} tolerate ({}): {}", g.name, g.tolerate.why, show(&t));
        if !within(&t) {
            failures.push(format!(
                "{}: the tolerated edit ({}) gives {}, over the thresholds: too tight",
                g.name,
                g.tolerate.why,
                show(&t)
            ));
        }

        let a = compare(
            &render_rib(&edited(&rib, &g.catch_max, &g.name)),
            &reference,
            &g.name,
        );
        eprintln!("{} catch_max ({}): {}", g.name, g.catch_max.why, show(&a));
        if worst(&a).0 <= g.max {
            failures.push(format!(
                "{}: `max` {} misses {} (worst max {:.3e})",
                g.name,
                g.max,
                g.catch_max.why,
                worst(&a).0
            ));
        }

        // The mean threshold must catch its edit on its own: the max threshold passes it.
        let b = compare(
            &render_rib(&edited(&rib, &g.catch_mean, &g.name)),
            &reference,
            &g.name,
        );
        eprintln!("{} catch_mean ({}): {}", g.name, g.catch_mean.why, show(&b));
        if worst(&b).1 <= g.mean || worst(&b).0 > g.max {
            failures.push(format!(
                "{}: `mean` {} must catch {} while `max` {} passes it: {}",
                g.name,
                g.mean,
                g.catch_mean.why,
                g.max,
                show(&b)
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_scene_and_image_in_the_folder_is_listed() {
    let goldens = goldens();
    let mut listed: Vec<String> = goldens
        .iter()
        .flat_map(|g| [g.scene.clone(), g.image.clone()])
        .collect();
    listed.sort();
    let mut found: Vec<String> = std::fs::read_dir(golden_dir())
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".rib") || n.ends_with(".png"))
        .collect();
    found.sort();
    assert_eq!(listed, found, "golden.toml and tests/golden/ disagree");
    for g in &goldens {
        let bytes = std::fs::metadata(golden_dir().join(&g.image))
            .unwrap()
            .len();
        assert!(
            bytes < 100_000,
            "{}: {bytes} bytes; keep references small",
            g.image
        );
    }
}
