//! Checker and resolver: scopes, types, overload resolution, global-variable rules.
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

use crate::ast::*;
use crate::builtins::{self, Overload, Slot};
use crate::diagnostic::Diagnostic;
use crate::span::Span;
use crate::types::{ArrayLen, BaseType, Detail, ShaderKind, Type};
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

/// What an argument offers to overload resolution.
struct ArgInfo {
    ty: Type,
    assignable: bool,
    is_str_literal: bool,
}

/// Cost of converting a value of `from` to `to` (`None` when impossible): exact 0, float →
/// triple 1, among point/vector/normal 2.
fn conversion_cost(from: Type, to: Type) -> Option<u32> {
    if from.base == BaseType::Unknown || to.base == BaseType::Unknown {
        return Some(0);
    }
    match (from.array, to.array) {
        (None, None) => {}
        (Some(_), Some(ArrayLen::Open)) => return (from.base == to.base).then_some(0),
        (Some(a), Some(b)) => return (from.base == to.base && a == b).then_some(0),
        _ => return None,
    }
    if from.base == to.base {
        Some(0)
    } else if from.base == BaseType::Float && (to.base.is_triple() || to.base == BaseType::Matrix) {
        Some(1)
    } else if from.base.is_geometric() && to.base.is_geometric() {
        Some(2)
    } else {
        None
    }
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

    // ----- statements -----------------------------------------------------------------------

    /// The statements of a body or block in a new scope.
    fn block_stmts(&mut self, b: &mut Block) {
        self.frame().scopes.push(HashMap::new());
        self.func_scopes.push(Vec::new());
        for s in &mut b.stmts {
            self.stmt(s);
        }
        self.func_scopes.pop();
        self.frame().scopes.pop();
    }

    /// A statement that is the body of a control construct gets its own scope too.
    fn scoped_stmt(&mut self, s: &mut Stmt) {
        self.frame().scopes.push(HashMap::new());
        self.stmt(s);
        self.frame().scopes.pop();
    }

    fn stmt(&mut self, s: &mut Stmt) {
        let span = s.span;
        match &mut s.kind {
            StmtKind::Decl(d) => self.decl(d),
            StmtKind::Expr(e) => self.expr(e, None),
            StmtKind::Block(b) => self.block_stmts(b),
            StmtKind::If {
                cond,
                then,
                otherwise,
            } => {
                self.condition(cond, "if");
                self.scoped_stmt(then);
                if let Some(o) = otherwise {
                    self.scoped_stmt(o);
                }
            }
            StmtKind::While { cond, body } => {
                self.condition(cond, "while");
                self.loop_body(body);
            }
            StmtKind::For {
                init,
                cond,
                step,
                body,
            } => {
                if let Some(i) = init {
                    self.expr(i, None);
                }
                if let Some(c) = cond {
                    self.condition(c, "for");
                }
                if let Some(st) = step {
                    self.expr(st, None);
                }
                self.loop_body(body);
            }
            StmtKind::Break(n) | StmtKind::Continue(n) => {
                let n = *n;
                let loops = self.frame().loops;
                if n > loops {
                    let what = if matches!(s.kind, StmtKind::Break(_)) {
                        "break"
                    } else {
                        "continue"
                    };
                    self.error(
                        span,
                        format!("'{what} {n}' needs {n} enclosing loop(s), found {loops}"),
                    );
                }
            }
            StmtKind::Return(value) => self.return_stmt(span, value.as_mut()),
            StmtKind::Illuminance(il) => self.illuminance(span, il),
            StmtKind::Illuminate(il) => {
                self.require_light(span, "illuminate");
                self.expr(&mut il.position, Some(BaseType::Point));
                self.coerce(&mut il.position, Type::POINT, "illuminate position");
                if let Some(c) = il.cone.as_mut() {
                    self.cone(c);
                }
                self.frame().light_construct += 1;
                self.scoped_stmt(&mut il.body);
                self.frame().light_construct -= 1;
            }
            StmtKind::Solar(so) => {
                self.require_light(span, "solar");
                if let Some(c) = so.cone.as_mut() {
                    self.cone(c);
                }
                self.frame().light_construct += 1;
                self.scoped_stmt(&mut so.body);
                self.frame().light_construct -= 1;
            }
            StmtKind::Function(id) => {
                let id = *id;
                self.function(id);
                self.register_function(id);
            }
            StmtKind::Empty | StmtKind::Error => {}
        }
    }

    fn loop_body(&mut self, body: &mut Stmt) {
        self.frame().loops += 1;
        self.scoped_stmt(body);
        self.frame().loops -= 1;
    }

    fn condition(&mut self, e: &mut Expr, what: &str) {
        self.expr(e, Some(BaseType::Float));
        if !unknown(e.ty) && e.ty != Type::FLOAT {
            self.error(
                e.span,
                format!(
                    "{what} condition: expected a float or relation, found {}",
                    e.ty
                ),
            );
        }
    }

    fn cone(&mut self, c: &mut Cone) {
        self.expr(&mut c.axis, Some(BaseType::Vector));
        self.coerce(&mut c.axis, Type::VECTOR, "cone axis");
        self.expr(&mut c.angle, Some(BaseType::Float));
        self.coerce(&mut c.angle, Type::FLOAT, "cone angle");
    }

    fn require_light(&mut self, span: Span, what: &str) {
        if let Some(k) = self.frame().shader_kind {
            if k != ShaderKind::Light {
                self.error(
                    span,
                    format!("'{what}' is only allowed in light shaders, not in a {k} shader"),
                );
            }
        }
    }

    fn illuminance(&mut self, span: Span, il: &mut Illuminance) {
        if let Some(k) = self.frame().shader_kind {
            if !matches!(k, ShaderKind::Surface | ShaderKind::Volume) {
                self.error(
                    span,
                    format!("'illuminance' is only allowed in surface and volume shaders, not in a {k} shader"),
                );
            }
        }
        if let Some(c) = il.category.as_mut() {
            self.expr(c, Some(BaseType::String));
            self.coerce(c, Type::STRING, "illuminance category");
        }
        self.expr(&mut il.position, Some(BaseType::Point));
        self.coerce(&mut il.position, Type::POINT, "illuminance position");
        if let Some(c) = il.cone.as_mut() {
            self.cone(c);
        }
        self.frame().reads_varying = true;
        self.frame().illuminance += 1;
        self.loop_body(&mut il.body);
        self.frame().illuminance -= 1;
    }

    fn return_stmt(&mut self, span: Span, value: Option<&mut Expr>) {
        let ret = self.frame().ret;
        let in_function = self.frame().shader_kind.is_none();
        match value {
            Some(v) => {
                self.expr(v, Some(ret.base));
                if !in_function || ret == Type::VOID {
                    self.error(
                        span,
                        "'return' with a value outside a function that returns one",
                    );
                } else {
                    self.coerce(v, ret, "return value");
                }
            }
            None if in_function && ret != Type::VOID => {
                self.error(span, format!("expected a return value of type {ret}"));
            }
            None => {}
        }
    }

    fn decl(&mut self, d: &mut Decl) {
        for v in &mut d.vars {
            let ty = Type {
                base: d.base,
                array: v.array,
            };
            if d.is_extern {
                v.var = self.extern_ref(&v.name, v.span, ty);
                if let Some(r) = v.var {
                    self.frame()
                        .scopes
                        .last_mut()
                        .expect("a frame has a scope")
                        .insert(v.name.clone(), r);
                }
                if v.init.is_some() {
                    self.error(
                        v.span,
                        format!("extern variable '{}' cannot have an initial value", v.name),
                    );
                }
                continue;
            }
            if let Some(init) = v.init.as_mut() {
                self.expr(init, Some(d.base));
                let what = format!("initial value of '{}'", v.name);
                self.coerce(init, ty, &what);
            }
            // RI 3.2 has no varying strings: an unqualified string local is uniform.
            let default = if d.base == BaseType::String {
                Detail::Uniform
            } else {
                Detail::Varying
            };
            let detail = d.detail.unwrap_or(default);
            let id = self.declare(&v.name, v.span, ty, VarKind::Local, d.detail, detail);
            v.var = Some(VarRef::Slot(id));
        }
    }

    /// Resolves `extern type name`: a variable of an enclosing function or shader, else a
    /// global.
    fn extern_ref(&mut self, name: &str, span: Span, ty: Type) -> Option<VarRef> {
        let n = self.frames.len();
        for fi in (0..n.saturating_sub(1)).rev() {
            let found = self.frames[fi]
                .scopes
                .iter()
                .rev()
                .find_map(|s| s.get(name).copied());
            if let Some(r) = found {
                let r = match r {
                    VarRef::Slot(var) => VarRef::Outer {
                        owner: self.frames[fi].owner,
                        var,
                    },
                    other => other,
                };
                self.check_extern_type(name, span, ty, r);
                self.frame().reads_varying = true;
                return Some(r);
            }
        }
        match Global::from_name(name) {
            Some(g) => {
                let r = VarRef::Global(g);
                self.check_extern_type(name, span, ty, r);
                if g.detail() == Detail::Varying {
                    self.frame().reads_varying = true;
                }
                Some(r)
            }
            None => {
                self.error(
                    span,
                    format!("extern '{name}' is neither a global variable nor a variable of an enclosing function"),
                );
                None
            }
        }
    }

    fn check_extern_type(&mut self, name: &str, span: Span, ty: Type, r: VarRef) {
        let actual = self.var_type(r);
        if actual != ty && !unknown(actual) {
            self.error(
                span,
                format!("extern '{name}' is declared {ty} but the variable is {actual}"),
            );
        }
    }

    // ----- variables ------------------------------------------------------------------------

    fn var_type(&self, r: VarRef) -> Type {
        match r {
            VarRef::Global(g) => g.ty(),
            VarRef::Slot(id) => self
                .frames
                .last()
                .and_then(|f| f.vars.get(id.0 as usize))
                .map_or(Type::UNKNOWN, |v| v.ty),
            VarRef::Outer { owner, var } => self
                .frames
                .iter()
                .find(|f| f.owner == owner)
                .and_then(|f| f.vars.get(var.0 as usize))
                .map_or(Type::UNKNOWN, |v| v.ty),
        }
    }

    /// Looks `name` up: the current frame's scopes, then globals. `PI` is handled by the
    /// caller.
    fn lookup(&mut self, name: &str, span: Span) -> Option<VarRef> {
        let frame = self.frames.last()?;
        if let Some(r) = frame.scopes.iter().rev().find_map(|s| s.get(name).copied()) {
            return Some(r);
        }
        if let Some(g) = Global::from_name(name) {
            if let Some(kind) = frame.shader_kind {
                if g.access(kind) == Access::None {
                    self.error(
                        span,
                        format!("global '{name}' is not available in a {kind} shader"),
                    );
                    return None;
                }
                if matches!(g, Global::L | Global::Cl | Global::Ol)
                    && matches!(kind, ShaderKind::Surface | ShaderKind::Volume)
                    && frame.illuminance == 0
                {
                    self.error(
                        span,
                        format!("'{name}' is only defined inside an illuminance loop"),
                    );
                    return None;
                }
            }
            if g.detail() == Detail::Varying {
                self.frame().reads_varying = true;
            }
            return Some(VarRef::Global(g));
        }
        let enclosing = self.frames[..self.frames.len() - 1]
            .iter()
            .any(|f| f.scopes.iter().any(|s| s.contains_key(name)));
        if enclosing {
            self.error(
                span,
                format!(
                    "'{name}' belongs to an enclosing function: declare it 'extern' to use it here"
                ),
            );
        } else {
            self.error(span, format!("undeclared variable '{name}'"));
        }
        None
    }

    /// Whether a variable may be assigned, with the reason when not.
    fn writable(&self, r: VarRef) -> Result<(), String> {
        match r {
            VarRef::Global(g) => match self.frames.last().and_then(|f| f.shader_kind) {
                Some(kind) if g.access(kind) != Access::ReadWrite => Err(format!(
                    "global '{}' is read-only in a {kind} shader",
                    g.name()
                )),
                _ => Ok(()),
            },
            VarRef::Slot(id) => {
                let v = &self.frames.last().expect("in a frame").vars[id.0 as usize];
                match v.kind {
                    VarKind::FunctionParam { output: false } => Err(format!(
                        "function parameter '{}' is read-only (declare it 'output' to write it)",
                        v.name
                    )),
                    _ => Ok(()),
                }
            }
            VarRef::Outer { .. } => Ok(()),
        }
    }

    // ----- expressions ----------------------------------------------------------------------

    /// Converts `e` to `to`, inserting an explicit promotion or cast, or reports `what:
    /// expected …, found …`.
    fn coerce(&mut self, e: &mut Expr, to: Type, what: &str) {
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

    fn expr(&mut self, e: &mut Expr, expected: Option<BaseType>) {
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

    fn cast(&mut self, to: BaseType, space: Option<&mut Expr>, expr: &mut Box<Expr>) -> Type {
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
    fn unify(&mut self, a: &mut Expr, b: &mut Expr) -> Type {
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

    fn binary(
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
    fn numeric_pair(&mut self, lhs: &mut Expr, rhs: &mut Expr) -> Option<(BaseType, BaseType)> {
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

    fn assign(&mut self, op: AssignOp, target: &mut LValue, value: &mut Box<Expr>) -> Type {
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
    fn lookup_target(&mut self, target: &mut LValue) -> Option<VarRef> {
        let r = self.lookup(&target.name, target.span)?;
        target.var = Some(r);
        if let Err(msg) = self.writable(r) {
            self.error(target.span, format!("cannot assign: {msg}"));
        }
        Some(r)
    }

    // ----- calls ----------------------------------------------------------------------------

    fn visible_user_functions(&self, name: &str) -> Vec<FuncId> {
        let mut out = Vec::new();
        for scope in self.func_scopes.iter().rev() {
            for id in scope.iter().rev() {
                if self.functions[id.0 as usize].name == name {
                    out.push(*id);
                }
            }
        }
        out
    }

    fn call(&mut self, span: Span, call: &mut Call, expected: Option<BaseType>) -> Type {
        for a in &mut call.args {
            self.expr(a, None);
        }
        let infos: Vec<ArgInfo> = call
            .args
            .iter()
            .map(|a| ArgInfo {
                ty: a.ty,
                assignable: self.assignable(a),
                is_str_literal: matches!(a.kind, ExprKind::Str(_)),
            })
            .collect();
        let users = self.visible_user_functions(&call.name);
        if call.name == "PI" {
            self.error(span, "'PI' is a constant, not a function");
            return Type::UNKNOWN;
        }
        if !users.is_empty() {
            return self.user_call(span, call, &users, &infos);
        }
        if self
            .in_progress
            .iter()
            .any(|id| self.functions[id.0 as usize].name == call.name)
        {
            self.error(
                span,
                format!(
                    "'{}' calls itself: the Shading Language has no recursion",
                    call.name
                ),
            );
            return Type::UNKNOWN;
        }
        let overloads: Vec<&Overload> = builtins::overloads(&call.name).collect();
        if overloads.is_empty() {
            self.error(span, format!("unknown function '{}'", call.name));
            return Type::UNKNOWN;
        }
        let mut best: Option<(u32, Signature, Option<usize>)> = None;
        for ov in &overloads {
            if let Some(m) = match_builtin(ov, &infos, expected) {
                if best.as_ref().is_none_or(|b| m.0 < b.0) {
                    best = Some(m);
                }
            }
        }
        let Some((_, sig, optional_from)) = best else {
            let found: Vec<String> = infos.iter().map(|a| a.ty.to_string()).collect();
            self.error(
                span,
                format!(
                    "no overload of '{}' takes ({}){}",
                    call.name,
                    found.join(", "),
                    output_hint(&overloads, &infos)
                ),
            );
            return Type::UNKNOWN;
        };
        if call.name == "lightsource"
            && self.frame().illuminance == 0
            && self.frame().shader_kind.is_some()
        {
            self.error(
                span,
                "'lightsource' may only be called inside an illuminance loop",
            );
        }
        if builtins::is_inherently_varying(&call.name) {
            self.frame().reads_varying = true;
        }
        self.convert_args(&mut call.args, &sig, &call.name);
        let ret = sig.ret;
        call.callee = Some(Callee::Builtin(BuiltinCall {
            name: call.name.clone(),
            sig,
            optional_from,
        }));
        ret
    }

    fn user_call(
        &mut self,
        span: Span,
        call: &mut Call,
        users: &[FuncId],
        infos: &[ArgInfo],
    ) -> Type {
        let mut best: Option<(u32, FuncId)> = None;
        for &id in users {
            let f = &self.functions[id.0 as usize];
            if f.params.len() != infos.len() {
                continue;
            }
            let mut cost = 0;
            let mut ok = true;
            for (p, a) in f.params.iter().zip(infos) {
                if p.output {
                    ok &= a.assignable
                        && (a.ty == p.ty
                            || unknown(a.ty)
                            || (p.ty.array == Some(ArrayLen::Open) && a.ty.base == p.ty.base));
                } else {
                    match conversion_cost(a.ty, p.ty) {
                        Some(c) => cost += c,
                        None => ok = false,
                    }
                }
            }
            if ok && best.is_none_or(|b| cost < b.0) {
                best = Some((cost, id));
            }
        }
        let Some((_, id)) = best else {
            let found: Vec<String> = infos.iter().map(|a| a.ty.to_string()).collect();
            self.error(
                span,
                format!("no function '{}' takes ({})", call.name, found.join(", ")),
            );
            return Type::UNKNOWN;
        };
        if self.in_progress.contains(&id) {
            self.error(
                span,
                format!(
                    "'{}' calls itself: the Shading Language has no recursion",
                    call.name
                ),
            );
        }
        let f = &self.functions[id.0 as usize];
        let sig = Signature {
            ret: f.ret,
            params: f
                .params
                .iter()
                .zip(infos)
                .map(|(p, a)| SigParam {
                    ty: if p.ty.array == Some(ArrayLen::Open) {
                        a.ty
                    } else {
                        p.ty
                    },
                    output: p.output,
                })
                .collect(),
        };
        let (ret, reads) = (f.ret, f.reads_varying);
        if reads {
            self.frame().reads_varying = true;
        }
        self.convert_args(&mut call.args, &sig, &call.name);
        call.callee = Some(Callee::User(id));
        ret
    }

    fn convert_args(&mut self, args: &mut [Expr], sig: &Signature, name: &str) {
        for (i, (a, p)) in args.iter_mut().zip(&sig.params).enumerate() {
            if p.output {
                self.mark_output_arg(a);
            } else {
                let what = format!("argument {} of '{name}'", i + 1);
                self.coerce(a, p.ty, &what);
            }
        }
    }

    /// An `output` argument is written: it must be writable.
    fn mark_output_arg(&mut self, a: &Expr) {
        let r = match &a.kind {
            ExprKind::Var(v) => v.var,
            ExprKind::Index { array, .. } => match &array.kind {
                ExprKind::Var(v) => v.var,
                _ => None,
            },
            _ => None,
        };
        if let Some(r) = r {
            if let Err(msg) = self.writable(r) {
                self.error(a.span, format!("cannot pass as output: {msg}"));
            }
        }
    }

    fn assignable(&self, a: &Expr) -> bool {
        match &a.kind {
            ExprKind::Var(v) => v.var.is_some(),
            ExprKind::Index { array, .. } => {
                matches!(&array.kind, ExprKind::Var(v) if v.var.is_some())
            }
            _ => false,
        }
    }

    fn texture(&mut self, span: Span, tc: &mut TextureCall, expected: Option<BaseType>) -> Type {
        self.expr(&mut tc.map, Some(BaseType::String));
        self.coerce(&mut tc.map, Type::STRING, "texture name");
        if let Some(ch) = tc.channel.as_mut() {
            self.expr(ch, Some(BaseType::Float));
            self.coerce(ch, Type::FLOAT, "texture channel");
        }
        let name = tc.kind.name();
        let (coord_ty, forms): (Type, &[usize]) = match tc.kind {
            TextureKind::Texture => (Type::FLOAT, &[0, 2, 8]),
            TextureKind::Environment => (Type::VECTOR, &[1, 4]),
            TextureKind::Shadow => (Type::POINT, &[1, 4]),
            TextureKind::Bump => (Type::FLOAT, &[3, 5, 11]),
        };
        if !forms.contains(&tc.coords.len()) {
            let want: Vec<String> = forms.iter().map(|n| n.to_string()).collect();
            self.error(
                span,
                format!(
                    "{name} takes {} coordinate argument(s) after the name, found {}",
                    want.join(" or "),
                    tc.coords.len()
                ),
            );
        }
        for (i, c) in tc.coords.iter_mut().enumerate() {
            // bump (name, N, dPds, dPdt [, s, t…]): the first three are vectors.
            let want = if tc.kind == TextureKind::Bump && i < 3 {
                Type::VECTOR
            } else {
                coord_ty
            };
            self.expr(c, Some(want.base));
            let what = format!("coordinate {} of {name}", i + 1);
            self.coerce(c, want, &what);
        }
        for p in &mut tc.params {
            self.expr(&mut p.name, Some(BaseType::String));
            self.coerce(&mut p.name, Type::STRING, "optional parameter name");
            self.expr(&mut p.value, None);
        }
        self.frame().reads_varying = true;
        match (tc.kind, expected) {
            (TextureKind::Bump, _) => Type::VECTOR,
            (_, Some(BaseType::Color)) => Type::COLOR,
            _ => Type::FLOAT,
        }
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

/// A hint for "no overload" errors whose cause is a non-assignable output argument.
fn output_hint(overloads: &[&Overload], args: &[ArgInfo]) -> String {
    let needs_output = overloads.iter().any(|o| {
        o.params.len() == args.len()
            && o.params
                .iter()
                .zip(args)
                .any(|(p, a)| p.output && !a.assignable)
    });
    if needs_output {
        " (an output argument must be a variable)".to_string()
    } else {
        String::new()
    }
}

/// Matches a table overload against the arguments: `(cost, concrete signature,
/// optional_from)`, or `None` if it does not apply.
fn match_builtin(
    ov: &Overload,
    args: &[ArgInfo],
    expected: Option<BaseType>,
) -> Option<(u32, Signature, Option<usize>)> {
    // How many arguments are positional: with pairs allowed, positional ones end at the
    // first string literal at or after the fixed parameters.
    let fixed = ov.params.len();
    let repeat = ov.params.last().is_some_and(|p| p.repeat);
    let positional = if ov.pairs {
        let split = (fixed.saturating_sub(usize::from(repeat))..args.len())
            .find(|&i| args[i].is_str_literal)
            .unwrap_or(args.len());
        if split < fixed.saturating_sub(usize::from(repeat)) || (args.len() - split) % 2 != 0 {
            return None;
        }
        split
    } else {
        args.len()
    };
    // A repeating last parameter may appear zero or more times.
    let min = if repeat { fixed - 1 } else { fixed };
    if positional < min || (!repeat && positional > fixed) {
        return None;
    }
    let spec_at = |i: usize| &ov.params[i.min(fixed - 1)];
    // Bind T: the first triple among T arguments, else float. G: the first geometric.
    let mut t = None;
    let mut g = None;
    for (i, a) in args[..positional].iter().enumerate() {
        let s = spec_at(i);
        match s.slot {
            Slot::Generic if a.ty.base.is_triple() && t.is_none() => t = Some(a.ty.base),
            Slot::Geometric if a.ty.base.is_geometric() && g.is_none() => g = Some(a.ty.base),
            _ => {}
        }
    }
    let t = t.unwrap_or(if ov.ret == Slot::Generic {
        expected
            .filter(|b| *b == BaseType::Float)
            .unwrap_or(BaseType::Float)
    } else {
        BaseType::Float
    });
    let g = g.unwrap_or(BaseType::Vector);
    let r = match expected {
        Some(b @ (BaseType::Float | BaseType::Color | BaseType::Point | BaseType::Vector)) => b,
        _ => BaseType::Float,
    };
    let mut cost = 0;
    let mut params = Vec::with_capacity(args.len());
    for (i, a) in args.iter().enumerate() {
        if i >= positional {
            // "name", value pairs: names are strings, values any type.
            let ty = if (i - positional) % 2 == 0 {
                Type::STRING
            } else {
                a.ty
            };
            if (i - positional) % 2 == 0 && a.ty.base != BaseType::String {
                return None;
            }
            params.push(SigParam { ty, output: false });
            continue;
        }
        let s = spec_at(i);
        let base = match s.slot {
            Slot::Fixed(b) => b,
            Slot::Generic => t,
            Slot::Geometric => g,
            Slot::ContextReturn => r,
            Slot::Any => a.ty.base,
        };
        let ty = if s.array {
            if !a.ty.is_array() {
                return None;
            }
            Type {
                base,
                array: a.ty.array,
            }
        } else if s.slot == Slot::Any {
            a.ty
        } else {
            Type::scalar(base)
        };
        if s.output {
            if !a.assignable || (a.ty != ty && !unknown(a.ty)) {
                return None;
            }
        } else {
            cost += conversion_cost(a.ty, ty)?;
        }
        params.push(SigParam {
            ty,
            output: s.output,
        });
    }
    let ret = match ov.ret {
        Slot::Fixed(b) => b,
        Slot::Generic => t,
        Slot::Geometric => g,
        Slot::ContextReturn => r,
        Slot::Any => BaseType::Float,
    };
    let optional_from = (ov.pairs && positional < args.len()).then_some(positional);
    Some((
        cost,
        Signature {
            ret: Type::scalar(ret),
            params,
        },
        optional_from,
    ))
}
