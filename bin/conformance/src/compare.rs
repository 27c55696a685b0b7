//! Comparing an output image with its reference.
//!
//! The metric: mean absolute error over the R, G and B channels of every pixel, both images
//! read as values in 0..1 (alpha is left out: the references are a mix of RGB and RGBA files,
//! and both renderers store premultiplied colour over black, so coverage shows in RGB too), and
//! the share of pixels whose three channels are all within 8/255 of the reference. MAE judges
//! the verdict; the share tells a few wildly wrong pixels (speckle, a missing thin curve) from a
//! global shift (a different specular exponent, a darker light).
use image::{Rgb32FImage, RgbImage};
use std::path::Path;

/// The tolerance of "within": 8 steps of an 8-bit channel.
pub const WITHIN: f32 = 8.0 / 255.0;

/// The comparison of two images of the same size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metrics {
    /// Mean absolute error over RGB, 0..1.
    pub mae: f64,
    /// Share of pixels with every channel within [`WITHIN`], 0..1.
    pub within: f64,
}

/// Reads an image as linear-as-stored RGB floats in 0..1.
pub fn load_rgb(path: &Path) -> Result<Rgb32FImage, String> {
    image::open(path)
        .map(|i| i.to_rgb32f())
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// MAE and within-share of `ours` against `reference`; an error when their sizes differ.
pub fn compare(ours: &Rgb32FImage, reference: &Rgb32FImage) -> Result<Metrics, String> {
    if ours.dimensions() != reference.dimensions() {
        return Err(format!(
            "size {}x{} differs from the reference's {}x{}",
            ours.width(),
            ours.height(),
            reference.width(),
            reference.height()
        ));
    }
    let (mut sum, mut within, mut pixels) = (0.0f64, 0usize, 0usize);
    for (a, b) in ours.pixels().zip(reference.pixels()) {
        let d = [0, 1, 2].map(|c| (a[c].clamp(0.0, 1.0) - b[c].clamp(0.0, 1.0)).abs());
        sum += d.iter().map(|&x| x as f64).sum::<f64>();
        // A hair of slack so an exact 8-step difference of 8-bit data counts as within.
        within += usize::from(d.iter().all(|&x| x <= WITHIN + 1e-6));
        pixels += 1;
    }
    if pixels == 0 {
        return Err("empty image".to_string());
    }
    Ok(Metrics {
        mae: sum / (3 * pixels) as f64,
        within: within as f64 / pixels as f64,
    })
}

/// |ours − reference| per channel, amplified by `gain` and clamped, as an 8-bit image (for the
/// contact sheet; the amplification makes a 0.02 error visible).
pub fn difference(ours: &Rgb32FImage, reference: &Rgb32FImage, gain: f32) -> RgbImage {
    RgbImage::from_fn(reference.width(), reference.height(), |x, y| {
        let a = ours
            .get_pixel_checked(x, y)
            .copied()
            .unwrap_or(image::Rgb([0.0; 3]));
        let b = reference.get_pixel(x, y);
        image::Rgb([0, 1, 2].map(|c| {
            let d = (a[c].clamp(0.0, 1.0) - b[c].clamp(0.0, 1.0)).abs() * gain;
            (d.min(1.0) * 255.0).round() as u8
        }))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mae_and_within_share_of_known_images() {
        // 4 pixels: identical, one channel 0.5 off, all channels 8/255 off, 9/255 off in one.
        let reference = Rgb32FImage::from_raw(2, 2, vec![0.25; 12]).unwrap();
        let mut v = vec![0.25f32; 12];
        v[3] = 0.75;
        for x in &mut v[6..9] {
            *x += 8.0 / 255.0;
        }
        v[9] += 9.0 / 255.0;
        let ours = Rgb32FImage::from_raw(2, 2, v).unwrap();
        let m = compare(&ours, &reference).unwrap();
        let expected = (0.5 + 3.0 * 8.0 / 255.0 + 9.0 / 255.0) / 12.0;
        assert!((m.mae - expected).abs() < 1e-6, "{m:?} vs {expected}");
        assert_eq!(m.within, 0.5);
        let small = Rgb32FImage::new(1, 2);
        assert!(compare(&small, &reference).unwrap_err().contains("1x2"));
    }
}
