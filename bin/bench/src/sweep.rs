//! One scene's sweep: the converged reference, then every applicable knob's values, each point
//! rendered, measured and compared.

use crate::closed_form::Reference;
use crate::knob::{Knob, Settings, ALL_KNOBS};
use crate::measure::{run_render, Cost};
use crate::metrics::{compare, ErrorStats};
use crate::pareto::pareto_front;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// One measured render.
#[derive(Clone, Debug)]
pub struct Point {
    pub scene: String,
    /// `None` for the converged reference.
    pub knob: Option<Knob>,
    pub value: f64,
    pub settings: Settings,
    pub cost: Cost,
    pub vs_converged: Option<ErrorStats>,
    pub vs_closed: Option<ErrorStats>,
    /// On the scene's Pareto front of (wall time, [`Point::error`]).
    pub pareto: bool,
}

impl Point {
    /// The error the plot and the Pareto front use: RMSE against the closed form where the
    /// scene has one (the truth), else against the converged render.
    pub fn error(&self) -> f64 {
        self.vs_closed
            .or(self.vs_converged)
            .map_or(f64::NAN, |e| e.rmse)
    }

    /// The time the plot, the Pareto front and the target table use: the render's CPU
    /// seconds (user + system). On this shared 2-core machine other jobs stretch wall time by
    /// up to 10× from one point to the next, while CPU time counts only the render's own
    /// work; wall time is recorded beside it. Wall time when CPU time is unavailable.
    pub fn time(&self) -> f64 {
        if self.cost.cpu_seconds.is_finite() {
            self.cost.cpu_seconds
        } else {
            self.cost.wall_seconds
        }
    }

    /// Whether `error` is measured against the closed form.
    pub fn against_closed_form(&self) -> bool {
        self.vs_closed.is_some()
    }
}

/// How a sweep runs.
pub struct SweepConfig<'a> {
    pub render: &'a Path,
    pub scratch: &'a Path,
    pub quick: bool,
    /// Renders per point; the fastest is kept (noise on a shared machine only adds time).
    pub repeat: usize,
    pub defaults: Settings,
}

fn to_rgb(img: &illume_imageio::Image) -> Result<Vec<[f64; 3]>, String> {
    let idx: Vec<usize> = ["r", "g", "b"]
        .iter()
        .map(|c| {
            img.channel_index(c)
                .ok_or_else(|| format!("output has no channel {c}"))
        })
        .collect::<Result<_, _>>()?;
    let nc = img.channels.len();
    Ok(img
        .data
        .chunks_exact(nc)
        .map(|p| [0, 1, 2].map(|k| f64::from(p[idx[k]])))
        .collect())
}

/// Renders the scene with `s` `repeat` times, keeping the smallest wall and the smallest CPU
/// time seen (load from other jobs only ever adds time), and reads `out.tif` back.
fn render_point(
    scene: &Scene,
    s: &Settings,
    dir: &Path,
    cfg: &SweepConfig,
) -> Result<(Cost, Vec<[f64; 3]>), String> {
    std::fs::write(dir.join("scene.rib"), scene.rib(s)?).map_err(|e| e.to_string())?;
    let mut best: Option<Cost> = None;
    for _ in 0..cfg.repeat.max(1) {
        let _ = std::fs::remove_file(dir.join("out.tif"));
        let c = run_render(cfg.render, dir, "scene.rib", s.threads)?;
        best = Some(match best {
            Some(b) => Cost {
                wall_seconds: b.wall_seconds.min(c.wall_seconds),
                cpu_seconds: b.cpu_seconds.min(c.cpu_seconds),
                ..c
            },
            None => c,
        });
    }
    let img = illume_imageio::read_image(&dir.join("out.tif")).map_err(|e| e.to_string())?;
    Ok((best.unwrap_or_default(), to_rgb(&img)?))
}

fn closed_stats(reference: Option<&Reference>, rgb: &[[f64; 3]]) -> Option<ErrorStats> {
    reference.and_then(|r| compare(rgb, &r.rgb, Some(&r.mask)))
}

/// Runs the scene's sweep. Failed points are reported on stderr and left out; a failed
/// converged render fails the scene.
pub fn sweep_scene(scene: &Scene, cfg: &SweepConfig) -> Result<Vec<Point>, String> {
    let dir: PathBuf = cfg.scratch.join(&scene.name);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    scene.prepare(&dir)?;
    let closed = scene.closed_form();
    let conv_settings = cfg.defaults.converged();
    let (conv_cost, converged) = render_point(scene, &conv_settings, &dir, cfg)?;
    eprintln!(
        "bench: {}: converged reference in {:.2} s",
        scene.name, conv_cost.wall_seconds
    );
    let mut points = vec![Point {
        scene: scene.name.clone(),
        knob: None,
        value: f64::NAN,
        settings: conv_settings,
        cost: conv_cost,
        vs_converged: None,
        vs_closed: closed_stats(closed.as_ref(), &converged),
        pareto: false,
    }];
    // Each distinct setting is rendered once; knobs that share it (the defaults) share the row.
    let mut done: Vec<Point> = Vec::new();
    for knob in ALL_KNOBS.into_iter().filter(|k| k.applies_to(&scene.kind)) {
        for value in knob.values(cfg.quick) {
            let s = cfg.defaults.with(knob, value);
            let measured = match done.iter().find(|p| p.settings == s) {
                Some(p) => Ok((p.cost, p.vs_converged, p.vs_closed)),
                None => render_point(scene, &s, &dir, cfg).map(|(cost, rgb)| {
                    (
                        cost,
                        compare(&rgb, &converged, None),
                        closed_stats(closed.as_ref(), &rgb),
                    )
                }),
            };
            match measured {
                Ok((cost, vs_converged, vs_closed)) => {
                    let p = Point {
                        scene: scene.name.clone(),
                        knob: Some(knob),
                        value,
                        settings: s,
                        cost,
                        vs_converged,
                        vs_closed,
                        pareto: false,
                    };
                    eprintln!(
                        "bench: {}: {:<36} wall {:>7.3} s  CPU {:>6.2} s  RMSE {:.3e}",
                        scene.name,
                        knob.describe(value),
                        cost.wall_seconds,
                        cost.cpu_seconds,
                        p.error()
                    );
                    done.push(p.clone());
                    points.push(p);
                }
                Err(e) => eprintln!("bench: {}: {}: {e}", scene.name, knob.describe(value)),
            }
        }
    }
    mark_pareto(&mut points);
    Ok(points)
}

/// Marks the Pareto front of the swept points' ([`Point::time`], [`Point::error`]). Not candidates: the reference (it is the
/// yardstick of the converged errors) and the time-only knobs ([`Knob::changes_image`]), whose
/// points have the defaults' image and differ only by timing. A setting several knobs share
/// is marked once.
pub fn mark_pareto(points: &mut [Point]) {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .map(|p| match p.knob {
            Some(k) if k.changes_image() => (p.time(), p.error()),
            _ => (f64::NAN, f64::NAN),
        })
        .collect();
    for p in points.iter_mut() {
        p.pareto = false;
    }
    for i in pareto_front(&xy) {
        points[i].pareto = true;
    }
}
