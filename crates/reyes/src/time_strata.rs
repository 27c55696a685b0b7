//! Time strata of a bucket's samples, so a moving micropolygon is tested only against the
//! samples whose time can see it where it is (issue 21 part 2).
//!
//! Each pixel's `n` samples have stratified times: exactly one falls in each of the `n` equal
//! slices of the shutter (`sampling::sample_time_lens`). Stored in time order, the sample at
//! position `f` of its pixel therefore lies in slice `f`, and any `T ≤ n` coarser strata are
//! contiguous runs of those positions: stratum `k` of `T` is positions
//! `⌈k·n/T⌉ .. ⌈(k+1)·n/T⌉`, with times inside the matching part of the shutter. A moving
//! micropolygon is bounded once per stratum (over that part of the shutter only) and each
//! bound visits only its stratum's run in every pixel it covers: a micropolygon sweeping `D`
//! pixels costs about `D + n` tests per pixel row it covers instead of `D·n`.
use crate::sampling::TimeLens;
use std::ops::Range;

/// A sample as a moving micropolygon visits it: raster position, time, lens position (unit
/// disk) and its index in the bucket's sample buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TimedSample {
    pub x: f32,
    pub y: f32,
    pub t: f32,
    pub lens: (f32, f32),
    /// Index of the sample in the buffer (pixel-major, `sample_position` order).
    pub s: u32,
    /// Not about this sample: the time-ordered position in this pixel of the sample whose
    /// lens index (`sampling::lens_strata`) equals this one's position, so a lens cell finds
    /// its sample in every pixel without a search.
    pub by_lens: u32,
}

/// Appends one pixel's samples in time order: the sample of time stratum `f` at position `f`
/// (its times are non-decreasing in `f`, since they are `open + (close − open)·(f + j)/n`
/// rounded monotonically), with the lens index table `by_lens` filled in. `first` is the
/// buffer index of the pixel's first sample.
pub(crate) fn push_time_ordered(
    pos: &[(f32, f32)],
    time_lens: &[TimeLens],
    first: usize,
    out: &mut Vec<TimedSample>,
) {
    let start = out.len();
    let blank = TimedSample {
        x: 0.0,
        y: 0.0,
        t: 0.0,
        lens: (0.0, 0.0),
        s: 0,
        by_lens: 0,
    };
    out.resize(start + time_lens.len(), blank);
    for (i, (tl, p)) in time_lens.iter().zip(pos).enumerate() {
        out[start + tl.stratum as usize] = TimedSample {
            x: p.0,
            y: p.1,
            t: tl.t,
            lens: tl.lens,
            s: (first + i) as u32,
            by_lens: 0,
        };
    }
    for tl in time_lens {
        out[start + tl.lens_index as usize].by_lens = tl.stratum;
    }
}

/// How many time strata a micropolygon whose path spans `sweep` raster pixels beyond its own
/// size is bounded over, with `n` samples per pixel: about one pixel of motion per stratum
/// (a finer bound still covers whole pixels), at most one stratum per sample.
pub(crate) fn stratum_count(sweep: f64, n: usize) -> usize {
    if sweep.is_nan() {
        return 1;
    }
    (sweep.ceil().max(1.0) as usize).clamp(1, n.max(1))
}

/// The time-ordered positions within a pixel of stratum `k` of `strata` (`strata ≤ n`).
#[inline]
pub(crate) fn stratum_samples(k: usize, strata: usize, n: usize) -> Range<usize> {
    (k * n).div_ceil(strata)..((k + 1) * n).div_ceil(strata)
}

/// The `strata + 1` times that cut the shutter `[open, close]` into the strata of `n`
/// samples per pixel: stratum `k`'s samples have times in `[cuts[k], cuts[k+1]]`, give or take
/// [`time_slack`].
pub(crate) fn stratum_cuts(strata: usize, n: usize, [open, close]: [f64; 2]) -> Vec<f64> {
    let dur = close - open;
    (0..=strata)
        .map(|k| open + dur * (k * n).div_ceil(strata) as f64 / n as f64)
        .collect()
}

/// How far an f32 sample time may fall outside its stratum's cuts through rounding (a few
/// ulps of the shutter's magnitude; the sample times are `open + (close − open)·u` in f32).
pub(crate) fn time_slack([open, close]: [f64; 2]) -> f64 {
    4.0 * f64::from(f32::EPSILON) * ((close - open).abs() + open.abs().max(close.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::sample_time_lens;

    /// Every stratum's samples, in every pixel, have times inside the stratum's interval, for
    /// shutters whose f32 rounding differs (a frame far from zero, a short shutter), with and
    /// without jitter, and for stratum counts that do and do not divide `n`.
    #[test]
    fn every_sample_lies_in_its_strata_times() {
        let shutters = [[0.0f32, 1.0], [1.5, 2.5], [100.0, 100.04], [-3.0, 7.0]];
        for spp in [[1u32, 1], [3, 3], [4, 4], [5, 3]] {
            let n = (spp[0] * spp[1]) as usize;
            for shutter in shutters {
                for jitter in [true, false] {
                    for (px, py) in [(0, 0), (17, -4), (-300, 999)] {
                        let mut tl = Vec::new();
                        sample_time_lens(px, py, spp, 3, jitter, shutter, true, &mut tl);
                        let pos = vec![(0.0, 0.0); n];
                        let mut timed = Vec::new();
                        push_time_ordered(&pos, &tl, 0, &mut timed);
                        let mut seen: Vec<u32> = timed.iter().map(|t| t.s).collect();
                        seen.sort();
                        assert_eq!(seen, (0..n as u32).collect::<Vec<_>>());
                        for strata in 1..=n {
                            let mut covered = 0;
                            for k in 0..strata {
                                let r = stratum_samples(k, strata, n);
                                covered += r.len();
                                let sh = shutter.map(f64::from);
                                let cuts = stratum_cuts(strata, n, sh);
                                let slack = time_slack(sh);
                                let (ta, tb) = (cuts[k] - slack, cuts[k + 1] + slack);
                                for ts in &timed[r] {
                                    let t = f64::from(ts.t);
                                    assert!(
                                        t >= ta && t <= tb,
                                        "spp {spp:?} shutter {shutter:?} stratum {k}/{strata}: {t} outside [{ta}, {tb}]"
                                    );
                                }
                            }
                            assert_eq!(covered, n);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn stratum_count_follows_the_sweep_up_to_the_sample_count() {
        assert_eq!(stratum_count(0.0, 16), 1);
        assert_eq!(stratum_count(0.3, 16), 1);
        assert_eq!(stratum_count(2.5, 16), 3);
        assert_eq!(stratum_count(400.0, 16), 16);
        assert_eq!(stratum_count(f64::NAN, 16), 1);
        assert_eq!(stratum_count(f64::INFINITY, 9), 9);
        assert_eq!(stratum_count(5.0, 0), 1);
    }
}
