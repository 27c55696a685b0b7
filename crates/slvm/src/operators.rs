//! The Shading Language operators over grid values (RI 3.2 §11.3): arithmetic on floats,
//! triples (component-wise) and matrices, `^` (cross product), `.` (dot product), comparisons
//! and logic giving floats 0/1. Mixed float/triple operands are promoted here as the language
//! does (the checker may also have made the promotion explicit; both work).
use crate::geometric::{matrix_inverse, matrix_mul};
use crate::value::{zip2, zip2_owned, Slot, Value};
use glam::{DMat4, Vec3};
use std::sync::Arc;

/// A binary operator by its SL spelling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    /// `^`: cross product of triples.
    Cross,
    /// `.`: dot product of triples.
    Dot,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    And,
    Or,
}

/// Float division that stays finite: SL programs divide by `L·L` and lengths that can be 0;
/// PRMan returns 0 there rather than infinity, and so do we.
#[inline]
fn fdiv(a: f32, b: f32) -> f32 {
    if b == 0.0 {
        0.0
    } else {
        a / b
    }
}

#[inline]
fn vdiv(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(fdiv(a.x, b.x), fdiv(a.y, b.y), fdiv(a.z, b.z))
}

fn b2f(b: bool) -> f32 {
    if b {
        1.0
    } else {
        0.0
    }
}

fn float_op(op: BinOp, a: f32, b: f32) -> f32 {
    match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul | BinOp::Dot => a * b,
        BinOp::Div => fdiv(a, b),
        BinOp::Cross => 0.0,
        BinOp::Lt => b2f(a < b),
        BinOp::Le => b2f(a <= b),
        BinOp::Gt => b2f(a > b),
        BinOp::Ge => b2f(a >= b),
        BinOp::Eq => b2f(a == b),
        BinOp::Ne => b2f(a != b),
        BinOp::And => b2f(a != 0.0 && b != 0.0),
        BinOp::Or => b2f(a != 0.0 || b != 0.0),
    }
}

/// Triple results of triple operands; `None` for the float-valued ones.
fn triple_op(op: BinOp, a: Vec3, b: Vec3) -> Vec3 {
    match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div => vdiv(a, b),
        BinOp::Cross => a.cross(b),
        _ => Vec3::ZERO,
    }
}

fn triple_to_float(op: BinOp, a: Vec3, b: Vec3) -> f32 {
    match op {
        BinOp::Dot => a.dot(b),
        BinOp::Eq => b2f(a == b),
        BinOp::Ne => b2f(a != b),
        _ => 0.0,
    }
}

fn splat(s: &Slot<f32>) -> Slot<Vec3> {
    s.map(|&x| Vec3::splat(x))
}

/// `a op b` over an `n`-point grid; `None` when the operand kinds do not combine.
pub fn binary(op: BinOp, a: &Value, b: &Value, n: usize) -> Option<Value> {
    use Value::*;
    let float_valued = matches!(
        op,
        BinOp::Dot | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge | BinOp::Eq | BinOp::Ne
    ) || matches!(op, BinOp::And | BinOp::Or);
    Some(match (a, b) {
        (Float(x), Float(y)) => Float(zip2(x, y, n, |&x, &y| float_op(op, x, y))),
        (Triple(x), Triple(y)) if float_valued => {
            Float(zip2(x, y, n, |&x, &y| triple_to_float(op, x, y)))
        }
        (Triple(x), Triple(y)) => Triple(zip2(x, y, n, |&x, &y| triple_op(op, x, y))),
        (Float(x), Triple(_)) => return binary(op, &Triple(splat(x)), b, n),
        (Triple(_), Float(y)) => return binary(op, a, &Triple(splat(y)), n),
        (Matrix(x), Matrix(y)) => match op {
            BinOp::Mul => Matrix(zip2(x, y, n, matrix_mul)),
            BinOp::Div => Matrix(zip2(x, y, n, |x, y| matrix_mul(x, &matrix_inverse(y)))),
            BinOp::Add => Matrix(zip2(x, y, n, |x, y| *x + *y)),
            BinOp::Sub => Matrix(zip2(x, y, n, |x, y| *x - *y)),
            BinOp::Eq => Float(zip2(x, y, n, |x, y| b2f(x == y))),
            BinOp::Ne => Float(zip2(x, y, n, |x, y| b2f(x != y))),
            _ => return None,
        },
        (Float(x), Matrix(y)) => scalar_matrix(op, x, y, n, false)?,
        (Matrix(y), Float(x)) => scalar_matrix(op, x, y, n, true)?,
        (String(x), String(y)) => match op {
            BinOp::Eq => Float(zip2(x, y, n, |x, y| b2f(x == y))),
            BinOp::Ne => Float(zip2(x, y, n, |x, y| b2f(x != y))),
            _ => return None,
        },
        _ => return None,
    })
}

/// [`binary`] on operands the caller gives up: the result is written into an operand's lanes
/// when they are not shared (a temporary such as `Kd*diffuse(Nf)`'s `diffuse(Nf)`), so a
/// chain of arithmetic allocates nothing after its first varying node. Same bits as [`binary`]:
/// the per-point kernels are the same functions.
pub fn binary_owned(op: BinOp, a: Value, b: Value, n: usize) -> Option<Value> {
    use Value::*;
    let float_valued = matches!(
        op,
        BinOp::Dot | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge | BinOp::Eq | BinOp::Ne
    ) || matches!(op, BinOp::And | BinOp::Or);
    Some(match (a, b) {
        (Float(x), Float(y)) => Float(zip_reuse(x, y, n, |&x, &y| float_op(op, x, y))),
        (Triple(x), Triple(y)) if !float_valued => {
            Triple(zip_reuse(x, y, n, |&x, &y| triple_op(op, x, y)))
        }
        (Float(x), Triple(y)) if !float_valued && unshared(&y) => {
            Triple(zip2_owned(y, &x, n, |&t, &f| {
                triple_op(op, Vec3::splat(f), t)
            }))
        }
        (Triple(x), Float(y)) if !float_valued && unshared(&x) => {
            Triple(zip2_owned(x, &y, n, |&t, &f| {
                triple_op(op, t, Vec3::splat(f))
            }))
        }
        (a, b) => return binary(op, &a, &b, n),
    })
}

/// Whether `s` has per-point lanes no one else holds (so they can be overwritten).
fn unshared<T>(s: &Slot<T>) -> bool {
    matches!(s, Slot::Varying(v) if Arc::strong_count(v) == 1 && Arc::weak_count(v) == 0)
}

/// `f(a, b)` into `a`'s lanes, or else `b`'s, when unshared; a new allocation otherwise.
fn zip_reuse<T: Clone>(a: Slot<T>, b: Slot<T>, n: usize, f: impl Fn(&T, &T) -> T) -> Slot<T> {
    if !unshared(&a) && unshared(&b) {
        return zip2_owned(b, &a, n, |y, x| f(x, y));
    }
    zip2_owned(a, &b, n, f)
}

/// `f * m`, `m * f`, `m / f`, `f / m` (= `f · inverse(m)`): a float is the scaled identity.
fn scalar_matrix(
    op: BinOp,
    f: &Slot<f32>,
    m: &Slot<DMat4>,
    n: usize,
    matrix_left: bool,
) -> Option<Value> {
    let fm = f.map(|&x| DMat4::from_diagonal(glam::DVec4::splat(x as f64)));
    let (a, b) = if matrix_left {
        (Value::Matrix(m.clone()), Value::Matrix(fm))
    } else {
        (Value::Matrix(fm), Value::Matrix(m.clone()))
    };
    match op {
        BinOp::Mul | BinOp::Div => binary(op, &a, &b, n),
        _ => None,
    }
}

/// Unary minus.
pub fn negate(a: &Value) -> Option<Value> {
    Some(match a {
        Value::Float(x) => Value::Float(x.map(|&x| -x)),
        Value::Triple(x) => Value::Triple(x.map(|&x| -x)),
        Value::Matrix(x) => Value::Matrix(x.map(|&x| -x)),
        _ => return None,
    })
}

/// [`negate`] in place when the operand's lanes are unshared.
pub fn negate_owned(a: Value) -> Option<Value> {
    Some(match a {
        Value::Float(x) => Value::Float(x.map_owned(|&x| -x)),
        Value::Triple(x) => Value::Triple(x.map_owned(|&x| -x)),
        a => return negate(&a),
    })
}

/// Logical not.
pub fn not(a: &Value) -> Option<Value> {
    match a {
        Value::Float(x) => Some(Value::Float(x.map(|&x| b2f(x == 0.0)))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: Vec3) -> Value {
        Value::triple(x)
    }

    #[test]
    fn cross_and_dot_follow_the_right_hand_rule() {
        let c = binary(BinOp::Cross, &v(Vec3::X), &v(Vec3::Y), 1).unwrap();
        assert_eq!(c, v(Vec3::Z));
        let d = binary(BinOp::Dot, &v(Vec3::new(1.0, 2.0, 3.0)), &v(Vec3::ONE), 1).unwrap();
        assert_eq!(d, Value::float(6.0));
    }

    #[test]
    fn float_promotes_to_triple() {
        let r = binary(
            BinOp::Mul,
            &Value::float(2.0),
            &v(Vec3::new(1.0, 2.0, 3.0)),
            1,
        )
        .unwrap();
        assert_eq!(r, v(Vec3::new(2.0, 4.0, 6.0)));
        let r = binary(BinOp::Sub, &v(Vec3::ONE), &Value::float(1.0), 1).unwrap();
        assert_eq!(r, v(Vec3::ZERO));
    }

    #[test]
    fn division_by_zero_is_zero_not_infinite() {
        assert_eq!(
            binary(BinOp::Div, &Value::float(1.0), &Value::float(0.0), 1),
            Some(Value::float(0.0))
        );
    }

    #[test]
    fn comparisons_are_varying_when_an_operand_is() {
        let a = Value::Float(Slot::varying(vec![1.0, 3.0]));
        let r = binary(BinOp::Lt, &a, &Value::float(2.0), 2).unwrap();
        assert_eq!(r, Value::Float(Slot::varying(vec![1.0, 0.0])));
        assert_eq!(
            not(&r).unwrap(),
            Value::Float(Slot::varying(vec![0.0, 1.0]))
        );
    }

    #[test]
    fn matrix_division_is_multiplication_by_the_inverse() {
        let m = crate::geometric::scale(&DMat4::IDENTITY, Vec3::splat(2.0));
        let r = binary(
            BinOp::Div,
            &Value::Matrix(Slot::Uniform(m)),
            &Value::Matrix(Slot::Uniform(m)),
            1,
        )
        .unwrap();
        let Value::Matrix(Slot::Uniform(r)) = r else {
            panic!("matrix expected")
        };
        assert!(r.abs_diff_eq(DMat4::IDENTITY, 1e-12));
        let r = binary(
            BinOp::Mul,
            &Value::float(3.0),
            &Value::Matrix(Slot::Uniform(DMat4::IDENTITY)),
            1,
        )
        .unwrap();
        assert_eq!(
            r,
            Value::Matrix(Slot::Uniform(DMat4::from_diagonal(glam::DVec4::splat(3.0))))
        );
    }
}
