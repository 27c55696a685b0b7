//! Stratified, jittered sample positions. Each position is a hash of (pixel, sample, frame)
//! only, never of the bucket or thread that computes it, so images are bit-identical for any
//! thread count and any crop window.

use illume_core::hash::lowbias32 as hash;

fn unit(h: u32) -> f32 {
    // 24 high bits → [0, 1).
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Position of sample `(i, j)` of pixel `(px, py)` in raster space, `[px, px+1)×[py, py+1)`.
pub fn sample_position(
    px: i32,
    py: i32,
    i: u32,
    j: u32,
    samples: [u32; 2],
    frame: i32,
    jitter: bool,
) -> (f32, f32) {
    let jit = jitter.then(|| hash(frame as u32 ^ 0x27d4_eb2f));
    let index = hash((j * samples[0] + i).wrapping_mul(0x85eb_ca6b));
    let row = hash((py as u32).wrapping_add(0x632b_e5ab));
    position(px, py, i, j, samples, jit.map(|f| (f, row, index)))
}

/// [`sample_position`] with its hashes of the frame, the pixel row and the sample index given
/// (`None`: no jitter): the parts a bucket's samples share.
#[inline]
fn position(
    px: i32,
    py: i32,
    i: u32,
    j: u32,
    samples: [u32; 2],
    hashes: Option<(u32, u32, u32)>,
) -> (f32, f32) {
    let (jx, jy) = match hashes {
        Some((frame, row, index)) => pixel_jitter(hash(
            (px as u32).wrapping_mul(0x9e37_79b9) ^ row ^ index ^ frame,
        )),
        None => (0.5, 0.5),
    };
    (
        px as f32 + (i as f32 + jx) / samples[0] as f32,
        py as f32 + (j as f32 + jy) / samples[1] as f32,
    )
}

/// A sample's jitter inside its stratum, `[0, 1)²`, from its seed.
#[inline(always)]
fn pixel_jitter(seed: u32) -> (f32, f32) {
    (unit(hash(seed)), unit(hash(seed ^ 0x5bd1_e995)))
}

/// Appends the [`sample_position`]s of every pixel of `[x0, x1) × [y0, y1)`, row by row, each
/// pixel's samples in `(i, j)` order (index `j·samples[0] + i`): the same values, with the
/// hashes of the frame, rows and sample indices made once instead of per sample (they were
/// 5% of `rib/teapot.rib`'s time), and a pixel's samples computed side by side from per-index
/// tables into a slice, so the hashes and divisions go through the vector unit (the loop
/// took 58 instructions per sample, 5% of `rib/sphere.rib`'s at 2×).
pub fn pixel_sample_positions(
    [x0, x1, y0, y1]: [i32; 4],
    samples: [u32; 2],
    frame: i32,
    jitter: bool,
    out: &mut Vec<(f32, f32)>,
) {
    let frame_hash = hash(frame as u32 ^ 0x27d4_eb2f);
    let n = (samples[0] * samples[1]) as usize;
    let (width, height) = ((x1 - x0).max(0) as usize, (y1 - y0).max(0) as usize);
    if n == 0 || width == 0 || height == 0 {
        return;
    }
    let index: Vec<u32> = (0..n as u32)
        .map(|k| hash(k.wrapping_mul(0x85eb_ca6b)) ^ frame_hash)
        .collect();
    // Each sample's stratum `i` and `j` as floats, and the stratum counts.
    let si: Vec<f32> = (0..n as u32).map(|k| (k % samples[0]) as f32).collect();
    let sj: Vec<f32> = (0..n as u32).map(|k| (k / samples[0]) as f32).collect();
    let (nx, ny) = (samples[0] as f32, samples[1] as f32);
    let first = out.len();
    out.resize(first + width * height * n, (0.0, 0.0));
    let mut pixels = out[first..].chunks_exact_mut(n);
    for py in y0..y1 {
        let row = hash((py as u32).wrapping_add(0x632b_e5ab));
        let fy = py as f32;
        for px in x0..x1 {
            let cell = pixels.next().expect("one chunk per pixel");
            let fx = px as f32;
            if !jitter {
                for ((q, &i), &j) in cell.iter_mut().zip(&si).zip(&sj) {
                    *q = (fx + (i + 0.5) / nx, fy + (j + 0.5) / ny);
                }
                continue;
            }
            let pixel = (px as u32).wrapping_mul(0x9e37_79b9) ^ row;
            for (((q, &ix), &i), &j) in cell.iter_mut().zip(&index).zip(&si).zip(&sj) {
                let (jx, jy) = pixel_jitter(hash(pixel ^ ix));
                *q = (fx + (i + jx) / nx, fy + (j + jy) / ny);
            }
        }
    }
}

/// A permutation of `0..n` hashed from `seed` (Fisher–Yates).
fn shuffled(n: usize, seed: u32) -> Vec<u32> {
    let mut p: Vec<u32> = (0..n as u32).collect();
    fisher_yates(n, seed, |a, b| p.swap(a, b));
    p
}

/// The swaps of [`shuffled`]'s Fisher–Yates shuffle of `n` items, handed to `swap`, so a
/// permutation can be made in place inside other records (no allocation per pixel).
fn fisher_yates(n: usize, seed: u32, mut swap: impl FnMut(usize, usize)) {
    for k in (1..n).rev() {
        swap(k, swap_partner(seed, hash(k as u32), k) as usize);
    }
}

/// The item in `0..=k` that step `k` of [`fisher_yates`] swaps item `k` with, from the
/// shuffle's seed and the step's key `hash(k)`.
#[inline(always)]
fn swap_partner(seed: u32, key: u32, k: usize) -> u32 {
    ((u64::from(hash(seed ^ key)) * (k as u64 + 1)) >> 32) as u32
}

/// One sample's time, lens position and time stratum, as [`sample_time_lens`] makes them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeLens {
    /// Time in `[open, close]`.
    pub t: f32,
    /// Lens position on the unit disk.
    pub lens: (f32, f32),
    /// Which of the pixel's `n` equal slices of the shutter `t` lies in (a permutation of
    /// `0..n` over the pixel's samples): its position when the samples are put in time order.
    pub stratum: u32,
    /// Its lens index: the lens position lies in cell [`lens_strata`]`[lens_index]`.
    pub lens_index: u32,
}

/// The lens stratum (cell of the `samples[0] × samples[1]` lens grid, row by row) of lens
/// index `j`, for every pixel of a frame: `lens_strata(..)[j]`. A pixel's sample of time
/// stratum `f` has lens index `(f − r) mod n`, `r` a shift hashed from the pixel.
///
/// One numbering of the lens cells for all pixels lets the hider bound a micropolygon once
/// per lens index for its lens shift: the samples of lens index `j` all look through one lens
/// cell, a `1/n` part of the lens, so each is tested only where the micropolygon can appear
/// through that cell (`motion.rs`). The per-pixel shift keeps every sample's time uniform over
/// the shutter and independent of its lens cell (a fixed pairing of time and lens strata
/// would integrate only `n` of the `n²` time-lens cells, a bias on things both moving and out
/// of focus); time and lens stay stratified per pixel, and each pixel pairs its `(x, y)` strata
/// with them by its own permutation.
pub fn lens_strata(samples: [u32; 2], frame: i32) -> Vec<u32> {
    let n = (samples[0] * samples[1]) as usize;
    shuffled(n, hash(frame as u32 ^ 0x846c_a68b) ^ 0x5851_f42d)
}

/// What every pixel of a frame shares in [`sample_time_lens`], made once per thread and
/// frame, and the scratch rows it fills per pixel.
#[derive(Default)]
struct FrameTables {
    samples: [u32; 2],
    frame: i32,
    /// [`lens_strata`]`(samples, frame)`.
    lens: Vec<u32>,
    /// `hash(k)` per shuffle step `k` (Fisher–Yates' per-step key).
    swap_key: Vec<u32>,
    /// `hash(s ^ 0x3243_f6a8)` per sample `s` (its jitter stream's key).
    sample_key: Vec<u32>,
    /// Per pixel: the shuffle's swap partners, and per sample its jitter hash.
    swaps: Vec<u32>,
    jitter: Vec<u32>,
}

thread_local! {
    /// The last [`FrameTables`] a thread made: every pixel of a frame asks for the same one.
    static FRAME_TABLES: std::cell::RefCell<FrameTables> =
        std::cell::RefCell::new(FrameTables::default());
}

/// [`FrameTables`] of `(samples, frame)`, through the thread's cache.
fn with_tables<R>(samples: [u32; 2], frame: i32, f: impl FnOnce(&mut FrameTables) -> R) -> R {
    FRAME_TABLES.with(|c| {
        let mut c = c.borrow_mut();
        if c.samples != samples || c.frame != frame || c.lens.is_empty() {
            let n = samples[0] * samples[1];
            *c = FrameTables {
                samples,
                frame,
                lens: lens_strata(samples, frame),
                swap_key: (0..n).map(hash).collect(),
                sample_key: (0..n).map(|s| hash(s ^ 0x3243_f6a8)).collect(),
                swaps: Vec::new(),
                jitter: Vec::new(),
            };
        }
        f(&mut c)
    })
}

/// The square `[u0, u1] × [v0, v1]` of the unit square that lens stratum `l` jitters over
/// before the concentric map onto the disk.
pub fn lens_cell(l: u32, samples: [u32; 2]) -> [f32; 4] {
    let (li, lj) = (l % samples[0], l / samples[0]);
    let (sx, sy) = (samples[0] as f32, samples[1] as f32);
    [
        li as f32 / sx,
        (li + 1) as f32 / sx,
        lj as f32 / sy,
        (lj + 1) as f32 / sy,
    ]
}

/// Time (in `[open, close]`), lens position (unit disk) and time stratum of every sample of
/// pixel `(px, py)`, in the order of [`sample_position`]'s `(i, j)` (index
/// `j·samples[0] + i`), appended to `out`.
///
/// Times are stratified over the pixel's samples: sample `s` takes time stratum `πt(s)` of `n`,
/// where `πt` is a permutation hashed from (pixel, frame) only, so time is decorrelated from
/// the x/y strata and the same for any bucket or thread count. The lens position follows the
/// time stratum shifted per pixel: stratum `f` looks through lens cell [`lens_strata`]`[j]`,
/// `j = (f − r) mod n`, jittered inside it, so the lens positions are stratified over the lens
/// grid too. Without a lens (`lens` false) every lens position is the disk's centre, as no
/// one looks at it (the times, strata and lens indices are the same).
#[allow(clippy::too_many_arguments)]
pub fn sample_time_lens(
    px: i32,
    py: i32,
    samples: [u32; 2],
    frame: i32,
    jitter: bool,
    shutter: [f32; 2],
    lens: bool,
    out: &mut Vec<TimeLens>,
) {
    let n = (samples[0] * samples[1]) as usize;
    let pixel = hash(
        (px as u32).wrapping_mul(0x2c1b_3c6d)
            ^ hash((py as u32).wrapping_add(0x297a_2d39))
            ^ hash(frame as u32 ^ 0x1b87_3593),
    );
    // The time permutation is made in place in the records' `stratum` fields (the records
    // differ in nothing else yet, so swapping records swaps strata), then each record is
    // filled in from its own.
    let first = out.len();
    out.extend((0..n as u32).map(|f| TimeLens {
        t: 0.0,
        lens: (0.0, 0.0),
        stratum: f,
        lens_index: 0,
    }));
    let mine = &mut out[first..];
    let shift = ((u64::from(hash(pixel ^ 0x2545_f491)) * n as u64) >> 32) as u32;
    let [open, close] = shutter;
    with_tables(samples, frame, |tables| {
        let FrameTables {
            lens: lens_of,
            swap_key,
            sample_key,
            swaps,
            jitter: jit,
            ..
        } = tables;
        // `fisher_yates`' swaps, their partners first and all at once: each depends on its
        // step and the seed only, so the hashes go side by side through the vector unit, as
        // do the samples' jitter hashes below (this function took 143 instructions per sample
        // on `rib/bench/camera_blur.rib`).
        let seed = pixel ^ 0x7feb_352d;
        swaps.clear();
        swaps.extend(
            swap_key
                .iter()
                .enumerate()
                .map(|(k, &key)| swap_partner(seed, key, k)),
        );
        for k in (1..n).rev() {
            mine.swap(k, swaps[k] as usize);
        }
        jit.clear();
        if jitter {
            jit.extend(sample_key.iter().map(|&key| hash(pixel ^ key)));
        }
        let n32 = n as u32;
        for (s, rec) in mine.iter_mut().enumerate() {
            let f = rec.stratum;
            // `(f − shift) mod n`, both below `n`.
            let j = match f + n32 - shift {
                j if j >= n32 => j - n32,
                j => j,
            };
            if !lens {
                let jt = if jitter { unit(hash(jit[s])) } else { 0.5 };
                *rec = TimeLens {
                    t: open + (close - open) * ((f as f32 + jt) / n as f32).min(1.0),
                    lens: (0.0, 0.0),
                    stratum: f,
                    lens_index: j,
                };
                continue;
            }
            let (jt, ju, jv) = if jitter {
                let h = jit[s];
                (
                    unit(hash(h)),
                    unit(hash(h ^ 0x9e37_79b9)),
                    unit(hash(h ^ 0x68e3_1da4)),
                )
            } else {
                (0.5, 0.5, 0.5)
            };
            let t = open + (close - open) * ((f as f32 + jt) / n as f32).min(1.0);
            let l = lens_of[j as usize];
            let (li, lj) = (l % samples[0], l / samples[0]);
            let lens = crate::lens::concentric_disk(
                (li as f32 + ju) / samples[0] as f32,
                (lj as f32 + jv) / samples[1] as f32,
            );
            *rec = TimeLens {
                t,
                lens,
                stratum: f,
                lens_index: j,
            };
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sample_time_lens` as it was written before its hashes were tabled and vectorized:
    /// one sample at a time, every hash made where it is used.
    #[allow(clippy::too_many_arguments)]
    fn sample_time_lens_one_by_one(
        (px, py): (i32, i32),
        samples: [u32; 2],
        frame: i32,
        jitter: bool,
        [open, close]: [f32; 2],
        lens: bool,
    ) -> Vec<TimeLens> {
        let n = (samples[0] * samples[1]) as usize;
        let pixel = hash(
            (px as u32).wrapping_mul(0x2c1b_3c6d)
                ^ hash((py as u32).wrapping_add(0x297a_2d39))
                ^ hash(frame as u32 ^ 0x1b87_3593),
        );
        let mut strata: Vec<u32> = (0..n as u32).collect();
        fisher_yates(n, pixel ^ 0x7feb_352d, |a, b| strata.swap(a, b));
        let shift = ((u64::from(hash(pixel ^ 0x2545_f491)) * n as u64) >> 32) as u32;
        let lens_of = lens_strata(samples, frame);
        (0..n)
            .map(|s| {
                let f = strata[s];
                let j = (f + n as u32 - shift) % n as u32;
                let h = hash(pixel ^ hash(s as u32 ^ 0x3243_f6a8));
                let jt = if jitter { unit(hash(h)) } else { 0.5 };
                let t = open + (close - open) * ((f as f32 + jt) / n as f32).min(1.0);
                let disk = if lens {
                    let (ju, jv) = if jitter {
                        (unit(hash(h ^ 0x9e37_79b9)), unit(hash(h ^ 0x68e3_1da4)))
                    } else {
                        (0.5, 0.5)
                    };
                    let l = lens_of[j as usize];
                    let (li, lj) = (l % samples[0], l / samples[0]);
                    crate::lens::concentric_disk(
                        (li as f32 + ju) / samples[0] as f32,
                        (lj as f32 + jv) / samples[1] as f32,
                    )
                } else {
                    (0.0, 0.0)
                };
                TimeLens {
                    t,
                    lens: disk,
                    stratum: f,
                    lens_index: j,
                }
            })
            .collect()
    }

    /// The tabled, vectorized samples are the one-by-one ones bit for bit, for sample counts
    /// of one to many, jittered or not, with and without a lens, across frames (each frame
    /// remakes the thread's tables) and pixels of either sign.
    #[test]
    fn sample_time_lens_is_the_one_by_one_computation() {
        let bits = |v: &[TimeLens]| -> Vec<[u32; 5]> {
            v.iter()
                .map(|r| {
                    [
                        r.t.to_bits(),
                        r.lens.0.to_bits(),
                        r.lens.1.to_bits(),
                        r.stratum,
                        r.lens_index,
                    ]
                })
                .collect()
        };
        for samples in [[1, 1], [2, 3], [4, 4], [5, 2], [16, 16]] {
            for frame in [0, 7, -3] {
                for jitter in [true, false] {
                    for lens in [true, false] {
                        for (px, py) in [(0, 0), (5, -2), (-17, 40), (639, 479)] {
                            let mut got = vec![TimeLens {
                                t: 9.0,
                                lens: (9.0, 9.0),
                                stratum: 99,
                                lens_index: 99,
                            }];
                            let shutter = [0.25, 1.5];
                            sample_time_lens(
                                px, py, samples, frame, jitter, shutter, lens, &mut got,
                            );
                            let want = sample_time_lens_one_by_one(
                                (px, py),
                                samples,
                                frame,
                                jitter,
                                shutter,
                                lens,
                            );
                            assert_eq!(got.len(), want.len() + 1, "appends after what is there");
                            assert_eq!(
                                bits(&got[1..]),
                                bits(&want),
                                "{samples:?} frame {frame} jitter {jitter} lens {lens} pixel {px},{py}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn samples_stay_in_their_stratum() {
        for s in 0..16u32 {
            let (i, j) = (s % 4, s / 4);
            let (x, y) = sample_position(-3, 7, i, j, [4, 4], 1, true);
            assert!(x >= -3.0 + i as f32 / 4.0 && x < -3.0 + (i + 1) as f32 / 4.0);
            assert!(y >= 7.0 + j as f32 / 4.0 && y < 7.0 + (j + 1) as f32 / 4.0);
        }
        assert_eq!(sample_position(0, 0, 0, 0, [1, 1], 0, false), (0.5, 0.5));
    }

    /// The bulk positions are the per-sample function's, bit for bit, jittered or not.
    #[test]
    fn pixel_sample_positions_match_sample_position() {
        for jitter in [true, false] {
            let mut out = Vec::new();
            pixel_sample_positions([-3, 2, 5, 7], [3, 2], 4, jitter, &mut out);
            let mut want = Vec::new();
            for py in 5..7 {
                for px in -3..2 {
                    for j in 0..2 {
                        for i in 0..3 {
                            want.push(sample_position(px, py, i, j, [3, 2], 4, jitter));
                        }
                    }
                }
            }
            assert_eq!(out, want);
        }
    }

    #[test]
    fn times_fill_every_stratum_once() {
        let mut out = Vec::new();
        sample_time_lens(5, -2, [4, 3], 7, true, [1.0, 3.0], true, &mut out);
        let mut strata: Vec<usize> = out
            .iter()
            .map(|tl| ((tl.t - 1.0) / 2.0 * 12.0).floor() as usize)
            .collect();
        // Each sample's time lies in the stratum it names.
        for (tl, &k) in out.iter().zip(&strata) {
            assert_eq!(tl.stratum as usize, k);
        }
        strata.sort();
        assert_eq!(strata, (0..12).collect::<Vec<_>>());
        assert!(out
            .iter()
            .all(|tl| tl.lens.0.powi(2) + tl.lens.1.powi(2) <= 1.0 + 1e-5));
        // The permutation differs between pixels (decorrelated), and repeats for the same one.
        let mut again = Vec::new();
        sample_time_lens(5, -2, [4, 3], 7, true, [1.0, 3.0], true, &mut again);
        assert_eq!(out, again);
        let mut other = Vec::new();
        sample_time_lens(6, -2, [4, 3], 7, true, [1.0, 3.0], true, &mut other);
        assert_ne!(out, other);
    }

    /// Lens index `j` of every pixel looks through lens cell `lens_strata[j]`, a pixel's samples
    /// cover every lens cell once, the lens cell does not follow the `(x, y)` stratum (sample 0
    /// sees different cells in different pixels) and the time-lens pairing varies by pixel.
    #[test]
    fn lens_positions_follow_the_time_stratum_and_fill_every_cell() {
        let spp = [4, 3];
        let cells = lens_strata(spp, 7);
        let mut first_cells = std::collections::BTreeSet::new();
        let mut shifts = std::collections::BTreeSet::new();
        for (px, py) in [(0, 0), (5, -2), (-40, 17), (300, 9), (1, 1), (2, 1)] {
            let mut out = Vec::new();
            sample_time_lens(px, py, spp, 7, true, [0.0, 1.0], true, &mut out);
            let mut seen = [false; 12];
            for tl in &out {
                let l = cells[tl.lens_index as usize];
                seen[l as usize] = true;
                let [u0, u1, v0, v1] = lens_cell(l, spp);
                // The lens position is the concentric image of a point of the cell: invert
                // the map by brute force on a fine grid of the cell.
                let mut best = f32::MAX;
                for i in 0..=64 {
                    for j in 0..=64 {
                        let u = u0 + (u1 - u0) * i as f32 / 64.0;
                        let v = v0 + (v1 - v0) * j as f32 / 64.0;
                        let (x, y) = crate::lens::concentric_disk(u, v);
                        best = best.min((x - tl.lens.0).hypot(y - tl.lens.1));
                    }
                }
                assert!(
                    best < 0.03,
                    "pixel ({px}, {py}) stratum {}: {best}",
                    tl.stratum
                );
            }
            assert!(
                seen.iter().all(|&s| s),
                "pixel ({px}, {py}) misses a lens cell"
            );
            first_cells.insert(cells[out[0].lens_index as usize]);
            // One shift per pixel: time stratum minus lens index is the same for every sample.
            let r = |tl: &TimeLens| (tl.stratum + 12 - tl.lens_index) % 12;
            assert!(out.iter().all(|tl| r(tl) == r(&out[0])));
            shifts.insert(r(&out[0]));
        }
        assert!(first_cells.len() > 1);
        assert!(
            shifts.len() > 1,
            "the time-lens shift does not vary between pixels"
        );
    }
}
