//! The contact sheet: per job a triptych ours | reference | difference, scaled small, several
//! per row in report order, with a verdict bar under each (green pass, red otherwise).
use crate::compare;
use crate::{JobResult, Verdict};
use image::imageops::{self, FilterType};
use image::{Rgb, RgbImage};
use std::path::Path;

/// Width and height of one thumbnail cell.
const CELL: (u32, u32) = (160, 120);
/// Height of the verdict bar and the gaps.
const BAR: u32 = 4;
const GAP: u32 = 6;
/// Amplification of the difference image.
pub const DIFF_GAIN: f32 = 4.0;

/// The full-size triptych of one job (also written per job for close inspection).
pub fn triptych(r: &JobResult) -> Option<RgbImage> {
    let reference = compare::load_rgb(&r.reference).ok()?;
    let (w, h) = reference.dimensions();
    let ours = r
        .image
        .as_deref()
        .and_then(|p| compare::load_rgb(p).ok())
        .filter(|o| o.dimensions() == (w, h));
    let mut out = RgbImage::from_pixel(3 * w + 2 * GAP, h, Rgb([40, 40, 40]));
    let to8 = |img: &image::Rgb32FImage| image::DynamicImage::ImageRgb32F(img.clone()).to_rgb8();
    match &ours {
        Some(o) => imageops::replace(&mut out, &to8(o), 0, 0),
        // No comparable image: a magenta panel says so.
        None => imageops::replace(
            &mut out,
            &RgbImage::from_pixel(w, h, Rgb([128, 0, 128])),
            0,
            0,
        ),
    }
    imageops::replace(&mut out, &to8(&reference), (w + GAP) as i64, 0);
    if let Some(o) = &ours {
        let diff = compare::difference(o, &reference, DIFF_GAIN);
        imageops::replace(&mut out, &diff, (2 * (w + GAP)) as i64, 0);
    }
    Some(out)
}

/// Writes the sheet of `results` to `path`, `per_row` triptychs across.
pub fn write_sheet(
    results: &[JobResult],
    max_mae: f64,
    per_row: u32,
    path: &Path,
    triptych_dir: Option<&Path>,
) -> Result<(), String> {
    let per_row = per_row.max(1);
    let tile_w = 3 * CELL.0 + 2 * BAR;
    let tile_h = CELL.1 + BAR;
    let rows = (results.len() as u32).div_ceil(per_row).max(1);
    let mut sheet = RgbImage::from_pixel(
        per_row * (tile_w + GAP) + GAP,
        rows * (tile_h + GAP) + GAP,
        Rgb([255, 255, 255]),
    );
    for (k, r) in results.iter().enumerate() {
        let (col, row) = (k as u32 % per_row, k as u32 / per_row);
        let (x0, y0) = (GAP + col * (tile_w + GAP), GAP + row * (tile_h + GAP));
        if let Some(t) = triptych(r) {
            if let Some(dir) = triptych_dir {
                let _ = std::fs::create_dir_all(dir);
                let _ = t.save(dir.join(format!("{}.png", r.job.name)));
            }
            let (w, h) = t.dimensions();
            let third = (w - 2 * GAP) / 3;
            for p in 0..3u32 {
                let panel = imageops::crop_imm(&t, p * (third + GAP), 0, third, h).to_image();
                let small = fit(&panel, CELL);
                let x = x0 + p * (CELL.0 + BAR) + (CELL.0 - small.width()) / 2;
                let y = y0 + (CELL.1 - small.height()) / 2;
                imageops::replace(&mut sheet, &small, x as i64, y as i64);
            }
        }
        let colour = if r.verdict(max_mae) == Verdict::Pass {
            Rgb([0, 170, 0])
        } else {
            Rgb([210, 0, 0])
        };
        let bar = RgbImage::from_pixel(tile_w, BAR, colour);
        imageops::replace(&mut sheet, &bar, x0 as i64, (y0 + CELL.1) as i64);
    }
    sheet
        .save(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// `img` scaled to fit `(w, h)` keeping its aspect ratio.
fn fit(img: &RgbImage, (w, h): (u32, u32)) -> RgbImage {
    let s = (w as f32 / img.width() as f32).min(h as f32 / img.height() as f32);
    let nw = ((img.width() as f32 * s).round() as u32).clamp(1, w);
    let nh = ((img.height() as f32 * s).round() as u32).clamp(1, h);
    imageops::resize(img, nw, nh, FilterType::Triangle)
}
