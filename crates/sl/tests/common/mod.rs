//! A depth-first walk over every expression of a checked program, shared by the tests.
#![allow(dead_code)]

use illume_sl::ast::*;
use illume_sl::types::BaseType;

/// Every expression of the program, depth first.
pub fn all_exprs(p: &Program) -> Vec<&Expr> {
    let mut out = Vec::new();
    for s in &p.shaders {
        for q in &s.params {
            if let Some(d) = &q.default {
                expr(d, &mut out);
            }
        }
        block(&s.body, &mut out);
    }
    for f in &p.functions {
        for q in &f.params {
            if let Some(d) = &q.default {
                expr(d, &mut out);
            }
        }
        block(&f.body, &mut out);
    }
    out
}

fn block<'a>(b: &'a Block, out: &mut Vec<&'a Expr>) {
    for s in &b.stmts {
        stmt(s, out);
    }
}

fn stmt<'a>(s: &'a Stmt, out: &mut Vec<&'a Expr>) {
    match &s.kind {
        StmtKind::Decl(d) => d
            .vars
            .iter()
            .filter_map(|v| v.init.as_ref())
            .for_each(|e| expr(e, out)),
        StmtKind::Expr(e) => expr(e, out),
        StmtKind::Block(b) => block(b, out),
        StmtKind::If {
            cond,
            then,
            otherwise,
        } => {
            expr(cond, out);
            stmt(then, out);
            if let Some(o) = otherwise {
                stmt(o, out);
            }
        }
        StmtKind::While { cond, body } => {
            expr(cond, out);
            stmt(body, out);
        }
        StmtKind::For {
            init,
            cond,
            step,
            body,
        } => {
            for e in [init, cond, step].into_iter().flatten() {
                expr(e, out);
            }
            stmt(body, out);
        }
        StmtKind::Return(Some(e)) => expr(e, out),
        StmtKind::Illuminance(i) => {
            if let Some(c) = &i.category {
                expr(c, out);
            }
            expr(&i.position, out);
            cone(i.cone.as_ref(), out);
            stmt(&i.body, out);
        }
        StmtKind::Illuminate(i) => {
            expr(&i.position, out);
            cone(i.cone.as_ref(), out);
            stmt(&i.body, out);
        }
        StmtKind::Solar(s) => {
            cone(s.cone.as_ref(), out);
            stmt(&s.body, out)
        }
        _ => {}
    }
}

fn cone<'a>(c: Option<&'a Cone>, out: &mut Vec<&'a Expr>) {
    if let Some(c) = c {
        expr(&c.axis, out);
        expr(&c.angle, out);
    }
}

fn expr<'a>(e: &'a Expr, out: &mut Vec<&'a Expr>) {
    out.push(e);
    match &e.kind {
        ExprKind::Tuple(v) | ExprKind::ArrayInit(v) => v.iter().for_each(|x| expr(x, out)),
        ExprKind::Cast { space, expr: x, .. } => {
            if let Some(s) = space {
                expr(s, out);
            }
            expr(x, out);
        }
        ExprKind::Promote(x) | ExprKind::Unary { expr: x, .. } => expr(x, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            expr(lhs, out);
            expr(rhs, out);
        }
        ExprKind::Ternary {
            cond,
            then,
            otherwise,
        } => {
            expr(cond, out);
            expr(then, out);
            expr(otherwise, out);
        }
        ExprKind::Assign { target, value, .. } => {
            if let Some(i) = &target.index {
                expr(i, out);
            }
            expr(value, out);
        }
        ExprKind::Index { array, index } => {
            expr(array, out);
            expr(index, out);
        }
        ExprKind::Call(c) => c.args.iter().for_each(|x| expr(x, out)),
        ExprKind::Texture(t) => {
            expr(&t.map, out);
            if let Some(c) = &t.channel {
                expr(c, out);
            }
            t.coords.iter().for_each(|x| expr(x, out));
            t.params.iter().for_each(|p| {
                expr(&p.name, out);
                expr(&p.value, out);
            });
        }
        _ => {}
    }
}

/// The invariants `ast.rs` promises for a program checked without errors: every expression
/// typed, every variable and call resolved, no error placeholders. Returns what is violated.
pub fn invariant_violations(p: &Program) -> Vec<String> {
    let mut bad = Vec::new();
    for e in all_exprs(p) {
        if e.ty.base == BaseType::Unknown {
            bad.push(format!(
                "untyped expression at {:?}: {:?}",
                e.span.loc, e.kind
            ));
        }
        match &e.kind {
            ExprKind::Var(v) if v.var.is_none() => {
                bad.push(format!("unresolved variable {}", v.name))
            }
            ExprKind::Call(c) if c.callee.is_none() => {
                bad.push(format!("unresolved call {}", c.name))
            }
            ExprKind::Call(Call {
                callee: Some(Callee::Builtin(b)),
                args,
                ..
            }) => {
                if b.sig.params.len() != args.len() {
                    bad.push(format!(
                        "{}: {} params for {} args",
                        b.name,
                        b.sig.params.len(),
                        args.len()
                    ));
                }
                for (a, q) in args.iter().zip(&b.sig.params) {
                    if !q.output && a.ty != q.ty {
                        bad.push(format!(
                            "{}: argument typed {} for parameter {}",
                            b.name, a.ty, q.ty
                        ));
                    }
                }
            }
            ExprKind::Assign { target, .. } if target.var.is_none() => {
                bad.push(format!("unresolved assignment target {}", target.name))
            }
            ExprKind::Error => bad.push("error placeholder".into()),
            _ => {}
        }
    }
    bad
}
