//! Expressions by precedence climbing, casts with spaces, tuples, calls and the texture
//! family with its channel selector and optional parameters.

use super::{is_reserved, value_type, Failed, PResult, Parser, MAX_DEPTH};
use crate::ast::*;
use crate::lexer::{Punct, TokKind, Token};
use crate::span::Span;

impl Parser<'_> {
    /// A full expression (assignment level).
    pub(super) fn expression(&mut self) -> PResult<Expr> {
        self.assignment()
    }

    pub(super) fn assignment(&mut self) -> PResult<Expr> {
        self.nested(Self::assignment_inner)
    }

    pub(super) fn assignment_inner(&mut self) -> PResult<Expr> {
        let lhs = self.ternary()?;
        let op = match self.peek().kind {
            TokKind::Punct(Punct::Assign) => AssignOp::Assign,
            TokKind::Punct(Punct::PlusEq) => AssignOp::Add,
            TokKind::Punct(Punct::MinusEq) => AssignOp::Sub,
            TokKind::Punct(Punct::StarEq) => AssignOp::Mul,
            TokKind::Punct(Punct::SlashEq) => AssignOp::Div,
            _ => return Ok(lhs),
        };
        let op_tok = self.bump();
        let target = match lhs.kind {
            ExprKind::Var(v) => LValue {
                name: v.name,
                span: lhs.span,
                index: None,
                var: None,
            },
            ExprKind::Index { array, index } => match array.kind {
                ExprKind::Var(v) => LValue {
                    name: v.name,
                    span: array.span,
                    index: Some(index),
                    var: None,
                },
                _ => return Err(self.not_assignable(op_tok.span)),
            },
            _ => return Err(self.not_assignable(op_tok.span)),
        };
        let value = Box::new(self.assignment()?);
        Ok(Expr::new(ExprKind::Assign { op, target, value }, lhs.span))
    }

    pub(super) fn not_assignable(&mut self, span: Span) -> Failed {
        self.error_at(
            span,
            "expected a variable or array element on the left of the assignment".to_string(),
        )
    }

    pub(super) fn ternary(&mut self) -> PResult<Expr> {
        let cond = self.binary(0)?;
        if !self.at(Punct::Question) {
            return Ok(cond);
        }
        self.bump();
        let then = self.assignment()?;
        self.expect(Punct::Colon)?;
        let otherwise = self.ternary()?;
        let span = cond.span;
        Ok(Expr::new(
            ExprKind::Ternary {
                cond: Box::new(cond),
                then: Box::new(then),
                otherwise: Box::new(otherwise),
            },
            span,
        ))
    }

    /// Precedence climbing over the binary operators.
    pub(super) fn binary(&mut self, min_prec: u8) -> PResult<Expr> {
        let mut lhs = self.unary()?;
        // A left-associative chain builds a tree as deep as it is long: count it as nesting.
        let mut chain = 0;
        while let Some((op, prec)) = binary_op(self.peek()) {
            if prec < min_prec {
                break;
            }
            chain += 1;
            if self.depth + chain > MAX_DEPTH {
                let span = self.peek().span;
                return Err(self.error_at(span, format!("nesting deeper than {MAX_DEPTH} levels")));
            }
            let op_tok = self.bump();
            let rhs = self.binary(prec + 1)?;
            lhs = Expr::new(
                ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                op_tok.span,
            );
        }
        Ok(lhs)
    }

    pub(super) fn unary(&mut self) -> PResult<Expr> {
        self.nested(Self::unary_inner)
    }

    pub(super) fn unary_inner(&mut self) -> PResult<Expr> {
        let t = self.peek().clone();
        let op = match &t.kind {
            TokKind::Punct(Punct::Minus) => Some(UnaryOp::Neg),
            TokKind::Punct(Punct::Bang) => Some(UnaryOp::Not),
            TokKind::Punct(Punct::Plus) => {
                self.bump();
                return self.unary();
            }
            _ => None,
        };
        if let Some(op) = op {
            self.bump();
            let e = self.unary()?;
            return Ok(Expr::new(
                ExprKind::Unary {
                    op,
                    expr: Box::new(e),
                },
                t.span,
            ));
        }
        if let Some(to) = t.ident().and_then(value_type) {
            // Type cast: `color "hsv" (…)`, `vector E`, `float texture (…)`.
            self.bump();
            let space = if let TokKind::Str(_) = self.peek().kind {
                let s = self.bump();
                let TokKind::Str(v) = s.kind else {
                    return Err(Failed);
                };
                Some(Box::new(Expr::new(ExprKind::Str(v), s.span)))
            } else {
                None
            };
            let e = self.unary()?;
            return Ok(Expr::new(
                ExprKind::Cast {
                    to,
                    space,
                    expr: Box::new(e),
                },
                t.span,
            ));
        }
        self.postfix()
    }

    pub(super) fn postfix(&mut self) -> PResult<Expr> {
        let mut e = self.primary()?;
        while self.at(Punct::LBracket) {
            self.bump();
            let index = self.expression()?;
            self.expect(Punct::RBracket)?;
            let span = e.span;
            e = Expr::new(
                ExprKind::Index {
                    array: Box::new(e),
                    index: Box::new(index),
                },
                span,
            );
        }
        Ok(e)
    }

    pub(super) fn primary(&mut self) -> PResult<Expr> {
        let t = self.peek().clone();
        match &t.kind {
            TokKind::Number(v) => {
                self.bump();
                Ok(Expr::new(ExprKind::Float(*v), t.span))
            }
            TokKind::Str(s) => {
                self.bump();
                Ok(Expr::new(ExprKind::Str(s.clone()), t.span))
            }
            // `surface ("Kd", x)` and `displacement (…)` are message-passing calls even though
            // the words also introduce shaders.
            TokKind::Ident(w)
                if !is_reserved(w)
                    || (matches!(w.as_str(), "surface" | "displacement")
                        && self.peek_at(1).is(Punct::LParen)) =>
            {
                self.bump();
                if self.at(Punct::LParen) {
                    return self.call(w.clone(), t.span);
                }
                Ok(Expr::new(
                    ExprKind::Var(VarUse {
                        name: w.clone(),
                        var: None,
                    }),
                    t.span,
                ))
            }
            TokKind::Punct(Punct::LParen) => {
                self.bump();
                let first = self.expression()?;
                if self.eat(Punct::RParen) {
                    return Ok(first);
                }
                let mut elems = vec![first];
                while self.eat(Punct::Comma) {
                    elems.push(self.expression()?);
                }
                self.expect(Punct::RParen)?;
                Ok(Expr::new(ExprKind::Tuple(elems), t.span))
            }
            TokKind::Punct(Punct::LBrace) => {
                self.bump();
                let mut elems = Vec::new();
                if !self.at(Punct::RBrace) {
                    loop {
                        elems.push(self.assignment()?);
                        if !self.eat(Punct::Comma) {
                            break;
                        }
                    }
                }
                self.expect(Punct::RBrace)?;
                Ok(Expr::new(ExprKind::ArrayInit(elems), t.span))
            }
            _ => Err(self.expected("an expression")),
        }
    }

    pub(super) fn call(&mut self, name: String, span: Span) -> PResult<Expr> {
        self.expect(Punct::LParen)?;
        let mut args = Vec::new();
        if !self.at(Punct::RParen) {
            loop {
                args.push(self.assignment()?);
                if !self.eat(Punct::Comma) {
                    break;
                }
            }
        }
        self.expect(Punct::RParen)?;
        let kind = match name.as_str() {
            "texture" => Some(TextureKind::Texture),
            "environment" => Some(TextureKind::Environment),
            "shadow" => Some(TextureKind::Shadow),
            "bump" => Some(TextureKind::Bump),
            _ => None,
        };
        if let Some(kind) = kind {
            return self.texture_call(kind, args, span);
        }
        Ok(Expr::new(
            ExprKind::Call(Call {
                name,
                args,
                callee: None,
            }),
            span,
        ))
    }

    /// Splits `texture ("map"[chan], coords…, "param", value, …)` into its parts: the first
    /// string literal after the name starts the optional parameters (coordinates are never
    /// strings).
    pub(super) fn texture_call(
        &mut self,
        kind: TextureKind,
        args: Vec<Expr>,
        span: Span,
    ) -> PResult<Expr> {
        let mut it = args.into_iter();
        let Some(first) = it.next() else {
            return Err(self.error_at(
                span,
                format!(
                    "expected a texture name as the first argument of {}",
                    kind.name()
                ),
            ));
        };
        let (map, channel) = match first.kind {
            ExprKind::Index { array, index } => (array, Some(index)),
            other => (
                Box::new(Expr {
                    kind: other,
                    ..first
                }),
                None,
            ),
        };
        let rest: Vec<Expr> = it.collect();
        let split = rest
            .iter()
            .position(|e| matches!(e.kind, ExprKind::Str(_)))
            .unwrap_or(rest.len());
        let mut rest = rest.into_iter();
        let coords: Vec<Expr> = rest.by_ref().take(split).collect();
        let tail: Vec<Expr> = rest.collect();
        if tail.len() % 2 != 0 {
            let at = tail.last().map_or(span, |e| e.span);
            return Err(self.error_at(
                at,
                format!(
                    "expected \"name\", value pairs after the coordinates of {}",
                    kind.name()
                ),
            ));
        }
        let mut params = Vec::new();
        let mut t = tail.into_iter();
        while let (Some(name), Some(value)) = (t.next(), t.next()) {
            params.push(NamedArg { name, value });
        }
        Ok(Expr::new(
            ExprKind::Texture(TextureCall {
                kind,
                map,
                channel,
                coords,
                params,
            }),
            span,
        ))
    }
}

/// Takes `axis, angle` from the remaining construct arguments.
pub(super) fn cone(it: &mut impl Iterator<Item = Expr>) -> Option<Cone> {
    let axis = it.next()?;
    let angle = it.next()?;
    Some(Cone { axis, angle })
}

/// The binary operator a token spells and its precedence (higher binds tighter).
fn binary_op(t: &Token) -> Option<(BinaryOp, u8)> {
    let TokKind::Punct(p) = t.kind else {
        return None;
    };
    Some(match p {
        Punct::OrOr => (BinaryOp::Or, 1),
        Punct::AndAnd => (BinaryOp::And, 2),
        Punct::EqEq => (BinaryOp::Eq, 3),
        Punct::Ne => (BinaryOp::Ne, 3),
        Punct::Lt => (BinaryOp::Lt, 4),
        Punct::Le => (BinaryOp::Le, 4),
        Punct::Gt => (BinaryOp::Gt, 4),
        Punct::Ge => (BinaryOp::Ge, 4),
        Punct::Plus => (BinaryOp::Add, 5),
        Punct::Minus => (BinaryOp::Sub, 5),
        Punct::Caret => (BinaryOp::Cross, 6),
        Punct::Star => (BinaryOp::Mul, 7),
        Punct::Slash => (BinaryOp::Div, 7),
        Punct::Dot => (BinaryOp::Dot, 8),
        _ => return None,
    })
}
