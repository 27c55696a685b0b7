//! SL `noise`, `pnoise`, `cellnoise` are the renderer's one noise ([`illume_core::noise`], the
//! same function the built-in shaders call); `random()` is the VM's own.
use illume_core::hash::lowbias32;
pub use illume_core::noise::{cellnoise, noise, pnoise};

/// SL `random()`: a number in [0,1) that depends only on the point, the call site and the
/// frame seed, so renders repeat bit for bit.
pub fn random(point: usize, site: u32, seed: u32) -> f32 {
    let h = lowbias32(lowbias32(point as u32 ^ seed.wrapping_mul(0x85eb_ca6b)) ^ site);
    (h >> 8) as f32 / (1u32 << 24) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn random_is_a_pure_function_of_point_and_site() {
        assert_eq!(random(7, 1, 0), random(7, 1, 0));
        assert_ne!(random(7, 1, 0), random(8, 1, 0));
        let mean: f64 = (0..10_000).map(|i| random(i, 3, 0) as f64).sum::<f64>() / 10_000.0;
        // Uniform on [0,1): mean 1/2, standard error 1/sqrt(12·10⁴) ≈ 0.0029.
        assert!((mean - 0.5).abs() < 0.015, "mean {mean}");
    }
}
