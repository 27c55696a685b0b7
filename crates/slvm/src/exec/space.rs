//! Coordinate spaces: `point "space" (…)` casts, the projective spaces, and how a matrix
//! applies to points, vectors and normals.

use super::Exec;
use crate::value::Value;
use glam::{DMat4, DVec4, Vec3};
use illume_sl::types::BaseType;

impl Exec<'_> {
    /// `point "space" (…)` and friends: a value given in `space`, converted to current space.
    pub(super) fn cast_from_space(&mut self, to: BaseType, space: &str, v: Value) -> Value {
        match to {
            BaseType::Color => match v {
                Value::Triple(s) => {
                    let ok = crate::colorspaces::to_rgb(space, Vec3::ZERO).is_some();
                    if !ok {
                        self.problem(format!("unknown colour space \"{space}\"; taken as rgb"));
                        return Value::Triple(s);
                    }
                    Value::Triple(s.map(|c| crate::colorspaces::to_rgb(space, *c).unwrap_or(*c)))
                }
                v => v,
            },
            BaseType::Point | BaseType::Vector | BaseType::Normal => {
                let Some(m) = self.current_from(space) else {
                    self.problem(format!("unknown space \"{space}\"; taken as current"));
                    return v;
                };
                match v {
                    Value::Triple(s) => Value::Triple(s.map(|p| apply(to, &m, *p))),
                    v => v,
                }
            }
            BaseType::Matrix => {
                let Some(m) = self.camera_from(space) else {
                    self.problem(format!("unknown space \"{space}\"; taken as current"));
                    return v;
                };
                match v {
                    Value::Matrix(s) => Value::Matrix(s.map(|x| m * *x)),
                    v => v,
                }
            }
            _ => v,
        }
    }

    /// `current_from_space` including the projective spaces (inverted).
    pub(crate) fn current_from(&self, space: &str) -> Option<DMat4> {
        match self.projective_from_current(space) {
            Some(m) => Some(m.inverse()),
            None => self.camera_from(space),
        }
    }

    /// The shading environment's `camera_from_space` for an affine space, with `"eye"` (the
    /// RenderMan Companion's name for camera space: its `slideprojector` defaults `up` to
    /// `point "eye" (0, 1, 0)`) taken as `"camera"`.
    pub(crate) fn camera_from(&self, space: &str) -> Option<DMat4> {
        self.env
            .camera_from(if space == "eye" { "camera" } else { space })
    }

    /// `space_from_current`: the forward projective map for `screen`, `NDC`, `raster` (never
    /// inverted twice), the inverse of [`Self::current_from`] for the affine spaces.
    pub(crate) fn to_from_current(&self, space: &str) -> Option<DMat4> {
        match self.projective_from_current(space) {
            Some(m) => Some(m),
            None => Some(self.camera_from(space)?.inverse()),
        }
    }

    /// The camera → `screen`/`NDC`/`raster` matrix with a depth row, so that it can be
    /// inverted: the shading environment's perspective matrices send `(x, y, z)` to
    /// `(d·x, d·y, z, z)`, whose depth and `w` rows are equal (singular; every inverse was NaN,
    /// so `transform("NDC", P)` gave black). Depth becomes PRMan's screen z, 0 at the near and 1
    /// at the far clipping plane: `f·(z − n) / (z·(f − n))`, `(z − n)/z` for an infinite far plane.
    fn projective_from_current(&self, space: &str) -> Option<DMat4> {
        let mut m = match space {
            "screen" => self.env.screen_from_camera,
            "NDC" => self.env.ndc_from_camera,
            "raster" => self.env.raster_from_camera,
            _ => return None,
        };
        if m.row(3) == DVec4::new(0.0, 0.0, 1.0, 0.0) {
            let near = f64::from(self.env.clipping.0).max(1e-10);
            let far = f64::from(self.env.clipping.1);
            let (a, b) = if far.is_finite() && far > near {
                (far / (far - near), -far * near / (far - near))
            } else {
                (1.0, -near)
            };
            m.x_axis.z = 0.0;
            m.y_axis.z = 0.0;
            m.z_axis.z = a;
            m.w_axis.z = b;
        }
        Some(m)
    }
}

/// Applies `m` to a triple of kind `to`: points (projectively), vectors, normals (inverse
/// transpose).
pub(crate) fn apply(to: BaseType, m: &DMat4, p: Vec3) -> Vec3 {
    let d = p.as_dvec3();
    match to {
        BaseType::Point => m.project_point3(d).as_vec3(),
        BaseType::Vector => m.transform_vector3(d).as_vec3(),
        BaseType::Normal => m.inverse().transpose().transform_vector3(d).as_vec3(),
        _ => p,
    }
}
