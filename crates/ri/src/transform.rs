//! The transformation requests of RI Spec 3.2 §4.3 as `f64` matrices in glam's column-vector
//! convention. RIB writes matrices for row vectors (`p' = p·M`), so a RIB array read with
//! `from_cols_array` is already the column-vector matrix. Every request concatenates on the
//! object side, `CTM ← CTM · T`, which is why `Rotate 90 0 0 1` maps object +x to camera +y.
use crate::state::Ri;
use glam::{DMat3, DMat4, DVec3};
use illume_rib::{Request, Span};

/// A RIB `Transform`/`ConcatTransform` array (row-vector order) as a column-vector matrix.
pub fn from_rib(m: &[f32; 16]) -> DMat4 {
    DMat4::from_cols_array(&m.map(f64::from))
}

/// The inverse of [`from_rib`]: glam's column-major array is RIB's row-vector order.
pub fn to_rib(m: &DMat4) -> [f32; 16] {
    m.to_cols_array().map(|x| x as f32)
}

/// `Rotate angle dx dy dz`: right-handed rotation by `angle` degrees about the axis, which in
/// RenderMan's left-handed camera space still takes +x to +y for the z axis.
pub fn rotate(angle_degrees: f32, axis: [f32; 3]) -> Option<DMat4> {
    let axis = DVec3::from(axis.map(f64::from));
    let len = axis.length();
    if len.is_nan() || len <= 0.0 {
        return None;
    }
    Some(DMat4::from_axis_angle(
        axis / len,
        f64::from(angle_degrees).to_radians(),
    ))
}

/// `Skew angle d1 d2` (RI Spec 3.2 `RiSkew`): points move parallel to `d2`, by an amount
/// proportional to their distance from the `d2` axis in the plane of `d1`, such that `d1` turns
/// by `angle` toward `d2`. With θ the angle between d1 and d2 and `n` the unit component of d1
/// perpendicular to d2, the map is `p + k (p·n) d2̂` with `k = cot(θ − angle) − cot θ`;
/// the spec's limits (`angle < θ`, `angle > θ − 180°`) keep the cotangents finite.
pub fn skew(args: &[f32; 7]) -> Result<DMat4, String> {
    let angle = f64::from(args[0]).to_radians();
    let d1 = DVec3::new(args[1].into(), args[2].into(), args[3].into());
    let d2 = DVec3::new(args[4].into(), args[5].into(), args[6].into());
    let (Some(d1), Some(e)) = (d1.try_normalize(), d2.try_normalize()) else {
        return Err("axis vectors must not be zero".into());
    };
    let along = d1.dot(e);
    let perp = d1 - along * e;
    let Some(n) = perp.try_normalize() else {
        return Err("the two axes must not be parallel".into());
    };
    let theta = along.clamp(-1.0, 1.0).acos();
    if angle >= theta || angle <= theta - std::f64::consts::PI {
        return Err(format!(
            "angle {} must lie between {:.3} and {:.3} degrees (the angle between the axes)",
            args[0],
            (theta - std::f64::consts::PI).to_degrees(),
            theta.to_degrees()
        ));
    }
    let cot = |x: f64| x.cos() / x.sin();
    let k = cot(theta - angle) - cot(theta);
    // Column-vector form of p + k (p·n) e: I + k e nᵀ.
    let m = DMat3::IDENTITY + DMat3::from_cols(e * (k * n.x), e * (k * n.y), e * (k * n.z));
    Ok(DMat4::from_mat3(m))
}

/// `Perspective fov`: projects onto the z = 1 plane with `fov` spanning [-1, 1], keeping a
/// monotonic depth `1 − 1/z` in z so points stay ordered.
pub fn perspective(fov_degrees: f32) -> Option<DMat4> {
    let t = (f64::from(fov_degrees).to_radians() * 0.5).tan();
    if !(t > 0.0 && t.is_finite()) {
        return None;
    }
    let d = 1.0 / t;
    Some(DMat4::from_cols_array(&[
        d, 0.0, 0.0, 0.0, //
        0.0, d, 0.0, 0.0, //
        0.0, 0.0, 1.0, 1.0, //
        0.0, 0.0, -1.0, 0.0,
    ]))
}

// ---- the transformation requests in the RI state ---------------------------------------

impl Ri {
    /// The transformation requests of RI Spec 3.2 §4.3 and `CoordinateSystem` (§4.3.1).
    pub(crate) fn transform_request(&mut self, req: Request, span: &Span) {
        let name = req.name().to_string();
        use Request::*;
        match req {
            Identity => {
                self.ctm = self.camera_from_world.unwrap_or(DMat4::IDENTITY);
                self.ctm_motion = self.camera_motion.clone();
            }
            Transform(m) => {
                let m = from_rib(&m);
                self.ctm = self.camera_from_world.unwrap_or(DMat4::IDENTITY) * m;
                self.ctm_motion = self.camera_motion.as_ref().map(|c| c.then(m));
            }
            ConcatTransform(m) => self.concat(from_rib(&m)),
            Perspective(fov) => match perspective(fov) {
                Some(m) => self.concat(m),
                None => self.diagnostics.error(
                    span,
                    &name,
                    format!("fov must lie in (0, 180), found {fov}"),
                ),
            },
            Translate(t) => self.concat(DMat4::from_translation(DVec3::from(t.map(f64::from)))),
            Rotate { angle, axis } => match rotate(angle, axis) {
                Some(m) => self.concat(m),
                None => self.diagnostics.error(span, &name, "the axis is zero"),
            },
            Scale(s) => self.concat(DMat4::from_scale(DVec3::from(s.map(f64::from)))),
            Skew(a) => match skew(&a) {
                Ok(m) => self.concat(m),
                Err(e) => self.diagnostics.error(span, &name, e),
            },
            CoordinateSystem(n) => {
                self.coordinate_systems.insert(n, self.ctm);
            }
            CoordSysTransform(n) => match self.named_space(&n) {
                Some(m) => (self.ctm, self.ctm_motion) = (m, None),
                None => self.diagnostics.error(
                    span,
                    &name,
                    format!("unknown coordinate system \"{n}\""),
                ),
            },
            other => self.diagnostics.error_kind(
                crate::ErrorKind::Bug,
                span,
                other.name(),
                "request not handled here (internal)",
            ),
        }
    }

    pub(crate) fn concat(&mut self, m: DMat4) {
        self.ctm *= m;
        if let Some(mm) = &self.ctm_motion {
            self.ctm_motion = Some(mm.then(m));
        }
    }

    /// Camera from a named space (`camera`, `current`/`object`, `world`, a `CoordinateSystem`
    /// name): what `RiTransformPoints` composes.
    pub fn named_space(&self, name: &str) -> Option<DMat4> {
        match name {
            "camera" => Some(DMat4::IDENTITY),
            "current" | "object" => Some(self.ctm),
            "world" => self.camera_from_world.or(Some(DMat4::IDENTITY)),
            n => self.coordinate_systems.get(n).copied(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotate_90_about_z_maps_x_to_y() {
        let m = rotate(90.0, [0.0, 0.0, 1.0]).unwrap();
        let p = m.transform_point3(DVec3::X);
        assert!((p - DVec3::Y).length() < 1e-12, "{p}");
    }

    #[test]
    fn rib_translation_lives_in_elements_12_to_14() {
        let mut a = [0.0f32; 16];
        a[0] = 1.0;
        a[5] = 1.0;
        a[10] = 1.0;
        a[15] = 1.0;
        a[12] = 3.0;
        a[13] = -2.0;
        a[14] = 5.0;
        let p = from_rib(&a).transform_point3(DVec3::ZERO);
        assert_eq!(p, DVec3::new(3.0, -2.0, 5.0));
        assert_eq!(to_rib(&from_rib(&a)), a);
    }

    #[test]
    fn skew_turns_d1_by_the_angle() {
        // d1 = +y, d2 = +x (90° apart); a 45° skew maps +y to the direction 45° toward +x.
        let m = skew(&[45.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0]).unwrap();
        let p = m.transform_vector3(DVec3::Y).normalize();
        let angle = p.dot(DVec3::Y).acos().to_degrees();
        assert!((angle - 45.0).abs() < 1e-9, "{angle}");
        assert!(p.x > 0.0);
        // points along d2 do not move
        assert!((m.transform_vector3(DVec3::X) - DVec3::X).length() < 1e-12);
        assert!(skew(&[90.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0]).is_err());
    }
}
