//! Checker and resolver: scopes, types, overload resolution, global-variable rules.
//!
//! Files: this one holds the state and the definitions (shaders, functions, parameters);
//! `stmt.rs` statements and lighting constructs, `scope.rs` name lookup and `extern`,
//! `expr.rs` expressions and operators, `call.rs` calls and texture calls, `overload.rs`
//! overload resolution (built-in table and user functions).
//!
//! Walks each definition in source order, filling the annotations of the tree in place:
//! every identifier gets its [`VarRef`], every call its [`Callee`] with a concrete
//! [`Signature`], every expression its [`Type`]; implicit conversions become explicit
//! [`ExprKind::Promote`] (float → triple) and space-less [`ExprKind::Cast`] (point ↔ vector ↔
//! normal) nodes, so the executor never converts implicitly. Uniform/varying inference runs
//! afterwards over the typed tree (`detail.rs`).
//!
//! Rules taken from RI 3.2 chapters 11–15, with the leniencies real shaders rely on (globals
//! are visible in functions without `extern`; a tuple without context is a point).

mod call;
mod expr;
mod overload;
mod scope;
mod stmt;

use crate::ast::*;
use crate::diagnostic::Diagnostic;
use crate::span::Span;
use crate::types::{BaseType, Detail, ShaderKind, Type};
use std::collections::HashMap;

/// Checks and annotates `prog` in place. Errors go to `diags`.
pub fn check(prog: &mut Program, diags: &mut Vec<Diagnostic>) {
    let mut c = Checker {
        diags,
        functions: std::mem::take(&mut prog.functions),
        frames: Vec::new(),
        func_scopes: vec![Vec::new()],
        in_progress: Vec::new(),
        checked: Vec::new(),
    };
    c.checked = vec![false; c.functions.len()];
    for item in prog.items.clone() {
        match item {
            Item::Shader(id) => {
                let sh = &mut prog.shaders[id.0 as usize];
                c.shader(id, sh);
            }
            Item::Function(id) => {
                c.function(id);
                c.register_function(id);
            }
        }
    }
    prog.functions = c.functions;
    crate::detail::infer(prog, c.diags);
}

/// Checking state for one shader or function body.
struct Frame {
    owner: Owner,
    /// `Some` in a shader body; functions can be called from any kind of shader.
    shader_kind: Option<ShaderKind>,
    /// Function return type (`void` for shaders).
    ret: Type,
    vars: Vec<VarInfo>,
    scopes: Vec<HashMap<String, VarRef>>,
    loops: u32,
    illuminance: u32,
    light_construct: u32,
    reads_varying: bool,
}

struct Checker<'a> {
    diags: &'a mut Vec<Diagnostic>,
    functions: Vec<FunctionDef>,
    frames: Vec<Frame>,
    /// Visible user functions per block scope (file scope first).
    func_scopes: Vec<Vec<FuncId>>,
    /// Functions whose bodies are being checked (a call to one is recursion).
    in_progress: Vec<FuncId>,
    checked: Vec<bool>,
}

/// Replaces `e` with `f(e)` typed `to`.
fn wrap(e: &mut Expr, to: Type, f: impl FnOnce(Box<Expr>) -> ExprKind) {
    let span = e.span;
    let inner = std::mem::replace(e, Expr::new(ExprKind::Error, span));
    *e = Expr {
        kind: f(Box::new(inner)),
        span,
        ty: to,
        detail: Detail::Uniform,
    };
}

fn unknown(t: Type) -> bool {
    t.base == BaseType::Unknown
}

impl Checker<'_> {
    fn error(&mut self, span: Span, msg: impl Into<String>) {
        self.diags.push(Diagnostic::error(span, msg));
    }

    fn frame(&mut self) -> &mut Frame {
        self.frames
            .last_mut()
            .expect("checking happens inside a frame")
    }

    // ----- definitions ----------------------------------------------------------------------

    fn shader(&mut self, id: ShaderId, sh: &mut ShaderDef) {
        self.frames.push(Frame {
            owner: Owner::Shader(id),
            shader_kind: Some(sh.kind),
            ret: Type::VOID,
            vars: Vec::new(),
            scopes: vec![HashMap::new()],
            loops: 0,
            illuminance: 0,
            light_construct: 0,
            reads_varying: false,
        });
        self.params(&mut sh.params, true);
        self.func_scopes.push(Vec::new());
        self.block_stmts(&mut sh.body);
        self.func_scopes.pop();
        let frame = self.frames.pop().expect("pushed above");
        sh.vars = frame.vars;
    }

    fn function(&mut self, id: FuncId) {
        let i = id.0 as usize;
        if self.checked[i] {
            return;
        }
        self.checked[i] = true;
        let mut params = std::mem::take(&mut self.functions[i].params);
        let mut body = std::mem::take(&mut self.functions[i].body);
        let ret = self.functions[i].ret;
        self.frames.push(Frame {
            owner: Owner::Function(id),
            shader_kind: None,
            ret,
            vars: Vec::new(),
            scopes: vec![HashMap::new()],
            loops: 0,
            illuminance: 0,
            light_construct: 0,
            reads_varying: false,
        });
        self.params(&mut params, false);
        self.in_progress.push(id);
        self.func_scopes.push(Vec::new());
        self.block_stmts(&mut body);
        self.func_scopes.pop();
        self.in_progress.pop();
        let frame = self.frames.pop().expect("pushed above");
        let f = &mut self.functions[i];
        f.params = params;
        f.body = body;
        f.vars = frame.vars;
        f.reads_varying = frame.reads_varying;
    }

    /// Makes a checked function callable in the innermost scope; a second definition with
    /// the same name and parameter types in that scope is an error (calls would be ambiguous).
    fn register_function(&mut self, id: FuncId) {
        let f = &self.functions[id.0 as usize];
        let key: Vec<(Type, bool)> = f.params.iter().map(|p| (p.ty, p.output)).collect();
        let scope = self.func_scopes.last().expect("a scope is open");
        let duplicate = scope.iter().any(|other| {
            let g = &self.functions[other.0 as usize];
            g.name == f.name
                && g.params
                    .iter()
                    .map(|p| (p.ty, p.output))
                    .collect::<Vec<_>>()
                    == key
        });
        if duplicate {
            let (span, name) = (f.span, f.name.clone());
            self.error(
                span,
                format!("function '{name}' is already defined with these parameter types"),
            );
        }
        self.func_scopes
            .last_mut()
            .expect("a scope is open")
            .push(id);
    }

    fn params(&mut self, params: &mut [Param], shader: bool) {
        for p in params.iter_mut() {
            if let Some(d) = p.default.as_mut() {
                self.expr(d, Some(p.ty.base));
                let what = format!("default value of '{}'", p.name);
                self.coerce(d, p.ty, &what);
            } else if shader {
                self.error(
                    p.span,
                    format!("shader parameter '{}' needs a default value", p.name),
                );
            }
            let kind = if shader {
                VarKind::ShaderParam { output: p.output }
            } else {
                VarKind::FunctionParam { output: p.output }
            };
            let detail = p.detail.unwrap_or(if shader {
                Detail::Uniform
            } else {
                Detail::Varying
            });
            let id = self.declare(&p.name, p.span, p.ty, kind, p.detail, detail);
            p.var = Some(id);
        }
    }

    /// Adds a slot to the current frame and binds `name` in the innermost scope.
    fn declare(
        &mut self,
        name: &str,
        span: Span,
        ty: Type,
        kind: VarKind,
        declared: Option<Detail>,
        detail: Detail,
    ) -> VarId {
        let frame = self.frame();
        let id = VarId(frame.vars.len() as u32);
        frame.vars.push(VarInfo {
            name: name.to_string(),
            span,
            ty,
            kind,
            declared,
            detail,
            inferred: detail,
        });
        let scope = frame.scopes.last_mut().expect("a frame has a scope");
        if scope.insert(name.to_string(), VarRef::Slot(id)).is_some() {
            self.error(span, format!("'{name}' is already declared in this scope"));
        }
        id
    }
}
