//! `ShadingInterpolation "constant"` (RI Spec 3.2 §4.2: one colour per micropolygon): the
//! colour, opacity and output variables of a micropolygon are the mean of its four vertices'
//! shaded values, computed once per grid when it is shaded.
//!
//! Why the mean and not one vertex: the vertex value sits half a micropolygon away from the
//! micropolygon's centre, so a whole image shifts by half a micropolygon in u and v: on a lit
//! sphere a bias of |∇C|·h/2 in every pixel (issue 21: 20× the peer's mean error). The mean of
//! the four corners is the bilinear patch's value at the centre, which for any smoothly varying
//! colour is the centre value up to O(h²); a box pixel filter over whole micropolygons then
//! averages the piecewise-constant image to the smooth one's mean to first order.
//!
//! Why once per grid: a micropolygon is hit by ~`PixelSamples²/ShadingRate` samples, so one
//! mean per micropolygon costs less than interpolating per hit, and the per-micropolygon arrays
//! are smaller than the per-vertex ones they replace.

/// Per micropolygon `(i, j)` of an `nu × nv` vertex grid (row `j` first), the mean of the
/// `stride`-float records of its vertices `(i, j)`, `(i+1, j)`, `(i, j+1)` and `(i+1, j+1)`;
/// `(nu−1)·(nv−1)·stride` floats, micropolygon `j·(nu−1) + i` first.
pub(crate) fn micropolygon_means(values: &[f32], nu: usize, nv: usize, stride: usize) -> Vec<f32> {
    corner_means(values, nu, nv, stride)
}

/// [`micropolygon_means`] of a grid's per-vertex colours, taken on the colours where they lie
/// (flattening them into floats and back was two copies and a loop of unknown stride per grid;
/// 2% of `rib/sphere.rib`'s instructions): the same sums per channel, in the same order.
pub(crate) fn micropolygon_colours(values: &[glam::Vec3], nu: usize, nv: usize) -> Vec<glam::Vec3> {
    corner_means(values, nu, nv, 1)
}

/// The one mean of both: per micropolygon and per `stride` element of a vertex's record,
/// `((a + b) + (c + d)) · ¼` of the element at its four vertices.
#[inline]
fn corner_means<T>(values: &[T], nu: usize, nv: usize, stride: usize) -> Vec<T>
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<f32, Output = T>,
{
    if nu < 2 || nv < 2 || stride == 0 || values.len() != nu * nv * stride {
        return Vec::new();
    }
    let row = nu * stride;
    let mut out = Vec::with_capacity((nu - 1) * (nv - 1) * stride);
    for (lo, hi) in values
        .chunks_exact(row)
        .zip(values.chunks_exact(row).skip(1))
    {
        for a in 0..row - stride {
            // Summed as two pairs in a fixed order: four equal values give that value back
            // exactly (an opaque 1.0 stays opaque, an object id stays that id).
            let lower = lo[a] + lo[a + stride];
            let upper = hi[a] + hi[a + stride];
            out.push((lower + upper) * 0.25);
        }
    }
    out
}

/// The micropolygon index `j·(nu−1) + i` of the micropolygon whose first vertex is grid vertex
/// `first = j·nu + i`.
pub(crate) fn micropolygon_of(first: usize, nu: usize) -> usize {
    first - first / nu
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bilinear_field_averages_to_its_value_at_each_centre() {
        // f(u, v) = 1 + 2u − 3v + 0.5uv on a 4 × 3 grid, two channels (f and 2f): the mean of
        // a bilinear function's four corners is its value at the centre, exactly.
        let (nu, nv) = (4, 3);
        let f = |u: f64, v: f64| 1.0 + 2.0 * u - 3.0 * v + 0.5 * u * v;
        let values: Vec<f32> = (0..nv)
            .flat_map(|j| (0..nu).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                let x = f(i as f64, j as f64) as f32;
                [x, 2.0 * x]
            })
            .collect();
        let m = micropolygon_means(&values, nu, nv, 2);
        assert_eq!(m.len(), (nu - 1) * (nv - 1) * 2);
        for j in 0..nv - 1 {
            for i in 0..nu - 1 {
                let want = f(i as f64 + 0.5, j as f64 + 0.5);
                let k = micropolygon_of(j * nu + i, nu);
                assert_eq!(k, j * (nu - 1) + i);
                assert!((f64::from(m[2 * k]) - want).abs() < 1e-6, "({i}, {j})");
                assert!((f64::from(m[2 * k + 1]) - 2.0 * want).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn equal_corners_keep_their_value_bit_for_bit() {
        for x in [1.0f32, 0.1, 3.3e7, 1e-30] {
            let m = micropolygon_means(&[x; 4], 2, 2, 1);
            assert_eq!(m, vec![x]);
        }
    }

    #[test]
    fn colours_are_averaged_per_channel() {
        use glam::Vec3;
        let v = [
            Vec3::new(0.0, 1.0, 2.0),
            Vec3::new(4.0, 1.0, 2.0),
            Vec3::new(0.0, 5.0, 2.0),
            Vec3::new(4.0, 5.0, 6.0),
        ];
        assert_eq!(
            micropolygon_colours(&v, 2, 2),
            vec![Vec3::new(2.0, 3.0, 3.0)]
        );
    }

    /// The colour means are `micropolygon_means` of the flattened colours, bit for bit.
    #[test]
    fn colour_means_are_the_flat_means() {
        use glam::Vec3;
        let (nu, nv) = (7, 5);
        let mut h = 0x9e37_79b9u32;
        let mut next = || {
            h ^= h << 13;
            h ^= h >> 17;
            h ^= h << 5;
            (h % 100_000) as f32 / 3_333.0 - 7.0
        };
        let v: Vec<Vec3> = (0..nu * nv)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        let flat: Vec<f32> = v.iter().flat_map(|c| c.to_array()).collect();
        let want = micropolygon_means(&flat, nu, nv, 3);
        let got: Vec<f32> = micropolygon_colours(&v, nu, nv)
            .iter()
            .flat_map(|c| c.to_array())
            .collect();
        assert_eq!(got.len(), want.len());
        assert!(got
            .iter()
            .zip(&want)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(micropolygon_colours(&v[1..], nu, nv).is_empty());
    }

    #[test]
    fn a_grid_of_the_wrong_size_has_no_means() {
        assert!(micropolygon_means(&[1.0; 5], 2, 2, 1).is_empty());
        assert!(micropolygon_means(&[1.0; 3], 3, 1, 1).is_empty());
    }
}
