//! §15.2 geometric built-ins: component access (of triples and, for `comp`/`setcomp`, of
//! matrices), lengths and distances, `rotate` of a point, `faceforward`, `reflect`, `refract`,
//! `fresnel`, `transform`/`vtransform`/`ntransform`, `depth`.
use super::{fl, mx, st, tr, Args};
use crate::exec::{apply, Exec};
use crate::geometric;
use crate::value::{zip2, zip3, Value};
use glam::DMat4;
use illume_shade::{faceforward, fresnel, normalize_or_zero, reflect, refract};
use illume_sl::ast::{BuiltinId as B, Global};
use illume_sl::types::BaseType;

impl Exec<'_> {
    /// The geometric family; `None` for an overload the executor does not implement.
    pub(super) fn geometric(&mut self, c: &Args) -> Option<Value> {
        let (a, n) = (c.a, self.n);
        Some(match (c.id, a.len()) {
            (B::XComp | B::YComp | B::ZComp | B::SetXComp | B::SetYComp | B::SetZComp, _)
            | (B::Comp | B::SetComp, _) => self.components(c)?,
            (B::Length, 1) => Value::Float(tr(&a[0]).map(|p| p.as_dvec3().length() as f32)),
            (B::Normalize, 1) => Value::Triple(tr(&a[0]).map(|p| normalize_or_zero(*p))),
            (B::Distance, 2) => Value::Float(zip2(&tr(&a[0]), &tr(&a[1]), n, |p, q| {
                geometric::distance(*p, *q)
            })),
            (B::PtLineD, 3) => {
                Value::Float(zip3(&tr(&a[0]), &tr(&a[1]), &tr(&a[2]), n, |p, q, r| {
                    geometric::ptlined(*p, *q, *r)
                }))
            }
            (B::Rotate, 4) if !matches!(a[0], Value::Matrix(_)) => {
                let qa = zip2(&tr(&a[0]), &fl(&a[1]), n, |q, &x| (*q, x));
                Value::Triple(zip3(&qa, &tr(&a[2]), &tr(&a[3]), n, |(q, ang), p0, p1| {
                    geometric::rotate_point(*q, *ang, *p0, *p1)
                }))
            }
            // `rotate (m, angle, axis)` is §15.4's matrix rotation.
            (B::Rotate, 3) => self.matrix(c)?,
            (B::FaceForward, 2) => {
                let ng = tr(self.global(Global::Ng));
                Value::Triple(zip3(&tr(&a[0]), &tr(&a[1]), &ng, n, |nn, i, ng| {
                    faceforward(*nn, *i, *ng)
                }))
            }
            (B::FaceForward, 3) => {
                Value::Triple(zip3(&tr(&a[0]), &tr(&a[1]), &tr(&a[2]), n, |x, i, r| {
                    faceforward(*x, *i, *r)
                }))
            }
            (B::Reflect, 2) => {
                Value::Triple(zip2(&tr(&a[0]), &tr(&a[1]), n, |i, nn| reflect(*i, *nn)))
            }
            (B::Refract, 3) => {
                Value::Triple(zip3(&tr(&a[0]), &tr(&a[1]), &fl(&a[2]), n, |i, nn, &e| {
                    refract(*i, *nn, e)
                }))
            }
            (B::Fresnel, 5 | 7) => {
                let fr = zip3(&tr(&a[0]), &tr(&a[1]), &fl(&a[2]), n, |i, nn, &e| {
                    fresnel(*i, *nn, e)
                });
                let (exprs, mask) = (c.exprs, c.mask);
                self.write_back(&exprs[3], &Value::Float(fr.map(|f| f.kr)), mask);
                self.write_back(&exprs[4], &Value::Float(fr.map(|f| f.kt)), mask);
                if a.len() == 7 {
                    self.write_back(&exprs[5], &Value::Triple(fr.map(|f| f.r)), mask);
                    self.write_back(&exprs[6], &Value::Triple(fr.map(|f| f.t)), mask);
                }
                Value::Void
            }
            (B::Transform, 2..=3) => self.transform(BaseType::Point, a)?,
            (B::VTransform, 2..=3) => self.transform(BaseType::Vector, a)?,
            (B::NTransform, 2..=3) => self.transform(BaseType::Normal, a)?,
            (B::Depth, 1) => {
                // RI 3.2 §15.2: the camera-space z mapped so the near plane is 0, the far 1. An
                // infinite far plane (the default) gives 0 everywhere, as (z−near)/∞ would.
                let (near, far) = self.env.clipping;
                let range = f64::from(far) - f64::from(near);
                Value::Float(tr(&a[0]).map(move |p| {
                    if range.is_finite() && range > 0.0 {
                        ((f64::from(p.z) - f64::from(near)) / range) as f32
                    } else {
                        0.0
                    }
                }))
            }
            _ => return None,
        })
    }

    /// `xcomp`…`setzcomp`, `comp`, `setcomp` of triples and matrices; the `set` forms write
    /// their first argument back.
    fn components(&mut self, c: &Args) -> Option<Value> {
        let (a, n, exprs, mask) = (c.a, self.n, c.exprs, c.mask);
        Some(match (c.id, a.len()) {
            (B::XComp, 1) => Value::Float(tr(&a[0]).map(|p| p.x)),
            (B::YComp, 1) => Value::Float(tr(&a[0]).map(|p| p.y)),
            (B::ZComp, 1) => Value::Float(tr(&a[0]).map(|p| p.z)),
            (B::SetXComp | B::SetYComp | B::SetZComp, 2) => {
                let k = match c.id {
                    B::SetXComp => 0,
                    B::SetYComp => 1,
                    _ => 2,
                };
                let out = zip2(&tr(&a[0]), &fl(&a[1]), n, |p, &x| {
                    let mut p = *p;
                    p[k] = x;
                    p
                });
                self.write_back(&exprs[0], &Value::Triple(out), mask);
                Value::Void
            }
            (B::Comp, 2) => Value::Float(zip2(&tr(&a[0]), &fl(&a[1]), n, |p, &i| {
                p[(i.max(0.0) as usize).min(2)]
            })),
            (B::Comp, 3) => {
                Value::Float(zip3(&mx(&a[0]), &fl(&a[1]), &fl(&a[2]), n, |m, &r, &c| {
                    geometric::matrix_comp(m, r.max(0.0) as usize, c.max(0.0) as usize)
                }))
            }
            (B::SetComp, 3) => {
                let out = zip3(&tr(&a[0]), &fl(&a[1]), &fl(&a[2]), n, |p, &i, &x| {
                    let mut p = *p;
                    p[(i.max(0.0) as usize).min(2)] = x;
                    p
                });
                self.write_back(&exprs[0], &Value::Triple(out), mask);
                Value::Void
            }
            (B::SetComp, 4) => {
                let rc = zip2(&fl(&a[1]), &fl(&a[2]), n, |&r, &c| (r, c));
                let out = zip3(&mx(&a[0]), &rc, &fl(&a[3]), n, |m, (r, c), &x| {
                    let mut m = *m;
                    geometric::matrix_setcomp(&mut m, r.max(0.0) as usize, c.max(0.0) as usize, x);
                    m
                });
                self.write_back(&exprs[0], &Value::Matrix(out), mask);
                Value::Void
            }
            _ => return None,
        })
    }

    /// `transform([from,] to, p)` and `transform([from,] m, p)` for points, vectors, normals.
    fn transform(&mut self, kind: BaseType, a: &[Value]) -> Option<Value> {
        let n = self.n;
        let p = tr(a.last()?);
        let (from, to): (Option<String>, &Value) = if a.len() == 3 {
            (Some(st(&a[0])), &a[1])
        } else {
            (None, &a[0])
        };
        let current_from_from = match &from {
            Some(s) => match self.current_from(s) {
                Some(m) => m,
                None => {
                    self.problem(format!("transform: unknown space \"{s}\""));
                    return Some(Value::Triple(p));
                }
            },
            None => DMat4::IDENTITY,
        };
        Some(match to {
            Value::Matrix(m) => Value::Triple(zip2(m, &p, n, |m, p| {
                apply(kind, &(*m * current_from_from), *p)
            })),
            v => {
                let space = st(v);
                let Some(to_from_current) = self.to_from_current(&space) else {
                    self.problem(format!("transform: unknown space \"{space}\""));
                    return Some(Value::Triple(p));
                };
                let m = to_from_current * current_from_from;
                Value::Triple(p.map(|p| apply(kind, &m, *p)))
            }
        })
    }
}
