//! Definitions: shaders, functions (also nested ones), their formal parameters.

use super::{value_type, PResult, Parser};
use crate::ast::*;
use crate::lexer::{Punct, TokKind};
use crate::types::{ArrayLen, BaseType, Detail, ShaderKind, Type};

impl Parser<'_> {
    pub(super) fn program_items(&mut self) {
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

    pub(super) fn item(&mut self) -> PResult<()> {
        let word = self.peek().ident().unwrap_or("").to_string();
        if let Some(kind) = ShaderKind::from_keyword(&word) {
            self.bump();
            let id = self.shader(kind)?;
            self.program.items.push(Item::Shader(id));
            return Ok(());
        }
        // A qualified return type (`uniform float f () {…}`) is accepted and the qualifier
        // ignored, as peer compilers do; the call's detail is inferred from the body.
        if matches!(word.as_str(), "uniform" | "varying") && self.starts_function_at(1) {
            self.bump();
        }
        let word = self.peek().ident().unwrap_or("").to_string();
        if BaseType::from_keyword(&word).is_some() {
            let id = self.function()?;
            self.program.items.push(Item::Function(id));
            return Ok(());
        }
        Err(self.expected("a shader or function definition"))
    }

    pub(super) fn shader(&mut self, kind: ShaderKind) -> PResult<ShaderId> {
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
    pub(super) fn function(&mut self) -> PResult<FuncId> {
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

    pub(super) fn params_and_body(&mut self, shader: bool) -> PResult<(Vec<Param>, Block)> {
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
    pub(super) fn formals(&mut self, shader: bool) -> PResult<Vec<Param>> {
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
    pub(super) fn starts_param_group(&self) -> bool {
        self.peek().ident().is_some_and(|w| {
            value_type(w).is_some() || matches!(w, "output" | "uniform" | "varying")
        })
    }

    pub(super) fn detail(&mut self) -> Option<Detail> {
        if self.eat_word("uniform") {
            Some(Detail::Uniform)
        } else if self.eat_word("varying") {
            Some(Detail::Varying)
        } else {
            None
        }
    }

    /// `[n]` or (function parameters) `[]` after a name.
    pub(super) fn array_suffix(&mut self, allow_open: bool) -> PResult<Option<ArrayLen>> {
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
}
