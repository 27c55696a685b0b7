//! Statements: blocks, control flow, declarations and the lighting constructs, identified
//! by their argument counts.

use super::{expr::cone, is_reserved, value_type, Failed, PResult, Parser, MAX_DEPTH};
use crate::ast::*;
use crate::lexer::{Punct, TokKind};
use crate::span::Span;
use crate::types::BaseType;

impl Parser<'_> {
    pub(super) fn block(&mut self) -> PResult<Block> {
        let open = self.expect(Punct::LBrace)?;
        let mut stmts = Vec::new();
        while !self.at(Punct::RBrace) {
            if matches!(self.peek().kind, TokKind::Eof) {
                return Err(self.error_at(
                    self.peek().span,
                    "expected '}' to close the block, found end of file".to_string(),
                ));
            }
            if self.too_many_errors() {
                return Err(Failed);
            }
            let start = self.pos;
            match self.statement() {
                Ok(s) => stmts.push(s),
                Err(Failed) => {
                    let span = self.toks.get(start).map_or(open.span, |t| t.span);
                    self.sync_statement();
                    stmts.push(Stmt {
                        kind: StmtKind::Error,
                        span,
                    });
                }
            }
            if self.pos == start {
                self.bump();
            }
        }
        self.bump();
        Ok(Block {
            stmts,
            span: open.span,
        })
    }

    pub(super) fn statement(&mut self) -> PResult<Stmt> {
        self.nested(Self::statement_inner)
    }

    /// Runs `f` one nesting level deeper, failing past [`MAX_DEPTH`].
    pub(super) fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> PResult<T>) -> PResult<T> {
        if self.depth >= MAX_DEPTH {
            let span = self.peek().span;
            return Err(self.error_at(span, format!("nesting deeper than {MAX_DEPTH} levels")));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    pub(super) fn statement_inner(&mut self) -> PResult<Stmt> {
        let t = self.peek().clone();
        let span = t.span;
        let kind = match &t.kind {
            TokKind::Punct(Punct::LBrace) => StmtKind::Block(self.block()?),
            TokKind::Punct(Punct::Semi) => {
                self.bump();
                StmtKind::Empty
            }
            TokKind::Ident(w) => match w.as_str() {
                "if" => self.if_stmt()?,
                "while" => {
                    self.bump();
                    self.expect(Punct::LParen)?;
                    let cond = self.expression()?;
                    self.expect(Punct::RParen)?;
                    let body = Box::new(self.statement()?);
                    StmtKind::While { cond, body }
                }
                "for" => self.for_stmt()?,
                "break" | "continue" => {
                    self.bump();
                    let levels = match self.peek().kind {
                        TokKind::Number(v) if v >= 1.0 && v.fract() == 0.0 && v < 1e6 => {
                            self.bump();
                            v as u32
                        }
                        _ => 1,
                    };
                    self.expect(Punct::Semi)?;
                    if w == "break" {
                        StmtKind::Break(levels)
                    } else {
                        StmtKind::Continue(levels)
                    }
                }
                "return" => {
                    self.bump();
                    let value = if self.at(Punct::Semi) {
                        None
                    } else {
                        Some(self.expression()?)
                    };
                    self.expect(Punct::Semi)?;
                    StmtKind::Return(value)
                }
                "illuminance" => self.illuminance()?,
                "illuminate" => self.illuminate()?,
                "solar" => self.solar()?,
                // `uniform float urand () {…}`: a nested function with a qualified return type
                // (peer compilers accept it; the qualifier is ignored, the detail inferred).
                "uniform" | "varying" if self.starts_function_at(1) => {
                    self.bump();
                    StmtKind::Function(self.function()?)
                }
                "extern" | "uniform" | "varying" | "output" => self.declaration()?,
                _ if self.starts_function() => StmtKind::Function(self.function()?),
                _ if value_type(w).is_some() && self.peek_at(1).ident().is_some() => {
                    self.declaration()?
                }
                _ => {
                    let e = self.expression()?;
                    self.expect(Punct::Semi)?;
                    StmtKind::Expr(e)
                }
            },
            _ => {
                let e = self.expression()?;
                self.expect(Punct::Semi)?;
                StmtKind::Expr(e)
            }
        };
        Ok(Stmt { kind, span })
    }

    /// `type name (` (or `void name (`) starts a nested function definition.
    pub(super) fn starts_function(&self) -> bool {
        self.starts_function_at(0)
    }

    /// [`Self::starts_function`] `k` tokens ahead (after a `uniform`/`varying` qualifier).
    pub(super) fn starts_function_at(&self, k: usize) -> bool {
        self.peek_at(k)
            .ident()
            .and_then(BaseType::from_keyword)
            .is_some()
            && self.peek_at(k + 1).ident().is_some_and(|w| !is_reserved(w))
            && self.peek_at(k + 2).is(Punct::LParen)
    }

    pub(super) fn if_stmt(&mut self) -> PResult<StmtKind> {
        self.bump();
        self.expect(Punct::LParen)?;
        let cond = self.expression()?;
        self.expect(Punct::RParen)?;
        let then = Box::new(self.statement()?);
        let otherwise = if self.eat_word("else") {
            Some(Box::new(self.statement()?))
        } else {
            None
        };
        Ok(StmtKind::If {
            cond,
            then,
            otherwise,
        })
    }

    pub(super) fn for_stmt(&mut self) -> PResult<StmtKind> {
        self.bump();
        self.expect(Punct::LParen)?;
        let init = if self.at(Punct::Semi) {
            None
        } else {
            Some(self.expression()?)
        };
        self.expect(Punct::Semi)?;
        let cond = if self.at(Punct::Semi) {
            None
        } else {
            Some(self.expression()?)
        };
        self.expect(Punct::Semi)?;
        let step = if self.at(Punct::RParen) {
            None
        } else {
            Some(self.expression()?)
        };
        self.expect(Punct::RParen)?;
        let body = Box::new(self.statement()?);
        Ok(StmtKind::For {
            init,
            cond,
            step,
            body,
        })
    }

    /// `( e, … )` of a lighting construct.
    pub(super) fn construct_args(&mut self) -> PResult<(Span, Vec<Expr>)> {
        let open = self.expect(Punct::LParen)?;
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
        Ok((open.span, args))
    }

    pub(super) fn illuminance(&mut self) -> PResult<StmtKind> {
        let kw = self.bump();
        let (_, args) = self.construct_args()?;
        // The argument count identifies the form: (P), (cat, P), (P, axis, angle),
        // (cat, P, axis, angle).
        let mut it = args.into_iter();
        let (category, position, cone) = match it.len() {
            1 => (None, it.next(), None),
            2 => (it.next(), it.next(), None),
            3 => {
                let p = it.next();
                (None, p, cone(&mut it))
            }
            4 => {
                let c = it.next();
                let p = it.next();
                (c, p, cone(&mut it))
            }
            n => {
                return Err(self.error_at(
                    kw.span,
                    format!("expected illuminance ([category,] position [, axis, angle]), found {n} argument(s)"),
                ))
            }
        };
        let position = position.ok_or(Failed)?;
        let body = Box::new(self.statement()?);
        Ok(StmtKind::Illuminance(Illuminance {
            category,
            position,
            cone,
            body,
        }))
    }

    pub(super) fn illuminate(&mut self) -> PResult<StmtKind> {
        let kw = self.bump();
        let (_, args) = self.construct_args()?;
        let n = args.len();
        if n != 1 && n != 3 {
            return Err(self.error_at(
                kw.span,
                format!("expected illuminate (position [, axis, angle]), found {n} argument(s)"),
            ));
        }
        let mut it = args.into_iter();
        let position = it.next().ok_or(Failed)?;
        let cone = cone(&mut it);
        let body = Box::new(self.statement()?);
        Ok(StmtKind::Illuminate(Illuminate {
            position,
            cone,
            body,
        }))
    }

    pub(super) fn solar(&mut self) -> PResult<StmtKind> {
        let kw = self.bump();
        let (_, args) = self.construct_args()?;
        let n = args.len();
        if n != 0 && n != 2 {
            return Err(self.error_at(
                kw.span,
                format!("expected solar ([axis, angle]), found {n} argument(s)"),
            ));
        }
        let mut it = args.into_iter();
        let cone = cone(&mut it);
        let body = Box::new(self.statement()?);
        Ok(StmtKind::Solar(Solar { cone, body }))
    }

    /// `[extern] [uniform|varying] type declarator, … ;`
    pub(super) fn declaration(&mut self) -> PResult<StmtKind> {
        let is_extern = self.eat_word("extern");
        if self.at_word("output") {
            let t = self.bump();
            return Err(self.error_at(
                t.span,
                "'output' is only allowed on shader and function parameters".to_string(),
            ));
        }
        let detail = self.detail();
        let base = match self.peek().ident().and_then(value_type) {
            Some(b) => {
                self.bump();
                b
            }
            None => return Err(self.expected("a type")),
        };
        let mut vars = Vec::new();
        loop {
            let (name, span) = self.ident("a variable name")?;
            let array = self.array_suffix(false)?;
            let init = if self.eat(Punct::Assign) {
                Some(self.assignment()?)
            } else {
                None
            };
            vars.push(Declarator {
                name,
                span,
                array,
                init,
                var: None,
            });
            if !self.eat(Punct::Comma) {
                break;
            }
        }
        self.expect(Punct::Semi)?;
        Ok(StmtKind::Decl(Decl {
            is_extern,
            detail,
            base,
            vars,
        }))
    }
}
