//! The integer hash behind every deterministic random stream of the renderer (pixel sample
//! positions in the hider, shadow-ray and area-light samples here): values derive from what is
//! sampled (pixel, sample index, point, frame), never from threads or buckets, so images are
//! bit-identical for any thread count.

/// A 32-bit integer hash with good avalanche (the "lowbias32" finaliser).
pub fn lowbias32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}
