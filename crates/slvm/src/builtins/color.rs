//! §15.3 colour built-ins: `ctransform` between the colour spaces of [`crate::colorspaces`].
use super::{st, tr, Args};
use crate::colorspaces;
use crate::exec::Exec;
use crate::value::Value;
use glam::Vec3;
use illume_sl::ast::BuiltinId as B;

impl Exec<'_> {
    /// The colour family; `None` for an overload the executor does not implement.
    pub(super) fn color(&mut self, c: &Args) -> Option<Value> {
        let a = c.a;
        Some(match (c.id, a.len()) {
            (B::CTransform, 2) => {
                let to = st(&a[0]);
                self.color_convert("rgb", &to, &a[1])
            }
            (B::CTransform, 3) => {
                let (from, to) = (st(&a[0]), st(&a[1]));
                self.color_convert(&from, &to, &a[2])
            }
            _ => return None,
        })
    }

    /// `c` converted from space `from` to `to`; an unknown space is reported and `c` returned.
    fn color_convert(&mut self, from: &str, to: &str, c: &Value) -> Value {
        if colorspaces::ctransform(from, to, Vec3::ZERO).is_none() {
            self.problem(format!(
                "ctransform: unknown colour space \"{from}\" or \"{to}\""
            ));
            return c.clone();
        }
        Value::Triple(tr(c).map(|c| colorspaces::ctransform(from, to, *c).unwrap_or(*c)))
    }
}
