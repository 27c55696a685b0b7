//! The one noise of the renderer: `noise`, `pnoise`, `cellnoise` (RI 3.2 §15.1), Perlin
//! gradient noise over 1–4 dimensions remapped to `[0,1]` (0.5 at every lattice point), its
//! periodic variant, and a value constant on each integer cell. The SL VM and the built-in
//! shaders (`dented`) both call these functions, so a built-in and its SL listing give the same
//! pattern. Lattice gradients come from [`lowbias32`] hashes of the integer coordinates, so every
//! value is a pure function of the input (the same on every machine and thread count, and two
//! grids sharing a vertex displace it identically). `seed` separates the components of
//! triple-valued noise (0, 1, 2 for x, y, z); float noise uses seed 0.
use crate::hash::lowbias32;

fn hash_cell(cell: &[i32], seed: u32) -> u32 {
    let mut h = lowbias32(seed.wrapping_mul(0x9e37_79b9) ^ 0x1234_5678);
    for &c in cell {
        h = lowbias32(h ^ (c as u32).wrapping_mul(0x2c1b_3c6d));
    }
    h
}

/// What [`gradient`] adds to a corner's hash per axis.
const GRADIENT_AXIS: u32 = 0x68e3_1da4;

/// A gradient component in [-1, 1] from bits of a hash.
#[cfg(test)]
fn gradient(h: u32, axis: usize) -> f32 {
    // wrapping_mul: the fourth axis overflows a checked multiply (debug builds panicked).
    gradient_of_bits(lowbias32(
        h.wrapping_add((axis as u32).wrapping_mul(GRADIENT_AXIS)),
    ))
}

/// [`gradient`] from the hash of the corner's hash and the axis.
#[inline(always)]
fn gradient_of_bits(hashed: u32) -> f32 {
    (hashed >> 8) as f32 / (1u32 << 23) as f32 - 1.0
}

/// Perlin's quintic fade `6t⁵ - 15t⁴ + 10t³` (C² continuous across cells).
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// `x.floor()` for a finite `x` without a call to `floorf` (x86-64's baseline has no rounding
/// instruction): the same bits, `-0.0` included.
#[inline]
fn floor_finite(x: f32) -> f32 {
    if x.abs() < 8_388_608.0 {
        let t = x as i32 as f32;
        if t > x {
            t - 1.0
        } else if t == x {
            x
        } else {
            t
        }
    } else {
        // Every float this large is an integer.
        x
    }
}

/// The signed gradient noise at `x` (1 to 4 coordinates), lattice coordinates wrapped by
/// `period` (`None`: not periodic). Roughly within [-1, 1].
///
/// The corners' hashes share their prefixes (`hash_cell` chains one coordinate at a time), so
/// they are built axis by axis (15 hashes instead of 32 in 3-D) and each axis is faded once;
/// every value is the same bits as hashing and fading per corner (issue 21: the noise was 28%
/// of `dented`'s frame).
fn gradient_noise(x: &[f32], period: Option<&[i32]>, seed: u32) -> f32 {
    // The dimension as a constant, so each variant's loops unroll.
    match x.len() {
        0 => gradient_noise_in::<0>(x, period, seed),
        1 => gradient_noise_in::<1>(x, period, seed),
        2 => gradient_noise_in::<2>(x, period, seed),
        3 => gradient_noise_in::<3>(x, period, seed),
        _ => gradient_noise_in::<4>(x, period, seed),
    }
}

/// [`gradient_noise`] in `D` dimensions (`x` holds at least `D` coordinates).
#[inline(always)]
fn gradient_noise_in<const D: usize>(x: &[f32], period: Option<&[i32]>, seed: u32) -> f32 {
    let d = D;
    if x.iter().any(|v| !v.is_finite()) {
        return 0.0;
    }
    let mut frac = [0f32; 4];
    let mut fades = [0f32; 4];
    let mut hashes = [0u32; 16];
    hashes[0] = lowbias32(seed.wrapping_mul(0x9e37_79b9) ^ 0x1234_5678);
    let mut n = 1;
    for k in 0..d {
        let f = floor_finite(x[k]);
        frac[k] = x[k] - f;
        fades[k] = fade(frac[k]);
        let lattice = |bit: i32| {
            let mut c = (f as i32).wrapping_add(bit);
            if let Some(p) = period {
                c = c.rem_euclid(p[k].max(1));
            }
            (c as u32).wrapping_mul(0x2c1b_3c6d)
        };
        let (c0, c1) = (lattice(0), lattice(1));
        // Corner `i + n` has bit k set; corners below `n` hold the hashes of bits 0..k.
        for i in 0..n {
            hashes[i + n] = lowbias32(hashes[i] ^ c1);
            hashes[i] = lowbias32(hashes[i] ^ c0);
        }
        n *= 2;
    }
    // Every corner's gradient, axis by axis over all corners at once: the 2^D hashes of an
    // axis are independent, so they go through the vector unit (each was a scalar `gradient`
    // call, 24 of the 39 hashes of a 3-D noise), and the values are `gradient`'s.
    let corners = 1usize << D;
    let mut grads = [[0f32; 16]; 4];
    for (k, g) in grads[..d].iter_mut().enumerate() {
        let add = (k as u32).wrapping_mul(GRADIENT_AXIS);
        for (g, &h) in g[..corners].iter_mut().zip(&hashes[..corners]) {
            *g = gradient_of_bits(lowbias32(h.wrapping_add(add)));
        }
    }
    let mut total = 0.0f32;
    // `corner` picks a column of `grads` and the corner's bits, not an element to iterate.
    #[allow(clippy::needless_range_loop)]
    for corner in 0..corners {
        let mut weight = 1.0f32;
        for (k, &w) in fades[..d].iter().enumerate() {
            weight *= if (corner >> k) & 1 == 1 { w } else { 1.0 - w };
        }
        let g: f32 = (0..d)
            .map(|k| grads[k][corner] * (frac[k] - ((corner >> k) & 1) as f32))
            .sum();
        total += weight * g;
    }
    total
}

/// Gain taking the signed noise (which rarely exceeds ±0.6 with these gradients) to about
/// ±1 before the remap to [0,1]; the remap clamps the rare excess.
const NOISE_GAIN: f32 = 1.6;

/// SL `noise(x…)` in [0,1]: 0.5 at integer lattice points.
pub fn noise(x: &[f32], seed: u32) -> f32 {
    (0.5 + 0.5 * NOISE_GAIN * gradient_noise(x, None, seed)).clamp(0.0, 1.0)
}

/// SL `pnoise(x…, period…)`: `noise` with period `period` (rounded to an integer ≥ 1) along
/// each axis.
pub fn pnoise(x: &[f32], period: &[f32], seed: u32) -> f32 {
    let mut p = [1i32; 4];
    for (k, v) in period.iter().take(4).enumerate() {
        p[k] = if v.is_finite() {
            (v.round() as i32).max(1)
        } else {
            1
        };
    }
    (0.5 + 0.5 * NOISE_GAIN * gradient_noise(x, Some(&p[..x.len().min(4)]), seed)).clamp(0.0, 1.0)
}

/// SL `cellnoise(x…)`: one value in [0,1) per integer cell (`floor` of each coordinate).
pub fn cellnoise(x: &[f32], seed: u32) -> f32 {
    let mut cell = [0i32; 4];
    let d = x.len().min(4);
    for k in 0..d {
        cell[k] = if x[k].is_finite() {
            x[k].floor() as i32
        } else {
            0
        };
    }
    (hash_cell(&cell[..d], seed ^ 0xce11) >> 8) as f32 / (1u32 << 24) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The per-corner gradient noise `gradient_noise` replaced (hash and fade per corner).
    fn gradient_noise_per_corner(x: &[f32], period: Option<&[i32]>, seed: u32) -> f32 {
        let d = x.len().min(4);
        if x.iter().any(|v| !v.is_finite()) {
            return 0.0;
        }
        let mut base = [0i32; 4];
        let mut frac = [0f32; 4];
        for k in 0..d {
            let f = x[k].floor();
            base[k] = f as i32;
            frac[k] = x[k] - f;
        }
        let mut total = 0.0f32;
        for corner in 0..(1usize << d) {
            let mut cell = [0i32; 4];
            let mut weight = 1.0f32;
            for k in 0..d {
                let bit = (corner >> k) & 1;
                let mut c = base[k].wrapping_add(bit as i32);
                if let Some(p) = period {
                    let pk = p[k].max(1);
                    c = c.rem_euclid(pk);
                }
                cell[k] = c;
                let w = fade(frac[k]);
                weight *= if bit == 1 { w } else { 1.0 - w };
            }
            let h = hash_cell(&cell[..d], seed);
            let g: f32 = (0..d)
                .map(|k| gradient(h, k) * (frac[k] - ((corner >> k) & 1) as f32))
                .sum();
            total += weight * g;
        }
        total
    }

    #[test]
    fn gradient_noise_is_the_per_corner_noise_bit_for_bit() {
        let mut h = 0x9e37_79b9u32;
        let mut next = || {
            h ^= h << 13;
            h ^= h >> 17;
            h ^= h << 5;
            h
        };
        let special = [
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1e-30,
            8_388_607.5,
            -8_388_609.0,
            3e9,
            -3e9,
            1e30,
        ];
        for i in 0..200_000 {
            let d = 1 + i % 4;
            let mut x = [0f32; 4];
            for v in x.iter_mut() {
                let r = next();
                *v = match r % 4 {
                    0 => special[(r >> 8) as usize % special.len()],
                    1 => f32::from_bits(r),
                    _ => (r as i32) as f32 / 65536.0 / (1 + (r >> 28)) as f32,
                };
            }
            let p = [1 + (next() % 7) as i32, (next() % 5) as i32, 3, -2];
            let seed = next() % 3;
            for period in [None, Some(&p[..d])] {
                let (a, b) = (
                    gradient_noise(&x[..d], period, seed),
                    gradient_noise_per_corner(&x[..d], period, seed),
                );
                assert_eq!(a.to_bits(), b.to_bits(), "{:?} {period:?} {seed}", &x[..d]);
            }
        }
    }

    #[test]
    fn noise_is_one_half_on_the_lattice() {
        // Gradient noise is zero at every lattice point: all offsets to the own corner are 0
        // and the other corners' weights vanish.
        for x in [[0.0f32, 0.0, 0.0], [3.0, -2.0, 7.0], [-5.0, 1.0, 0.0]] {
            assert!((noise(&x, 0) - 0.5).abs() < 1e-6);
        }
        assert!((noise(&[4.0], 0) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn noise_stays_in_range_and_varies() {
        let mut lo = 1.0f32;
        let mut hi = 0.0f32;
        for i in 0..2000 {
            let x = [i as f32 * 0.137, i as f32 * 0.071 + 0.3, i as f32 * 0.029];
            let v = noise(&x, 0);
            assert!((0.0..=1.0).contains(&v));
            lo = lo.min(v);
            hi = hi.max(v);
        }
        assert!(
            lo < 0.3 && hi > 0.7,
            "range [{lo}, {hi}] too narrow for Perlin noise"
        );
    }

    #[test]
    fn noise_is_continuous() {
        // A C¹ function: a step of 1e-3 moves it by at most |∇|·1e-3 (|∇| ≲ 4 here).
        for i in 0..500 {
            let x = i as f32 * 0.0371 + 0.01;
            let (a, b) = (noise(&[x, 0.5], 1), noise(&[x + 1e-3, 0.5], 1));
            assert!((a - b).abs() < 5e-3, "jump at {x}: {a} vs {b}");
        }
    }

    #[test]
    fn pnoise_repeats_with_its_period() {
        for i in 0..200 {
            let x = [i as f32 * 0.173, i as f32 * 0.311];
            let a = pnoise(&x, &[4.0, 3.0], 0);
            let b = pnoise(&[x[0] + 4.0, x[1] - 3.0], &[4.0, 3.0], 0);
            assert!((a - b).abs() < 2e-5, "{a} vs {b}");
        }
    }

    #[test]
    fn cellnoise_is_constant_per_cell() {
        let a = cellnoise(&[2.1, 5.9], 0);
        let b = cellnoise(&[2.9, 5.0], 0);
        let c = cellnoise(&[3.0, 5.0], 0);
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert!((0.0..1.0).contains(&a));
    }
}
