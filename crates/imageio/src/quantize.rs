//! `Quantize "rgba" one min max ditheramplitude` (RI spec 3.2, §4.1.6 "Display"):
//!
//! ```text
//! value = round(one · value + ditheramplitude · random())
//! value = clamp(value, min, max)
//! ```
//!
//! `random()` is uniform in [-1, 1), so the default amplitude 0.5 spreads the rounding error over
//! one code value. It is a hash of the pixel position and the channel, never a stateful generator:
//! the same pixel gets the same dither whatever the bucket order or thread count, so two renders
//! of one scene produce identical files.

use crate::Quantize;

/// The stored sample type a [`Quantize`] setting calls for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleDepth {
    /// `one == 0`: 32-bit float, values written as they are.
    Float,
    /// `0 ≤ min`, `max ≤ 255`: 8-bit unsigned.
    U8,
    /// `max ≤ 65535`: 16-bit unsigned.
    U16,
}

impl Quantize {
    /// PRMan's defaults for colour: 8-bit with one code value of dither.
    pub const RGBA_DEFAULT: Quantize = Quantize {
        one: 255,
        min: 0,
        max: 255,
        dither: 0.5,
    };
    /// Float output (the default for depth, and `Quantize "rgba" 0 0 0 0`).
    pub const FLOAT: Quantize = Quantize {
        one: 0,
        min: 0,
        max: 0,
        dither: 0.0,
    };

    /// The sample type this setting writes. Integer settings whose `max` exceeds 65535 have no
    /// unsigned type in PNG, so they are stored as float (holding the quantized integers).
    pub fn sample_depth(&self) -> SampleDepth {
        if self.one == 0 {
            SampleDepth::Float
        } else if self.max <= 255 {
            SampleDepth::U8
        } else if self.max <= 65535 {
            SampleDepth::U16
        } else {
            SampleDepth::Float
        }
    }

    /// Quantizes one sample of channel `channel` at pixel (`x`, `y`): the integer code value
    /// (as f64, exact), clamped to `[min, max]` and then to the unsigned range of the stored
    /// type. With `one == 0` returns the value unchanged.
    #[inline]
    pub fn quantize(&self, value: f32, x: u32, y: u32, channel: u32) -> f64 {
        Quantizer::new(self).at(value, x, y, channel)
    }
}

/// A [`Quantize`] setting with its constants prepared once for the many samples of an image:
/// the setting's integers converted, the clamp bounds ordered and the stored type's range
/// chosen per frame, not per sample (a quantized 8-bit sample took about 100 instructions,
/// callgrind on `rib/sphere.rib` at 2×; now about 90). The same arithmetic, so the
/// same values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Quantizer {
    /// `one == 0`: values pass unchanged.
    float: bool,
    one: f64,
    /// The dither amplitude, `None` for none.
    dither: Option<f64>,
    /// `[min, max]` (`min` no higher than `max`), then the stored type's range.
    range: [f64; 2],
    stored: [f64; 2],
    /// `range` clamped into `stored`: the one range both clamps amount to (see
    /// [`Quantizer::at_integer`]).
    both: [f64; 2],
}

impl Quantizer {
    pub(crate) fn new(q: &Quantize) -> Quantizer {
        let stored = match q.sample_depth() {
            SampleDepth::U8 => [0.0, 255.0],
            SampleDepth::U16 => [0.0, 65535.0],
            SampleDepth::Float => [f64::NEG_INFINITY, f64::INFINITY],
        };
        let range = [q.min.min(q.max) as f64, q.max as f64];
        Quantizer {
            float: q.one == 0,
            one: q.one as f64,
            dither: (q.dither != 0.0).then_some(q.dither as f64),
            range,
            stored,
            both: range.map(|r| r.clamp(stored[0], stored[1])),
        }
    }

    /// [`Quantize::quantize`].
    #[inline]
    pub(crate) fn at(&self, value: f32, x: u32, y: u32, channel: u32) -> f64 {
        if self.float {
            return value as f64;
        }
        let q = round(self.dithered(value, x, y, channel));
        let ([lo, hi], [tlo, thi]) = (self.range, self.stored);
        // A float type's range is ±∞: the second clamp keeps the value (never NaN here).
        q.clamp(lo, hi).clamp(tlo, thi)
    }

    /// `one · value + ditheramplitude · random()` before rounding, a NaN value taken as 0.
    #[inline]
    fn dithered(&self, value: f32, x: u32, y: u32, channel: u32) -> f64 {
        let v = if value.is_nan() { 0.0 } else { value as f64 };
        let noise = match self.dither {
            Some(amplitude) => amplitude * dither_noise(x, y, channel),
            None => 0.0,
        };
        self.one * v + noise
    }

    #[cfg(test)]
    fn sample_depth_is_float(&self) -> bool {
        !self.stored[1].is_finite()
    }

    /// [`Quantizer::at`] for an unsigned integer type (8 or 16 bits; `one ≠ 0`), the same
    /// value for every input with a third of the instructions (a quantized 8-bit sample took
    /// about 90; `quantize_image` was 4% of `rib/sphere.rib`'s instructions at 2× and the
    /// larger part of the serial work between bands). Rounding is monotone and leaves the
    /// integers `lo` and `hi` of the range fixed, so `clamp(round(x), lo, hi) = round(clamp(x,
    /// lo, hi))`, and two clamps in a row are one clamp to `both`; once clamped, `x` is finite
    /// and at least 0, where rounding half away from zero is the truncation plus one when the
    /// (exact) fraction is at least ½: no branches, no NaN or infinity cases.
    #[inline]
    pub(crate) fn at_integer(&self, value: f32, x: u32, y: u32, channel: u32) -> f64 {
        debug_assert!(!self.float && self.stored[0] == 0.0 && self.stored[1].is_finite());
        let [lo, hi] = self.both;
        let x = self.dithered(value, x, y, channel).clamp(lo, hi);
        let t = x as i64 as f64;
        t + if x - t >= 0.5 { 1.0 } else { 0.0 }
    }
}

/// `f64::round` (half away from zero, the sign of a zero kept) without its libm call (the
/// default x86-64 target has no `roundsd`): the truncation is exact below 2⁵², and so is the
/// fraction `x − t`, so comparing that with ½ decides exactly. Per quantized sample the call
/// was a sixth of the cost (`tests::round_is_f64_round`).
#[inline]
fn round(x: f64) -> f64 {
    if x.abs() >= 4_503_599_627_370_496.0 || x.is_nan() {
        return x; // |x| ≥ 2⁵² is an integer already; NaN and infinities stay.
    }
    let t = x as i64 as f64;
    let d = x - t;
    if d >= 0.5 {
        t + 1.0
    } else if d <= -0.5 {
        t - 1.0
    } else {
        t.copysign(x)
    }
}

/// Uniform noise in [-1, 1) from a hash of (x, y, channel): a 32-bit integer mix
/// (the "lowbias32" finaliser), good enough that neighbouring pixels are uncorrelated.
pub fn dither_noise(x: u32, y: u32, channel: u32) -> f64 {
    let h = illume_core::hash::lowbias32(
        x.wrapping_mul(0x9E37_79B1)
            .wrapping_add(y.wrapping_mul(0x85EB_CA77))
            .wrapping_add(channel.wrapping_mul(0xC2B2_AE3D))
            ^ 0x27D4_EB2F,
    );
    (h as f64) / 2_147_483_648.0 - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_is_f64_round() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -0.49999999999999994,
            1.4999999999999998,
            -0.3,
            4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            -4_503_599_627_370_495.5,
            9.1e18,
            -9.3e18,
            f64::MAX,
            f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let mut h = 0x9e37_79b9_7f4a_7c15u64;
        for k in 0..400_000 {
            h ^= h << 13;
            h ^= h >> 7;
            h ^= h << 17;
            // Every bit pattern, and values near the quantizer's range at quarter steps.
            xs.push(f64::from_bits(h));
            xs.push((h % 262_144) as f64 / 4.0 - 32_768.0 + (k % 3) as f64 * f64::EPSILON);
        }
        for x in xs {
            let (a, b) = (round(x), x.round());
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{x:e}: {a} {b}"
            );
        }
    }

    #[test]
    fn dither_noise_is_bounded_and_roughly_uniform() {
        let mut sum = 0.0;
        let mut bins = [0u32; 8];
        let n = 256 * 256;
        for y in 0..256 {
            for x in 0..256 {
                let r = dither_noise(x, y, 0);
                assert!((-1.0..1.0).contains(&r), "noise {r} out of [-1,1)");
                sum += r;
                bins[((r + 1.0) * 4.0) as usize] += 1;
            }
        }
        assert!((sum / n as f64).abs() < 0.01, "mean {}", sum / n as f64);
        for b in bins {
            let expected = n as f64 / 8.0;
            assert!(
                (b as f64 - expected).abs() < 0.05 * expected,
                "bins {bins:?}"
            );
        }
    }

    #[test]
    fn dither_is_a_function_of_position_only() {
        let q = Quantize::RGBA_DEFAULT;
        let a: Vec<f64> = (0..1000)
            .map(|i| q.quantize(0.3, i % 37, i / 37, i % 3))
            .collect();
        let b: Vec<f64> = (0..1000)
            .rev()
            .map(|i| q.quantize(0.3, i % 37, i / 37, i % 3))
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        assert_eq!(a, b);
        // It actually dithers: 0.3·255 = 76.5 lands on both neighbours.
        assert!(a.contains(&76.0) && a.contains(&77.0));
    }

    #[test]
    fn dither_error_stays_within_amplitude_plus_half() {
        let q = Quantize {
            one: 1000,
            min: -100000,
            max: 100000,
            dither: 2.0,
        };
        for i in 0..5000u32 {
            let v = (i as f32) * 0.013 - 20.0;
            let out = q.quantize(v, i, i * 7, 1);
            let exact = 1000.0 * v as f64;
            assert!((out - exact).abs() <= 2.5 + 1e-9, "{v}: {out} vs {exact}");
        }
    }

    #[test]
    fn quantize_clamps_to_min_max_and_type_range() {
        let q = Quantize {
            one: 255,
            min: 16,
            max: 235,
            dither: 0.0,
        };
        assert_eq!(q.quantize(-3.0, 0, 0, 0), 16.0);
        assert_eq!(q.quantize(7.0, 0, 0, 0), 235.0);
        assert_eq!(q.quantize(0.5, 0, 0, 0), 128.0); // 127.5 rounds away from zero
        assert_eq!(q.quantize(f32::NAN, 0, 0, 0), 16.0);
        let wide = Quantize {
            one: 255,
            min: -50,
            max: 255,
            dither: 0.0,
        };
        assert_eq!(wide.quantize(-1.0, 0, 0, 0), 0.0, "unsigned 8-bit floor");
        assert_eq!(Quantize::FLOAT.quantize(-1.25, 3, 4, 0), -1.25);
    }

    #[test]
    fn sample_depth_follows_one_and_max() {
        assert_eq!(Quantize::RGBA_DEFAULT.sample_depth(), SampleDepth::U8);
        assert_eq!(Quantize::FLOAT.sample_depth(), SampleDepth::Float);
        let q16 = Quantize {
            one: 65535,
            min: 0,
            max: 65535,
            dither: 0.5,
        };
        assert_eq!(q16.sample_depth(), SampleDepth::U16);
    }

    /// The integer path against the general one on the cases where rounding and clamping are
    /// delicate: exact halves (`one` 2 or 4 makes `k/4` land on them), a hair either side of
    /// them and of the clamp bounds, NaN, ±∞, ±0, and bounds inside, across and outside the
    /// stored type's range.
    #[test]
    fn the_integer_path_equals_the_general_one() {
        let mut values: Vec<f32> = vec![f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -0.0];
        for k in -1200..1200 {
            let v = k as f32 / 4.0;
            values.extend([v, v.next_up(), v.next_down()]);
        }
        for (one, min, max) in [
            (2, 0, 255),
            (4, 0, 255),
            (255, 0, 255),
            (255, 16, 235),
            (255, -40, 200),
            (2, 300, 200),
            (4, 0, 65535),
            (1000, 20, 900),
            (65535, -5, 70000),
        ] {
            for dither in [0.0, 0.5, 1.75] {
                let q = Quantizer::new(&Quantize {
                    one,
                    min,
                    max,
                    dither,
                });
                if q.float || q.sample_depth_is_float() {
                    continue;
                }
                for (i, &v) in values.iter().enumerate() {
                    let (x, y, c) = (i as u32 * 7, i as u32 / 3, i as u32 % 4);
                    let (a, b) = (q.at(v, x, y, c), q.at_integer(v, x, y, c));
                    assert!(
                        a == b,
                        "one {one} [{min}, {max}] dither {dither} v {v:e}: {a} vs {b}"
                    );
                }
            }
        }
    }

    /// `quantize_image` (row by row in parallel, positions counted along the row) against
    /// `Quantize::quantize` per sample: the same stored value for every depth, with and
    /// without dither, clamps that bind, NaN and infinities, and positions whose hash input
    /// wraps around `u32`.
    #[test]
    fn a_quantized_image_is_its_samples_quantized_one_by_one() {
        let settings = [
            Quantize::RGBA_DEFAULT,
            Quantize {
                one: 255,
                min: 0,
                max: 255,
                dither: 0.0,
            },
            Quantize {
                one: 65535,
                min: 0,
                max: 65535,
                dither: 0.5,
            },
            Quantize {
                one: 1000,
                min: 20,
                max: 900,
                dither: 3.0,
            },
            Quantize {
                one: 255,
                min: -40,
                max: 300,
                dither: 0.5,
            },
            Quantize {
                one: 0,
                min: 0,
                max: 0,
                dither: 0.0,
            },
        ];
        let mut h = 0x2545_f491u32;
        let mut next = || {
            h ^= h << 13;
            h ^= h >> 17;
            h ^= h << 5;
            h
        };
        for q in settings {
            for origin in [[0, 0], [17, 3], [u32::MAX - 2, u32::MAX - 1]] {
                let mut image = crate::Image::new(7, 5, "rgba");
                for v in &mut image.data {
                    *v = match next() % 12 {
                        0 => f32::NAN,
                        1 => f32::INFINITY,
                        2 => f32::NEG_INFINITY,
                        3 => -0.3,
                        _ => (next() % 3000) as f32 / 2000.0 - 0.2,
                    };
                }
                let want = |i: usize| {
                    let (p, c) = (i / 4, i % 4);
                    let (x, y) = (p as u32 % 7, p as u32 / 7);
                    let (x, y) = (origin[0].wrapping_add(x), origin[1].wrapping_add(y));
                    q.quantize(image.data[i], x, y, c as u32)
                };
                let got: Vec<f64> = match quantize_image(&image, q, origin) {
                    Samples::U8(v) => v.into_iter().map(f64::from).collect(),
                    Samples::U16(v) => v.into_iter().map(f64::from).collect(),
                    Samples::F32(v) => v.into_iter().map(f64::from).collect(),
                };
                assert_eq!(got.len(), image.data.len());
                for (i, g) in got.iter().enumerate() {
                    let w = match q.sample_depth() {
                        SampleDepth::U8 => f64::from(want(i) as u8),
                        SampleDepth::U16 => f64::from(want(i) as u16),
                        SampleDepth::Float => f64::from(want(i) as f32),
                    };
                    assert!(
                        g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan()),
                        "{q:?} at {origin:?} sample {i}: {g} vs {w}"
                    );
                }
            }
        }
    }
}

/// Quantized samples ready for an encoder, interleaved like the [`crate::Image`] they came from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Samples {
    U8(Vec<u8>),
    U16(Vec<u16>),
    F32(Vec<f32>),
}

/// Quantizes every sample of `image` (pixel order, channel index as dither stream). `origin` is
/// the full-frame raster position of the image's top-left pixel: dither is keyed on full-frame
/// positions, so crop windows rendered separately tile into the full image bit for bit.
pub(crate) fn quantize_image(
    image: &crate::Image,
    quantize: Quantize,
    origin: [u32; 2],
) -> Samples {
    let nc = image.channels.len().max(1);
    let row = image.width.max(1) as usize * nc;
    // Row by row (one task per row, not per sample) into an output of the image's size, the
    // pixel position counted along the row instead of divided out of the sample index; the
    // same `quantize` per sample. (A flat-mapped parallel collect of the samples cost more
    // than the quantizing: 6% of `rib/teapot.rib`'s instructions.)
    fn rows<T: Send + Copy + Default>(
        image: &crate::Image,
        (row, nc): (usize, usize),
        origin: [u32; 2],
        q: impl Fn(f32, u32, u32, u32) -> T + Sync,
    ) -> Vec<T> {
        use rayon::prelude::*;
        let mut out = vec![T::default(); image.data.len()];
        out.par_chunks_mut(row)
            .zip(image.data.par_chunks(row))
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(y, (dst, src))| {
                let y = origin[1].wrapping_add(y as u32);
                if nc == 4 {
                    // RGBA, the common display: a loop unrolled over the four channels.
                    let pixels = dst.chunks_exact_mut(4).zip(src.chunks_exact(4));
                    for (x, (d, s)) in pixels.enumerate() {
                        let x = origin[0].wrapping_add(x as u32);
                        for c in 0..4 {
                            d[c] = q(s[c], x, y, c as u32);
                        }
                    }
                    return;
                }
                for (x, (d, s)) in dst.chunks_mut(nc).zip(src.chunks(nc)).enumerate() {
                    let x = origin[0].wrapping_add(x as u32);
                    for (c, (d, &v)) in d.iter_mut().zip(s).enumerate() {
                        *d = q(v, x, y, c as u32);
                    }
                }
            });
        out
    }
    let prepared = Quantizer::new(&quantize);
    let at = |v, x, y, c| prepared.at(v, x, y, c);
    let integer = |v, x, y, c| prepared.at_integer(v, x, y, c);
    match quantize.sample_depth() {
        SampleDepth::U8 => Samples::U8(rows(image, (row, nc), origin, |v, x, y, c| {
            integer(v, x, y, c) as u8
        })),
        SampleDepth::U16 => Samples::U16(rows(image, (row, nc), origin, |v, x, y, c| {
            integer(v, x, y, c) as u16
        })),
        SampleDepth::Float => Samples::F32(rows(image, (row, nc), origin, |v, x, y, c| {
            at(v, x, y, c) as f32
        })),
    }
}

/// The fewest rows one parallel quantize task takes. A streamed display quantizes a few rows
/// at a time while the next band renders on the other threads: split per row, each call woke
/// them for tasks of a few microseconds.
const ROWS_PER_TASK: usize = 16;
