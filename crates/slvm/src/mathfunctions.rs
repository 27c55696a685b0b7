//! RI 3.2 §15.1 mathematical functions, one point at a time (the executor maps them over grids).
//! Each is defined for every input: no panic, NaN only where the math has no value.

/// SL `mod(a, b)`: `a - b·floor(a/b)`, the result has the sign of `b` (not Rust's `%`).
pub fn sl_mod(a: f32, b: f32) -> f32 {
    if b == 0.0 {
        return 0.0;
    }
    a - b * (a / b).floor()
}

/// SL `sign(x)`: -1, 0 or 1.
pub fn sign(x: f32) -> f32 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// SL `step(edge, x)`: 0 below the edge, 1 at and above.
pub fn step(edge: f32, x: f32) -> f32 {
    if x < edge {
        0.0
    } else {
        1.0
    }
}

/// SL `round(x)`: to the nearest integer, halves away from zero.
pub fn round(x: f32) -> f32 {
    x.round()
}

/// SL `log(x, base)`.
pub fn log_base(x: f32, base: f32) -> f32 {
    x.ln() / base.ln()
}

/// SL `inversesqrt(x)`.
pub fn inversesqrt(x: f32) -> f32 {
    1.0 / x.sqrt()
}

/// SL `clamp(x, lo, hi)` as the RI spec words it: `lo` if `x < lo`, else `hi` if `x > hi`, else
/// `x` (no panic when `lo > hi`, unlike `f32::clamp`). When `lo > hi` the lower bound wins, as
/// in Aqsis and PRMan: Advanced RenderMan's ray marchers (`smoke.sl`, `cellclouds.sl`) step by
/// `ss = clamp(ss, 0.005, end - d)` and only terminate because the step never drops below
/// 0.005 once `d` reaches `end` (`min(max(..))` would give a zero step and loop forever).
/// A NaN `x` gives `lo`, as before (a NaN never reaches a pixel through `clamp`).
pub fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    if x < lo || x.is_nan() {
        lo
    } else if x > hi {
        hi
    } else {
        x
    }
}

/// SL `filterstep(edge, x)` with the filter width `w` of `x` over the point's footprint
/// (`|Du(x)·du| + |Dv(x)·dv|`): the box-filtered step, the fraction of `[x - w/2, x + w/2]`
/// at or above `edge`; the plain step when `w = 0`.
pub fn filterstep(edge: f32, x: f32, w: f32) -> f32 {
    if w.is_nan() || w <= 0.0 {
        return step(edge, x);
    }
    clamp((x + 0.5 * w - edge) / w, 0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sl_mod_takes_the_sign_of_the_divisor() {
        for (a, b) in [(5.5f32, 2.0f32), (-5.5, 2.0), (5.5, -2.0), (-0.25, 1.0)] {
            let (a64, b64) = (a as f64, b as f64);
            let want = a64 - b64 * (a64 / b64).floor();
            assert!((sl_mod(a, b) as f64 - want).abs() < 1e-6, "{a} mod {b}");
            assert!(sl_mod(a, b) == 0.0 || sign(sl_mod(a, b)) == sign(b));
        }
        assert_eq!(sl_mod(1.0, 0.0), 0.0);
    }

    #[test]
    fn filterstep_is_the_box_filtered_step() {
        // The box [x - w/2, x + w/2] = [0.9, 1.1] straddles the edge 1.05: 0.05/0.2 above it.
        assert!((filterstep(1.05, 1.0, 0.2) - 0.25).abs() < 1e-6);
        assert_eq!(filterstep(1.0, 0.5, 0.0), 0.0);
        assert_eq!(filterstep(1.0, 1.5, 0.1), 1.0);
        assert_eq!(step(1.0, 1.0), 1.0);
    }

    #[test]
    fn log_base_matches_f64() {
        assert!((log_base(8.0, 2.0) - 3.0).abs() < 1e-6);
        assert!((inversesqrt(4.0) - 0.5).abs() < 1e-7);
        assert_eq!(clamp(5.0, 0.0, 1.0), 1.0);
    }

    #[test]
    fn clamp_with_crossed_bounds_gives_the_lower_bound_below_it() {
        // RI spec order: `x < lo` is tested first. `clamp(0.003, 0.005, 0)` is 0.005 (a
        // ray-marching step that keeps advancing), not 0 as `min(max(x, lo), hi)` would give.
        assert_eq!(clamp(0.003, 0.005, 0.0), 0.005);
        assert_eq!(clamp(0.1, 0.005, 0.0), 0.0);
        assert_eq!(clamp(0.5, 0.0, 1.0), 0.5);
        assert_eq!(clamp(-1.0, 0.0, 1.0), 0.0);
        assert_eq!(clamp(f32::NAN, 0.0, 1.0), 0.0);
    }
}
