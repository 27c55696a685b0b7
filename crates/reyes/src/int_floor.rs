//! Integer floors of raster positions without libm: the baseline x86-64 target has no
//! rounding instruction, so `x.floor()` is a call (`floorf`, or a software `floor` for `f64`)
//! on the hiders' hot paths. Each is checked against `x.floor() as i32` on every kind of
//! float (the tests below).

/// `x.floor() as i32` without a call to `floorf` (x86-64's baseline has no rounding
/// instruction): the same result for every `f32`, NaN and infinities included.
#[inline]
pub(crate) fn floor_to_i32(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) > x {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// `x.floor() as i32` without the software `floor` the baseline x86-64 target calls (4.6% of
/// `rib/bench/camera_blur.rib`'s instructions, from `motion::buffer_pixels`): the same value
/// for every `f64`, NaN and infinities included.
#[inline]
pub(crate) fn floor_f64_to_i32(x: f64) -> i32 {
    let t = x as i32;
    if f64::from(t) > x {
        t.saturating_sub(1)
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_to_i32_is_floor_for_every_kind_of_float() {
        let mut xs = vec![
            0.0f32,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            2147483520.0,
            2147483648.0,
            -2147483648.0,
            -2147483904.0,
            16777217.0,
            -16777217.5,
        ];
        // A spread of bit patterns across every exponent, both signs.
        let mut h = 0x9e37_79b9u32;
        for _ in 0..200_000 {
            h ^= h << 13;
            h ^= h >> 17;
            h ^= h << 5;
            xs.push(f32::from_bits(h));
        }
        for x in xs {
            assert_eq!(
                floor_to_i32(x),
                x.floor() as i32,
                "{x:e} ({:#x})",
                x.to_bits()
            );
        }
    }

    #[test]
    fn floor_f64_to_i32_is_floor() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            -1.0,
            2147483647.0,
            2147483647.5,
            2147483648.0,
            -2147483648.0,
            -2147483648.5,
            -2147483649.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
        ];
        let mut h = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            h ^= h << 13;
            h ^= h >> 7;
            h ^= h << 17;
            xs.push(f64::from_bits(h));
            xs.push((h % 1_000_000) as f64 / 64.0 - 7_812.5);
        }
        for x in xs {
            assert_eq!(floor_f64_to_i32(x), x.floor() as i32, "{x:e}");
        }
    }
}
