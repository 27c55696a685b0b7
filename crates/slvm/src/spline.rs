//! SL `spline([basis,] t, v0, v1, …, vn)` (RI 3.2 §15.1) for floats and triples: the curve
//! through the knots with the basis' segments (`step` knots apart, four knots each) spread
//! evenly over `t ∈ [0,1]`. `catmull-rom` (default) and `bspline` step 1, `hermite` 2
//! (knots are value, tangent pairs), `bezier` 3. `linear` and `constant` ignore the first and
//! last knot as catmull-rom does, so the same knot list can switch basis.
use glam::Vec3;

/// A spline basis by its SL name; `None` for an unknown name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Basis {
    CatmullRom,
    Bezier,
    BSpline,
    Hermite,
    Linear,
    Constant,
}

impl Basis {
    pub fn from_name(name: &str) -> Option<Basis> {
        Some(match name {
            "catmull-rom" | "catrom" => Basis::CatmullRom,
            "bezier" => Basis::Bezier,
            "bspline" | "b-spline" => Basis::BSpline,
            "hermite" => Basis::Hermite,
            "linear" => Basis::Linear,
            "constant" => Basis::Constant,
            _ => return None,
        })
    }

    /// The RIB name of a cubic basis in [`illume_core::basis`]; `None` for linear/constant.
    fn rib_name(self) -> Option<&'static str> {
        match self {
            Basis::CatmullRom => Some("catmull-rom"),
            Basis::Bezier => Some("bezier"),
            Basis::BSpline => Some("b-spline"),
            Basis::Hermite => Some("hermite"),
            // Not cubic: handled in `spline` directly.
            Basis::Linear | Basis::Constant => None,
        }
    }

    /// The RI basis matrix (row `i` multiplies `t^(3-i)`) and step, the same matrices as the
    /// RIB `Basis` request uses.
    fn matrix_and_step(self) -> ([[f32; 4]; 4], usize) {
        match self.rib_name().and_then(illume_core::basis::basis_matrix) {
            Some((m, step)) => (
                std::array::from_fn(|r| std::array::from_fn(|c| m[4 * r + c])),
                step as usize,
            ),
            None => ([[0.0; 4]; 4], 1),
        }
    }
}

/// Values a spline can interpolate.
pub trait Knot: Copy + std::ops::Add<Output = Self> + std::ops::Mul<f32, Output = Self> {
    fn zero() -> Self;
}

impl Knot for f32 {
    fn zero() -> Self {
        0.0
    }
}

impl Knot for Vec3 {
    fn zero() -> Self {
        Vec3::ZERO
    }
}

/// The spline through `knots` at `t` (clamped to [0,1]); zero with fewer than four knots
/// (two for linear/constant after dropping the ends).
pub fn spline<T: Knot>(basis: Basis, t: f32, knots: &[T]) -> T {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    match basis {
        Basis::Linear | Basis::Constant => {
            if knots.len() < 3 {
                return knots.first().copied().unwrap_or_else(T::zero);
            }
            let inner = &knots[1..knots.len() - 1];
            let nseg = inner.len() - 1;
            if nseg == 0 {
                return inner[0];
            }
            let x = t * nseg as f32;
            let seg = (x.floor() as usize).min(nseg - 1);
            let f = x - seg as f32;
            if basis == Basis::Constant {
                // Each knot holds over its own 1/(nseg+1) of the range.
                let k = ((t * (nseg + 1) as f32).floor() as usize).min(nseg);
                return inner[k];
            }
            inner[seg] * (1.0 - f) + inner[seg + 1] * f
        }
        _ => {
            let (m, step) = basis.matrix_and_step();
            if knots.len() < 4 {
                return T::zero();
            }
            let nseg = (knots.len() - 4) / step + 1;
            let x = t * nseg as f32;
            let seg = (x.floor() as usize).min(nseg - 1);
            let u = x - seg as f32;
            let powers = [u * u * u, u * u, u, 1.0];
            let mut out = T::zero();
            for (j, knot) in knots[seg * step..seg * step + 4].iter().enumerate() {
                let w: f32 = (0..4).map(|i| powers[i] * m[i][j]).sum();
                out = out + *knot * w;
            }
            out
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catmull_rom_passes_through_the_inner_knots() {
        let k = [0.0f32, 1.0, 4.0, 2.0, 3.0, 7.0];
        // Three segments: t = 0, 1/3, 2/3, 1 land on knots 1..=4.
        for (i, want) in [1.0, 4.0, 2.0, 3.0].iter().enumerate() {
            let got = spline(Basis::CatmullRom, i as f32 / 3.0, &k);
            assert!((got - want).abs() < 1e-5, "t={} got {got}", i as f32 / 3.0);
        }
    }

    #[test]
    fn bezier_midpoint_is_the_de_casteljau_value() {
        // B(1/2) = (p0 + 3p1 + 3p2 + p3)/8.
        let k = [0.0f32, 2.0, 5.0, 1.0];
        let want = (0.0 + 3.0 * 2.0 + 3.0 * 5.0 + 1.0) / 8.0;
        assert!((spline(Basis::Bezier, 0.5, &k) - want).abs() < 1e-6);
    }

    #[test]
    fn bspline_start_is_the_weighted_average() {
        // B-spline at u=0: (p0 + 4p1 + p2)/6.
        let k = [6.0f32, 0.0, 12.0, 3.0];
        assert!((spline(Basis::BSpline, 0.0, &k) - 3.0).abs() < 1e-6);
    }

    #[test]
    fn hermite_interpolates_values_with_tangents() {
        // p0=1, t0=0, p1=3, t1=0: h(1/2) = (p0+p1)/2 by symmetry of the basis.
        let k = [1.0f32, 0.0, 3.0, 0.0];
        assert!((spline(Basis::Hermite, 0.5, &k) - 2.0).abs() < 1e-6);
        assert!((spline(Basis::Hermite, 1.0, &k) - 3.0).abs() < 1e-6);
    }

    #[test]
    fn linear_and_constant_use_the_inner_knots() {
        let k = [9.0f32, 0.0, 10.0, 20.0, 9.0];
        assert!((spline(Basis::Linear, 0.25, &k) - 5.0).abs() < 1e-5);
        assert_eq!(spline(Basis::Constant, 0.5, &k), 10.0);
        let v = spline(
            Basis::CatmullRom,
            0.5,
            &[Vec3::ZERO, Vec3::ONE, Vec3::ONE, Vec3::ZERO],
        );
        // Symmetric knots: at the middle CR gives (-p0 + 9p1 + 9p2 - p3)/16 = 18/16.
        assert!((v.x - 18.0 / 16.0).abs() < 1e-6);
    }
}
