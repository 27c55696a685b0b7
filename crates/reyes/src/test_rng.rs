//! A seeded stream of uniform numbers in `[0, 1)` for the randomized tests (xorshift32): the
//! same cases on every run and every machine, without a dependency.

/// The stream seeded with `seed` (not zero).
pub(crate) fn unit_stream(seed: u32) -> impl FnMut() -> f64 {
    let mut h = seed;
    move || {
        h ^= h << 13;
        h ^= h >> 17;
        h ^= h << 5;
        f64::from(h >> 8) / 16_777_216.0
    }
}
