//! RI 3.2 §15.2 geometric functions not already in `illume_shade` (which provides
//! `faceforward`, `reflect`, `refract`, `fresnel`, `normalize_or_zero`): `ptlined`, `rotate`,
//! and the matrix functions of §15.4. Matrices follow the SL row-vector convention of
//! [`crate::Value::Matrix`]: glam column-vector storage, `p' = m · p`.
use glam::{DMat4, DVec3, Vec3};

/// SL `distance(p0, p1)`.
pub fn distance(a: Vec3, b: Vec3) -> f32 {
    (a.as_dvec3() - b.as_dvec3()).length() as f32
}

/// SL `ptlined(p0, p1, q)`: the distance from `q` to the segment `p0 p1`.
pub fn ptlined(p0: Vec3, p1: Vec3, q: Vec3) -> f32 {
    let (a, b, q) = (p0.as_dvec3(), p1.as_dvec3(), q.as_dvec3());
    let d = b - a;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        ((q - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q - (a + d * t)).length() as f32
}

/// SL `rotate(q, angle, p0, p1)`: `q` rotated by `angle` radians about the axis through `p0`
/// and `p1` (right-handed about `p1 - p0`).
pub fn rotate_point(q: Vec3, angle: f32, p0: Vec3, p1: Vec3) -> Vec3 {
    let axis = (p1.as_dvec3() - p0.as_dvec3()).normalize_or_zero();
    if axis == DVec3::ZERO {
        return q;
    }
    let m = DMat4::from_translation(p0.as_dvec3())
        * DMat4::from_axis_angle(axis, angle as f64)
        * DMat4::from_translation(-p0.as_dvec3());
    m.transform_point3(q.as_dvec3()).as_vec3()
}

/// SL `matrix(m00, …, m33)` from 16 floats in row-major (RIB) order.
pub fn matrix_from_rows(m: [f64; 16]) -> DMat4 {
    DMat4::from_cols_array(&m)
}

/// SL `comp(m, row, column)`.
pub fn matrix_comp(m: &DMat4, row: usize, col: usize) -> f32 {
    if row > 3 || col > 3 {
        return 0.0;
    }
    m.col(row)[col] as f32
}

/// SL `setcomp(m, row, column, x)`.
pub fn matrix_setcomp(m: &mut DMat4, row: usize, col: usize, x: f32) {
    if row <= 3 && col <= 3 {
        m.col_mut(row)[col] = x as f64;
    }
}

/// SL `m1 * m2` (row vectors: `p·m1·m2` applies `m1` first).
pub fn matrix_mul(a: &DMat4, b: &DMat4) -> DMat4 {
    *b * *a
}

/// SL `inverse(m)` (`1/m`); a singular matrix gives the zero matrix rather than infinities.
pub fn matrix_inverse(m: &DMat4) -> DMat4 {
    let d = m.determinant();
    if d == 0.0 || !d.is_finite() {
        DMat4::ZERO
    } else {
        m.inverse()
    }
}

/// SL `translate(m, t)`: `m` with a translation by `t` applied first, as `Translate` in RIB
/// applies on the object side of the CTM.
pub fn translate(m: &DMat4, t: Vec3) -> DMat4 {
    *m * DMat4::from_translation(t.as_dvec3())
}

/// SL `rotate(m, angle, axis)` (radians), applied first like [`translate`].
pub fn rotate(m: &DMat4, angle: f32, axis: Vec3) -> DMat4 {
    let a = axis.as_dvec3().normalize_or_zero();
    if a == DVec3::ZERO {
        return *m;
    }
    *m * DMat4::from_axis_angle(a, angle as f64)
}

/// SL `scale(m, s)`, applied first like [`translate`].
pub fn scale(m: &DMat4, s: Vec3) -> DMat4 {
    *m * DMat4::from_scale(s.as_dvec3())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ptlined_measures_to_the_segment_not_the_line() {
        let (a, b) = (Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0));
        assert!((ptlined(a, b, Vec3::new(1.0, 3.0, 0.0)) - 3.0).abs() < 1e-6);
        // Beyond the end: distance to the endpoint, sqrt(1 + 1).
        assert!((ptlined(a, b, Vec3::new(3.0, 1.0, 0.0)) - 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn rotate_about_z_maps_x_to_y() {
        let q = rotate_point(Vec3::X, std::f32::consts::FRAC_PI_2, Vec3::ZERO, Vec3::Z);
        assert!((q - Vec3::Y).length() < 1e-6, "{q:?}");
        // About an offset axis through (1,0,0): the point (2,0,0) goes to (1,1,0).
        let q = rotate_point(
            Vec3::new(2.0, 0.0, 0.0),
            std::f32::consts::FRAC_PI_2,
            Vec3::X,
            Vec3::new(1.0, 0.0, 1.0),
        );
        assert!((q - Vec3::new(1.0, 1.0, 0.0)).length() < 1e-6, "{q:?}");
    }

    #[test]
    fn matrix_literal_is_row_major_with_translation_last_row() {
        let mut m = [0.0; 16];
        m[0] = 1.0;
        m[5] = 1.0;
        m[10] = 1.0;
        m[15] = 1.0;
        m[12] = 5.0; // row 3, column 0: x translation in RIB order
        let m = matrix_from_rows(m);
        assert_eq!(m.transform_point3(DVec3::ZERO), DVec3::new(5.0, 0.0, 0.0));
        assert_eq!(matrix_comp(&m, 3, 0), 5.0);
        let s = scale(&m, Vec3::splat(2.0));
        // Scale first, then the translation: (1,0,0) -> (2,0,0) -> (7,0,0).
        assert_eq!(s.transform_point3(DVec3::X), DVec3::new(7.0, 0.0, 0.0));
        assert!((s.determinant() - 8.0).abs() < 1e-12);
        let id = matrix_mul(&s, &matrix_inverse(&s));
        assert!(id.abs_diff_eq(DMat4::IDENTITY, 1e-12));
        assert_eq!(matrix_inverse(&DMat4::ZERO), DMat4::ZERO);
    }

    #[test]
    fn matrix_product_applies_the_left_factor_first() {
        let t = translate(&DMat4::IDENTITY, Vec3::X);
        let s = scale(&DMat4::IDENTITY, Vec3::splat(3.0));
        // p·t·s: translate then scale: 0 -> (1,0,0) -> (3,0,0).
        let ts = matrix_mul(&t, &s);
        assert_eq!(ts.transform_point3(DVec3::ZERO), DVec3::new(3.0, 0.0, 0.0));
        let r = rotate(&DMat4::IDENTITY, std::f32::consts::FRAC_PI_2, Vec3::Z);
        // f32 π/2 is off by 4.4e-8 rad.
        assert!(r.transform_point3(DVec3::X).abs_diff_eq(DVec3::Y, 1e-7));
    }
}
