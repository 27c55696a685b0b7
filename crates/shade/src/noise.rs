//! Shading Language `noise(point)` (RI Spec 3.2 §15.1): a smooth pseudo-random function of
//! position with values in [0, 1] averaging 0.5, here Perlin's gradient noise (improved fade
//! curve). The lattice gradients come from [`lowbias32`] of the integer cell coordinates, so the
//! value depends on the point alone: two grids that share a vertex displace it identically,
//! whatever bucket or thread shades them.
use crate::hash::lowbias32;
use glam::Vec3;

/// The twelve edge directions of a cube (Perlin 2002): no axis is favoured.
const GRADIENTS: [[f64; 3]; 12] = [
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, -1.0, 1.0],
    [0.0, 1.0, -1.0],
    [0.0, -1.0, -1.0],
];

fn gradient(x: i64, y: i64, z: i64) -> [f64; 3] {
    let h = lowbias32(x as u32 ^ lowbias32(y as u32 ^ lowbias32(z as u32)));
    GRADIENTS[(h % 12) as usize]
}

/// `6t⁵ − 15t⁴ + 10t³`: zero first and second derivatives at the lattice, so displaced
/// surfaces have continuous normals across cells.
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// `float noise(point p)`: in [0, 1], 0.5 at every lattice point.
pub fn noise(p: Vec3) -> f32 {
    let p = p.as_dvec3();
    let cell = p.floor();
    let f = p - cell;
    let (ix, iy, iz) = (cell.x as i64, cell.y as i64, cell.z as i64);
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let corner = |dx: i64, dy: i64, dz: i64| {
        let g = gradient(ix + dx, iy + dy, iz + dz);
        g[0] * (f.x - dx as f64) + g[1] * (f.y - dy as f64) + g[2] * (f.z - dz as f64)
    };
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), u);
    let x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), u);
    let x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), u);
    let x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), u);
    let n = lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
    // Gradient noise with these gradients stays within about ±1.04: clamp the rare excess.
    (0.5 + 0.5 * n).clamp(0.0, 1.0) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn is_one_half_on_the_lattice_and_varies_between() {
        for p in [
            Vec3::ZERO,
            Vec3::new(3.0, -2.0, 7.0),
            Vec3::new(-1.0, 5.0, 0.0),
        ] {
            assert_eq!(noise(p), 0.5);
        }
        let values: Vec<f32> = (0..200)
            .map(|i| noise(Vec3::new(i as f32 * 0.37, i as f32 * 0.11, 0.5)))
            .collect();
        assert!(values.iter().all(|v| (0.0..=1.0).contains(v)));
        let (lo, hi) = values
            .iter()
            .fold((1.0f32, 0.0f32), |(a, b), &v| (a.min(v), b.max(v)));
        assert!(lo < 0.35 && hi > 0.65, "range {lo}..{hi}");
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        assert!((mean - 0.5).abs() < 0.05, "mean {mean}");
    }

    #[test]
    fn is_continuous() {
        // A Lipschitz bound: gradients have length √2 and the fade is C², so the slope stays
        // below a few units; a step of 1e-4 changes the value by far less than 1e-2.
        for i in 0..100 {
            let p = Vec3::new(i as f32 * 0.173, 0.29 * i as f32, -0.41 * i as f32);
            let d = (noise(p) - noise(p + Vec3::splat(1e-4))).abs();
            assert!(d < 1e-2, "{d} at {p}");
        }
    }
}
