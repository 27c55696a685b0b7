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

use crate::ast::*;
use crate::diagnostic::Diagnostic;
use crate::lexer::{Punct, TokKind, Token};
use crate::span::Span;
use crate::types::{ArrayLen, BaseType, Detail, ShaderKind, Type};

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

    // ----- definitions ----------------------------------------------------------------------

    fn program_items(&mut self) {
        while !matches!(self.peek().kind, TokKind::Eof) && !self.too_many_errors() {
            let start = self.pos;
            if self.item().is_err() {
                self.sync_item();
            }
            if self.pos == start {
                self.bump(); // always make progress
            }
        }
    }

    fn item(&mut self) -> PResult<()> {
        let word = self.peek().ident().unwrap_or("").to_string();
        if let Some(kind) = ShaderKind::from_keyword(&word) {
            self.bump();
            let id = self.shader(kind)?;
            self.program.items.push(Item::Shader(id));
            return Ok(());
        }
        if BaseType::from_keyword(&word).is_some() {
            let id = self.function()?;
            self.program.items.push(Item::Function(id));
            return Ok(());
        }
        Err(self.expected("a shader or function definition"))
    }

    fn shader(&mut self, kind: ShaderKind) -> PResult<ShaderId> {
        let (name, span) = self.ident("a shader name")?;
        let id = ShaderId(self.program.shaders.len() as u32);
        self.program.shaders.push(ShaderDef {
            kind,
            name,
            span,
            params: Vec::new(),
            body: Block::default(),
            vars: Vec::new(),
        });
        self.owners.push(Owner::Shader(id));
        let result = self.params_and_body(true);
        self.owners.pop();
        let (params, body) = result?;
        let s = &mut self.program.shaders[id.0 as usize];
        s.params = params;
        s.body = body;
        Ok(id)
    }

    /// `type name ( formals ) { body }` — the current token is the return type.
    fn function(&mut self) -> PResult<FuncId> {
        let ret_tok = self.bump();
        let ret = Type::scalar(BaseType::from_keyword(&ret_tok.text).unwrap_or(BaseType::Void));
        let (name, span) = self.ident("a function name")?;
        let id = FuncId(self.program.functions.len() as u32);
        self.program.functions.push(FunctionDef {
            name,
            span,
            ret,
            params: Vec::new(),
            body: Block::default(),
            vars: Vec::new(),
            parent: self.owners.last().copied(),
            reads_varying: false,
        });
        self.owners.push(Owner::Function(id));
        let result = self.params_and_body(false);
        self.owners.pop();
        let (params, body) = result?;
        let f = &mut self.program.functions[id.0 as usize];
        f.params = params;
        f.body = body;
        Ok(id)
    }

    fn params_and_body(&mut self, shader: bool) -> PResult<(Vec<Param>, Block)> {
        self.expect(Punct::LParen)?;
        let params = self.formals(shader)?;
        self.expect(Punct::RParen)?;
        if !self.at(Punct::LBrace) {
            return Err(self.expected("'{' to start the body"));
        }
        let body = self.block()?;
        Ok((params, body))
    }

    /// `[output] [uniform|varying] type name [= default], … ; …` up to `)`. A `;` after the
    /// last group is optional (chapter 9 writes `float Ka, Kd;)`).
    fn formals(&mut self, shader: bool) -> PResult<Vec<Param>> {
        let mut params = Vec::new();
        'groups: while !self.at(Punct::RParen) {
            let output = self.eat_word("output");
            let detail = self.detail();
            let base = match self.peek().ident().and_then(value_type) {
                Some(b) => {
                    self.bump();
                    b
                }
                None => return Err(self.expected("a parameter type")),
            };
            loop {
                let (name, span) = self.ident("a parameter name")?;
                let array = self.array_suffix(!shader)?;
                let default = if self.eat(Punct::Assign) {
                    Some(self.assignment()?)
                } else {
                    None
                };
                params.push(Param {
                    name,
                    span,
                    output,
                    detail,
                    ty: Type { base, array },
                    default,
                    var: None,
                });
                if !self.eat(Punct::Comma) {
                    break;
                }
                if self.starts_param_group() {
                    continue 'groups; // C style `float a, float b` is accepted too
                }
            }
            if !self.eat(Punct::Semi) && !self.at(Punct::RParen) {
                return Err(self.expected("';' or ')' after a parameter"));
            }
        }
        Ok(params)
    }

    /// The current token can start a parameter group (`output`, a detail or a type).
    fn starts_param_group(&self) -> bool {
        self.peek().ident().is_some_and(|w| {
            value_type(w).is_some() || matches!(w, "output" | "uniform" | "varying")
        })
    }

    fn detail(&mut self) -> Option<Detail> {
        if self.eat_word("uniform") {
            Some(Detail::Uniform)
        } else if self.eat_word("varying") {
            Some(Detail::Varying)
        } else {
            None
        }
    }

    /// `[n]` or (function parameters) `[]` after a name.
    fn array_suffix(&mut self, allow_open: bool) -> PResult<Option<ArrayLen>> {
        if !self.at(Punct::LBracket) {
            return Ok(None);
        }
        let open = self.bump();
        if self.at(Punct::RBracket) {
            self.bump();
            if allow_open {
                return Ok(Some(ArrayLen::Open));
            }
            return Err(self.error_at(open.span, "expected an array length".to_string()));
        }
        let t = self.peek().clone();
        let len = match t.kind {
            TokKind::Number(v) if v >= 1.0 && v.fract() == 0.0 && v <= 1.0e6 => v as u32,
            _ => return Err(self.expected("an array length (a positive integer)")),
        };
        self.bump();
        self.expect(Punct::RBracket)?;
        Ok(Some(ArrayLen::Fixed(len)))
    }

    // ----- statements -----------------------------------------------------------------------

    fn block(&mut self) -> PResult<Block> {
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

    fn statement(&mut self) -> PResult<Stmt> {
        self.nested(Self::statement_inner)
    }

    /// Runs `f` one nesting level deeper, failing past [`MAX_DEPTH`].
    fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> PResult<T>) -> PResult<T> {
        if self.depth >= MAX_DEPTH {
            let span = self.peek().span;
            return Err(self.error_at(span, format!("nesting deeper than {MAX_DEPTH} levels")));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn statement_inner(&mut self) -> PResult<Stmt> {
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
    fn starts_function(&self) -> bool {
        self.peek()
            .ident()
            .and_then(BaseType::from_keyword)
            .is_some()
            && self.peek_at(1).ident().is_some_and(|w| !is_reserved(w))
            && self.peek_at(2).is(Punct::LParen)
    }

    fn if_stmt(&mut self) -> PResult<StmtKind> {
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

    fn for_stmt(&mut self) -> PResult<StmtKind> {
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
    fn construct_args(&mut self) -> PResult<(Span, Vec<Expr>)> {
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

    fn illuminance(&mut self) -> PResult<StmtKind> {
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

    fn illuminate(&mut self) -> PResult<StmtKind> {
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

    fn solar(&mut self) -> PResult<StmtKind> {
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
    fn declaration(&mut self) -> PResult<StmtKind> {
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

    // ----- expressions ----------------------------------------------------------------------

    /// A full expression (assignment level).
    fn expression(&mut self) -> PResult<Expr> {
        self.assignment()
    }

    fn assignment(&mut self) -> PResult<Expr> {
        self.nested(Self::assignment_inner)
    }

    fn assignment_inner(&mut self) -> PResult<Expr> {
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

    fn not_assignable(&mut self, span: Span) -> Failed {
        self.error_at(
            span,
            "expected a variable or array element on the left of the assignment".to_string(),
        )
    }

    fn ternary(&mut self) -> PResult<Expr> {
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
    fn binary(&mut self, min_prec: u8) -> PResult<Expr> {
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

    fn unary(&mut self) -> PResult<Expr> {
        self.nested(Self::unary_inner)
    }

    fn unary_inner(&mut self) -> PResult<Expr> {
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

    fn postfix(&mut self) -> PResult<Expr> {
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

    fn primary(&mut self) -> PResult<Expr> {
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

    fn call(&mut self, name: String, span: Span) -> PResult<Expr> {
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
    fn texture_call(&mut self, kind: TextureKind, args: Vec<Expr>, span: Span) -> PResult<Expr> {
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
fn cone(it: &mut impl Iterator<Item = Expr>) -> Option<Cone> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preprocess::{preprocess_str, PpOptions};
    use crate::span::SourceMap;

    fn parse_src(src: &str) -> (Program, Vec<String>) {
        let mut map = SourceMap::new();
        let mut d = Vec::new();
        let toks = preprocess_str(&mut map, "t.sl", src, &PpOptions::default(), &mut d);
        let prog = parse(&toks, &mut d);
        let msgs = d.iter().map(|d| d.render(&map).to_string()).collect();
        (prog, msgs)
    }

    fn body_expr(p: &Program) -> &Expr {
        match &p.shaders[0].body.stmts[0].kind {
            StmtKind::Expr(e) => e,
            other => panic!("expected an expression statement, got {other:?}"),
        }
    }

    #[test]
    fn dot_binds_tighter_than_times_and_cross_looser() {
        let (p, e) = parse_src("surface s() { x = a * b . c ^ d + e; }");
        assert!(e.is_empty(), "{e:?}");
        let ExprKind::Assign { value, .. } = &body_expr(&p).kind else {
            panic!()
        };
        // ((a * (b . c)) ^ d) + e
        let ExprKind::Binary {
            op: BinaryOp::Add,
            lhs,
            ..
        } = &value.kind
        else {
            panic!("{value:?}")
        };
        let ExprKind::Binary {
            op: BinaryOp::Cross,
            lhs,
            ..
        } = &lhs.kind
        else {
            panic!()
        };
        let ExprKind::Binary {
            op: BinaryOp::Mul,
            rhs,
            ..
        } = &lhs.kind
        else {
            panic!()
        };
        assert!(matches!(
            rhs.kind,
            ExprKind::Binary {
                op: BinaryOp::Dot,
                ..
            }
        ));
    }

    #[test]
    fn casts_with_spaces_tuples_and_texture_channels() {
        let (p, e) = parse_src(
            "surface s(point from = point \"shader\" (0,0,0);) { a = float texture (m[3], s, t, \"blur\", 0.1); }",
        );
        assert!(e.is_empty(), "{e:?}");
        let d = p.shaders[0].params[0].default.as_ref().unwrap();
        let ExprKind::Cast {
            to: BaseType::Point,
            space: Some(_),
            expr,
        } = &d.kind
        else {
            panic!()
        };
        assert!(matches!(&expr.kind, ExprKind::Tuple(v) if v.len() == 3));
        let ExprKind::Assign { value, .. } = &body_expr(&p).kind else {
            panic!()
        };
        let ExprKind::Cast {
            to: BaseType::Float,
            expr,
            ..
        } = &value.kind
        else {
            panic!()
        };
        let ExprKind::Texture(tc) = &expr.kind else {
            panic!()
        };
        assert_eq!(tc.kind, TextureKind::Texture);
        assert!(tc.channel.is_some());
        assert_eq!(tc.coords.len(), 2);
        assert_eq!(tc.params.len(), 1);
    }

    #[test]
    fn lighting_construct_forms_are_identified_by_argument_count() {
        let (p, e) = parse_src(
            "surface s() { illuminance (P) {} illuminance (\"spec\", P) {} illuminance (P, N, 1) {} illuminance (\"c\", P, N, 1) ; }
             light l() { illuminate (P) {} illuminate (P, N, 1) {} solar () {} solar (N, 0) {} }",
        );
        assert!(e.is_empty(), "{e:?}");
        let forms: Vec<(bool, bool)> = p.shaders[0]
            .body
            .stmts
            .iter()
            .map(|s| match &s.kind {
                StmtKind::Illuminance(i) => (i.category.is_some(), i.cone.is_some()),
                _ => panic!(),
            })
            .collect();
        assert_eq!(
            forms,
            vec![(false, false), (true, false), (false, true), (true, true)]
        );
        let light: Vec<bool> = p.shaders[1]
            .body
            .stmts
            .iter()
            .map(|s| match &s.kind {
                StmtKind::Illuminate(i) => i.cone.is_some(),
                StmtKind::Solar(s) => s.cone.is_some(),
                _ => panic!(),
            })
            .collect();
        assert_eq!(light, vec![false, true, false, true]);
    }

    #[test]
    fn nested_functions_record_their_parent() {
        let (p, e) = parse_src(
            "color f (normal N; float a, b;) { float sqr (float x) { return x*x; } return sqr(a); }",
        );
        assert!(e.is_empty(), "{e:?}");
        assert_eq!(p.functions.len(), 2);
        assert_eq!(p.functions[0].name, "f");
        assert_eq!(p.functions[0].params.len(), 3);
        assert_eq!(p.functions[1].parent, Some(Owner::Function(FuncId(0))));
        assert!(matches!(
            p.functions[0].body.stmts[0].kind,
            StmtKind::Function(FuncId(1))
        ));
    }

    #[test]
    fn break_and_continue_levels_and_array_declarations() {
        let (p, e) = parse_src(
            "surface s() { float a[3] = {1, 2, 3}; for (i = 0; i < 3; i += 1) { while (1) { break 2; } continue; } }",
        );
        assert!(e.is_empty(), "{e:?}");
        let StmtKind::Decl(d) = &p.shaders[0].body.stmts[0].kind else {
            panic!()
        };
        assert_eq!(d.vars[0].array, Some(ArrayLen::Fixed(3)));
        assert!(
            matches!(d.vars[0].init.as_ref().unwrap().kind, ExprKind::ArrayInit(ref v) if v.len() == 3)
        );
    }

    #[test]
    fn errors_name_what_was_expected_and_recover_at_semicolons() {
        let (_, e) =
            parse_src("surface s() {\n  float a = ;\n  b = 1 +* 2;\n  c = (1, 2;\n  d = 3;\n}\n");
        assert_eq!(
            e,
            vec![
                "t.sl:2:13: error: expected an expression, found ';'",
                "t.sl:3:10: error: expected an expression, found '*'",
                "t.sl:4:12: error: expected ')', found ';'",
            ]
        );
    }

    #[test]
    fn errors_at_file_scope_skip_the_broken_definition() {
        let (p, e) = parse_src("surface (x) { }\nsurface ok() { Ci = 1; }\n42\n");
        assert_eq!(
            e,
            vec![
                "t.sl:1:9: error: expected a shader name, found '('",
                "t.sl:3:1: error: expected a shader or function definition, found number 42",
            ]
        );
        assert!(p.shaders.iter().any(|s| s.name == "ok"));
    }

    #[test]
    fn assignment_to_a_non_variable_is_an_error() {
        let (_, e) = parse_src("surface s() { 1 = 2; }");
        assert_eq!(
            e,
            vec!["t.sl:1:17: error: expected a variable or array element on the left of the assignment"]
        );
    }
}
