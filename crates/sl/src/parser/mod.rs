//! Parser: preprocessed tokens to an unchecked [`Program`].
//!
//! Hand-written recursive descent with one function per grammar production, and precedence
//! climbing for binary operators. A hand-written parser over the lexer's tokens (rather than
//! nom over text) because the preprocessor already produced located tokens, because SL needs
//! two-token lookahead in a few places (`color c` declaration vs `color (…)` cast, `float f (`
//! nested function), and because error recovery — skip to `;` or `}` and go on, so one run
//! reports several errors — is direct to express here.
//!
//! Operator precedence follows the RI 3.2 grammar, lowest first: assignment (right), `?:`
//! (right), `||`, `&&`, `== !=`, `< <= > >=`, `+ -`, `^`, `* /`, `.`, then unary `- !` and type
//! casts.
//!
//! Files: this one holds the token helpers and error recovery; `items.rs` shader and function
//! definitions, `stmt.rs` statements, `expr.rs` expressions and calls.

mod expr;
mod items;
mod stmt;
#[cfg(test)]
mod tests;

use crate::ast::*;
use crate::diagnostic::Diagnostic;
use crate::lexer::{Punct, TokKind, Token};
use crate::span::Span;
use crate::types::{BaseType, ShaderKind};

/// Stop after this many syntax errors: later ones are usually consequences of the first.
const MAX_ERRORS: usize = 50;
/// Deepest nesting of expressions and statements accepted, so hostile input such as ten
/// thousand `(` reports an error instead of overflowing the stack (here and in the checker).
const MAX_DEPTH: usize = 256;

/// Parses a preprocessed token stream. Syntax errors go to `diags`; the returned program holds
/// everything that parsed (with [`StmtKind::Error`] / [`ExprKind::Error`] where recovery
/// skipped input).
pub fn parse(tokens: &[Token], diags: &mut Vec<Diagnostic>) -> Program {
    let eof_span = tokens.last().map(|t| t.span).unwrap_or_default();
    let mut p = Parser {
        toks: tokens,
        pos: 0,
        eof: Token {
            kind: TokKind::Eof,
            span: eof_span,
            text: String::new(),
            line_start: true,
            space_before: true,
        },
        diags,
        errors: 0,
        depth: 0,
        program: Program::default(),
        owners: Vec::new(),
    };
    p.program_items();
    p.program
}

/// Marker for "an error was reported; recover".
struct Failed;

type PResult<T> = Result<T, Failed>;

struct Parser<'a> {
    toks: &'a [Token],
    pos: usize,
    eof: Token,
    diags: &'a mut Vec<Diagnostic>,
    errors: usize,
    /// Current recursion depth of `statement` + `unary`.
    depth: usize,
    program: Program,
    /// Enclosing shader/function definitions (for [`FunctionDef::parent`]).
    owners: Vec<Owner>,
}

/// Words the grammar reserves (they cannot name variables or functions).
fn is_reserved(word: &str) -> bool {
    BaseType::from_keyword(word).is_some()
        || ShaderKind::from_keyword(word).is_some()
        || matches!(
            word,
            "uniform"
                | "varying"
                | "output"
                | "extern"
                | "if"
                | "else"
                | "while"
                | "for"
                | "break"
                | "continue"
                | "return"
                | "illuminance"
                | "illuminate"
                | "solar"
        )
}

/// A value type keyword (`void` excluded: it only names function return types).
fn value_type(word: &str) -> Option<BaseType> {
    BaseType::from_keyword(word).filter(|b| *b != BaseType::Void)
}

impl<'a> Parser<'a> {
    // ----- token helpers -------------------------------------------------------------------

    fn peek(&self) -> &Token {
        self.toks.get(self.pos).unwrap_or(&self.eof)
    }

    fn peek_at(&self, k: usize) -> &Token {
        self.toks.get(self.pos + k).unwrap_or(&self.eof)
    }

    fn bump(&mut self) -> Token {
        let t = self.peek().clone();
        if self.pos < self.toks.len() {
            self.pos += 1;
        }
        t
    }

    fn at(&self, p: Punct) -> bool {
        self.peek().is(p)
    }

    fn at_word(&self, w: &str) -> bool {
        self.peek().ident() == Some(w)
    }

    fn eat(&mut self, p: Punct) -> bool {
        if self.at(p) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn eat_word(&mut self, w: &str) -> bool {
        if self.at_word(w) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn error_at(&mut self, span: Span, msg: String) -> Failed {
        self.errors += 1;
        if self.errors <= MAX_ERRORS {
            self.diags.push(Diagnostic::error(span, msg));
        }
        Failed
    }

    /// `expected X, found Y` at the current token.
    fn expected(&mut self, what: &str) -> Failed {
        let t = self.peek().clone();
        self.error_at(t.span, format!("expected {what}, found {}", t.describe()))
    }

    fn expect(&mut self, p: Punct) -> PResult<Token> {
        if self.at(p) {
            Ok(self.bump())
        } else {
            Err(self.expected(&format!("'{}'", p.text())))
        }
    }

    fn ident(&mut self, what: &str) -> PResult<(String, Span)> {
        match self.peek().ident() {
            Some(w) if !is_reserved(w) => {
                let t = self.bump();
                Ok((t.text, t.span))
            }
            _ => Err(self.expected(what)),
        }
    }

    fn too_many_errors(&self) -> bool {
        self.errors > MAX_ERRORS
    }

    /// Error recovery inside a body: skip to just after the next `;` at this nesting level, or
    /// to (not past) a `}` that closes the current block.
    fn sync_statement(&mut self) {
        let mut depth = 0usize;
        loop {
            let t = self.peek();
            match &t.kind {
                TokKind::Eof => return,
                TokKind::Punct(Punct::Semi) if depth == 0 => {
                    self.bump();
                    return;
                }
                TokKind::Punct(Punct::LBrace) | TokKind::Punct(Punct::LParen) => depth += 1,
                TokKind::Punct(Punct::RBrace) | TokKind::Punct(Punct::RParen) => {
                    if depth == 0 {
                        if t.is(Punct::RParen) {
                            self.bump();
                            continue;
                        }
                        return;
                    }
                    depth -= 1;
                    if depth == 0 && self.peek().is(Punct::RBrace) {
                        self.bump();
                        return;
                    }
                }
                _ => {}
            }
            self.bump();
        }
    }

    /// Error recovery at file scope: skip past the next balanced `{ … }` (the rest of a broken
    /// definition) or to the next token that can start a definition.
    fn sync_item(&mut self) {
        let mut depth = 0usize;
        loop {
            let t = self.peek().clone();
            match &t.kind {
                TokKind::Eof => return,
                TokKind::Punct(Punct::LBrace) => depth += 1,
                TokKind::Punct(Punct::RBrace) => {
                    if depth <= 1 {
                        self.bump();
                        return;
                    }
                    depth -= 1;
                }
                TokKind::Ident(w)
                    if depth == 0
                        && t.line_start
                        && (ShaderKind::from_keyword(w).is_some()
                            || BaseType::from_keyword(w).is_some()) =>
                {
                    return;
                }
                _ => {}
            }
            self.bump();
        }
    }
}
