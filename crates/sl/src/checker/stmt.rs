//! Statements: blocks and scopes, control flow, declarations, `return`, and the lighting
//! constructs with the shader kinds that may use them.

use super::{unknown, Checker};
use crate::ast::*;
use crate::span::Span;
use crate::types::{BaseType, Detail, ShaderKind, Type};
use std::collections::HashMap;

impl Checker<'_> {
    // ----- statements -----------------------------------------------------------------------

    /// The statements of a body or block in a new scope.
    pub(super) fn block_stmts(&mut self, b: &mut Block) {
        self.frame().scopes.push(HashMap::new());
        self.func_scopes.push(Vec::new());
        for s in &mut b.stmts {
            self.stmt(s);
        }
        self.func_scopes.pop();
        self.frame().scopes.pop();
    }

    /// A statement that is the body of a control construct gets its own scope too.
    pub(super) fn scoped_stmt(&mut self, s: &mut Stmt) {
        self.frame().scopes.push(HashMap::new());
        self.stmt(s);
        self.frame().scopes.pop();
    }

    pub(super) fn stmt(&mut self, s: &mut Stmt) {
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

    pub(super) fn loop_body(&mut self, body: &mut Stmt) {
        self.frame().loops += 1;
        self.scoped_stmt(body);
        self.frame().loops -= 1;
    }

    pub(super) fn condition(&mut self, e: &mut Expr, what: &str) {
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

    pub(super) fn cone(&mut self, c: &mut Cone) {
        self.expr(&mut c.axis, Some(BaseType::Vector));
        self.coerce(&mut c.axis, Type::VECTOR, "cone axis");
        self.expr(&mut c.angle, Some(BaseType::Float));
        self.coerce(&mut c.angle, Type::FLOAT, "cone angle");
    }

    pub(super) fn require_light(&mut self, span: Span, what: &str) {
        if let Some(k) = self.frame().shader_kind {
            if k != ShaderKind::Light {
                self.error(
                    span,
                    format!("'{what}' is only allowed in light shaders, not in a {k} shader"),
                );
            }
        }
    }

    pub(super) fn illuminance(&mut self, span: Span, il: &mut Illuminance) {
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

    pub(super) fn return_stmt(&mut self, span: Span, value: Option<&mut Expr>) {
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

    pub(super) fn decl(&mut self, d: &mut Decl) {
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
}
