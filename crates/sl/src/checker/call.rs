//! Calls: user functions shadow built-ins of the same name; the built-in is resolved once to
//! its [`BuiltinId`] and overload (see `overload.rs`); the texture family.

use super::overload::{self, ArgInfo};
use super::Checker;
use crate::ast::*;
use crate::diagnostic::Diagnostic;
use crate::span::Span;
use crate::types::{BaseType, Type};

impl Checker<'_> {
    pub(super) fn visible_user_functions(&self, name: &str) -> Vec<FuncId> {
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

    pub(super) fn call(&mut self, span: Span, call: &mut Call, expected: Option<BaseType>) -> Type {
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
        let Some(id) = BuiltinId::from_name(&call.name) else {
            return self.unknown_call(span, call, expected);
        };
        let Some((sig, optional_from)) = overload::resolve_builtin(id, &infos, expected) else {
            let found: Vec<String> = infos.iter().map(|a| a.ty.to_string()).collect();
            self.error(
                span,
                format!(
                    "no overload of '{}' takes ({}){}",
                    call.name,
                    found.join(", "),
                    overload::output_hint(id, &infos)
                ),
            );
            return Type::UNKNOWN;
        };
        if id == BuiltinId::LightSource
            && self.frame().illuminance == 0
            && self.frame().shader_kind.is_some()
        {
            self.error(
                span,
                "'lightsource' may only be called inside an illuminance loop",
            );
        }
        if id.is_inherently_varying() {
            self.frame().reads_varying = true;
        }
        self.convert_args(&mut call.args, &sig, &call.name);
        let ret = sig.ret;
        call.callee = Some(Callee::Builtin(BuiltinCall {
            name: call.name.clone(),
            id,
            sig,
            optional_from,
        }));
        ret
    }

    /// A call to a name that is neither a visible user function nor a built-in. A function
    /// of that name defined later in the file is an error (SL functions are defined before
    /// use). Anything else is taken for another renderer's extension (`bake`,
    /// `transmission`, …), as peer compilers do: a warning here, the call left unresolved
    /// (`callee: None`, typed from context, float without one), and an error reported by the
    /// executor only if the call is reached.
    fn unknown_call(&mut self, span: Span, call: &Call, expected: Option<BaseType>) -> Type {
        if self.functions.iter().any(|f| f.name == call.name) {
            self.error(span, format!("unknown function '{}'", call.name));
            return Type::UNKNOWN;
        }
        self.diags.push(Diagnostic::warning(
            span,
            format!(
                "unknown function '{}' (another renderer's extension?): calling it at run time is an error",
                call.name
            ),
        ));
        self.frame().reads_varying = true;
        match expected {
            Some(b) if b != BaseType::Void && b != BaseType::Unknown => Type::scalar(b),
            _ => Type::FLOAT,
        }
    }

    pub(super) fn user_call(
        &mut self,
        span: Span,
        call: &mut Call,
        users: &[FuncId],
        infos: &[ArgInfo],
    ) -> Type {
        let Some(id) = overload::best_user(&self.functions, users, infos) else {
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
        let sig = overload::user_signature(f, infos);
        let (ret, reads) = (f.ret, f.reads_varying);
        if reads {
            self.frame().reads_varying = true;
        }
        self.convert_args(&mut call.args, &sig, &call.name);
        call.callee = Some(Callee::User(id));
        ret
    }

    pub(super) fn convert_args(&mut self, args: &mut [Expr], sig: &Signature, name: &str) {
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
    pub(super) fn mark_output_arg(&mut self, a: &Expr) {
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

    pub(super) fn assignable(&self, a: &Expr) -> bool {
        match &a.kind {
            ExprKind::Var(v) => v.var.is_some(),
            ExprKind::Index { array, .. } => {
                matches!(&array.kind, ExprKind::Var(v) if v.var.is_some())
            }
            _ => false,
        }
    }

    pub(super) fn texture(
        &mut self,
        span: Span,
        tc: &mut TextureCall,
        expected: Option<BaseType>,
    ) -> Type {
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
