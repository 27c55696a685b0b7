//! Name lookup: block scopes, `extern` references to an encloser's variables or globals, and
//! which variables may be written.

use super::{unknown, Checker};
use crate::ast::*;
use crate::diagnostic::Diagnostic;
use crate::span::Span;
use crate::types::{Detail, ShaderKind, Type};

impl Checker<'_> {
    /// Resolves `extern type name`: a variable of an enclosing function or shader, else a
    /// global.
    pub(super) fn extern_ref(&mut self, name: &str, span: Span, ty: Type) -> Option<VarRef> {
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

    pub(super) fn check_extern_type(&mut self, name: &str, span: Span, ty: Type, r: VarRef) {
        let actual = self.var_type(r);
        if actual != ty && !unknown(actual) {
            self.error(
                span,
                format!("extern '{name}' is declared {ty} but the variable is {actual}"),
            );
        }
    }

    // ----- variables ------------------------------------------------------------------------

    pub(super) fn var_type(&self, r: VarRef) -> Type {
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
    pub(super) fn lookup(&mut self, name: &str, span: Span) -> Option<VarRef> {
        let frame = self.frames.last()?;
        if let Some(r) = frame.scopes.iter().rev().find_map(|s| s.get(name).copied()) {
            return Some(r);
        }
        if let Some(mut g) = Global::from_name(name) {
            if let Some(kind) = frame.shader_kind {
                // `Ps` in a surface shader: peers (Aqsis, PRMan) accept it as the surface point,
                // and library shaders written for them use it; a warning, and it reads `P`.
                if g == Global::Ps && kind == ShaderKind::Surface {
                    self.diags.push(Diagnostic::warning(
                        span,
                        format!("global 'Ps' is not defined in a {kind} shader: using P"),
                    ));
                    g = Global::P;
                }
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
    pub(super) fn writable(&self, r: VarRef) -> Result<(), String> {
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
}
