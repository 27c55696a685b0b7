//! The built-in functions of RI 3.2 chapter 15 over grid values, dispatched by the
//! [`BuiltinId`] the checker resolved and its [`Family`]: one file per family (`math`,
//! `noise`, `derivative`, `geometric`, `color`, `matrix`, `strings`, `shading`, `message`,
//! `texture`), so no name is compared at run time. Uniform arguments give uniform results
//! (one evaluation per grid); the per-point kernels live in the crate's kernel modules
//! (`mathfunctions`, `noise`, …) or in `illume_shade` where the built-in shaders already use
//! them (so both agree bit for bit).
mod bump;
mod color;
mod derivative;
mod geometric;
mod math;
mod matrix;
mod message;
mod noise;
mod shading;
mod strings;
mod texture;

use crate::exec::{zero_of, Exec};
use crate::value::{zip2, zip3, Mask, Slot, Value};
use glam::{DMat4, Vec3};
use illume_sl::ast::{BuiltinCall, BuiltinId, Expr, Family};
use illume_sl::types::{BaseType, Type};

/// One evaluated built-in call, as the family implementations see it.
pub(crate) struct Args<'c> {
    /// The built-in.
    id: BuiltinId,
    /// The return type the checker chose (float or triple for `noise`-like calls).
    ret: BaseType,
    /// The positional argument values (optional `"name", value` pairs excluded).
    a: &'c [Value],
    /// The argument expressions, for writing `output` arguments back.
    exprs: &'c [Expr],
    /// The running points.
    mask: &'c Mask,
}

impl Exec<'_> {
    pub(crate) fn call_builtin(
        &mut self,
        call: &BuiltinCall,
        args: &[Expr],
        mask: &Mask,
        ty: Type,
    ) -> Value {
        // Optional "name", value pairs (filterstep's "width", …) are not positional arguments.
        let positional = &args[..call.optional_from.unwrap_or(args.len()).min(args.len())];
        let vals: Vec<Value> = positional.iter().map(|a| self.eval(a, mask)).collect();
        let c = Args {
            id: call.id,
            ret: ty.base,
            a: &vals,
            exprs: positional,
            mask,
        };
        let result = match call.id.family() {
            Family::Math => self.math(&c),
            Family::Noise => self.noise(&c),
            Family::Derivative => self.derivative(&c),
            Family::Geometric => self.geometric(&c),
            Family::Color => self.color(&c),
            Family::Matrix => self.matrix(&c),
            Family::String => self.strings(&c),
            Family::Shading => self.shading(&c),
            Family::Message => self.message(&c),
        };
        match result {
            Some(v) => v,
            None => {
                self.problem(format!(
                    "built-in `{}` is not implemented by the executor; it returns 0",
                    call.id.name()
                ));
                zero_of(ty)
            }
        }
    }
}

/// A float argument (anything else reads as 0).
fn fl(v: &Value) -> Slot<f32> {
    match v {
        Value::Float(s) => s.clone(),
        _ => Slot::Uniform(0.0),
    }
}

/// A triple argument (a float is splatted).
fn tr(v: &Value) -> Slot<Vec3> {
    match v {
        Value::Triple(s) => s.clone(),
        Value::Float(s) => s.map(|&x| Vec3::splat(x)),
        _ => Slot::Uniform(Vec3::ZERO),
    }
}

/// A matrix argument (anything else reads as the identity).
fn mx(v: &Value) -> Slot<DMat4> {
    match v {
        Value::Matrix(s) => s.clone(),
        _ => Slot::Uniform(DMat4::IDENTITY),
    }
}

/// A uniform string argument (SL names of spaces, maps, bases are uniform in practice; a
/// varying one is read at the first point).
fn st(v: &Value) -> String {
    match v {
        Value::String(s) => s.at(0).to_string(),
        _ => String::new(),
    }
}

/// `f` on a float, component-wise on a triple.
fn unary(v: &Value, f: impl Fn(f32) -> f32) -> Value {
    match v {
        Value::Triple(s) => Value::Triple(s.map(|p| Vec3::new(f(p.x), f(p.y), f(p.z)))),
        v => Value::Float(fl(v).map(|&x| f(x))),
    }
}

/// `f` on two floats, component-wise when either is a triple.
fn binary(a: &Value, b: &Value, n: usize, f: impl Fn(f32, f32) -> f32) -> Value {
    match (a, b) {
        (Value::Float(x), Value::Float(y)) => Value::Float(zip2(x, y, n, |&x, &y| f(x, y))),
        _ => Value::Triple(zip2(&tr(a), &tr(b), n, |p, q| {
            Vec3::new(f(p.x, q.x), f(p.y, q.y), f(p.z, q.z))
        })),
    }
}

/// `f` on three floats, component-wise when any is a triple.
fn ternary(a: &Value, b: &Value, c: &Value, n: usize, f: impl Fn(f32, f32, f32) -> f32) -> Value {
    match (a, b, c) {
        (Value::Float(x), Value::Float(y), Value::Float(z)) => {
            Value::Float(zip3(x, y, z, n, |&x, &y, &z| f(x, y, z)))
        }
        _ => Value::Triple(zip3(&tr(a), &tr(b), &tr(c), n, |p, q, r| {
            Vec3::new(f(p.x, q.x, r.x), f(p.y, q.y, r.y), f(p.z, q.z, r.z))
        })),
    }
}
