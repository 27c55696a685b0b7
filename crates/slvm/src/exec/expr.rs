//! Expressions: every node evaluates for all grid points at once; a varying `?:` evaluates
//! each side under its half of the mask; user-function calls get their own frame.

use super::vars::{lvalue_of, read_element};
use super::{zero_of, Exec, Frame};
use crate::operators::{self, BinOp};
use crate::value::{zip2, Mask, Slot, Value};
use glam::{DMat4, Vec3};
use illume_sl::ast::{BinaryOp, Callee, Expr, ExprKind, FuncId, Owner, UnaryOp};
use illume_sl::types::{BaseType, Type};

impl Exec<'_> {
    pub(crate) fn eval_float(&mut self, e: &Expr, mask: &Mask) -> Slot<f32> {
        match self.eval(e, mask) {
            Value::Float(s) => s,
            _ => Slot::Uniform(0.0),
        }
    }

    pub(crate) fn eval_triple(&mut self, e: &Expr, mask: &Mask) -> Slot<Vec3> {
        match self.eval(e, mask) {
            Value::Triple(s) => s,
            Value::Float(s) => s.map(|&x| Vec3::splat(x)),
            _ => Slot::Uniform(Vec3::ZERO),
        }
    }

    /// A condition as a float slot (non-zero = true).
    pub(super) fn eval_cond(&mut self, e: &Expr, mask: &Mask) -> Slot<f32> {
        match self.eval(e, mask) {
            Value::Float(s) => s,
            Value::Triple(s) => s.map(|v| (*v != Vec3::ZERO) as u8 as f32),
            Value::String(s) => s.map(|v| (!v.is_empty()) as u8 as f32),
            _ => Slot::Uniform(0.0),
        }
    }

    pub fn eval(&mut self, e: &Expr, mask: &Mask) -> Value {
        let n = self.n;
        match &e.kind {
            ExprKind::Float(x) => Value::float(*x as f32),
            ExprKind::Str(s) => Value::string(s),
            ExprKind::Var(u) => match u.var {
                Some(r) => self.read_var(r),
                None => zero_of(e.ty),
            },
            ExprKind::Tuple(items) => {
                let vals: Vec<Slot<f32>> = items.iter().map(|x| self.eval_float(x, mask)).collect();
                build_tuple(e.ty.base, &vals, n)
            }
            ExprKind::ArrayInit(items) => {
                let elem = e.ty.element();
                Value::Array(
                    items
                        .iter()
                        .map(|x| {
                            let v = self.eval(x, mask);
                            convert_kind(v, elem.base)
                        })
                        .collect(),
                )
            }
            ExprKind::Cast { to, space, expr } => {
                let v = self.eval(expr, mask);
                let v = convert_kind(v, *to);
                match space {
                    None => v,
                    Some(s) => {
                        let space = match self.eval(s, mask) {
                            Value::String(s) => s.at(0).to_string(),
                            _ => String::new(),
                        };
                        self.cast_from_space(*to, &space, v)
                    }
                }
            }
            ExprKind::Promote(x) => {
                let v = self.eval(x, mask);
                convert_kind(v, e.ty.base)
            }
            ExprKind::Unary { op, expr } => {
                let v = self.eval(expr, mask);
                match op {
                    UnaryOp::Neg => operators::negate_owned(v),
                    UnaryOp::Not => operators::not(&v),
                }
                .unwrap_or_else(|| zero_of(e.ty))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.eval(lhs, mask);
                let b = self.eval(rhs, mask);
                operators::binary_owned(binop(*op), a, b, n).unwrap_or_else(|| zero_of(e.ty))
            }
            ExprKind::Ternary {
                cond,
                then,
                otherwise,
            } => {
                let c = self.eval_cond(cond, mask);
                match c {
                    Slot::Uniform(c) => {
                        if c != 0.0 {
                            self.eval(then, mask)
                        } else {
                            self.eval(otherwise, mask)
                        }
                    }
                    Slot::Varying(_) => {
                        let (on, off) = mask.split(&c);
                        let a = self.eval(then, &on);
                        let b = self.eval(otherwise, &off);
                        let mut out = b;
                        out.assign(&a, Some(&on), n);
                        out
                    }
                }
            }
            ExprKind::Assign { op, target, value } => {
                let v = self.eval(value, mask);
                let v = match op.binary() {
                    None => v,
                    Some(bop) => {
                        let cur = self.read_lvalue(target, mask);
                        operators::binary_owned(binop(bop), cur, v.clone(), n).unwrap_or(v)
                    }
                };
                self.write(target, &v, mask);
                v
            }
            ExprKind::Index { array, index } => {
                let a = self.eval(array, mask);
                let idx = self.eval_float(index, mask);
                read_element(&a, &idx, n).unwrap_or_else(|| zero_of(e.ty))
            }
            ExprKind::Call(call) => match &call.callee {
                Some(Callee::User(f)) => self.call_user(*f, &call.args, mask, e.ty),
                Some(Callee::Builtin(b)) => self.call_builtin(b, &call.args, mask, e.ty),
                None => {
                    // Unknown to the checker (another renderer's extension, warned about at
                    // compile time): an error now that it is reached.
                    self.problem(format!(
                        "error: call to unknown function `{}`; it returns 0",
                        call.name
                    ));
                    zero_of(e.ty)
                }
            },
            ExprKind::Texture(t) => self.texture_call(t, mask, e.ty),
            ExprKind::Error => zero_of(e.ty),
        }
    }

    /// A user function call: arguments by value, `output` parameters copied back to the
    /// caller's variables at the running points.
    pub(super) fn call_user(&mut self, fid: FuncId, args: &[Expr], mask: &Mask, ty: Type) -> Value {
        let f = self.prog.function(fid);
        let values: Vec<Value> = args.iter().map(|a| self.eval(a, mask)).collect();
        let mut vars: Vec<Value> = f.vars.iter().map(|v| zero_of(v.ty)).collect();
        for (p, v) in f.params.iter().zip(&values) {
            if let Some(slot) = p.var {
                vars[slot.0 as usize] = v.clone();
            }
        }
        self.frames.push(Frame {
            owner: Owner::Function(fid),
            vars,
            ret: Value::Void,
            returned: Mask::from_bits(vec![false; self.n]),
            loops: Vec::new(),
        });
        self.exec_block(&f.body, mask);
        let frame = self.frames.pop().expect("pushed above");
        for (p, arg) in f.params.iter().zip(args) {
            if !p.output {
                continue;
            }
            let Some(slot) = p.var else { continue };
            let out = frame.vars[slot.0 as usize].clone();
            if let Some(target) = lvalue_of(arg) {
                self.write(&target, &out, mask);
            }
        }
        match frame.ret {
            Value::Void => zero_of(ty),
            v => v,
        }
    }
}

fn binop(op: BinaryOp) -> BinOp {
    match op {
        BinaryOp::Add => BinOp::Add,
        BinaryOp::Sub => BinOp::Sub,
        BinaryOp::Mul => BinOp::Mul,
        BinaryOp::Div => BinOp::Div,
        BinaryOp::Dot => BinOp::Dot,
        BinaryOp::Cross => BinOp::Cross,
        BinaryOp::Eq => BinOp::Eq,
        BinaryOp::Ne => BinOp::Ne,
        BinaryOp::Lt => BinOp::Lt,
        BinaryOp::Le => BinOp::Le,
        BinaryOp::Gt => BinOp::Gt,
        BinaryOp::Ge => BinOp::Ge,
        BinaryOp::And => BinOp::And,
        BinaryOp::Or => BinOp::Or,
    }
}

/// `(a, b, c)` as a triple, `(m00 … m33)` (or one float on the diagonal) as a matrix.
fn build_tuple(base: BaseType, vals: &[Slot<f32>], n: usize) -> Value {
    if base == BaseType::Matrix {
        let all_uniform = vals.iter().all(Slot::is_uniform);
        let at = |i: usize| -> DMat4 {
            if vals.len() == 16 {
                let mut m = [0.0f64; 16];
                for (k, v) in vals.iter().enumerate() {
                    m[k] = *v.at(i) as f64;
                }
                crate::geometric::matrix_from_rows(m)
            } else {
                let x = vals.first().map_or(1.0, |v| *v.at(i)) as f64;
                DMat4::from_diagonal(glam::DVec4::splat(x))
            }
        };
        return Value::Matrix(if all_uniform {
            Slot::Uniform(at(0))
        } else {
            Slot::varying((0..n).map(at).collect())
        });
    }
    let get = |k: usize| vals.get(k).cloned().unwrap_or(Slot::Uniform(0.0));
    let (x, y, z) = (get(0), get(1), get(2));
    if vals.len() == 1 {
        return Value::Triple(x.map(|&v| Vec3::splat(v)));
    }
    let xy = zip2(&x, &y, n, |a, b| (*a, *b));
    Value::Triple(crate::value::zip2(&xy, &z, n, |(a, b), c| {
        Vec3::new(*a, *b, *c)
    }))
}

/// Reinterprets a value as `base`: float → triple/matrix promotion, triple kinds unchanged.
pub(crate) fn convert_kind(v: Value, base: BaseType) -> Value {
    match (v, base) {
        (Value::Float(s), b) if b.is_triple() => Value::Triple(s.map(|&x| Vec3::splat(x))),
        (Value::Float(s), BaseType::Matrix) => {
            Value::Matrix(s.map(|&x| DMat4::from_diagonal(glam::DVec4::splat(x as f64))))
        }
        (v, _) => v,
    }
}
