//! Statements under a running-state mask: blocks, varying `if`, loops with `break n` /
//! `continue n` bookkeeping, `return`, declarations.

use super::{zero_of, Exec, LoopState, MAX_LOOP_ITERATIONS, MAX_TOTAL_ITERATIONS};
use crate::value::{zip2, Mask, Slot, Value};
use glam::Vec3;
use illume_sl::ast::{Block, Expr, Global, Stmt, StmtKind, VarRef};

impl Exec<'_> {
    /// `mask` without the points that returned, broke or continued in the innermost loop.
    pub(super) fn live(&self, mask: &Mask) -> Mask {
        self.retired(mask).unwrap_or_else(|| mask.clone())
    }

    /// [`Exec::live`], or `None` when no point has left (the common case: no copy of `mask`).
    fn retired(&self, mask: &Mask) -> Option<Mask> {
        let f = self.frames.last()?;
        let l = f.loops.last();
        if f.returned.none() && l.is_none_or(|l| l.broken.none() && l.continued.none()) {
            return None;
        }
        let mut m = mask.minus(&f.returned);
        if let Some(l) = l {
            m = m.minus(&l.broken).minus(&l.continued);
        }
        Some(m)
    }

    pub(super) fn exec_block(&mut self, block: &Block, mask: &Mask) {
        for stmt in &block.stmts {
            let retired = self.retired(mask);
            let m = retired.as_ref().unwrap_or(mask);
            if m.none() {
                return;
            }
            self.exec_stmt(stmt, m);
        }
    }

    pub(super) fn exec_stmt(&mut self, stmt: &Stmt, mask: &Mask) {
        self.at = Some(stmt.span.loc);
        match &stmt.kind {
            StmtKind::Decl(d) => {
                for decl in &d.vars {
                    if d.is_extern {
                        continue;
                    }
                    let Some(VarRef::Slot(slot)) = decl.var else {
                        continue;
                    };
                    let ty = self.var_type(slot);
                    let v = match &decl.init {
                        Some(e) => self.eval(e, mask),
                        None => zero_of(ty),
                    };
                    let f = self.frames.last_mut().expect("a frame runs");
                    // A declaration (re)creates the variable: inside a loop or varying branch
                    // only the running points take the initial value.
                    f.vars[slot.0 as usize].assign(&v, Some(mask), self.n);
                }
            }
            StmtKind::Expr(e) => {
                self.eval(e, mask);
            }
            StmtKind::Block(b) => self.exec_block(b, mask),
            StmtKind::If {
                cond,
                then,
                otherwise,
            } => {
                let c = self.eval_cond(cond, mask);
                let (on, off) = mask.split(&c);
                if !on.none() {
                    self.exec_stmt(then, &on);
                }
                if let Some(o) = otherwise {
                    let off = self.live(&off);
                    if !off.none() {
                        self.exec_stmt(o, &off);
                    }
                }
            }
            StmtKind::While { cond, body } => self.exec_loop(None, Some(cond), None, body, mask),
            StmtKind::For {
                init,
                cond,
                step,
                body,
            } => self.exec_loop(init.as_ref(), cond.as_ref(), step.as_ref(), body, mask),
            StmtKind::Break(levels) => self.retire(*levels, mask, false),
            StmtKind::Continue(levels) => self.retire(*levels, mask, true),
            StmtKind::Return(e) => {
                let v = e.as_ref().map(|e| self.eval(e, mask));
                let n = self.n;
                let f = self.frames.last_mut().expect("a frame runs");
                if let Some(v) = v {
                    if matches!(f.ret, Value::Void) {
                        f.ret = v;
                    } else {
                        f.ret.assign(&v, Some(mask), n);
                    }
                }
                f.returned = f.returned.union(mask);
            }
            StmtKind::Illuminance(il) => self.exec_illuminance(il, mask),
            StmtKind::Illuminate(il) => {
                let pos = self.eval(&il.position, mask);
                let ps = self.global(Global::Ps).clone();
                let n = self.n;
                let l = match (&ps, &pos) {
                    (Value::Triple(a), Value::Triple(b)) => zip2(a, b, n, |a, b| *a - *b),
                    _ => Slot::Uniform(Vec3::ZERO),
                };
                let cone = il.cone.as_ref().map(|c| {
                    (
                        self.eval_triple(&c.axis, mask),
                        self.eval_float(&c.angle, mask),
                    )
                });
                self.emit(l, cone, &il.body, mask);
            }
            StmtKind::Solar(s) => {
                // solar(axis, angle): light arriving along `axis` (L = axis); without a cone
                // the direction is the surface point's own (-I) — an omnidirectional sky.
                // solar(axis, angle): light travelling along `axis` (L = axis). L = axis is
                // inside the cone it names, so every running point is lit. Without a cone the
                // light comes from wherever the surface faces (L = -N).
                let l = match &s.cone {
                    Some(c) => self.eval_triple(&c.axis, mask),
                    None => {
                        let nn = self.global(Global::N).as_triple().cloned();
                        nn.unwrap_or(Slot::Uniform(Vec3::Z)).map(|v| -*v)
                    }
                };
                self.emit(l, None, &s.body, mask);
            }
            StmtKind::Function(_) | StmtKind::Empty | StmtKind::Error => {}
        }
    }

    pub(super) fn push_loop(&mut self) {
        let n = self.n;
        if let Some(f) = self.frames.last_mut() {
            f.loops.push(LoopState {
                broken: Mask::from_bits(vec![false; n]),
                continued: Mask::from_bits(vec![false; n]),
            });
        }
    }

    pub(super) fn pop_loop(&mut self) {
        if let Some(f) = self.frames.last_mut() {
            f.loops.pop();
        }
    }

    /// `break n` / `continue n`: the points leave the `n - 1` innermost loops, then leave (or
    /// skip the iteration of) the `n`th.
    pub(super) fn retire(&mut self, levels: u32, mask: &Mask, is_continue: bool) {
        let Some(f) = self.frames.last_mut() else {
            return;
        };
        let depth = f.loops.len();
        let levels = (levels.max(1) as usize).min(depth);
        for k in 0..levels {
            let l = &mut f.loops[depth - 1 - k];
            if is_continue && k + 1 == levels {
                l.continued = l.continued.union(mask);
            } else {
                l.broken = l.broken.union(mask);
            }
        }
    }

    pub(super) fn exec_loop(
        &mut self,
        init: Option<&Expr>,
        cond: Option<&Expr>,
        step: Option<&Expr>,
        body: &Stmt,
        mask: &Mask,
    ) {
        if let Some(e) = init {
            self.eval(e, mask);
        }
        self.push_loop();
        let mut running = mask.clone();
        // Bounds on iterations so that a shader whose condition never fails cannot hang the
        // renderer (no RI 3.2 program needs 65536 iterations of one loop on one grid);
        // hitting one is an error naming the shader and the loop's line (see `report`).
        let mut iterations = 0u32;
        let line = cond.or(step).map(|e| (e.span.loc.line, e.span.loc.col));
        // The loop statement itself (the body's statements move `at` on).
        let loop_at = self.at;
        loop {
            iterations += 1;
            self.loop_iterations += 1;
            if self.runaway
                || iterations > MAX_LOOP_ITERATIONS
                || self.loop_iterations > MAX_TOTAL_ITERATIONS
            {
                if !self.runaway {
                    let at = line.map_or(String::new(), |(l, c)| format!(" (line {l}:{c})"));
                    let message = format!(
                        "a loop{at} ran {} times on one grid ({} in all loops; limits \
                         {MAX_LOOP_ITERATIONS} per loop, {MAX_TOTAL_ITERATIONS} in all) and was \
                         stopped",
                        iterations - 1,
                        self.loop_iterations - 1
                    );
                    let e = (loop_at, message);
                    if !self.errors.contains(&e) {
                        self.errors.push(e);
                    }
                }
                self.runaway = true;
                break;
            }
            let live = {
                let f = self.frames.last().expect("a frame runs");
                let l = f.loops.last().expect("pushed");
                running.minus(&l.broken).minus(&f.returned)
            };
            if live.none() {
                break;
            }
            running = match cond {
                Some(c) => {
                    let cv = self.eval_cond(c, &live);
                    live.split(&cv).0
                }
                None => live,
            };
            if running.none() {
                break;
            }
            self.exec_stmt(body, &running);
            if let Some(l) = self.frames.last_mut().and_then(|f| f.loops.last_mut()) {
                l.continued = Mask::from_bits(vec![false; l.continued.len()]);
            }
            if let Some(s) = step {
                let m = self.live(&running);
                if !m.none() {
                    self.eval(s, &m);
                }
            }
        }
        self.pop_loop();
    }
}
