//! §15.4 matrix built-ins: `determinant`, `translate`, `rotate` and `scale` of a matrix.
use super::{fl, mx, tr, Args};
use crate::exec::Exec;
use crate::geometric;
use crate::value::{zip2, zip3, Value};
use illume_sl::ast::BuiltinId as B;

impl Exec<'_> {
    /// The matrix family (also `rotate (m, angle, axis)`, whose id is the point `rotate`'s);
    /// `None` for an overload the executor does not implement.
    pub(super) fn matrix(&mut self, c: &Args) -> Option<Value> {
        let (a, n) = (c.a, self.n);
        Some(match (c.id, a.len()) {
            (B::Determinant, 1) => Value::Float(mx(&a[0]).map(|m| m.determinant() as f32)),
            (B::Translate, 2) => Value::Matrix(zip2(&mx(&a[0]), &tr(&a[1]), n, |m, t| {
                geometric::translate(m, *t)
            })),
            (B::Scale, 2) => Value::Matrix(zip2(&mx(&a[0]), &tr(&a[1]), n, |m, s| {
                geometric::scale(m, *s)
            })),
            (B::Rotate, 3) => {
                Value::Matrix(zip3(&mx(&a[0]), &fl(&a[1]), &tr(&a[2]), n, |m, &x, ax| {
                    geometric::rotate(m, x, *ax)
                }))
            }
            _ => return None,
        })
    }
}
