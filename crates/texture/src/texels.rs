//! How a cached tile keeps its texels: in the file's own precision.
//!
//! `.tx` files store `half` by default (DESIGN.md, "Files"); widening every tile to `f32` in the
//! cache doubled its footprint, so a 2K cube map (6 × 2048² RGB, 201 MB as half with its mip
//! levels) no longer fit the default 256 MB `texturememory` and environment lookups thrashed
//! (issue 23, part 5: 0.05 M lookups/s). Half tiles are widened per texel on read, which costs
//! a few nanoseconds against a tile decode of ~100 µs. Float files (shadow maps, `-float`
//! textures) and integer channels keep `f32`, so depths stay exact.

use half::f16;

/// Interleaved texels of one tile in stored channel order.
pub(crate) enum Texels {
    /// Every channel of the file is `half`.
    Half(Vec<f16>),
    /// Some channel is `float` or `uint`: widened to `f32`.
    Float(Vec<f32>),
}

impl Texels {
    /// Bytes held (what the cache budget counts).
    pub fn bytes(&self) -> usize {
        match self {
            Texels::Half(v) => v.len() * 2,
            Texels::Float(v) => v.len() * 4,
        }
    }

    /// Copies `out.len()` values starting at sample index `i`, widened to `f32`.
    pub fn read(&self, i: usize, out: &mut [f32]) {
        let n = out.len();
        match self {
            Texels::Half(v) => {
                for (o, h) in out.iter_mut().zip(&v[i..i + n]) {
                    *o = h.to_f32();
                }
            }
            Texels::Float(v) => out.copy_from_slice(&v[i..i + n]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_texels_widen_exactly_and_count_two_bytes() {
        // Values exactly representable in half come back bit-identical.
        let vals = [0.0f32, 1.0, 0.5, -2.25, 65504.0, 0.000061035156];
        let t = Texels::Half(vals.iter().map(|&v| f16::from_f32(v)).collect());
        assert_eq!(t.bytes(), 12);
        let mut out = [0.0f32; 3];
        t.read(3, &mut out);
        assert_eq!(out, [-2.25, 65504.0, 0.000061035156]);
    }

    #[test]
    fn float_texels_are_untouched() {
        let vals = vec![0.1f32, 1e-30, 3.0e38];
        let t = Texels::Float(vals.clone());
        assert_eq!(t.bytes(), 12);
        let mut out = [0.0f32; 3];
        t.read(0, &mut out);
        assert_eq!(out.to_vec(), vals);
    }
}
