//! Image error metrics: RMSE, largest absolute error and PSNR over the RGB channels of the
//! pixels a mask selects.
//!
//! PSNR uses a peak of 1.0 because every scene the bench renders is lit to stay within [0, 1]
//! (the closed-form scenes by construction, the gallery scenes as their figures are graded);
//! `PSNR = 20·log10(1 / RMSE)`, +∞ for identical images.

/// The three numbers recorded per comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorStats {
    pub rmse: f64,
    pub max_abs: f64,
    pub psnr: f64,
    /// Pixels compared (the mask's count).
    pub pixels: usize,
}

/// Compares two RGB images (`[r, g, b]` per pixel, same order) over the pixels where `mask`
/// is true (`None`: every pixel). Accumulates in f64 so a million pixels of tiny differences
/// do not lose precision. `None` when the sizes differ or no pixel is selected.
pub fn compare(a: &[[f64; 3]], b: &[[f64; 3]], mask: Option<&[bool]>) -> Option<ErrorStats> {
    if a.len() != b.len() || mask.is_some_and(|m| m.len() != a.len()) {
        return None;
    }
    let (mut sum_sq, mut max_abs, mut pixels) = (0.0f64, 0.0f64, 0usize);
    for i in 0..a.len() {
        if mask.is_some_and(|m| !m[i]) {
            continue;
        }
        pixels += 1;
        for c in 0..3 {
            let d = a[i][c] - b[i][c];
            sum_sq += d * d;
            max_abs = max_abs.max(d.abs());
        }
    }
    if pixels == 0 {
        return None;
    }
    let rmse = (sum_sq / (3 * pixels) as f64).sqrt();
    Some(ErrorStats {
        rmse,
        max_abs,
        psnr: psnr(rmse),
        pixels,
    })
}

/// Peak signal-to-noise ratio in dB for a peak of 1.0.
pub fn psnr(rmse: f64) -> f64 {
    if rmse > 0.0 {
        -20.0 * rmse.log10()
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rmse_and_psnr_of_a_uniform_offset() {
        let a = vec![[0.5; 3]; 10];
        let b = vec![[0.6; 3]; 10];
        let e = compare(&a, &b, None).unwrap();
        assert!((e.rmse - 0.1).abs() < 1e-12, "{e:?}");
        assert!((e.max_abs - 0.1).abs() < 1e-12);
        assert!((e.psnr - 20.0).abs() < 1e-9, "{e:?}");
        assert_eq!(e.pixels, 10);
    }

    #[test]
    fn rmse_weights_every_channel_and_mask_excludes_pixels() {
        // One pixel off by 0.3 in red only, three of four pixels compared:
        // RMSE = sqrt(0.09 / 9) = 0.1.
        let a = vec![[0.0; 3]; 4];
        let mut b = a.clone();
        b[1] = [0.3, 0.0, 0.0];
        b[3] = [1.0, 1.0, 1.0];
        let mask = [true, true, true, false];
        let e = compare(&a, &b, Some(&mask)).unwrap();
        assert!((e.rmse - 0.1).abs() < 1e-12, "{e:?}");
        assert!((e.max_abs - 0.3).abs() < 1e-12);
        assert_eq!(e.pixels, 3);
    }

    #[test]
    fn identical_images_have_infinite_psnr() {
        let a = vec![[0.25, 0.5, 0.75]; 3];
        let e = compare(&a, &a, None).unwrap();
        assert_eq!(e.rmse, 0.0);
        assert!(e.psnr.is_infinite());
    }

    #[test]
    fn mismatched_sizes_and_empty_masks_compare_to_nothing() {
        let a = vec![[0.0; 3]; 2];
        assert!(compare(&a, &a[..1], None).is_none());
        assert!(compare(&a, &a, Some(&[false, false])).is_none());
        assert!(compare(&a, &a, Some(&[true])).is_none());
    }
}
