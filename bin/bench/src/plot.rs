//! `speed_error.png`: one log-log panel per scene (render CPU time on x, RMSE on y), one polyline per
//! knob in sweep order, the Pareto front dashed in black with rings on its points.

use crate::font::{draw_text, text_height, text_width};
use crate::knob::{Knob, ALL_KNOBS};
use crate::sweep::Point;
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform};

const PANEL_W: u32 = 600;
const PANEL_H: u32 = 420;
const COLUMNS: u32 = 2;
/// Height of one legend row and the legend's margin.
const LEGEND_ROW: f32 = 26.0;
const LEGEND_MARGIN: f32 = 20.0;
/// Plot-area margins inside a panel: left (tick labels + axis label), right, top, bottom.
const MARGIN: [f32; 4] = [92.0, 20.0, 40.0, 62.0];

/// A distinct colour per knob (Okabe–Ito first, readable by colour-blind readers), as RGB.
pub fn knob_rgb(k: Knob) -> [u8; 3] {
    let i = ALL_KNOBS.iter().position(|&x| x == k).unwrap_or(0);
    const C: [[u8; 3]; ALL_KNOBS.len()] = [
        [230, 159, 0],
        [86, 180, 233],
        [0, 158, 115],
        [240, 60, 200],
        [213, 94, 0],
        [0, 114, 178],
        [204, 121, 167],
        [170, 170, 0],
        [90, 200, 30],
        [0, 200, 200],
        [255, 40, 40],
        [40, 40, 120],
        [120, 60, 200],
        [128, 128, 128],
        [180, 40, 60],
    ];
    C[i]
}

fn knob_color(k: Knob) -> Color {
    let [r, g, b] = knob_rgb(k);
    Color::from_rgba8(r, g, b, 255)
}

fn paint(color: Color) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(color);
    p.anti_alias = true;
    p
}

/// Decade range [floor(log10 min), ceil(log10 max)] of the positive finite values, at least
/// one decade wide.
pub fn decades(values: impl Iterator<Item = f64>) -> Option<(i32, i32)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return None;
    }
    let a = lo.log10().floor() as i32;
    let b = (hi.log10().ceil() as i32).max(a + 1);
    Some((a, b))
}

/// Maps data to pixels inside one panel's plot area.
struct Axes {
    area: [f32; 4], // x0, y0, x1, y1
    x: (i32, i32),
    y: (i32, i32),
}

impl Axes {
    fn to_px(&self, t: f64, e: f64) -> (f32, f32) {
        let [x0, y0, x1, y1] = self.area;
        let fx = (t.log10() - f64::from(self.x.0)) / f64::from(self.x.1 - self.x.0);
        let fy = (e.log10() - f64::from(self.y.0)) / f64::from(self.y.1 - self.y.0);
        (x0 + fx as f32 * (x1 - x0), y1 - fy as f32 * (y1 - y0))
    }
}

/// Strokes the polyline `pts` (anti-aliased, dashed 7/4 when `dash`); also `scaling_plot`'s.
pub(crate) fn line(pixmap: &mut Pixmap, pts: &[(f32, f32)], color: Color, width: f32, dash: bool) {
    let mut pb = PathBuilder::new();
    for (i, &(x, y)) in pts.iter().enumerate() {
        if i == 0 {
            pb.move_to(x, y);
        } else {
            pb.line_to(x, y);
        }
    }
    let Some(path) = pb.finish() else { return };
    let stroke = Stroke {
        width,
        dash: if dash {
            StrokeDash::new(vec![7.0, 4.0], 0.0)
        } else {
            None
        },
        ..Stroke::default()
    };
    pixmap.stroke_path(&path, &paint(color), &stroke, Transform::identity(), None);
}

fn circle(pixmap: &mut Pixmap, x: f32, y: f32, r: f32, color: Color, filled: bool) {
    let Some(path) = PathBuilder::from_circle(x, y, r) else {
        return;
    };
    if filled {
        pixmap.fill_path(
            &path,
            &paint(color),
            tiny_skia::FillRule::Winding,
            Transform::identity(),
            None,
        );
    } else {
        let stroke = Stroke {
            width: 1.5,
            ..Stroke::default()
        };
        pixmap.stroke_path(&path, &paint(color), &stroke, Transform::identity(), None);
    }
}

fn tick_label(exp: i32) -> String {
    format!("1E{exp}")
}

/// The plottable (time, error) of a swept point.
fn xy(p: &Point) -> Option<(f64, f64)> {
    let (t, e) = (p.time(), p.error());
    (p.knob.is_some() && t > 0.0 && t.is_finite() && e > 0.0 && e.is_finite()).then_some((t, e))
}

fn draw_axes(pixmap: &mut Pixmap, ax: &Axes, title: &str, y_label: &str) {
    let [x0, y0, x1, y1] = ax.area;
    let black = Color::BLACK;
    let grey = Color::from_rgba8(220, 220, 220, 255);
    for d in ax.x.0..=ax.x.1 {
        for m in 1..10 {
            let t = 10f64.powi(d) * f64::from(m);
            if d == ax.x.1 && m > 1 {
                break;
            }
            let (x, _) = ax.to_px(t, 10f64.powi(ax.y.0));
            let (c, len) = if m == 1 { (grey, 8.0) } else { (grey, 4.0) };
            if m == 1 {
                line(pixmap, &[(x, y0), (x, y1)], c, 1.0, false);
                let label = tick_label(d);
                draw_text(
                    pixmap,
                    x - text_width(&label, 2.0) / 2.0,
                    y1 + 8.0,
                    2.0,
                    &label,
                    black,
                    false,
                );
            }
            line(pixmap, &[(x, y1), (x, y1 - len)], black, 1.0, false);
        }
    }
    for d in ax.y.0..=ax.y.1 {
        for m in 1..10 {
            if d == ax.y.1 && m > 1 {
                break;
            }
            let e = 10f64.powi(d) * f64::from(m);
            let (_, y) = ax.to_px(10f64.powi(ax.x.0), e);
            let len = if m == 1 { 8.0 } else { 4.0 };
            if m == 1 {
                line(pixmap, &[(x0, y), (x1, y)], grey, 1.0, false);
                let label = tick_label(d);
                let w = text_width(&label, 2.0);
                draw_text(
                    pixmap,
                    x0 - w - 8.0,
                    y - text_height(2.0) / 2.0,
                    2.0,
                    &label,
                    black,
                    false,
                );
            }
            line(pixmap, &[(x0, y), (x0 + len, y)], black, 1.0, false);
        }
    }
    line(
        pixmap,
        &[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
        black,
        1.5,
        false,
    );
    let xl = "CPU TIME (S)";
    draw_text(
        pixmap,
        (x0 + x1 - text_width(xl, 2.0)) / 2.0,
        y1 + 34.0,
        2.0,
        xl,
        black,
        false,
    );
    let yw = text_width(y_label, 2.0);
    draw_text(
        pixmap,
        x0 - 88.0,
        (y0 + y1 + yw) / 2.0,
        2.0,
        y_label,
        black,
        true,
    );
    draw_text(pixmap, x0, y0 - 26.0, 2.0, title, black, false);
}

/// Draws one scene's panel with its plot area's top-left at (ox, oy).
fn draw_panel(pixmap: &mut Pixmap, ox: f32, oy: f32, scene: &str, points: &[Point]) {
    let swept: Vec<(&Point, (f64, f64))> = points
        .iter()
        .filter_map(|p| xy(p).map(|q| (p, q)))
        .collect();
    let closed = swept.iter().any(|(p, _)| p.against_closed_form());
    let (Some(x), Some(y)) = (
        decades(swept.iter().map(|(_, q)| q.0)),
        decades(swept.iter().map(|(_, q)| q.1)),
    ) else {
        draw_text(
            pixmap,
            ox + 20.0,
            oy + 40.0,
            2.0,
            &format!("{scene}: NO DATA"),
            Color::BLACK,
            false,
        );
        return;
    };
    let ax = Axes {
        area: [
            ox + MARGIN[0],
            oy + MARGIN[2],
            ox + PANEL_W as f32 - MARGIN[1],
            oy + PANEL_H as f32 - MARGIN[3],
        ],
        x,
        y,
    };
    let title = format!(
        "{}: VS {}",
        scene.to_uppercase().replace('_', " "),
        if closed { "CLOSED FORM" } else { "CONVERGED" }
    );
    draw_axes(pixmap, &ax, &title, "RMSE");
    for knob in ALL_KNOBS {
        let pts: Vec<(f32, f32)> = swept
            .iter()
            .filter(|(p, _)| p.knob == Some(knob))
            .map(|(_, (t, e))| ax.to_px(*t, *e))
            .collect();
        line(pixmap, &pts, knob_color(knob), 2.0, false);
        for &(px, py) in &pts {
            circle(pixmap, px, py, 3.5, knob_color(knob), true);
        }
    }
    let mut front: Vec<(f64, f64)> = swept
        .iter()
        .filter(|(p, _)| p.pareto)
        .map(|(_, q)| *q)
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let front: Vec<(f32, f32)> = front.iter().map(|&(t, e)| ax.to_px(t, e)).collect();
    line(pixmap, &front, Color::BLACK, 1.5, true);
    for &(px, py) in &front {
        circle(pixmap, px, py, 7.0, Color::BLACK, false);
    }
}

/// Legend entries (`None`: the Pareto front) placed left to right, wrapping at `width`:
/// (entry, x, row).
fn legend_layout(width: f32, knobs: &[Knob]) -> Vec<(Option<Knob>, f32, u32)> {
    let mut entries: Vec<Option<Knob>> = knobs.iter().map(|k| Some(*k)).collect();
    entries.push(None);
    let (mut x, mut row) = (LEGEND_MARGIN, 0);
    let mut out = Vec::new();
    for knob in entries {
        let w = 34.0 + text_width(legend_name(knob), 2.0) + 24.0;
        if x + w > width && x > LEGEND_MARGIN {
            x = LEGEND_MARGIN;
            row += 1;
        }
        out.push((knob, x, row));
        x += w;
    }
    out
}

fn legend_name(knob: Option<Knob>) -> &'static str {
    knob.map_or("PARETO FRONT", |k| k.name())
}

fn draw_legend(pixmap: &mut Pixmap, y: f32, knobs: &[Knob]) {
    for (knob, x, row) in legend_layout(pixmap.width() as f32, knobs) {
        let name = legend_name(knob);
        let row_y = y + row as f32 * LEGEND_ROW;
        let cy = row_y + 7.0;
        match knob {
            Some(k) => {
                line(
                    pixmap,
                    &[(x, cy), (x + 26.0, cy)],
                    knob_color(k),
                    2.0,
                    false,
                );
                circle(pixmap, x + 13.0, cy, 3.5, knob_color(k), true);
            }
            None => {
                line(pixmap, &[(x, cy), (x + 26.0, cy)], Color::BLACK, 1.5, true);
                circle(pixmap, x + 13.0, cy, 7.0, Color::BLACK, false);
            }
        }
        draw_text(pixmap, x + 34.0, row_y, 2.0, name, Color::BLACK, false);
    }
}

/// The PNG bytes of the plot of `scenes` (name, that scene's points).
pub fn plot_png(scenes: &[(String, Vec<Point>)]) -> Result<Vec<u8>, String> {
    let rows = (scenes.len() as u32).div_ceil(COLUMNS).max(1);
    let used: Vec<Knob> = ALL_KNOBS
        .into_iter()
        .filter(|k| {
            scenes
                .iter()
                .any(|(_, ps)| ps.iter().any(|p| p.knob == Some(*k)))
        })
        .collect();
    let w = PANEL_W * COLUMNS;
    let legend_rows = legend_layout(w as f32, &used).last().map_or(0, |e| e.2) + 1;
    let legend_h = (legend_rows as f32 * LEGEND_ROW + LEGEND_MARGIN) as u32;
    let h = PANEL_H * rows + legend_h;
    let mut pixmap = Pixmap::new(w, h).ok_or("plot: cannot allocate the image")?;
    pixmap.fill(Color::WHITE);
    for (i, (name, points)) in scenes.iter().enumerate() {
        let (col, row) = (i as u32 % COLUMNS, i as u32 / COLUMNS);
        draw_panel(
            &mut pixmap,
            (col * PANEL_W) as f32,
            (row * PANEL_H) as f32,
            name,
            points,
        );
    }
    draw_legend(&mut pixmap, (PANEL_H * rows + 10) as f32, &used);
    pixmap.encode_png().map_err(|e| format!("plot: {e}"))
}
