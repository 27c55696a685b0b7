//! `#if`/`#elif` conditions: `defined`, macro expansion, then C integer arithmetic by
//! precedence climbing (unknown identifiers are 0).

use super::Pp;
use crate::lexer::{Punct, TokKind, Token};
use crate::span::Span;

impl Pp<'_> {
    /// Evaluates an `#if`/`#elif` condition: `defined` first, then macro expansion, then C
    /// integer arithmetic with unknown identifiers as 0.
    pub(super) fn eval_if(&mut self, at: &Token, rest: &[Token]) -> bool {
        let mut resolved = Vec::new();
        let mut i = 0;
        while i < rest.len() {
            if rest[i].ident() == Some("defined") {
                let (name, next) = if rest.get(i + 1).is_some_and(|t| t.is(Punct::LParen)) {
                    let ok = rest.get(i + 3).is_some_and(|t| t.is(Punct::RParen));
                    (
                        rest.get(i + 2).and_then(|t| t.ident()).filter(|_| ok),
                        i + 4,
                    )
                } else {
                    (rest.get(i + 1).and_then(|t| t.ident()), i + 2)
                };
                let Some(name) = name else {
                    self.err(rest[i].span, "expected a macro name after 'defined'");
                    return false;
                };
                let v = self.macros.contains_key(name);
                resolved.push(number_token(if v { 1.0 } else { 0.0 }, rest[i].span));
                i = next;
            } else {
                resolved.push(rest[i].clone());
                i += 1;
            }
        }
        let mut expanded = Vec::new();
        self.expand(&resolved, &mut Vec::new(), &mut expanded, 0);
        if expanded.is_empty() {
            self.err(at.span, "expected an expression after #if");
            return false;
        }
        let mut ev = IfEval {
            toks: &expanded,
            pos: 0,
        };
        match ev.ternary() {
            Ok(v) if ev.pos == expanded.len() => v != 0,
            Ok(_) => {
                let t = &expanded[ev.pos];
                self.err(
                    t.span,
                    format!("expected end of #if expression, found {}", t.describe()),
                );
                false
            }
            Err(e) => {
                let span = expanded.get(e).map_or(at.span, |t| t.span);
                let found = expanded
                    .get(e)
                    .map_or("end of line".into(), |t| t.describe());
                self.err(
                    span,
                    format!("expected an integer expression in #if, found {found}"),
                );
                false
            }
        }
    }
}

fn number_token(v: f64, span: Span) -> Token {
    Token {
        kind: TokKind::Number(v),
        span,
        text: format!("{v}"),
        line_start: false,
        space_before: true,
    }
}

/// C integer expression evaluator for `#if` (precedence climbing over the expanded tokens).
/// Errors carry the index of the offending token.
struct IfEval<'a> {
    toks: &'a [Token],
    pos: usize,
}

impl IfEval<'_> {
    fn peek(&self) -> Option<&Token> {
        self.toks.get(self.pos)
    }

    fn eat(&mut self, p: Punct) -> bool {
        if self.peek().is_some_and(|t| t.is(p)) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    fn ternary(&mut self) -> Result<i64, usize> {
        let c = self.binary(0)?;
        if self.eat(Punct::Question) {
            let a = self.ternary()?;
            if !self.eat(Punct::Colon) {
                return Err(self.pos);
            }
            let b = self.ternary()?;
            return Ok(if c != 0 { a } else { b });
        }
        Ok(c)
    }

    fn binary(&mut self, min_prec: u8) -> Result<i64, usize> {
        let mut lhs = self.unary()?;
        while let Some(TokKind::Punct(p)) = self.peek().map(|t| &t.kind) {
            let p = *p;
            let prec = match p {
                Punct::OrOr => 1,
                Punct::AndAnd => 2,
                Punct::Pipe => 3,
                Punct::Caret => 4,
                Punct::Amp => 5,
                Punct::EqEq | Punct::Ne => 6,
                Punct::Lt | Punct::Gt | Punct::Le | Punct::Ge => 7,
                Punct::Plus | Punct::Minus => 8,
                Punct::Star | Punct::Slash | Punct::Percent => 9,
                _ => break,
            };
            if prec < min_prec {
                break;
            }
            let at = self.pos;
            self.pos += 1;
            let rhs = self.binary(prec + 1)?;
            lhs = match p {
                Punct::OrOr => ((lhs != 0) || (rhs != 0)) as i64,
                Punct::AndAnd => ((lhs != 0) && (rhs != 0)) as i64,
                Punct::Pipe => lhs | rhs,
                Punct::Caret => lhs ^ rhs,
                Punct::Amp => lhs & rhs,
                Punct::EqEq => (lhs == rhs) as i64,
                Punct::Ne => (lhs != rhs) as i64,
                Punct::Lt => (lhs < rhs) as i64,
                Punct::Gt => (lhs > rhs) as i64,
                Punct::Le => (lhs <= rhs) as i64,
                Punct::Ge => (lhs >= rhs) as i64,
                Punct::Plus => lhs.wrapping_add(rhs),
                Punct::Minus => lhs.wrapping_sub(rhs),
                Punct::Star => lhs.wrapping_mul(rhs),
                Punct::Slash | Punct::Percent if rhs == 0 => return Err(at),
                Punct::Slash => lhs.wrapping_div(rhs),
                _ => lhs.wrapping_rem(rhs),
            };
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<i64, usize> {
        let Some(t) = self.peek() else {
            return Err(self.pos);
        };
        let kind = t.kind.clone();
        self.pos += 1;
        match kind {
            TokKind::Number(v) => Ok(v as i64),
            TokKind::Ident(_) => Ok(0),
            TokKind::Punct(Punct::Minus) => Ok(self.unary()?.wrapping_neg()),
            TokKind::Punct(Punct::Plus) => self.unary(),
            TokKind::Punct(Punct::Bang) => Ok((self.unary()? == 0) as i64),
            TokKind::Punct(Punct::Tilde) => Ok(!self.unary()?),
            TokKind::Punct(Punct::LParen) => {
                let v = self.ternary()?;
                if self.eat(Punct::RParen) {
                    Ok(v)
                } else {
                    Err(self.pos)
                }
            }
            _ => Err(self.pos - 1),
        }
    }
}
