//! The executor: walks a checked `illume_sl` AST once per grid. Every expression evaluates for
//! all grid points at once into a [`Value`]; uniform operands give uniform results (computed
//! once). Statements run under a running-state [`Mask`]: a varying `if` splits it, loops retire
//! points whose condition fails or that `break`, `illuminance` runs its body once per light for
//! the points that light reaches. Assignments write only the running points.
//!
//! Files: this one holds the executor state and runs shaders; `stmt.rs` statements and loops,
//! `light.rs` `illuminance`/`illuminate`/`solar`, `expr.rs` expressions and user calls,
//! `vars.rs` variables and array elements, `globals.rs` the globals loaded from the grid on
//! first use, `space.rs` coordinate-space conversions; the built-ins are in `crate::builtins`.
mod expr;
mod globals;
mod light;
mod space;
mod stmt;
mod vars;

pub(crate) use space::apply;

use crate::lights::Lights;
use crate::value::{Mask, Slot, Value};
use glam::{DMat4, Vec3};
use illume_shade::{ShadingEnv, ShadingGrid};
use illume_sl::ast::{Global, Owner, Program, ShaderId};
use illume_sl::span::Loc;
use illume_sl::types::{BaseType, Type};
use std::cell::OnceCell;
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

/// Iterations one loop may run on one grid (see `exec_loop`).
const MAX_LOOP_ITERATIONS: u32 = 1 << 16;

/// Iterations all loops of one shader run may take together: nested loops that each stay
/// under [`MAX_LOOP_ITERATIONS`] can still multiply into hours.
const MAX_TOTAL_ITERATIONS: u64 = 1 << 22;

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
    /// Loaded from the grid on first use (`globals.rs`).
    globals: Vec<OnceCell<Value>>,
    frames: Vec<Frame>,
    /// The light of the innermost running `illuminance` body (for `lightsource()`).
    pub(crate) current_light: Option<usize>,
    pub(crate) emission: Emission,
    /// Counts `random()` call sites evaluated, so two calls differ.
    pub(crate) random_site: u32,
    /// Errors met while running (unknown built-ins, bad spaces), reported once by the caller,
    /// each with the statement it arose in.
    pub(crate) problems: Vec<(Option<Loc>, String)>,
    /// Runs that could not complete (a loop stopped by the iteration limits): errors, not
    /// warnings, since the shaded result is wrong.
    pub(crate) errors: Vec<(Option<Loc>, String)>,
    /// The statement being run (set by `exec_stmt`), for the position of `problems`.
    pub(crate) at: Option<Loc>,
    /// Loop iterations taken so far in this run, against [`MAX_TOTAL_ITERATIONS`].
    loop_iterations: u64,
    /// Set when a loop hit a limit: every enclosing loop stops too, so a runaway nest costs at
    /// most one limit's worth of iterations.
    runaway: bool,
    /// What message passing to the primitive's other shaders can read.
    pub(crate) messages: Messages,
    /// Lights at other points than the grid's (volume shaders' `illuminance(Pmarch)`).
    pub(crate) relight: Option<&'a dyn crate::Relight>,
}

impl<'a> Exec<'a> {
    /// An executor with the globals read from `grid` when first used (see `globals.rs` for
    /// their starting values).
    pub fn new(
        prog: &'a Program,
        grid: &'a ShadingGrid,
        env: &'a ShadingEnv<'a>,
        lights: &'a Lights<'a>,
    ) -> Exec<'a> {
        let n = grid.len();
        Exec {
            prog,
            grid,
            env,
            lights,
            n,
            globals: globals::unloaded(),
            frames: Vec::new(),
            current_light: None,
            emission: Emission::default(),
            random_site: 0,
            problems: Vec::new(),
            errors: Vec::new(),
            at: None,
            loop_iterations: 0,
            runaway: false,
            messages: Messages::default(),
            relight: None,
        }
    }

    pub(crate) fn problem(&mut self, message: String) {
        let p = (self.at, message);
        if !self.problems.contains(&p) {
            self.problems.push(p);
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
}

/// Shared compiled shader text: the checked program and which shader of it to run.
#[derive(Clone, Debug)]
pub struct CompiledShader {
    pub program: Arc<Program>,
    pub id: ShaderId,
}
