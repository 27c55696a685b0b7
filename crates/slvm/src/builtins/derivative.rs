//! Built-ins computed from differences across the grid: `Du`, `Dv`, `Deriv`, `filterstep`
//! (whose filter width is the change of its argument over one grid step), `area` and
//! `calculatenormal`.
use super::{binary, fl, tr, Args};
use crate::exec::Exec;
use crate::mathfunctions as mf;
use crate::value::{zip2, zip3, Slot, Value};
use glam::Vec3;
use illume_sl::ast::{BuiltinId as B, Global};

impl Exec<'_> {
    /// The derivative family; `None` for an overload the executor does not implement.
    pub(super) fn derivative(&mut self, c: &Args) -> Option<Value> {
        let (a, n) = (c.a, self.n);
        Some(match (c.id, a.len()) {
            (B::FilterStep, 2) => {
                let x = fl(&a[1]);
                let w = self.filter_width(&x);
                Value::Float(zip3(&fl(&a[0]), &x, &w, n, |&e, &x, &w| {
                    mf::filterstep(e, x, w)
                }))
            }
            (B::FilterStep, 3) => {
                // filterstep(edge, s0, s1): the fraction of [s0, s1] at or above the edge.
                Value::Float(zip3(
                    &fl(&a[0]),
                    &fl(&a[1]),
                    &fl(&a[2]),
                    n,
                    |&e, &x0, &x1| {
                        let (lo, hi) = (x0.min(x1), x0.max(x1));
                        mf::filterstep(e, 0.5 * (lo + hi), hi - lo)
                    },
                ))
            }
            (B::CalculateNormal, 1) => {
                let p = tr(&a[0]);
                let du = tr(&self.deriv(&Value::Triple(p.clone()), true));
                let dv = tr(&self.deriv(&Value::Triple(p), false));
                let ng = tr(self.global(Global::Ng));
                let c = zip2(&du, &dv, n, |a, b| a.cross(*b));
                // Oriented like Ng so that sidedness survives (as ShadingGrid::calculatenormal).
                Value::Triple(zip2(
                    &c,
                    &ng,
                    n,
                    |c, ng| if c.dot(*ng) < 0.0 { -*c } else { *c },
                ))
            }
            (B::Area, 1) => {
                let p = Value::Triple(tr(&a[0]));
                let (du, dv) = (tr(&self.deriv(&p, true)), tr(&self.deriv(&p, false)));
                let (gdu, gdv) = (self.grid.du, self.grid.dv);
                Value::Float(zip2(&du, &dv, n, |a, b| a.cross(*b).length() * gdu * gdv))
            }
            (B::Du, 1) => self.deriv(&a[0], true),
            (B::Dv, 1) => self.deriv(&a[0], false),
            (B::Deriv, 2) => {
                // Deriv(num, den) = Du(num)/Du(den) + Dv(num)/Dv(den) (RI 3.2 §15.2).
                let (nu, nv) = (self.deriv(&a[0], true), self.deriv(&a[0], false));
                let (du, dv) = (self.deriv(&a[1], true), self.deriv(&a[1], false));
                let div = |x: f32, y: f32| if y == 0.0 { 0.0 } else { x / y };
                let u = binary(&nu, &du, n, div);
                let v = binary(&nv, &dv, n, div);
                binary(&u, &v, n, |x, y| x + y)
            }
            _ => return None,
        })
    }

    /// `Du`/`Dv` of a float or triple, by grid differences.
    fn deriv(&self, v: &Value, along_u: bool) -> Value {
        let g = self.grid;
        match v {
            Value::Float(Slot::Varying(x)) => Value::Float(Slot::varying(if along_u {
                g.deriv_u(x)
            } else {
                g.deriv_v(x)
            })),
            Value::Triple(Slot::Varying(x)) => Value::Triple(Slot::varying(if along_u {
                g.deriv_u(x)
            } else {
                g.deriv_v(x)
            })),
            Value::Triple(_) => Value::triple(Vec3::ZERO),
            _ => Value::float(0.0),
        }
    }

    /// `filterstep`'s width: the change of `x` over one grid step in u plus one in v.
    fn filter_width(&self, x: &Slot<f32>) -> Slot<f32> {
        let (g, n) = (self.grid, self.n);
        match x {
            Slot::Uniform(_) => Slot::Uniform(0.0),
            Slot::Varying(v) => {
                let (du, dv) = (g.deriv_u(v), g.deriv_v(v));
                Slot::varying(
                    (0..n)
                        .map(|i| (du[i] * g.du).abs() + (dv[i] * g.dv).abs())
                        .collect(),
                )
            }
        }
    }
}
