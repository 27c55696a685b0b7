//! Uniform/varying inference over a typed tree (RI 3.2 §11.4).
//!
//! An expression is varying when anything it reads is varying. A local declared without
//! `uniform`/`varying` starts out *optimistically uniform* and becomes varying when a varying
//! value is assigned to it or when it is assigned under varying control flow (a varying `if`
//! or loop condition, a loop left by a varying `break`/`continue`/`return`, the statements
//! after a varying `return`, and every `illuminance`/`illuminate`/`solar` body). Because one local's detail
//! feeds another's, the walk repeats until nothing changes (details only ever rise from
//! uniform to varying, so this terminates). A final walk writes [`Expr::detail`] and
//! [`VarInfo::inferred`].
//!
//! A variable that is uniform by declaration (or as a shader parameter) but is given a varying
//! value or assigned under varying control flow is a warning, not an error, and the variable
//! becomes varying: peer compilers accept such shaders and exporters' shaders rely on it.
//!
//! Variables that a nested function reaches through `extern` keep their declared/default
//! detail: the nested body may write them in ways the encloser's walk does not see.

use crate::ast::*;
use crate::diagnostic::Diagnostic;
use crate::span::Span;
use crate::types::Detail;
use std::collections::{HashMap, HashSet};

/// Runs inference for every shader and function of a checked program.
pub fn infer(prog: &mut Program, diags: &mut Vec<Diagnostic>) {
    let pinned = extern_targets(prog);
    let mut done: HashMap<Owner, Vec<Detail>> = HashMap::new();
    let reads: Vec<bool> = prog.functions.iter().map(|f| f.reads_varying).collect();
    let outs: Vec<Vec<bool>> = prog
        .functions
        .iter()
        .map(|f| f.params.iter().map(|p| p.output).collect())
        .collect();
    let uniform_params: Vec<Vec<bool>> = prog
        .functions
        .iter()
        .map(|f| {
            f.params
                .iter()
                .map(|p| p.detail == Some(Detail::Uniform))
                .collect()
        })
        .collect();
    let ctx = Ctx {
        pinned: &pinned,
        reads: &reads,
        user_outputs: &outs,
        uniform_params: &uniform_params,
    };
    for i in 0..prog.shaders.len() {
        let owner = Owner::Shader(ShaderId(i as u32));
        let sh = &mut prog.shaders[i];
        let details = run(owner, &sh.vars, &mut sh.body, &ctx, &done, diags);
        for (v, d) in sh.vars.iter_mut().zip(&details) {
            v.inferred = *d;
        }
        annotate_defaults(&mut sh.params, &sh.vars, &ctx, &done);
        done.insert(owner, details);
    }
    for i in 0..prog.functions.len() {
        let owner = Owner::Function(FuncId(i as u32));
        let f = &mut prog.functions[i];
        let details = run(owner, &f.vars, &mut f.body, &ctx, &done, diags);
        for (v, d) in f.vars.iter_mut().zip(&details) {
            v.inferred = *d;
        }
        annotate_defaults(&mut f.params, &f.vars, &ctx, &done);
        done.insert(owner, details);
    }
}

/// Program-wide facts the walk needs.
struct Ctx<'a> {
    /// Slots reached through `extern` from nested functions.
    pinned: &'a HashSet<(Owner, VarId)>,
    /// Per user function: it reads something varying besides its parameters.
    reads: &'a [bool],
    /// Per user function: which parameters are `output`.
    user_outputs: &'a [Vec<bool>],
    /// Per user function: which parameters are declared `uniform`.
    uniform_params: &'a [Vec<bool>],
}

/// Parameter defaults are evaluated once per shader instance: annotate them too.
fn annotate_defaults(
    params: &mut [Param],
    vars: &[VarInfo],
    ctx: &Ctx<'_>,
    done: &HashMap<Owner, Vec<Detail>>,
) {
    let details: Vec<Detail> = vars.iter().map(|v| v.inferred).collect();
    let mut w = Walker {
        details,
        pinned_here: HashSet::new(),
        vars,
        done,
        reads: ctx.reads,
        user_outputs: ctx.user_outputs,
        uniform_params: ctx.uniform_params,
        changed: false,
        report: None,
        promoted: Vec::new(),
        varying_loops: HashSet::new(),
        loop_counter: 0,
        diverged: false,
        fn_diverged: false,
    };
    for p in params {
        if let Some(d) = p.default.as_mut() {
            w.expr(d, false);
        }
    }
}

/// Every `(owner, slot)` some nested function names through `extern`.
fn extern_targets(prog: &Program) -> HashSet<(Owner, VarId)> {
    let mut set = HashSet::new();
    for f in &prog.functions {
        for v in &f.body.stmts {
            collect_outer(v, &mut set);
        }
    }
    set
}

fn collect_outer(s: &Stmt, set: &mut HashSet<(Owner, VarId)>) {
    let mut visit = |r: Option<VarRef>| {
        if let Some(VarRef::Outer { owner, var }) = r {
            set.insert((owner, var));
        }
    };
    match &s.kind {
        StmtKind::Decl(d) => d.vars.iter().for_each(|v| visit(v.var)),
        StmtKind::Block(b) => b.stmts.iter().for_each(|s| collect_outer(s, set)),
        StmtKind::If {
            then, otherwise, ..
        } => {
            collect_outer(then, set);
            if let Some(o) = otherwise {
                collect_outer(o, set);
            }
        }
        StmtKind::While { body, .. } | StmtKind::For { body, .. } => collect_outer(body, set),
        StmtKind::Illuminance(i) => collect_outer(&i.body, set),
        StmtKind::Illuminate(i) => collect_outer(&i.body, set),
        StmtKind::Solar(i) => collect_outer(&i.body, set),
        _ => {}
    }
}

/// Fixpoint for one shader or function; returns the inferred detail of every slot.
fn run(
    owner: Owner,
    vars: &[VarInfo],
    body: &mut Block,
    ctx: &Ctx<'_>,
    done: &HashMap<Owner, Vec<Detail>>,
    diags: &mut Vec<Diagnostic>,
) -> Vec<Detail> {
    let pinned = ctx.pinned;
    let refinable = |i: usize| {
        let v = &vars[i];
        v.kind == VarKind::Local
            && v.declared.is_none()
            && !pinned.contains(&(owner, VarId(i as u32)))
    };
    let details: Vec<Detail> = (0..vars.len())
        .map(|i| {
            if refinable(i) {
                Detail::Uniform
            } else {
                vars[i].detail
            }
        })
        .collect();
    let pinned_here: HashSet<usize> = (0..vars.len()).filter(|&i| !refinable(i)).collect();
    let mut w = Walker {
        details,
        pinned_here,
        vars,
        done,
        reads: ctx.reads,
        user_outputs: ctx.user_outputs,
        uniform_params: ctx.uniform_params,
        changed: true,
        report: None,
        promoted: Vec::new(),
        varying_loops: HashSet::new(),
        loop_counter: 0,
        diverged: false,
        fn_diverged: false,
    };
    // Each round that changes something raises at least one slot, loop or the body to
    // varying, and nothing is ever lowered, so at most `slots + loops + 1` rounds change
    // anything; the bound only guards against a bug looping forever.
    let mut rounds = 0;
    while w.changed && rounds <= vars.len() + w.loop_counter + 2 {
        w.changed = false;
        w.loop_counter = 0;
        w.fn_diverged = false;
        w.block(body, false);
        rounds += 1;
    }
    let mut report = Vec::new();
    w.report = Some(&mut report);
    w.loop_counter = 0;
    w.fn_diverged = false;
    w.block(body, false);
    let details = w.details.clone();
    diags.append(&mut w.promoted);
    diags.extend(report);
    details
}

struct Walker<'a, 'r> {
    details: Vec<Detail>,
    /// Slots whose detail is fixed (declared, parameters, extern targets).
    pinned_here: HashSet<usize>,
    vars: &'a [VarInfo],
    done: &'a HashMap<Owner, Vec<Detail>>,
    reads: &'a [bool],
    /// Per user function, which parameters are `output`.
    user_outputs: &'a [Vec<bool>],
    /// Per user function, which parameters are declared `uniform`.
    uniform_params: &'a [Vec<bool>],
    changed: bool,
    /// `Some` on the final walk: where to report declared-uniform violations.
    report: Option<&'r mut Vec<Diagnostic>>,
    /// Warnings for declared-uniform variables raised to varying (one per variable).
    promoted: Vec<Diagnostic>,
    /// Loops (by walk order) whose body runs under varying control because of a varying
    /// `break`/`continue` inside.
    varying_loops: HashSet<usize>,
    loop_counter: usize,
    /// A `break`/`continue` under varying control was seen in the current loop body.
    diverged: bool,
    /// A `return` under varying control was seen earlier in this walk: the statements after
    /// it are varying control.
    fn_diverged: bool,
}

impl Walker<'_, '_> {
    fn var_detail(&self, r: VarRef) -> Detail {
        match r {
            VarRef::Global(g) => g.detail(),
            VarRef::Slot(id) => self
                .details
                .get(id.0 as usize)
                .copied()
                .unwrap_or(Detail::Varying),
            VarRef::Outer { owner, var } => self
                .done
                .get(&owner)
                .and_then(|d| d.get(var.0 as usize))
                .copied()
                .unwrap_or(Detail::Varying),
        }
    }

    /// Records that `r` receives a value of `detail` (under varying control if `vc`).
    fn assign(&mut self, r: Option<VarRef>, detail: Detail, vc: bool, span: Span) {
        let Some(VarRef::Slot(id)) = r else {
            return;
        };
        let i = id.0 as usize;
        if i >= self.details.len() {
            return;
        }
        let incoming = if vc { Detail::Varying } else { detail };
        if self.pinned_here.contains(&i)
            && self.details[i] == Detail::Uniform
            && incoming == Detail::Varying
        {
            // Peer compilers accept this with a warning and make the variable varying, and
            // exporter shaders (Liquid's liquidspot, Advanced RenderMan's terran.sl) rely on
            // it; warned once, at the first such assignment.
            let name = &self.vars[i].name;
            let msg = if detail == Detail::Varying {
                format!("uniform variable '{name}' is given a varying value; it becomes varying")
            } else {
                format!("uniform variable '{name}' is assigned under varying control flow (a varying condition, loop or lighting construct); it becomes varying")
            };
            self.promoted.push(Diagnostic::warning(span, msg));
        }
        if incoming == Detail::Varying && self.details[i] == Detail::Uniform {
            self.details[i] = Detail::Varying;
            self.changed = true;
        }
    }

    fn block(&mut self, b: &mut Block, vc: bool) {
        for s in &mut b.stmts {
            self.stmt(s, vc || self.fn_diverged);
        }
    }

    fn stmt(&mut self, s: &mut Stmt, vc: bool) {
        match &mut s.kind {
            StmtKind::Decl(d) => {
                for v in &mut d.vars {
                    if let Some(init) = v.init.as_mut() {
                        let det = self.expr(init, vc);
                        self.assign(v.var, det, vc, v.span);
                    }
                }
            }
            StmtKind::Expr(e) => {
                self.expr(e, vc);
            }
            StmtKind::Block(b) => self.block(b, vc),
            StmtKind::If {
                cond,
                then,
                otherwise,
            } => {
                let inner = vc || self.expr(cond, vc) == Detail::Varying;
                self.stmt(then, inner);
                if let Some(o) = otherwise {
                    self.stmt(o, inner);
                }
            }
            StmtKind::While { cond, body } => {
                let c = self.expr(cond, vc);
                self.looped(body, vc, c, None);
                // The condition is evaluated again after the body changed its inputs.
                self.expr(cond, vc);
            }
            StmtKind::For {
                init,
                cond,
                step,
                body,
            } => {
                if let Some(i) = init {
                    self.expr(i, vc);
                }
                let c = cond.as_mut().map_or(Detail::Uniform, |c| self.expr(c, vc));
                self.looped(body, vc, c, step.as_mut());
                if let Some(c) = cond {
                    self.expr(c, vc);
                }
            }
            StmtKind::Break(_) | StmtKind::Continue(_) => {
                if vc {
                    self.diverged = true;
                }
            }
            StmtKind::Return(v) => {
                if let Some(v) = v {
                    self.expr(v, vc);
                }
                // Points that returned stop running: everything after this statement (and, in
                // a loop, every later iteration) runs under a varying mask.
                if vc {
                    self.fn_diverged = true;
                    self.diverged = true;
                }
            }
            StmtKind::Illuminance(il) => {
                if let Some(c) = il.category.as_mut() {
                    self.expr(c, vc);
                }
                self.expr(&mut il.position, vc);
                if let Some(c) = il.cone.as_mut() {
                    self.expr(&mut c.axis, vc);
                    self.expr(&mut c.angle, vc);
                }
                // A loop over lights whose body runs masked per point.
                self.looped(&mut il.body, true, Detail::Varying, None);
            }
            StmtKind::Illuminate(il) => {
                self.expr(&mut il.position, vc);
                if let Some(c) = il.cone.as_mut() {
                    self.expr(&mut c.axis, vc);
                    self.expr(&mut c.angle, vc);
                }
                self.stmt(&mut il.body, true);
            }
            StmtKind::Solar(so) => {
                if let Some(c) = so.cone.as_mut() {
                    self.expr(&mut c.axis, vc);
                    self.expr(&mut c.angle, vc);
                }
                self.stmt(&mut so.body, true);
            }
            StmtKind::Function(_) | StmtKind::Empty | StmtKind::Error => {}
        }
    }

    /// A loop body (and step), under varying control when the condition is varying or a
    /// varying `break`/`continue` leaves it early.
    fn looped(&mut self, body: &mut Stmt, vc: bool, cond: Detail, step: Option<&mut Expr>) {
        let idx = self.loop_counter;
        self.loop_counter += 1;
        let inner = vc || cond == Detail::Varying || self.varying_loops.contains(&idx);
        let outer_diverged = std::mem::replace(&mut self.diverged, false);
        self.stmt(body, inner);
        if let Some(st) = step {
            self.expr(st, inner);
        }
        if self.diverged && self.varying_loops.insert(idx) {
            self.changed = true;
        }
        self.diverged = outer_diverged;
    }

    /// Computes, stores and returns the detail of `e`.
    fn expr(&mut self, e: &mut Expr, vc: bool) -> Detail {
        let span = e.span;
        let d = match &mut e.kind {
            ExprKind::Float(_) | ExprKind::Str(_) | ExprKind::Error => Detail::Uniform,
            ExprKind::Var(v) => v.var.map_or(Detail::Varying, |r| self.var_detail(r)),
            ExprKind::Tuple(el) | ExprKind::ArrayInit(el) => el
                .iter_mut()
                .fold(Detail::Uniform, |acc, x| acc.join(self.expr(x, vc))),
            ExprKind::Cast { space, expr, .. } => {
                let s = space.as_mut().map_or(Detail::Uniform, |s| self.expr(s, vc));
                s.join(self.expr(expr, vc))
            }
            ExprKind::Promote(x) => self.expr(x, vc),
            ExprKind::Unary { expr, .. } => self.expr(expr, vc),
            ExprKind::Binary { lhs, rhs, .. } => {
                let a = self.expr(lhs, vc);
                a.join(self.expr(rhs, vc))
            }
            ExprKind::Ternary {
                cond,
                then,
                otherwise,
            } => {
                let c = self.expr(cond, vc);
                let a = self.expr(then, vc);
                c.join(a).join(self.expr(otherwise, vc))
            }
            ExprKind::Assign { op, target, value } => {
                let ix = target
                    .index
                    .as_mut()
                    .map_or(Detail::Uniform, |i| self.expr(i, vc));
                let mut v = self.expr(value, vc).join(ix);
                if *op != AssignOp::Assign {
                    v = v.join(target.var.map_or(Detail::Varying, |r| self.var_detail(r)));
                }
                // Writing one element with a varying index makes the whole array varying.
                self.assign(target.var, v, vc, target.span);
                v
            }
            ExprKind::Index { array, index } => {
                let a = self.expr(array, vc);
                a.join(self.expr(index, vc))
            }
            ExprKind::Call(call) => self.call(call, vc, span),
            ExprKind::Texture(tc) => {
                self.expr(&mut tc.map, vc);
                if let Some(c) = tc.channel.as_mut() {
                    self.expr(c, vc);
                }
                for c in &mut tc.coords {
                    self.expr(c, vc);
                }
                for p in &mut tc.params {
                    self.expr(&mut p.name, vc);
                    self.expr(&mut p.value, vc);
                }
                Detail::Varying
            }
        };
        e.detail = d;
        d
    }

    fn call(&mut self, call: &mut Call, vc: bool, span: Span) -> Detail {
        let outputs: Vec<bool> = match &call.callee {
            Some(Callee::Builtin(b)) => b.sig.params.iter().map(|p| p.output).collect(),
            Some(Callee::User(id)) => self
                .user_outputs
                .get(id.0 as usize)
                .cloned()
                .unwrap_or_default(),
            None => Vec::new(),
        };
        let mut d = match &call.callee {
            Some(Callee::Builtin(b)) if b.id.is_inherently_varying() => Detail::Varying,
            Some(Callee::User(id)) if self.reads.get(id.0 as usize).copied().unwrap_or(true) => {
                Detail::Varying
            }
            Some(_) => Detail::Uniform,
            None => Detail::Varying,
        };
        // Inputs decide the call's detail; output arguments receive it.
        let uniform_params: Vec<bool> = match &call.callee {
            Some(Callee::User(id)) => self
                .uniform_params
                .get(id.0 as usize)
                .cloned()
                .unwrap_or_default(),
            _ => Vec::new(),
        };
        let mut out_targets = Vec::new();
        for (i, a) in call.args.iter_mut().enumerate() {
            let ad = self.expr(a, vc);
            if ad == Detail::Varying && uniform_params.get(i).copied().unwrap_or(false) {
                if let Some(rep) = self.report.as_deref_mut() {
                    rep.push(Diagnostic::error(
                        a.span,
                        format!(
                            "argument {} of '{}' must be uniform (the parameter is declared uniform), found a varying value",
                            i + 1,
                            call.name
                        ),
                    ));
                }
            }
            if outputs.get(i).copied().unwrap_or(false) {
                out_targets.push(i);
            } else {
                d = d.join(ad);
            }
        }
        for i in out_targets {
            let r = match &call.args[i].kind {
                ExprKind::Var(v) => v.var,
                ExprKind::Index { array, .. } => match &array.kind {
                    ExprKind::Var(v) => v.var,
                    _ => None,
                },
                _ => None,
            };
            self.assign(r, d, vc, span);
        }
        d
    }
}
