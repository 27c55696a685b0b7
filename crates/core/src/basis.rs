//! Cubic patch bases (RI Spec 3.2 §5.2 "Basis", the predefined `RiBezierBasis`, …) and the
//! power form every bicubic patch is evaluated in.
//!
//! A patch is `P(u,v) = [u³ u² u 1] · Mu · G · Mvᵀ · [v³ v² v 1]ᵀ` with `G[i][j]` the control
//! point at u-index `i`, v-index `j`. Multiplying out `C = Mu · G · Mvᵀ` once per patch (in
//! f64) makes evaluation, derivatives and any basis — named or an explicit matrix — the same
//! code, and transforming `C` (constant term as a point, the rest as vectors) is exact even for
//! bases whose weights do not sum to one (hermite, power).

/// A 4×4 basis matrix, rows in RIB order (`m[4·row + col]`).
pub type BasisMatrix = [f32; 16];

const SIXTH: f32 = 1.0 / 6.0;

/// The predefined bases and their default steps: `bezier` 3, `b-spline` 1, `catmull-rom` 1,
/// `hermite` 2, `power` 4. `None` for an unknown name (the caller reports it).
pub fn basis_matrix(name: &str) -> Option<(BasisMatrix, i32)> {
    Some(match name {
        "bezier" => (
            [
                -1.0, 3.0, -3.0, 1.0, //
                3.0, -6.0, 3.0, 0.0, //
                -3.0, 3.0, 0.0, 0.0, //
                1.0, 0.0, 0.0, 0.0,
            ],
            3,
        ),
        "b-spline" | "bspline" => (
            [
                -SIXTH,
                3.0 * SIXTH,
                -3.0 * SIXTH,
                SIXTH,
                3.0 * SIXTH,
                -6.0 * SIXTH,
                3.0 * SIXTH,
                0.0,
                -3.0 * SIXTH,
                0.0,
                3.0 * SIXTH,
                0.0,
                SIXTH,
                4.0 * SIXTH,
                SIXTH,
                0.0,
            ],
            1,
        ),
        "catmull-rom" | "catmullrom" => (
            [
                -0.5, 1.5, -1.5, 0.5, //
                1.0, -2.5, 2.0, -0.5, //
                -0.5, 0.0, 0.5, 0.0, //
                0.0, 1.0, 0.0, 0.0,
            ],
            1,
        ),
        "hermite" => (
            [
                2.0, 1.0, -2.0, 1.0, //
                -3.0, -2.0, 3.0, -1.0, //
                0.0, 1.0, 0.0, 0.0, //
                1.0, 0.0, 0.0, 0.0,
            ],
            2,
        ),
        "power" => (
            [
                1.0, 0.0, 0.0, 0.0, //
                0.0, 1.0, 0.0, 0.0, //
                0.0, 0.0, 1.0, 0.0, //
                0.0, 0.0, 0.0, 1.0,
            ],
            4,
        ),
        _ => return None,
    })
}

type M4 = [[f64; 4]; 4];

fn to_m4(m: &BasisMatrix) -> M4 {
    std::array::from_fn(|r| std::array::from_fn(|c| m[4 * r + c] as f64))
}

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..4).map(|k| a[r][k] * b[k][c]).sum()))
}

fn transpose(a: &M4) -> M4 {
    std::array::from_fn(|r| std::array::from_fn(|c| a[c][r]))
}

fn flatten(a: &M4) -> [f64; 16] {
    std::array::from_fn(|k| a[k / 4][k % 4])
}

/// Power-form coefficients `C = Mu · G · Mvᵀ` of one scalar: `g[j·4 + i]` is the control value
/// at u-index `i`, v-index `j` (RIB order, u fastest). `C[4·a + b]` multiplies `u^(3−a) v^(3−b)`.
pub fn power_coefficients(mu: &BasisMatrix, mv: &BasisMatrix, g: &[f64; 16]) -> [f64; 16] {
    let gm: M4 = std::array::from_fn(|i| std::array::from_fn(|j| g[j * 4 + i]));
    flatten(&mul(&mul(&to_m4(mu), &gm), &transpose(&to_m4(mv))))
}

/// The power-form matrix `R` with `[u³ u² u 1] = [s³ s² s 1] · R` for `u = u0 + h·s`.
fn reparam(u0: f64, h: f64) -> M4 {
    [
        [h * h * h, 0.0, 0.0, 0.0],
        [3.0 * h * h * u0, h * h, 0.0, 0.0],
        [3.0 * h * u0 * u0, 2.0 * h * u0, h, 0.0],
        [u0 * u0 * u0, u0 * u0, u0, 1.0],
    ]
}

/// The inverse of the Bézier basis: maps power coefficients to Bézier control values.
const BEZIER_INVERSE: M4 = [
    [0.0, 0.0, 0.0, 1.0],
    [0.0, 0.0, 1.0 / 3.0, 1.0],
    [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0],
    [1.0, 1.0, 1.0, 1.0],
];

/// The 16 Bézier control values of the sub-range `[u0,u1] × [v0,v1]` of a power-form scalar:
/// their hull contains the patch there (the convex-hull property gives a tight bound).
pub fn bezier_of_range(c: &[f64; 16], [u0, u1]: [f64; 2], [v0, v1]: [f64; 2]) -> [f64; 16] {
    let cm: M4 = std::array::from_fn(|a| std::array::from_fn(|b| c[4 * a + b]));
    let sub = mul(
        &mul(&reparam(u0, u1 - u0), &cm),
        &transpose(&reparam(v0, v1 - v0)),
    );
    flatten(&mul(
        &mul(&BEZIER_INVERSE, &sub),
        &transpose(&BEZIER_INVERSE),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bezier_inverse_inverts_the_bezier_basis() {
        let (b, _) = basis_matrix("bezier").unwrap();
        let p = mul(&BEZIER_INVERSE, &to_m4(&b));
        for (r, row) in p.iter().enumerate() {
            for (c, x) in row.iter().enumerate() {
                assert!((x - f64::from(u8::from(r == c))).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn every_named_basis_reproduces_constants_except_hermite_and_power() {
        // Bases whose weights sum to one map all-ones control values to the constant 1.
        for name in ["bezier", "b-spline", "catmull-rom"] {
            let (m, _) = basis_matrix(name).unwrap();
            let c = power_coefficients(&m, &m, &[1.0; 16]);
            for (k, x) in c.iter().enumerate() {
                let want = if k == 15 { 1.0 } else { 0.0 };
                assert!((x - want).abs() < 1e-6, "{name} {k} {x}");
            }
        }
        assert_eq!(basis_matrix("hermite").unwrap().1, 2);
        assert!(basis_matrix("nurbs").is_none());
    }

    #[test]
    fn sub_range_bezier_points_interpolate_the_range_corners() {
        let (m, _) = basis_matrix("catmull-rom").unwrap();
        let g: [f64; 16] = std::array::from_fn(|k| ((k * 7) % 5) as f64 - 1.3);
        let c = power_coefficients(&m, &m, &g);
        let eval = |u: f64, v: f64| {
            let uu = [u * u * u, u * u, u, 1.0];
            let vv = [v * v * v, v * v, v, 1.0];
            (0..16).map(|k| c[k] * uu[k / 4] * vv[k % 4]).sum::<f64>()
        };
        let b = bezier_of_range(&c, [0.25, 0.75], [0.1, 0.4]);
        assert!((b[0] - eval(0.25, 0.1)).abs() < 1e-9);
        assert!((b[15] - eval(0.75, 0.4)).abs() < 1e-9);
        // b[3] is u-index 0, v-index 3 in C's (a, b) = (u, v) layout.
        assert!((b[3] - eval(0.25, 0.4)).abs() < 1e-9);
    }
}
