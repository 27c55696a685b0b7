//! The executor: walks a checked `illume_sl` AST once per grid. Every expression evaluates for
//! all grid points at once into a [`Value`]; uniform operands give uniform results (computed
//! once). Statements run under a running-state [`Mask`]: a varying `if` splits it, loops retire
//! points whose condition fails or that `break`, `illuminance` runs its body once per light for
//! the points that light reaches. Assignments write only the running points.
use crate::lights::{in_cone, Lights};
use crate::operators::{self, BinOp};
use crate::value::{zip2, Mask, Slot, Value};
use glam::{DMat4, Vec3};
use illume_shade::{ShadingEnv, ShadingGrid};
use illume_sl::ast::{
    BinaryOp, Block, Callee, Expr, ExprKind, FuncId, Global, LValue, Owner, Program, ShaderId,
    Stmt, StmtKind, UnaryOp, VarId, VarRef,
};
use illume_sl::types::{BaseType, Type};
use std::sync::Arc;

/// The zero value of a type (matrices: the identity, so an unset matrix transforms nothing).
pub fn zero_of(ty: Type) -> Value {
    let elem = match ty.base {
        BaseType::Float => Value::float(0.0),
        BaseType::Color | BaseType::Point | BaseType::Vector | BaseType::Normal => {
            Value::triple(Vec3::ZERO)
        }
        BaseType::Matrix => Value::Matrix(Slot::Uniform(DMat4::IDENTITY)),
        BaseType::String => Value::string(""),
        BaseType::Void | BaseType::Unknown => Value::Void,
    };
    match ty.array_len() {
        Some(n) => Value::Array(vec![elem; n as usize]),
        None => elem,
    }
}

/// See `exec_loop`.
const MAX_LOOP_ITERATIONS: u32 = 1 << 16;

/// Index of a global in [`Global::ALL`].
fn gidx(g: Global) -> usize {
    Global::ALL.iter().position(|&x| x == g).unwrap_or(0)
}

/// The loop bookkeeping of `break`/`continue`: points that left the loop, and points that
/// skip the rest of this iteration.
struct LoopState {
    broken: Mask,
    continued: Mask,
}

/// One activation of a shader body or user function.
struct Frame {
    owner: Owner,
    vars: Vec<Value>,
    ret: Value,
    returned: Mask,
    loops: Vec<LoopState>,
}

/// What one light-shader run leaves for the surface (`illuminate`/`solar` bookkeeping).
#[derive(Default)]
pub(crate) struct Emission {
    /// Points whose `illuminate`/`solar` body ran.
    pub lit: Option<Mask>,
    /// The light had an `illuminate` or `solar` statement (otherwise it is ambient).
    pub directional: bool,
}

/// The other shaders' parameter values that `surface()`, `displacement()` and `atmosphere()`
/// read (RI 3.2 §15.6 message passing), by name. Empty lists answer "not found".
#[derive(Clone, Debug, Default)]
pub struct Messages {
    pub surface: Vec<(String, Value)>,
    pub displacement: Vec<(String, Value)>,
    pub atmosphere: Vec<(String, Value)>,
}

/// The executor over one grid.
pub struct Exec<'a> {
    pub(crate) prog: &'a Program,
    pub(crate) grid: &'a ShadingGrid,
    pub(crate) env: &'a ShadingEnv<'a>,
    pub(crate) lights: &'a Lights<'a>,
    pub(crate) n: usize,
    pub(crate) globals: Vec<Value>,
    frames: Vec<Frame>,
    /// The light of the innermost running `illuminance` body (for `lightsource()`).
    pub(crate) current_light: Option<usize>,
    pub(crate) emission: Emission,
    /// Counts `random()` call sites evaluated, so two calls differ.
    pub(crate) random_site: u32,
    /// Errors met while running (unknown built-ins, bad spaces), reported once by the caller.
    pub(crate) problems: Vec<String>,
    /// What message passing to the primitive's other shaders can read.
    pub(crate) messages: Messages,
}

impl<'a> Exec<'a> {
    /// An executor with the globals read from `grid` (P, N, Ng, I, s, t, …; `Ci = 0`, and
    /// `Oi = Os` as PRMan, BMRT and Aqsis start it: a surface shader that sets only `Ci` is
    /// opaque there, and real shaders such as Aqsis's regression `test.sl`/`mxmatch.sl` rely
    /// on it; starting at 0 made them transparent, so front and back surfaces summed).
    pub fn new(
        prog: &'a Program,
        grid: &'a ShadingGrid,
        env: &'a ShadingEnv<'a>,
        lights: &'a Lights<'a>,
    ) -> Exec<'a> {
        let n = grid.len();
        let mut globals: Vec<Value> = Global::ALL.iter().map(|g| zero_of(g.ty())).collect();
        let tv = |v: &Vec<Vec3>| Value::Triple(Slot::Varying(v.clone()));
        let fv = |v: &Vec<f32>| Value::Float(Slot::Varying(v.clone()));
        globals[gidx(Global::P)] = tv(&grid.p);
        globals[gidx(Global::Ps)] = tv(&grid.p);
        globals[gidx(Global::N)] = tv(&grid.n);
        globals[gidx(Global::Ng)] = tv(&grid.ng);
        globals[gidx(Global::I)] = tv(&grid.i);
        globals[gidx(Global::dPdu)] = tv(&grid.dpdu);
        globals[gidx(Global::dPdv)] = tv(&grid.dpdv);
        globals[gidx(Global::Cs)] = tv(&grid.cs);
        globals[gidx(Global::Os)] = tv(&grid.os);
        globals[gidx(Global::Oi)] = tv(&grid.os);
        globals[gidx(Global::s)] = fv(&grid.s);
        globals[gidx(Global::t)] = fv(&grid.t);
        globals[gidx(Global::u)] = fv(&grid.u);
        globals[gidx(Global::v)] = fv(&grid.v);
        globals[gidx(Global::du)] = Value::float(grid.du);
        globals[gidx(Global::dv)] = Value::float(grid.dv);
        globals[gidx(Global::ncomps)] = Value::float(3.0);
        globals[gidx(Global::alpha)] = Value::float(1.0);
        globals[gidx(Global::Ol)] = Value::triple(Vec3::ONE);
        Exec {
            prog,
            grid,
            env,
            lights,
            n,
            globals,
            frames: Vec::new(),
            current_light: None,
            emission: Emission::default(),
            random_site: 0,
            problems: Vec::new(),
            messages: Messages::default(),
        }
    }

    pub fn global(&self, g: Global) -> &Value {
        &self.globals[gidx(g)]
    }

    pub fn set_global(&mut self, g: Global, v: Value) {
        self.globals[gidx(g)] = v;
    }

    pub(crate) fn problem(&mut self, message: String) {
        if !self.problems.contains(&message) {
            self.problems.push(message);
        }
    }

    /// Runs shader `id` over the whole grid with its parameters set to `params` (one value per
    /// parameter, in declaration order: defaults already overridden by the RIB values).
    /// Returns the final parameter values (output parameters for message passing).
    pub fn run_shader(&mut self, id: ShaderId, params: Vec<Value>) -> Vec<Value> {
        let shader = self.prog.shader(id);
        let mut vars: Vec<Value> = shader.vars.iter().map(|v| zero_of(v.ty)).collect();
        for (k, v) in params.into_iter().enumerate() {
            if let Some(slot) = shader.params.get(k).and_then(|p| p.var) {
                vars[slot.0 as usize] = v;
            }
        }
        self.frames.push(Frame {
            owner: Owner::Shader(id),
            vars,
            ret: Value::Void,
            returned: Mask::from_bits(vec![false; self.n]),
            loops: Vec::new(),
        });
        let all = Mask::all_on(self.n);
        self.exec_block(&shader.body, &all);
        let frame = self.frames.pop().expect("pushed above");
        shader
            .params
            .iter()
            .map(|p| {
                p.var
                    .map(|v| frame.vars[v.0 as usize].clone())
                    .unwrap_or(Value::Void)
            })
            .collect()
    }

    /// Evaluates the default expressions of shader `id`'s parameters (uniform, evaluated once
    /// per grid: a default may name a space, `point "shader" (0,0,0)`).
    pub fn param_defaults(&mut self, id: ShaderId) -> Vec<Value> {
        let shader = self.prog.shader(id);
        let vars: Vec<Value> = shader.vars.iter().map(|v| zero_of(v.ty)).collect();
        self.frames.push(Frame {
            owner: Owner::Shader(id),
            vars,
            ret: Value::Void,
            returned: Mask::from_bits(vec![false; self.n]),
            loops: Vec::new(),
        });
        let all = Mask::all_on(self.n);
        let mut out = Vec::new();
        for p in &shader.params {
            let v = match &p.default {
                Some(e) => self.eval(e, &all),
                None => zero_of(p.ty),
            };
            // Later defaults may read earlier parameters.
            if let Some(slot) = p.var {
                self.frames.last_mut().expect("pushed").vars[slot.0 as usize] = v.clone();
            }
            out.push(v);
        }
        self.frames.pop();
        out
    }

    // ---- statements ------------------------------------------------------------------

    /// `mask` without the points that returned, broke or continued in the innermost loop.
    fn live(&self, mask: &Mask) -> Mask {
        let Some(f) = self.frames.last() else {
            return mask.clone();
        };
        let mut m = mask.minus(&f.returned);
        if let Some(l) = f.loops.last() {
            m = m.minus(&l.broken).minus(&l.continued);
        }
        m
    }

    fn exec_block(&mut self, block: &Block, mask: &Mask) {
        for stmt in &block.stmts {
            let m = self.live(mask);
            if m.none() {
                return;
            }
            self.exec_stmt(stmt, &m);
        }
    }

    fn exec_stmt(&mut self, stmt: &Stmt, mask: &Mask) {
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

    /// `illuminate`/`solar` body: `L` set, run where the cone admits it, the lit points
    /// recorded for the surface.
    fn emit(
        &mut self,
        l: Slot<Vec3>,
        cone: Option<(Slot<Vec3>, Slot<f32>)>,
        body: &Stmt,
        mask: &Mask,
    ) {
        let run = match &cone {
            Some((axis, angle)) => Mask::from_bits(
                (0..self.n)
                    .map(|i| mask.get(i) && in_cone(*l.at(i), *axis.at(i), *angle.at(i)))
                    .collect(),
            ),
            None => mask.clone(),
        };
        self.emission.directional = true;
        let n = self.n;
        self.globals[gidx(Global::L)].assign(&Value::Triple(l), Some(&run), n);
        if !run.none() {
            self.exec_stmt(body, &run);
        }
        let lit = match self.emission.lit.take() {
            Some(m) => m.union(&run),
            None => run,
        };
        self.emission.lit = Some(lit);
    }

    fn exec_illuminance(&mut self, il: &illume_sl::ast::Illuminance, mask: &Mask) {
        let category = match &il.category {
            Some(c) => match self.eval(c, mask) {
                Value::String(s) => s.at(0).to_string(),
                _ => String::new(),
            },
            None => String::new(),
        };
        let _position = self.eval(&il.position, mask);
        let cone = il.cone.as_ref().map(|c| {
            (
                self.eval_triple(&c.axis, mask),
                self.eval_float(&c.angle, mask),
            )
        });
        self.push_loop();
        let saved = (
            self.global(Global::L).clone(),
            self.global(Global::Cl).clone(),
            self.global(Global::Ol).clone(),
            self.current_light,
        );
        for k in 0..self.lights.lights.len() {
            let light = self.lights.lights[k];
            let s = light.samples;
            if s.ambient || !self.lights.matches(k, &category) {
                continue;
            }
            let live = self.live(mask);
            if live.none() {
                break;
            }
            let m = Mask::from_bits(
                (0..self.n)
                    .map(|i| {
                        live.get(i)
                            && s.lit[i]
                            && cone
                                .as_ref()
                                .is_none_or(|(a, ang)| in_cone(s.l[i], *a.at(i), *ang.at(i)))
                    })
                    .collect(),
            );
            if m.none() {
                continue;
            }
            self.set_global(Global::L, Value::Triple(Slot::Varying(s.l.clone())));
            self.set_global(Global::Cl, Value::Triple(Slot::Varying(s.cl.clone())));
            self.set_global(Global::Ol, Value::Triple(Slot::Varying(s.ol.clone())));
            self.current_light = Some(k);
            self.exec_stmt(&il.body, &m);
            if let Some(l) = self.frames.last_mut().and_then(|f| f.loops.last_mut()) {
                l.continued = Mask::from_bits(vec![false; l.continued.len()]);
            }
        }
        self.set_global(Global::L, saved.0);
        self.set_global(Global::Cl, saved.1);
        self.set_global(Global::Ol, saved.2);
        self.current_light = saved.3;
        self.pop_loop();
    }

    fn push_loop(&mut self) {
        let n = self.n;
        if let Some(f) = self.frames.last_mut() {
            f.loops.push(LoopState {
                broken: Mask::from_bits(vec![false; n]),
                continued: Mask::from_bits(vec![false; n]),
            });
        }
    }

    fn pop_loop(&mut self) {
        if let Some(f) = self.frames.last_mut() {
            f.loops.pop();
        }
    }

    /// `break n` / `continue n`: the points leave the `n - 1` innermost loops, then leave (or
    /// skip the iteration of) the `n`th.
    fn retire(&mut self, levels: u32, mask: &Mask, is_continue: bool) {
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

    fn exec_loop(
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
        // A bound on iterations so that a shader whose condition never fails cannot hang the
        // renderer (no RI 3.2 program needs 65536 iterations on one grid); hitting it warns.
        let mut iterations = 0u32;
        loop {
            iterations += 1;
            if iterations > MAX_LOOP_ITERATIONS {
                self.problem(format!(
                    "a loop ran {MAX_LOOP_ITERATIONS} times on one grid and was stopped"
                ));
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

    // ---- variables -------------------------------------------------------------------

    fn var_type(&self, slot: VarId) -> Type {
        let f = self.frames.last().expect("a frame runs");
        self.prog
            .vars(f.owner)
            .get(slot.0 as usize)
            .map_or(Type::FLOAT, |v| v.ty)
    }

    fn frame_index(&self, owner: Owner) -> Option<usize> {
        self.frames.iter().rposition(|f| f.owner == owner)
    }

    fn read_var(&self, r: VarRef) -> Value {
        match r {
            VarRef::Global(g) => self.global(g).clone(),
            VarRef::Slot(s) => self
                .frames
                .last()
                .and_then(|f| f.vars.get(s.0 as usize))
                .cloned()
                .unwrap_or(Value::float(0.0)),
            VarRef::Outer { owner, var } => self
                .frame_index(owner)
                .and_then(|k| self.frames[k].vars.get(var.0 as usize))
                .cloned()
                .unwrap_or(Value::float(0.0)),
        }
    }

    fn var_mut(&mut self, r: VarRef) -> Option<&mut Value> {
        match r {
            VarRef::Global(g) => Some(&mut self.globals[gidx(g)]),
            VarRef::Slot(s) => self
                .frames
                .last_mut()
                .and_then(|f| f.vars.get_mut(s.0 as usize)),
            VarRef::Outer { owner, var } => {
                let k = self.frame_index(owner)?;
                self.frames[k].vars.get_mut(var.0 as usize)
            }
        }
    }

    /// Writes `v` to `target` (a variable or one array element) at the running points.
    fn write(&mut self, target: &LValue, v: &Value, mask: &Mask) {
        let Some(r) = target.var else {
            return;
        };
        let index = target.index.as_ref().map(|e| self.eval_float(e, mask));
        let n = self.n;
        let Some(dst) = self.var_mut(r) else {
            return;
        };
        match (index, dst) {
            (None, dst) => dst.assign(v, Some(mask), n),
            (Some(idx), Value::Array(elems)) => write_element(elems, &idx, v, mask, n),
            (Some(_), _) => {}
        }
    }

    // ---- expressions -----------------------------------------------------------------

    pub(crate) fn eval_float(&mut self, e: &Expr, mask: &Mask) -> Slot<f32> {
        match self.eval(e, mask) {
            Value::Float(s) => s,
            _ => Slot::Uniform(0.0),
        }
    }

    pub(crate) fn eval_triple(&mut self, e: &Expr, mask: &Mask) -> Slot<Vec3> {
        match self.eval(e, mask) {
            Value::Triple(s) => s,
            Value::Float(s) => s.map(|&x| Vec3::splat(x)),
            _ => Slot::Uniform(Vec3::ZERO),
        }
    }

    /// A condition as a float slot (non-zero = true).
    fn eval_cond(&mut self, e: &Expr, mask: &Mask) -> Slot<f32> {
        match self.eval(e, mask) {
            Value::Float(s) => s,
            Value::Triple(s) => s.map(|v| (*v != Vec3::ZERO) as u8 as f32),
            Value::String(s) => s.map(|v| (!v.is_empty()) as u8 as f32),
            _ => Slot::Uniform(0.0),
        }
    }

    pub fn eval(&mut self, e: &Expr, mask: &Mask) -> Value {
        let n = self.n;
        match &e.kind {
            ExprKind::Float(x) => Value::float(*x as f32),
            ExprKind::Str(s) => Value::string(s),
            ExprKind::Var(u) => match u.var {
                Some(r) => self.read_var(r),
                None => zero_of(e.ty),
            },
            ExprKind::Tuple(items) => {
                let vals: Vec<Slot<f32>> = items.iter().map(|x| self.eval_float(x, mask)).collect();
                build_tuple(e.ty.base, &vals, n)
            }
            ExprKind::ArrayInit(items) => {
                let elem = e.ty.element();
                Value::Array(
                    items
                        .iter()
                        .map(|x| {
                            let v = self.eval(x, mask);
                            convert_kind(v, elem.base)
                        })
                        .collect(),
                )
            }
            ExprKind::Cast { to, space, expr } => {
                let v = self.eval(expr, mask);
                let v = convert_kind(v, *to);
                match space {
                    None => v,
                    Some(s) => {
                        let space = match self.eval(s, mask) {
                            Value::String(s) => s.at(0).to_string(),
                            _ => String::new(),
                        };
                        self.cast_from_space(*to, &space, v)
                    }
                }
            }
            ExprKind::Promote(x) => {
                let v = self.eval(x, mask);
                convert_kind(v, e.ty.base)
            }
            ExprKind::Unary { op, expr } => {
                let v = self.eval(expr, mask);
                match op {
                    UnaryOp::Neg => operators::negate(&v),
                    UnaryOp::Not => operators::not(&v),
                }
                .unwrap_or_else(|| zero_of(e.ty))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.eval(lhs, mask);
                let b = self.eval(rhs, mask);
                operators::binary(binop(*op), &a, &b, n).unwrap_or_else(|| zero_of(e.ty))
            }
            ExprKind::Ternary {
                cond,
                then,
                otherwise,
            } => {
                let c = self.eval_cond(cond, mask);
                match c {
                    Slot::Uniform(c) => {
                        if c != 0.0 {
                            self.eval(then, mask)
                        } else {
                            self.eval(otherwise, mask)
                        }
                    }
                    Slot::Varying(_) => {
                        let (on, off) = mask.split(&c);
                        let a = self.eval(then, &on);
                        let b = self.eval(otherwise, &off);
                        let mut out = b;
                        out.assign(&a, Some(&on), n);
                        out
                    }
                }
            }
            ExprKind::Assign { op, target, value } => {
                let v = self.eval(value, mask);
                let v = match op.binary() {
                    None => v,
                    Some(bop) => {
                        let cur = self.read_lvalue(target, mask);
                        operators::binary(binop(bop), &cur, &v, n).unwrap_or(v)
                    }
                };
                self.write(target, &v, mask);
                v
            }
            ExprKind::Index { array, index } => {
                let a = self.eval(array, mask);
                let idx = self.eval_float(index, mask);
                read_element(&a, &idx, n).unwrap_or_else(|| zero_of(e.ty))
            }
            ExprKind::Call(call) => match &call.callee {
                Some(Callee::User(f)) => self.call_user(*f, &call.args, mask, e.ty),
                Some(Callee::Builtin(b)) => self.call_builtin(b, &call.args, mask, e.ty),
                None => zero_of(e.ty),
            },
            ExprKind::Texture(t) => self.texture_call(t, mask, e.ty),
            ExprKind::Error => zero_of(e.ty),
        }
    }

    fn read_lvalue(&mut self, target: &LValue, mask: &Mask) -> Value {
        let Some(r) = target.var else {
            return Value::float(0.0);
        };
        let v = self.read_var(r);
        match &target.index {
            None => v,
            Some(i) => {
                let idx = self.eval_float(i, mask);
                read_element(&v, &idx, self.n).unwrap_or(Value::float(0.0))
            }
        }
    }

    /// A user function call: arguments by value, `output` parameters copied back to the
    /// caller's variables at the running points.
    fn call_user(&mut self, fid: FuncId, args: &[Expr], mask: &Mask, ty: Type) -> Value {
        let f = self.prog.function(fid);
        let values: Vec<Value> = args.iter().map(|a| self.eval(a, mask)).collect();
        let mut vars: Vec<Value> = f.vars.iter().map(|v| zero_of(v.ty)).collect();
        for (p, v) in f.params.iter().zip(&values) {
            if let Some(slot) = p.var {
                vars[slot.0 as usize] = v.clone();
            }
        }
        self.frames.push(Frame {
            owner: Owner::Function(fid),
            vars,
            ret: Value::Void,
            returned: Mask::from_bits(vec![false; self.n]),
            loops: Vec::new(),
        });
        self.exec_block(&f.body, mask);
        let frame = self.frames.pop().expect("pushed above");
        for (p, arg) in f.params.iter().zip(args) {
            if !p.output {
                continue;
            }
            let Some(slot) = p.var else { continue };
            let out = frame.vars[slot.0 as usize].clone();
            if let Some(target) = lvalue_of(arg) {
                self.write(&target, &out, mask);
            }
        }
        match frame.ret {
            Value::Void => zero_of(ty),
            v => v,
        }
    }

    /// Writes an `output` argument of a built-in back to the caller's variable.
    pub(crate) fn write_back(&mut self, arg: &Expr, v: &Value, mask: &Mask) {
        if let Some(target) = lvalue_of(arg) {
            self.write(&target, v, mask);
        }
    }

    /// `point "space" (…)` and friends: a value given in `space`, converted to current space.
    fn cast_from_space(&mut self, to: BaseType, space: &str, v: Value) -> Value {
        match to {
            BaseType::Color => match v {
                Value::Triple(s) => {
                    let ok = crate::colorspaces::to_rgb(space, Vec3::ZERO).is_some();
                    if !ok {
                        self.problem(format!("unknown colour space \"{space}\"; taken as rgb"));
                        return Value::Triple(s);
                    }
                    Value::Triple(s.map(|c| crate::colorspaces::to_rgb(space, *c).unwrap_or(*c)))
                }
                v => v,
            },
            BaseType::Point | BaseType::Vector | BaseType::Normal => {
                let Some(m) = self.current_from(space) else {
                    self.problem(format!("unknown space \"{space}\"; taken as current"));
                    return v;
                };
                match v {
                    Value::Triple(s) => Value::Triple(s.map(|p| apply(to, &m, *p))),
                    v => v,
                }
            }
            BaseType::Matrix => {
                let Some(m) = self.env.camera_from(space) else {
                    self.problem(format!("unknown space \"{space}\"; taken as current"));
                    return v;
                };
                match v {
                    Value::Matrix(s) => Value::Matrix(s.map(|x| m * *x)),
                    v => v,
                }
            }
            _ => v,
        }
    }

    /// `current_from_space` including the projective spaces (inverted).
    pub(crate) fn current_from(&self, space: &str) -> Option<DMat4> {
        match space {
            "screen" => Some(self.env.screen_from_camera.inverse()),
            "NDC" => Some(self.env.ndc_from_camera.inverse()),
            "raster" => Some(self.env.raster_from_camera.inverse()),
            _ => self.env.camera_from(space),
        }
    }
}

/// Applies `m` to a triple of kind `to`: points (projectively), vectors, normals (inverse
/// transpose).
pub(crate) fn apply(to: BaseType, m: &DMat4, p: Vec3) -> Vec3 {
    let d = p.as_dvec3();
    match to {
        BaseType::Point => m.project_point3(d).as_vec3(),
        BaseType::Vector => m.transform_vector3(d).as_vec3(),
        BaseType::Normal => m.inverse().transpose().transform_vector3(d).as_vec3(),
        _ => p,
    }
}

fn binop(op: BinaryOp) -> BinOp {
    match op {
        BinaryOp::Add => BinOp::Add,
        BinaryOp::Sub => BinOp::Sub,
        BinaryOp::Mul => BinOp::Mul,
        BinaryOp::Div => BinOp::Div,
        BinaryOp::Dot => BinOp::Dot,
        BinaryOp::Cross => BinOp::Cross,
        BinaryOp::Eq => BinOp::Eq,
        BinaryOp::Ne => BinOp::Ne,
        BinaryOp::Lt => BinOp::Lt,
        BinaryOp::Le => BinOp::Le,
        BinaryOp::Gt => BinOp::Gt,
        BinaryOp::Ge => BinOp::Ge,
        BinaryOp::And => BinOp::And,
        BinaryOp::Or => BinOp::Or,
    }
}

/// The assignable target an `output` argument names.
fn lvalue_of(arg: &Expr) -> Option<LValue> {
    match &arg.kind {
        ExprKind::Var(u) => Some(LValue {
            name: u.name.clone(),
            span: arg.span,
            index: None,
            var: u.var,
        }),
        ExprKind::Index { array, index } => match &array.kind {
            ExprKind::Var(u) => Some(LValue {
                name: u.name.clone(),
                span: arg.span,
                index: Some(index.clone()),
                var: u.var,
            }),
            _ => None,
        },
        _ => None,
    }
}

/// `(a, b, c)` as a triple, `(m00 … m33)` (or one float on the diagonal) as a matrix.
fn build_tuple(base: BaseType, vals: &[Slot<f32>], n: usize) -> Value {
    if base == BaseType::Matrix {
        let all_uniform = vals.iter().all(Slot::is_uniform);
        let at = |i: usize| -> DMat4 {
            if vals.len() == 16 {
                let mut m = [0.0f64; 16];
                for (k, v) in vals.iter().enumerate() {
                    m[k] = *v.at(i) as f64;
                }
                crate::geometric::matrix_from_rows(m)
            } else {
                let x = vals.first().map_or(1.0, |v| *v.at(i)) as f64;
                DMat4::from_diagonal(glam::DVec4::splat(x))
            }
        };
        return Value::Matrix(if all_uniform {
            Slot::Uniform(at(0))
        } else {
            Slot::Varying((0..n).map(at).collect())
        });
    }
    let get = |k: usize| vals.get(k).cloned().unwrap_or(Slot::Uniform(0.0));
    let (x, y, z) = (get(0), get(1), get(2));
    if vals.len() == 1 {
        return Value::Triple(x.map(|&v| Vec3::splat(v)));
    }
    let xy = zip2(&x, &y, n, |a, b| (*a, *b));
    Value::Triple(crate::value::zip2(&xy, &z, n, |(a, b), c| {
        Vec3::new(*a, *b, *c)
    }))
}

/// Reinterprets a value as `base`: float → triple/matrix promotion, triple kinds unchanged.
pub(crate) fn convert_kind(v: Value, base: BaseType) -> Value {
    match (v, base) {
        (Value::Float(s), b) if b.is_triple() => Value::Triple(s.map(|&x| Vec3::splat(x))),
        (Value::Float(s), BaseType::Matrix) => {
            Value::Matrix(s.map(|&x| DMat4::from_diagonal(glam::DVec4::splat(x as f64))))
        }
        (v, _) => v,
    }
}

/// `a[i]` with a uniform or per-point index (truncated, clamped to the array).
fn read_element(a: &Value, idx: &Slot<f32>, n: usize) -> Option<Value> {
    let Value::Array(elems) = a else {
        return None;
    };
    if elems.is_empty() {
        return None;
    }
    let clampi = |x: f32| (x.max(0.0) as usize).min(elems.len() - 1);
    match idx {
        Slot::Uniform(i) => Some(elems[clampi(*i)].clone()),
        Slot::Varying(ix) => {
            let mut out = elems[0].clone();
            for (k, e) in elems.iter().enumerate().skip(1) {
                let m = Mask::from_bits(ix.iter().map(|&i| clampi(i) == k).collect());
                if !m.none() {
                    out.assign(e, Some(&m), n);
                }
            }
            Some(out)
        }
    }
}

fn write_element(elems: &mut [Value], idx: &Slot<f32>, v: &Value, mask: &Mask, n: usize) {
    if elems.is_empty() {
        return;
    }
    let len = elems.len();
    let clampi = |x: f32| (x.max(0.0) as usize).min(len - 1);
    match idx {
        Slot::Uniform(i) => elems[clampi(*i)].assign(v, Some(mask), n),
        Slot::Varying(ix) => {
            for (k, e) in elems.iter_mut().enumerate() {
                let m =
                    Mask::from_bits((0..n).map(|i| mask.get(i) && clampi(ix[i]) == k).collect());
                if !m.none() {
                    e.assign(v, Some(&m), n);
                }
            }
        }
    }
}

/// Shared compiled shader text: the checked program and which shader of it to run.
#[derive(Clone, Debug)]
pub struct CompiledShader {
    pub program: Arc<Program>,
    pub id: ShaderId,
}
