//! `scaling.png`: one column per axis of `bench --scaling`, CPU seconds in the top row and
//! peak RSS in the bottom row, both log-log against the axis's work (pixels, spheres, samples
//! per pixel, AOVs + 1). The primitive axis draws instanced (dashed) and unique (solid).

use crate::font::{draw_text, text_width};
use crate::plot::{decades, line};
use crate::scaling::{all_series, series, Axis, ScalingRow};
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, Transform};

const PANEL_W: u32 = 420;
const PANEL_H: u32 = 320;
/// Plot-area margins: left, right, top, bottom.
const MARGIN: [f32; 4] = [80.0, 16.0, 36.0, 56.0];

/// One panel: `value` of every series of `axis`, log-log, decade ticks.
fn panel(pixmap: &mut Pixmap, ox: f32, oy: f32, rows: &[ScalingRow], axis: Axis, cpu: bool) {
    let value = |r: &ScalingRow| if cpu { r.cpu_seconds } else { r.peak_rss_mb };
    let of_axis: Vec<&ScalingRow> = rows.iter().filter(|r| r.axis == axis).collect();
    let (Some(xd), Some(yd)) = (
        decades(of_axis.iter().map(|r| axis.work(&r.spec))),
        decades(of_axis.iter().map(|r| value(r))),
    ) else {
        return;
    };
    let (x0, y0) = (ox + MARGIN[0], oy + MARGIN[2]);
    let (x1, y1) = (
        ox + PANEL_W as f32 - MARGIN[1],
        oy + PANEL_H as f32 - MARGIN[3],
    );
    let map = |x: f64, y: f64| {
        let fx = (x.log10() - f64::from(xd.0)) / f64::from(xd.1 - xd.0);
        let fy = (y.log10() - f64::from(yd.0)) / f64::from(yd.1 - yd.0);
        (x0 + fx as f32 * (x1 - x0), y1 - fy as f32 * (y1 - y0))
    };
    let grey = Color::from_rgba8(200, 200, 200, 255);
    for e in xd.0..=xd.1 {
        let (x, _) = map(10f64.powi(e), 10f64.powi(yd.0));
        line(pixmap, &[(x, y0), (x, y1)], grey, 2.5, false);
        let label = format!("1e{e}");
        draw_text(
            pixmap,
            x - text_width(&label, 1.5) / 2.0,
            y1 + 6.0,
            1.5,
            &label,
            Color::BLACK,
            false,
        );
    }
    for e in yd.0..=yd.1 {
        let (_, y) = map(10f64.powi(xd.0), 10f64.powi(e));
        line(pixmap, &[(x0, y), (x1, y)], grey, 2.5, false);
        let label = format!("1e{e}");
        draw_text(
            pixmap,
            x0 - text_width(&label, 1.5) - 6.0,
            y - 5.0,
            1.5,
            &label,
            Color::BLACK,
            false,
        );
    }
    line(
        pixmap,
        &[(x0, y0), (x0, y1), (x1, y1)],
        Color::BLACK,
        2.5,
        false,
    );
    let title = format!(
        "{}: {}",
        axis.name(),
        if cpu { "CPU s" } else { "peak RSS MB" }
    );
    draw_text(pixmap, x0, oy + 10.0, 2.0, &title, Color::BLACK, false);
    let xl = axis.work_label();
    draw_text(
        pixmap,
        (x0 + x1 - text_width(xl, 1.5)) / 2.0,
        y1 + 26.0,
        1.5,
        xl,
        Color::BLACK,
        false,
    );
    let color = if cpu {
        Color::from_rgba8(0, 114, 178, 255)
    } else {
        Color::from_rgba8(213, 94, 0, 255)
    };
    for (a, name) in all_series(rows).into_iter().filter(|(a, _)| *a == axis) {
        let pts: Vec<(f32, f32)> = series(rows, a, name)
            .iter()
            .filter(|r| value(r) > 0.0 && value(r).is_finite())
            .map(|r| map(axis.work(&r.spec), value(r)))
            .collect();
        line(pixmap, &pts, color, 2.5, name == "instanced");
        for &(x, y) in &pts {
            if let Some(c) = PathBuilder::from_circle(x, y, 4.0) {
                let mut paint = Paint::default();
                paint.set_color(color);
                pixmap.fill_path(
                    &c,
                    &paint,
                    tiny_skia::FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
    }
}

/// The PNG bytes of the plot.
pub fn plot_png(rows: &[ScalingRow]) -> Result<Vec<u8>, String> {
    let mut pixmap = Pixmap::new(PANEL_W * Axis::ALL.len() as u32, PANEL_H * 2)
        .ok_or("plot: cannot allocate the image")?;
    pixmap.fill(Color::WHITE);
    for (i, axis) in Axis::ALL.into_iter().enumerate() {
        for (j, cpu) in [true, false].into_iter().enumerate() {
            panel(
                &mut pixmap,
                (i as u32 * PANEL_W) as f32,
                (j as u32 * PANEL_H) as f32,
                rows,
                axis,
                cpu,
            );
        }
    }
    pixmap.encode_png().map_err(|e| format!("plot: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scaling::plan;

    #[test]
    fn the_plot_is_a_png_of_four_columns_and_two_rows() {
        let rows: Vec<ScalingRow> = plan(true, 10_000)
            .into_iter()
            .enumerate()
            .map(|(i, (axis, spec))| ScalingRow {
                axis,
                spec,
                wall_seconds: 1.0 + i as f64,
                cpu_seconds: 0.5 + i as f64,
                peak_rss_mb: 20.0 + i as f64,
            })
            .collect();
        let bytes = plot_png(&rows).unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let reader = decoder.read_info().unwrap();
        assert_eq!(
            (reader.info().width, reader.info().height),
            (4 * PANEL_W, 2 * PANEL_H)
        );
    }
}
