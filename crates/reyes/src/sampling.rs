//! Stratified, jittered sample positions. Each position is a hash of (pixel, sample, frame)
//! only, never of the bucket or thread that computes it, so images are bit-identical for any
//! thread count and any crop window.

use illume_shade::lowbias32 as hash;

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
}
