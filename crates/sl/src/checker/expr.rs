//! Expressions: literals, variables, casts, operators and assignments, with the implicit
//! conversions made explicit.

use super::overload::conversion_cost;
use super::{unknown, wrap, Checker};
use crate::ast::*;
use crate::builtins;
use crate::span::Span;
use crate::types::{BaseType, Type};

impl Checker<'_> {
    // ----- expressions ----------------------------------------------------------------------

    /// Converts `e` to `to`, inserting an explicit promotion or cast, or reports `what:
    /// expected …, found …`.
    pub(super) fn coerce(&mut self, e: &mut Expr, to: Type, what: &str) {
        if unknown(e.ty) || unknown(to) || e.ty == to {
            return;
        }
        match conversion_cost(e.ty, to) {
            Some(0) => {}
            Some(1) => wrap(e, to, ExprKind::Promote),
            Some(_) => wrap(e, to, |inner| ExprKind::Cast {
                to: to.base,
                space: None,
                expr: inner,
            }),
            None => {
                let found = e.ty;
                self.error(e.span, format!("{what}: expected {to}, found {found}"));
            }
        }
    }

    pub(super) fn expr(&mut self, e: &mut Expr, expected: Option<BaseType>) {
        let span = e.span;
        let ty = match &mut e.kind {
            ExprKind::Float(_) => Type::FLOAT,
            ExprKind::Str(_) => Type::STRING,
            ExprKind::Var(v) => {
                if v.name == "PI"
                    && self
                        .frames
                        .last()
                        .is_some_and(|f| !f.scopes.iter().any(|s| s.contains_key("PI")))
                {
                    e.kind = ExprKind::Float(builtins::PI);
                    Type::FLOAT
                } else {
                    v.var = self.lookup(&v.name.clone(), span);
                    v.var.map_or(Type::UNKNOWN, |r| self.var_type(r))
                }
            }
            ExprKind::Tuple(elems) => {
                let want = match (expected, elems.len()) {
                    (Some(b), 3) if b.is_triple() => b,
                    (_, 3) => BaseType::Point,
                    (_, 16) => BaseType::Matrix,
                    (_, n) => {
                        self.error(
                            span,
                            format!("expected 3 or 16 components in parentheses, found {n}"),
                        );
                        BaseType::Unknown
                    }
                };
                for el in elems.iter_mut() {
                    self.expr(el, Some(BaseType::Float));
                    self.coerce(el, Type::FLOAT, "component");
                }
                Type::scalar(want)
            }
            ExprKind::ArrayInit(elems) => {
                let base = expected.unwrap_or(BaseType::Float);
                for el in elems.iter_mut() {
                    self.expr(el, Some(base));
                    self.coerce(el, Type::scalar(base), "array element");
                }
                Type::array(base, elems.len() as u32)
            }
            ExprKind::Cast { to, space, expr } => self.cast(*to, space.as_deref_mut(), expr),
            ExprKind::Promote(inner) => {
                self.expr(inner, None);
                e.ty
            }
            ExprKind::Unary { op, expr } => {
                self.expr(expr, expected);
                match op {
                    UnaryOp::Neg => {
                        let t = expr.ty;
                        if !unknown(t)
                            && (t.is_array() || matches!(t.base, BaseType::String | BaseType::Void))
                        {
                            self.error(span, format!("cannot negate a {t}"));
                            Type::UNKNOWN
                        } else {
                            t
                        }
                    }
                    UnaryOp::Not => {
                        self.coerce(expr, Type::FLOAT, "operand of '!'");
                        Type::FLOAT
                    }
                }
            }
            ExprKind::Binary { op, lhs, rhs } => self.binary(span, *op, lhs, rhs, expected),
            ExprKind::Ternary {
                cond,
                then,
                otherwise,
            } => {
                self.condition(cond, "'?:'");
                self.expr(then, expected);
                self.expr(otherwise, expected.or(Some(then.ty.base)));
                self.unify(then, otherwise)
            }
            ExprKind::Assign { op, target, value } => self.assign(*op, target, value),
            ExprKind::Index { array, index } => {
                self.expr(array, None);
                self.expr(index, Some(BaseType::Float));
                self.coerce(index, Type::FLOAT, "array index");
                if unknown(array.ty) {
                    Type::UNKNOWN
                } else if !array.ty.is_array() {
                    self.error(
                        span,
                        format!("cannot index a {}: it is not an array", array.ty),
                    );
                    Type::UNKNOWN
                } else {
                    array.ty.element()
                }
            }
            ExprKind::Call(call) => self.call(span, call, expected),
            ExprKind::Texture(tc) => self.texture(span, tc, expected),
            ExprKind::Error => Type::UNKNOWN,
        };
        e.ty = ty;
    }

    pub(super) fn cast(
        &mut self,
        to: BaseType,
        space: Option<&mut Expr>,
        expr: &mut Box<Expr>,
    ) -> Type {
        self.expr(expr, Some(to));
        if let Some(s) = space {
            self.expr(s, Some(BaseType::String));
            self.coerce(s, Type::STRING, "space name");
            if !(to.is_triple() || to == BaseType::Matrix) {
                self.error(s.span, format!("a {to} cast cannot name a space"));
            }
        }
        let from = expr.ty;
        if unknown(from) {
            return Type::scalar(to);
        }
        let ok = from.array.is_none()
            && (from.base == to
                || (from.base == BaseType::Float && (to.is_triple() || to == BaseType::Matrix))
                || (from.base.is_triple() && to.is_triple()));
        if !ok {
            let span = expr.span;
            self.error(span, format!("cannot cast {from} to {to}"));
            return Type::UNKNOWN;
        }
        if from.base == BaseType::Float && to != BaseType::Float {
            wrap(expr, Type::scalar(to), ExprKind::Promote);
        }
        Type::scalar(to)
    }

    /// Brings the two arms of `?:` to one type.
    pub(super) fn unify(&mut self, a: &mut Expr, b: &mut Expr) -> Type {
        if unknown(a.ty) || unknown(b.ty) {
            return Type::UNKNOWN;
        }
        if a.ty == b.ty {
            return a.ty;
        }
        if a.ty == Type::FLOAT && b.ty.base.is_triple() && !b.ty.is_array() {
            let t = b.ty;
            wrap(a, t, ExprKind::Promote);
            return t;
        }
        let t = a.ty;
        self.coerce(b, t, "second arm of '?:'");
        t
    }

    pub(super) fn binary(
        &mut self,
        span: Span,
        op: BinaryOp,
        lhs: &mut Box<Expr>,
        rhs: &mut Box<Expr>,
        expected: Option<BaseType>,
    ) -> Type {
        use BaseType as B;
        let arith = !op.is_condition() && !matches!(op, BinaryOp::Dot | BinaryOp::Cross);
        let expect_lhs = if arith { expected } else { None };
        self.expr(lhs, expect_lhs);
        let expect_rhs = if lhs.ty.base.is_triple() || lhs.ty.base == B::Matrix {
            Some(lhs.ty.base)
        } else {
            expect_lhs
        };
        self.expr(
            rhs,
            if arith || op == BinaryOp::Eq || op == BinaryOp::Ne {
                expect_rhs
            } else {
                None
            },
        );
        let (l, r) = (lhs.ty, rhs.ty);
        if unknown(l) || unknown(r) {
            return if op.is_condition() || op == BinaryOp::Dot {
                Type::FLOAT
            } else {
                Type::UNKNOWN
            };
        }
        let bad = |c: &mut Self| {
            c.error(
                span,
                format!("operator '{}' cannot combine {l} and {r}", op.symbol()),
            );
            Type::UNKNOWN
        };
        if l.is_array() || r.is_array() {
            return bad(self);
        }
        match op {
            BinaryOp::And | BinaryOp::Or => {
                if l != Type::FLOAT || r != Type::FLOAT {
                    return bad(self);
                }
                Type::FLOAT
            }
            BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge => {
                if l != Type::FLOAT || r != Type::FLOAT {
                    return bad(self);
                }
                Type::FLOAT
            }
            BinaryOp::Eq | BinaryOp::Ne => {
                if l.base == B::String || r.base == B::String {
                    if l.base != r.base {
                        return bad(self);
                    }
                } else if self.numeric_pair(lhs, rhs).is_none() {
                    return bad(self);
                }
                Type::FLOAT
            }
            BinaryOp::Dot => {
                if !(l.base.is_triple() && r.base.is_triple()) {
                    return bad(self);
                }
                if l.base.is_geometric() != r.base.is_geometric() {
                    return bad(self);
                }
                Type::FLOAT
            }
            BinaryOp::Cross => {
                if !(l.base.is_geometric() && r.base.is_geometric()) {
                    return bad(self);
                }
                Type::VECTOR
            }
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div => {
                if l.base == B::Matrix || r.base == B::Matrix {
                    // Matrix algebra: m op m, or a float scale (kept unpromoted: promoting to a
                    // matrix would put the float on the diagonal only).
                    let ok = match op {
                        BinaryOp::Mul | BinaryOp::Div => {
                            (l.base == B::Matrix || l.base == B::Float)
                                && (r.base == B::Matrix || r.base == B::Float)
                        }
                        _ => l.base == B::Matrix && r.base == B::Matrix,
                    };
                    return if ok { Type::MATRIX } else { bad(self) };
                }
                if matches!(l.base, B::String | B::Void) || matches!(r.base, B::String | B::Void) {
                    return bad(self);
                }
                match self.numeric_pair(lhs, rhs) {
                    None => bad(self),
                    Some((a, b)) => Type::scalar(arith_result(op, a, b)),
                }
            }
        }
    }

    /// Promotes a float operand to the other's triple type. Returns both operand bases, or
    /// `None` when a colour meets a geometric type.
    pub(super) fn numeric_pair(
        &mut self,
        lhs: &mut Expr,
        rhs: &mut Expr,
    ) -> Option<(BaseType, BaseType)> {
        let (l, r) = (lhs.ty.base, rhs.ty.base);
        if l == BaseType::Float && r.is_triple() {
            wrap(lhs, Type::scalar(r), ExprKind::Promote);
            return Some((r, r));
        }
        if r == BaseType::Float && l.is_triple() {
            wrap(rhs, Type::scalar(l), ExprKind::Promote);
            return Some((l, l));
        }
        if l == r || (l.is_geometric() && r.is_geometric()) {
            return Some((l, r));
        }
        None
    }

    pub(super) fn assign(
        &mut self,
        op: AssignOp,
        target: &mut LValue,
        value: &mut Box<Expr>,
    ) -> Type {
        let Some(r) = self.lookup_target(target) else {
            self.expr(value, None);
            return Type::UNKNOWN;
        };
        let var_ty = self.var_type(r);
        let ty = match target.index.as_mut() {
            Some(ix) => {
                self.expr(ix, Some(BaseType::Float));
                self.coerce(ix, Type::FLOAT, "array index");
                if !var_ty.is_array() && !unknown(var_ty) {
                    self.error(
                        target.span,
                        format!("cannot index '{}': it is not an array", target.name),
                    );
                    Type::UNKNOWN
                } else {
                    var_ty.element()
                }
            }
            None => var_ty,
        };
        self.expr(value, Some(ty.base));
        if op != AssignOp::Assign {
            if ty.is_array() || matches!(ty.base, BaseType::String) {
                self.error(
                    target.span,
                    format!(
                        "operator '{}=' cannot apply to {ty}",
                        op.binary().map_or("", |b| b.symbol())
                    ),
                );
                return ty;
            }
            let scalable = ty.base == BaseType::Matrix
                && value.ty == Type::FLOAT
                && matches!(op, AssignOp::Mul | AssignOp::Div);
            if !scalable {
                let what = format!(
                    "right side of '{}='",
                    op.binary().map_or("", |b| b.symbol())
                );
                self.coerce(value, ty, &what);
            }
            return ty;
        }
        let what = format!("assignment to '{}'", target.name);
        self.coerce(value, ty, &what);
        ty
    }

    /// Resolves an assignment target and checks it is writable.
    pub(super) fn lookup_target(&mut self, target: &mut LValue) -> Option<VarRef> {
        let r = self.lookup(&target.name, target.span)?;
        target.var = Some(r);
        if let Err(msg) = self.writable(r) {
            self.error(target.span, format!("cannot assign: {msg}"));
        }
        Some(r)
    }
}

/// The result base type of `a op b` for numeric operands (after float promotion), following
/// RI 3.2 §11.2: point − point is a vector, point ± vector is a point, mixed
/// vector/normal is a vector.
fn arith_result(op: BinaryOp, a: BaseType, b: BaseType) -> BaseType {
    use BaseType as B;
    if a == b {
        return if a == B::Point && op == BinaryOp::Sub {
            B::Vector
        } else {
            a
        };
    }
    if (a == B::Point || b == B::Point) && matches!(op, BinaryOp::Add | BinaryOp::Sub) {
        return B::Point;
    }
    if a == B::Point {
        return B::Point;
    }
    B::Vector
}
