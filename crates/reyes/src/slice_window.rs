//! Which time slices of a pixel a moving micropolygon's stratum can reach: each pixel's `n`
//! samples are stored in time order, the sample at position `f` with its time in slice `f`
//! of the shutter (`time_strata.rs`). A sample is tested once moved back along the
//! stratum's mean velocity `v` (`stratum_bound.rs`), and a pixel column (or row) reaches the
//! micropolygon's still box `[lo, hi]` only at the times when the box, moving at `v`, passes
//! over it: a contiguous run of slices. Over a long stratum (a rigid move along an axis has
//! one for the whole shutter) the pixels the micropolygon passes early or late then skip the
//! other slices' samples instead of moving each back and rejecting it.
use crate::int_floor::floor_f64_to_i32;
use crate::time_strata::time_slack;

/// Along one axis, the slices whose samples in a pixel column (or row) can lie inside
/// `[lo, hi]` once moved back by `v·(t − t0)`.
pub(crate) struct SliceWindow {
    /// `1 / (v · slice length)`; `None` without motion along the axis (every slice).
    k: Option<f64>,
    lo: f64,
    hi: f64,
    /// `(open ∓ slack − t0) / slice length`, the second plus one: the time offsets of the
    /// slices' starts and ends, in slices.
    c0: f64,
    c1: f64,
}

/// A margin (pixels) for the rounding of this bound against the box test's own arithmetic.
const HAIR: f64 = 1e-3;

impl SliceWindow {
    /// The window of still box `[lo, hi]` moved back from `t0` at `v` (pixels per unit time)
    /// along one axis, for `n` samples per pixel over `shutter`.
    pub(crate) fn new(t0: f64, v: f64, [lo, hi]: [f64; 2], shutter: [f64; 2], n: usize) -> Self {
        let [open, close] = shutter;
        let slice = (close - open) / n as f64;
        let slack = time_slack(shutter);
        let k = 1.0 / (v * slice);
        let moving = v != 0.0 && k.is_finite() && lo.is_finite() && hi.is_finite();
        SliceWindow {
            k: moving.then_some(k),
            lo,
            hi,
            c0: (open - slack - t0) / slice,
            c1: (open + slack - t0) / slice + 1.0,
        }
    }

    /// The slices `[a, b)` within `[a0, b0)` whose samples in the pixel column (or row)
    /// starting at raster position `q` can lie in the box once moved back. A sample at `x` in
    /// `[q, q + 1]` moves back into `[lo, hi]` when `v·dt` lies in `[q − hi, q + 1 − lo]`, and
    /// slice `f`'s times give `dt` in `[open − slack − t0, open + slack − t0] + [f, f + 1]`
    /// slices.
    #[inline]
    pub(crate) fn slices(&self, q: i32, a0: i32, b0: i32) -> [i32; 2] {
        let Some(k) = self.k else { return [a0, b0] };
        let q = f64::from(q);
        let e1 = (q + 1.0 - self.lo + HAIR) * k;
        let e2 = (q - self.hi - HAIR) * k;
        let f_hi = e1.max(e2) - self.c0;
        let f_lo = e1.min(e2) - self.c1;
        // The first slice at or after `f_lo` (a ceiling), the last at or before `f_hi`.
        [
            a0.max(floor_f64_to_i32(-f_lo).saturating_neg()),
            b0.min(floor_f64_to_i32(f_hi).saturating_add(1)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sample_that_moves_back_into_the_box_is_in_its_window() {
        // Random velocities (both signs, and none), boxes, stratum starts and shutters; a
        // sample anywhere in its pixel at any time of its slice (its slack included) that
        // lands in the box once moved back must have its slice in the pixel's window, and the
        // windows must skip most slices (else the test would hold for `[a0, b0)` alone).
        let mut unit = crate::test_rng::unit_stream(0x6a09_e667);
        let (mut inside, mut skipped, mut slices) = (0, 0, 0);
        for case in 0..300 {
            let n = [4, 9, 16, 64][case % 4];
            let open = if case % 5 == 0 { 1000.0 } else { 0.0 };
            let shutter = [open, open + 0.25 + unit()];
            let v = match case % 7 {
                0 => 0.0,
                _ => 200.0 * (unit() - 0.5),
            };
            let t0 = shutter[0] + 0.3 * unit() * (shutter[1] - shutter[0]);
            let lo = 50.0 + 10.0 * unit();
            let hi = lo + 4.0 * unit();
            let w = SliceWindow::new(t0, v, [lo, hi], shutter, n);
            let slice = (shutter[1] - shutter[0]) / n as f64;
            let slack = time_slack(shutter);
            for q in 0..120 {
                let [a, b] = w.slices(q, 0, n as i32);
                slices += n;
                skipped += n - (b - a).max(0) as usize;
                for f in 0..n {
                    for _ in 0..8 {
                        let t =
                            shutter[0] + slice * (f as f64 + unit()) + slack * (2.0 * unit() - 1.0);
                        let x = f64::from(q) + unit();
                        let back = x - v * (t - t0);
                        if back >= lo && back <= hi {
                            inside += 1;
                            let f = f as i32;
                            assert!(
                                a <= f && f < b,
                                "case {case}: pixel {q} slice {f} outside [{a}, {b})"
                            );
                        }
                    }
                }
            }
        }
        assert!(
            inside > 5_000 && skipped * 2 > slices,
            "{inside} {skipped} {slices}"
        );
    }
}
