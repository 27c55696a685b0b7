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
    let (jx, jy) = if jitter {
        let seed = hash(
            (px as u32).wrapping_mul(0x9e37_79b9)
                ^ hash((py as u32).wrapping_add(0x632b_e5ab))
                ^ hash((j * samples[0] + i).wrapping_mul(0x85eb_ca6b))
                ^ hash(frame as u32 ^ 0x27d4_eb2f),
        );
        (unit(hash(seed)), unit(hash(seed ^ 0x5bd1_e995)))
    } else {
        (0.5, 0.5)
    };
    (
        px as f32 + (i as f32 + jx) / samples[0] as f32,
        py as f32 + (j as f32 + jy) / samples[1] as f32,
    )
}

/// A permutation of `0..n` hashed from `seed` (Fisher–Yates).
fn shuffled(n: usize, seed: u32) -> Vec<u32> {
    let mut p: Vec<u32> = (0..n as u32).collect();
    for k in (1..n).rev() {
        let r = (hash(seed ^ hash(k as u32)) as u64 * (k as u64 + 1)) >> 32;
        p.swap(k, r as usize);
    }
    p
}

/// Time (in `[open, close]`) and lens position (unit disk) of every sample of pixel
/// `(px, py)`, in the order of [`sample_position`]'s `(i, j)` (index `j·samples[0] + i`),
/// appended to `out`.
///
/// Both are stratified over the pixel's samples: sample `s` takes time stratum `πt(s)` of `n`
/// and lens stratum `πl(s)` of the `samples[0] × samples[1]` lens grid, where `πt` and `πl`
/// are permutations hashed from (pixel, frame) only, each with its own seed, so time and lens
/// are decorrelated from the x/y strata and from each other, and the same for any bucket or
/// thread count.
pub fn sample_time_lens(
    px: i32,
    py: i32,
    samples: [u32; 2],
    frame: i32,
    jitter: bool,
    shutter: [f32; 2],
    out: &mut Vec<(f32, (f32, f32))>,
) {
    let n = (samples[0] * samples[1]) as usize;
    let pixel = hash(
        (px as u32).wrapping_mul(0x2c1b_3c6d)
            ^ hash((py as u32).wrapping_add(0x297a_2d39))
            ^ hash(frame as u32 ^ 0x1b87_3593),
    );
    let time_perm = shuffled(n, pixel ^ 0x7feb_352d);
    let lens_perm = shuffled(n, hash(pixel ^ 0x846c_a68b));
    let [open, close] = shutter;
    for s in 0..n {
        let (jt, ju, jv) = if jitter {
            let h = hash(pixel ^ hash(s as u32 ^ 0x3243_f6a8));
            (
                unit(hash(h)),
                unit(hash(h ^ 0x9e37_79b9)),
                unit(hash(h ^ 0x68e3_1da4)),
            )
        } else {
            (0.5, 0.5, 0.5)
        };
        let t = open + (close - open) * ((time_perm[s] as f32 + jt) / n as f32).min(1.0);
        let l = lens_perm[s];
        let (li, lj) = (l % samples[0], l / samples[0]);
        let lens = crate::lens::concentric_disk(
            (li as f32 + ju) / samples[0] as f32,
            (lj as f32 + jv) / samples[1] as f32,
        );
        out.push((t, lens));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn times_fill_every_stratum_once() {
        let mut out = Vec::new();
        sample_time_lens(5, -2, [4, 3], 7, true, [1.0, 3.0], &mut out);
        let mut strata: Vec<usize> = out
            .iter()
            .map(|&(t, _)| ((t - 1.0) / 2.0 * 12.0).floor() as usize)
            .collect();
        strata.sort();
        assert_eq!(strata, (0..12).collect::<Vec<_>>());
        assert!(out.iter().all(|&(_, (u, v))| u * u + v * v <= 1.0 + 1e-5));
        // The permutation differs between pixels (decorrelated), and repeats for the same one.
        let mut again = Vec::new();
        sample_time_lens(5, -2, [4, 3], 7, true, [1.0, 3.0], &mut again);
        assert_eq!(out, again);
        let mut other = Vec::new();
        sample_time_lens(6, -2, [4, 3], 7, true, [1.0, 3.0], &mut other);
        assert_ne!(out, other);
    }
}
