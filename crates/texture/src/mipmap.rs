//! In-memory mip-map levels and the separable resampler that builds them.
//!
//! Levels follow OpenEXR's round-down rule (`max(1, n >> l)`), so a `.tx` written from these
//! levels is read by any OpenEXR tiled reader. Each level is filtered from the one above with the
//! named filter in linear (float) space; the filter width is in destination pixels, so `box` of
//! width 1 is the exact 2×2 average.

use crate::filter::FilterKind;
use crate::wrapmode::WrapMode;
use rayon::prelude::*;

/// One resolution level: `width·height·channels` floats, interleaved, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub width: usize,
    pub height: usize,
    pub channels: usize,
    pub data: Vec<f32>,
}

impl Level {
    pub fn new(width: usize, height: usize, channels: usize) -> Level {
        Level {
            width,
            height,
            channels,
            data: vec![0.0; width * height * channels],
        }
    }

    #[inline]
    pub fn texel(&self, x: usize, y: usize) -> &[f32] {
        let i = (y * self.width + x) * self.channels;
        &self.data[i..i + self.channels]
    }
}

/// Size of level `l` of an axis of `full` texels, OpenEXR round-down.
pub fn level_size(full: usize, level: usize) -> usize {
    (full >> level).max(1)
}

/// Number of round-down mip levels for a `w×h` image: `floor(log2(max(w,h))) + 1`.
pub fn level_count(w: usize, h: usize) -> usize {
    let m = w.max(h).max(1);
    (usize::BITS - m.leading_zeros()) as usize
}

/// A decimation (or magnification) filter with its widths per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resampler {
    pub filter: FilterKind,
    pub swidth: f32,
    pub twidth: f32,
    pub wrap: [WrapMode; 2],
}

/// Weights of one axis: for each destination index, the first source index and its weights.
struct AxisWeights {
    taps: Vec<(i64, Vec<f32>)>,
}

fn axis_weights(src: usize, dst: usize, filter: FilterKind, width: f32) -> AxisWeights {
    let scale = (src as f64 / dst as f64).max(1.0);
    let ratio = src as f64 / dst as f64;
    let radius = 0.5 * width as f64 * scale;
    let taps = (0..dst)
        .map(|x| {
            let centre = (x as f64 + 0.5) * ratio;
            let lo = (centre - radius - 0.5).ceil() as i64;
            let hi = (centre + radius - 0.5).floor() as i64;
            let mut w: Vec<f32> = (lo..=hi)
                .map(|i| filter.eval(((i as f64 + 0.5 - centre) / scale) as f32, width))
                .collect();
            let mut sum: f32 = w.iter().sum();
            if w.is_empty() || sum.abs() < 1e-8 {
                // Filter narrower than the source spacing: nearest sample.
                let i = (centre - 0.5).round() as i64;
                return (i, vec![1.0]);
            }
            if sum == 0.0 {
                sum = 1.0;
            }
            for v in &mut w {
                *v /= sum;
            }
            (lo, w)
        })
        .collect();
    AxisWeights { taps }
}

/// Resamples `src` to `w×h` with a separable filter (horizontal pass, then vertical).
pub fn resample(src: &Level, w: usize, h: usize, r: &Resampler) -> Level {
    let c = src.channels;
    let xs = axis_weights(src.width, w, r.filter, r.swidth);
    let ys = axis_weights(src.height, h, r.filter, r.twidth);
    // Horizontal: src.height rows of w texels.
    let mut mid = vec![0.0f32; w * src.height * c];
    mid.par_chunks_mut(w * c).enumerate().for_each(|(y, row)| {
        let srow = &src.data[y * src.width * c..(y + 1) * src.width * c];
        for (x, (lo, wts)) in xs.taps.iter().enumerate() {
            let out = &mut row[x * c..(x + 1) * c];
            for (k, wt) in wts.iter().enumerate() {
                if let Some(i) = r.wrap[0].texel(lo + k as i64, src.width) {
                    for ch in 0..c {
                        out[ch] += wt * srow[i * c + ch];
                    }
                }
            }
        }
    });
    let mut out = Level::new(w, h, c);
    out.data
        .par_chunks_mut(w * c)
        .enumerate()
        .for_each(|(y, row)| {
            let (lo, wts) = &ys.taps[y];
            for (k, wt) in wts.iter().enumerate() {
                if let Some(j) = r.wrap[1].texel(lo + k as i64, src.height) {
                    let mrow = &mid[j * w * c..(j + 1) * w * c];
                    for (o, m) in row.iter_mut().zip(mrow) {
                        *o += wt * m;
                    }
                }
            }
        });
    out
}

/// Builds the whole round-down pyramid, level 0 first; each level is filtered from the previous.
pub fn build_pyramid(level0: Level, r: &Resampler) -> Vec<Level> {
    let n = level_count(level0.width, level0.height);
    let (w0, h0) = (level0.width, level0.height);
    let mut levels = vec![level0];
    for l in 1..n {
        let next = resample(&levels[l - 1], level_size(w0, l), level_size(h0, l), r);
        levels.push(next);
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;

    fn box_resampler() -> Resampler {
        Resampler {
            filter: FilterKind::Box,
            swidth: 1.0,
            twidth: 1.0,
            wrap: [WrapMode::Clamp; 2],
        }
    }

    #[test]
    fn level_counts_follow_openexr_round_down() {
        assert_eq!(level_count(1, 1), 1);
        assert_eq!(level_count(64, 64), 7);
        assert_eq!(level_count(100, 37), 7);
        assert_eq!(level_size(100, 3), 12);
        assert_eq!(level_size(37, 6), 1);
    }

    #[test]
    fn box_pyramid_preserves_the_mean_of_a_power_of_two_image() {
        let mut l = Level::new(16, 8, 1);
        for (i, v) in l.data.iter_mut().enumerate() {
            *v = ((i * 37) % 11) as f32;
        }
        let mean: f64 = l.data.iter().map(|&v| v as f64).sum::<f64>() / l.data.len() as f64;
        let p = build_pyramid(l, &box_resampler());
        assert_eq!(p.len(), 5);
        let last = p.last().unwrap();
        assert_eq!((last.width, last.height), (1, 1));
        assert!((last.data[0] as f64 - mean).abs() < 1e-4);
        // Level 1 texel (0,0) is the exact 2×2 average.
        let l0 = &p[0];
        let avg =
            (l0.texel(0, 0)[0] + l0.texel(1, 0)[0] + l0.texel(0, 1)[0] + l0.texel(1, 1)[0]) / 4.0;
        assert!((p[1].texel(0, 0)[0] - avg).abs() < 1e-5);
    }

    #[test]
    fn every_filter_keeps_a_constant_image_constant() {
        for f in [
            FilterKind::Box,
            FilterKind::Triangle,
            FilterKind::Gaussian,
            FilterKind::CatmullRom,
            FilterKind::Lanczos,
            FilterKind::Mitchell,
            FilterKind::Sinc,
        ] {
            let mut l = Level::new(13, 7, 2);
            l.data.iter_mut().for_each(|v| *v = 0.25);
            let r = Resampler {
                filter: f,
                swidth: f.default_width(),
                twidth: f.default_width(),
                wrap: [WrapMode::Periodic, WrapMode::Clamp],
            };
            for lv in build_pyramid(l, &r) {
                assert!(lv.data.iter().all(|v| (v - 0.25).abs() < 1e-5), "{f:?}");
            }
        }
    }
}
