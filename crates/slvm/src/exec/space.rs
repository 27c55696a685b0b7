//! Coordinate spaces: `point "space" (…)` casts, the projective spaces, and how a matrix
//! applies to points, vectors and normals.

use super::Exec;
use crate::value::Value;
use glam::{DMat4, Vec3};
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
                let Some(m) = self.env.camera_from(space) else {
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
        match space {
            "screen" => Some(self.env.screen_from_camera.inverse()),
            "NDC" => Some(self.env.ndc_from_camera.inverse()),
            "raster" => Some(self.env.raster_from_camera.inverse()),
            _ => self.env.camera_from(space),
        }
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
