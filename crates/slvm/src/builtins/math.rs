//! §15.1 mathematical built-ins of one point at a time, mapped over the grid: trigonometry,
//! powers, rounding, `min`/`max`/`clamp`/`mix`, `step`/`smoothstep`, and `spline`.
use super::{binary, fl, ternary, tr, unary, Args};
use crate::exec::Exec;
use crate::mathfunctions as mf;
use crate::spline;
use crate::value::{zip2, Slot, Value};
use illume_sl::ast::BuiltinId as B;
use illume_sl::types::BaseType;

impl Exec<'_> {
    /// The math family; `None` for an overload the executor does not implement.
    pub(super) fn math(&mut self, c: &Args) -> Option<Value> {
        let (a, n) = (c.a, self.n);
        Some(match (c.id, a.len()) {
            (B::Radians, 1) => unary(&a[0], f32::to_radians),
            (B::Degrees, 1) => unary(&a[0], f32::to_degrees),
            (B::Sin, 1) => unary(&a[0], f32::sin),
            (B::Cos, 1) => unary(&a[0], f32::cos),
            (B::Tan, 1) => unary(&a[0], f32::tan),
            (B::Asin, 1) => unary(&a[0], f32::asin),
            (B::Acos, 1) => unary(&a[0], f32::acos),
            (B::Atan, 1) => unary(&a[0], f32::atan),
            (B::Atan, 2) => binary(&a[0], &a[1], n, f32::atan2),
            (B::Pow, 2) => binary(&a[0], &a[1], n, f32::powf),
            (B::Exp, 1) => unary(&a[0], f32::exp),
            (B::Sqrt, 1) => unary(&a[0], f32::sqrt),
            (B::InverseSqrt, 1) => unary(&a[0], mf::inversesqrt),
            (B::Log, 1) => unary(&a[0], f32::ln),
            (B::Log, 2) => binary(&a[0], &a[1], n, mf::log_base),
            (B::Mod, 2) => binary(&a[0], &a[1], n, mf::sl_mod),
            (B::Abs, 1) => unary(&a[0], f32::abs),
            (B::Sign, 1) => unary(&a[0], mf::sign),
            (B::Floor, 1) => unary(&a[0], f32::floor),
            (B::Ceil, 1) => unary(&a[0], f32::ceil),
            (B::Round, 1) => unary(&a[0], mf::round),
            (B::Min, k) if k >= 1 => a[1..]
                .iter()
                .fold(a[0].clone(), |acc, x| binary(&acc, x, n, f32::min)),
            (B::Max, k) if k >= 1 => a[1..]
                .iter()
                .fold(a[0].clone(), |acc, x| binary(&acc, x, n, f32::max)),
            (B::Clamp, 3) => ternary(&a[0], &a[1], &a[2], n, mf::clamp),
            (B::Step, 2) => binary(&a[0], &a[1], n, mf::step),
            (B::SmoothStep, 3) => ternary(&a[0], &a[1], &a[2], n, illume_shade::smoothstep),
            (B::Mix, 3) => match (&a[0], &a[1], &a[2]) {
                (Value::Float(_), Value::Float(_), _) | (_, _, Value::Triple(_)) => {
                    ternary(&a[0], &a[1], &a[2], n, |x, y, t| x * (1.0 - t) + y * t)
                }
                _ => {
                    let t = fl(&a[2]);
                    let xy = zip2(&tr(&a[0]), &tr(&a[1]), n, |x, y| (*x, *y));
                    Value::Triple(zip2(&xy, &t, n, |(x, y), &t| *x * (1.0 - t) + *y * t))
                }
            },
            (B::Spline, k) if k >= 2 => self.spline(c.ret, a)?,
            _ => return None,
        })
    }

    /// `spline([basis,] t, knots…)` and `spline([basis,] t, knots[])`; an unknown basis is
    /// reported and taken as Catmull-Rom.
    fn spline(&mut self, ret: BaseType, a: &[Value]) -> Option<Value> {
        let n = self.n;
        let (basis, rest) = match &a[0] {
            Value::String(s) => {
                let name = s.at(0).to_string();
                match spline::Basis::from_name(&name) {
                    Some(b) => (b, &a[1..]),
                    None => {
                        self.problem(format!("spline: unknown basis \"{name}\"; catmull-rom"));
                        (spline::Basis::CatmullRom, &a[1..])
                    }
                }
            }
            _ => (spline::Basis::CatmullRom, a),
        };
        let t = fl(rest.first()?);
        let knots: Vec<Value> = match rest.get(1..)? {
            [Value::Array(items)] => items.clone(),
            k => k.to_vec(),
        };
        Some(if ret == BaseType::Float {
            let ks: Vec<Slot<f32>> = knots.iter().map(fl).collect();
            let uniform = t.is_uniform() && ks.iter().all(Slot::is_uniform);
            let at = |i: usize| {
                let k: Vec<f32> = ks.iter().map(|s| *s.at(i)).collect();
                spline::spline(basis, *t.at(i), &k)
            };
            Value::Float(if uniform {
                Slot::Uniform(at(0))
            } else {
                Slot::varying((0..n).map(at).collect())
            })
        } else {
            let ks: Vec<Slot<glam::Vec3>> = knots.iter().map(tr).collect();
            let uniform = t.is_uniform() && ks.iter().all(Slot::is_uniform);
            let at = |i: usize| {
                let k: Vec<glam::Vec3> = ks.iter().map(|s| *s.at(i)).collect();
                spline::spline(basis, *t.at(i), &k)
            };
            Value::Triple(if uniform {
                Slot::Uniform(at(0))
            } else {
                Slot::varying((0..n).map(at).collect())
            })
        })
    }
}
