//! Shading Language mathematical functions the chapter uses (RI Spec 3.2 §15.1).

/// `smoothstep(e0, e1, x)`: 0 below `e0`, 1 at or above `e1`, the cubic `3t² - 2t³` between.
/// With `e0 == e1` it is a step at `e0` (Listing 9.13 with `sharpness = 1`).
pub fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    if x < e0 {
        0.0
    } else if x >= e1 {
        1.0
    } else {
        let t = (x - e0) / (e1 - e0);
        t * t * (3.0 - 2.0 * t)
    }
}

/// `mix(a, b, t) = a (1 - t) + b t`.
pub fn mix<T>(a: T, b: T, t: f32) -> T
where
    T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    a * (1.0 - t) + b * t
}
