//! A compiled shader bound to one `Surface`/`Displacement`/`LightSource` request's parameters,
//! and the per-grid entry points the renderer calls: [`SlInstance::shade_surface`],
//! [`SlInstance::displace`], [`SlInstance::run_light`].
//!
//! Parameter binding follows `illume_shade`'s rules: RIB values must match the declared type
//! and count (inline declarations are checked against it), mismatches and unknown names warn
//! and are ignored. `point`/`vector`/`normal` values are given in the request's "shader" space
//! and converted to camera space; a user primitive variable of the same name (one or one-per-
//! point values) overrides both the default and the RIB value (RI Spec §5).
use crate::exec::{apply, CompiledShader, Exec, Messages};
use crate::lights::Lights;
use crate::value::{Slot, Value};
use glam::{DMat4, Vec3};
use illume_rib::{Declaration, Param};
use illume_shade::{LightSamples, ShadingEnv, ShadingGrid};
use illume_sl::ast::Global;
use illume_sl::types::{BaseType, ShaderKind, Type};
use std::sync::Arc;

/// A bound Shading Language shader.
#[derive(Clone, Debug)]
pub struct SlInstance {
    pub shader: CompiledShader,
    /// Per parameter (declaration order): the RIB value, if one was bound.
    overrides: Vec<Option<Value>>,
}

/// What one grid's shading reports.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlStats {
    /// Points whose `Ci`/`Oi` (or displaced `P`/`N`) came out non-finite and were repaired.
    pub nonfinite: usize,
}

impl SlInstance {
    /// The shader's name as declared in the `.sl` file.
    pub fn name(&self) -> &str {
        &self.shader.program.shader(self.shader.id).name
    }

    pub fn kind(&self) -> ShaderKind {
        self.shader.program.shader(self.shader.id).kind
    }

    /// Binds `params` (RIB names, possibly with inline declarations). `camera_from_shader` is
    /// the CTM of the request: geometric parameter values are converted by it. Returns the
    /// instance and the warnings (wrong type/count, unknown names).
    pub fn bind(
        shader: CompiledShader,
        params: &[Param],
        camera_from_shader: DMat4,
    ) -> (SlInstance, Vec<String>) {
        let def = shader.program.shader(shader.id);
        let mut overrides = vec![None; def.params.len()];
        let mut warnings = Vec::new();
        for param in params {
            let (decl, name) = match Declaration::split_inline(&param.name) {
                Ok(x) => x,
                Err(e) => {
                    warnings.push(format!(
                        "shader `{}`: parameter \"{}\": bad declaration ({e}); ignored",
                        def.name, param.name
                    ));
                    continue;
                }
            };
            let Some(k) = def.params.iter().position(|p| p.name == name) else {
                if !name.starts_with("__") {
                    warnings.push(format!(
                        "shader `{}` has no parameter `{name}`; ignored",
                        def.name
                    ));
                }
                continue;
            };
            let ty = def.params[k].ty;
            if let Some(d) = &decl {
                if !rib_type_fits(d.ty, ty.base) {
                    warnings.push(format!(
                        "shader `{}`: parameter `{name}` is declared `{}` but the shader expects \
                         `{ty}`; ignored",
                        def.name, d.ty
                    ));
                    continue;
                }
            }
            match from_rib(&param.value, ty, &camera_from_shader) {
                Some(v) => overrides[k] = Some(v),
                None => warnings.push(format!(
                    "shader `{}`: parameter `{name}` expects {ty}, found {} value(s); ignored",
                    def.name,
                    param.value.len()
                )),
            }
        }
        (SlInstance { shader, overrides }, warnings)
    }

    /// The parameter values for one grid: defaults, then RIB values, then primitive variables.
    fn params(&self, exec: &mut Exec, grid: &ShadingGrid) -> Vec<Value> {
        let def = self.shader.program.shader(self.shader.id);
        let mut values = exec.param_defaults(self.shader.id);
        for (k, v) in values.iter_mut().enumerate() {
            if let Some(o) = &self.overrides[k] {
                *v = o.clone();
            }
            let p = &def.params[k];
            if p.ty.is_array() {
                continue;
            }
            let comps = match p.ty.base {
                BaseType::Float => 1,
                b if b.is_triple() => 3,
                _ => continue,
            };
            if let Some(var) = grid.var(&p.name, comps) {
                *v = primvar(var, comps, grid.len());
            }
        }
        values
    }

    /// This shader's parameter values for `grid` before it runs (defaults, RIB values,
    /// primitive variables), by name: what another shader's `surface()`/`displacement()`
    /// message passing reads.
    pub fn parameter_values(&self, grid: &ShadingGrid, env: &ShadingEnv) -> Vec<(String, Value)> {
        let lights = Lights::default();
        let mut exec = Exec::new(&self.shader.program, grid, env, &lights);
        let values = self.params(&mut exec, grid);
        let def = self.shader.program.shader(self.shader.id);
        def.params
            .iter()
            .map(|p| p.name.clone())
            .zip(values)
            .collect()
    }

    /// [`SlInstance::params`] for the other entry points of the crate.
    pub(crate) fn params_for(&self, exec: &mut Exec, grid: &ShadingGrid) -> Vec<Value> {
        self.params(exec, grid)
    }

    pub(crate) fn report_problems(exec: &Exec, env: &ShadingEnv, name: &str) {
        Self::report(exec, env, name);
    }

    fn report(exec: &Exec, env: &ShadingEnv, name: &str) {
        // The statement's file:line:col in the shader's source, for the report's position.
        let at = |loc: &Option<illume_sl::span::Loc>| {
            let loc = (*loc)?;
            let file = exec.prog.files.get(loc.file.0 as usize)?;
            Some(illume_shade::SourceAt {
                file: file.display().to_string(),
                line: loc.line,
                col: loc.col,
            })
        };
        for (loc, p) in &exec.problems {
            env.warn_at(at(loc).as_ref(), &format!("shader `{name}`: {p}"));
        }
        for (loc, e) in &exec.errors {
            env.error_at(at(loc).as_ref(), &format!("shader `{name}`: {e}"));
        }
    }

    /// Runs a surface shader over `grid` with `lights` already run for this grid: writes
    /// `Ci`, `Oi` (non-finite values repaired to black / opaque).
    pub fn shade_surface(
        &self,
        grid: &mut ShadingGrid,
        lights: &Lights,
        env: &ShadingEnv,
    ) -> SlStats {
        self.shade_surface_with(grid, lights, env, Messages::default())
    }

    /// [`SlInstance::shade_surface`] with what `displacement()`/`atmosphere()` read.
    pub fn shade_surface_with(
        &self,
        grid: &mut ShadingGrid,
        lights: &Lights,
        env: &ShadingEnv,
        messages: Messages,
    ) -> SlStats {
        self.shade_surface_outputs(grid, lights, env, messages, &mut [])
    }

    /// The shader's `output` parameters of type float, colour, point, vector or normal:
    /// (name, floats per point, whether it is a colour). What a display may name as an
    /// arbitrary output variable.
    pub fn output_parameters(&self) -> Vec<(String, usize, bool)> {
        let def = self.shader.program.shader(self.shader.id);
        def.params
            .iter()
            .filter(|p| p.output && !p.ty.is_array())
            .filter_map(|p| match p.ty.base {
                BaseType::Float => Some((p.name.clone(), 1, false)),
                b if b.is_triple() => Some((p.name.clone(), 3, b == BaseType::Color)),
                _ => None,
            })
            .collect()
    }

    /// [`SlInstance::shade_surface_with`] that also hands back the values the shader left in
    /// the output parameters named in `wanted` (`(name, values)`: the values are filled with
    /// one float or triple per point, flattened; a name the shader lacks stays empty).
    pub fn shade_surface_outputs(
        &self,
        grid: &mut ShadingGrid,
        lights: &Lights,
        env: &ShadingEnv,
        messages: Messages,
        wanted: &mut [(&str, Vec<f32>)],
    ) -> SlStats {
        let (ci, oi) = {
            let g: &ShadingGrid = grid;
            let mut exec = Exec::new(&self.shader.program, g, env, lights);
            exec.messages = messages;
            let params = self.params(&mut exec, g);
            let out = exec.run_shader(self.shader.id, params);
            Self::report(&exec, env, self.name());
            let n = g.len();
            let def = self.shader.program.shader(self.shader.id);
            for (name, values) in wanted.iter_mut() {
                let Some(k) = def.params.iter().position(|p| p.name == *name && p.output) else {
                    continue;
                };
                match out.get(k) {
                    Some(Value::Float(s)) => values.extend(s.to_varying(n)),
                    Some(Value::Triple(s)) => {
                        values.extend(s.to_varying(n).into_iter().flat_map(|v| v.to_array()))
                    }
                    _ => {}
                }
            }
            (exec.take_global(Global::Ci), exec.take_global(Global::Oi)).into_pair(n)
        };
        let mut stats = SlStats::default();
        for i in 0..grid.len() {
            let (c, o) = (ci[i], oi[i]);
            stats.nonfinite += (!c.is_finite() || !o.is_finite()) as usize;
            grid.ci[i] = if c.is_finite() { c } else { Vec3::ZERO };
            grid.oi[i] = if o.is_finite() { o } else { Vec3::ONE };
        }
        stats
    }

    /// Runs a displacement shader: writes the new `P` and `N` into `grid`.
    pub fn displace(&self, grid: &mut ShadingGrid, env: &ShadingEnv) -> SlStats {
        let lights = Lights::default();
        let (p, nn) = {
            let g: &ShadingGrid = grid;
            let mut exec = Exec::new(&self.shader.program, g, env, &lights);
            let params = self.params(&mut exec, g);
            exec.run_shader(self.shader.id, params);
            Self::report(&exec, env, self.name());
            let n = g.len();
            (exec.take_global(Global::P), exec.take_global(Global::N)).into_pair(n)
        };
        let mut stats = SlStats::default();
        for i in 0..grid.len() {
            if p[i].is_finite() && nn[i].is_finite() {
                grid.p[i] = p[i];
                grid.n[i] = nn[i];
            } else {
                stats.nonfinite += 1;
            }
        }
        stats
    }

    /// Runs a light shader for the surface points of `grid` (its `Ps`): the samples every
    /// illuminance loop of the surface reads, and the light's parameters after the run (for
    /// `lightsource()`). `env.camera_from_shader` must be the light's shader space.
    pub fn run_light(
        &self,
        grid: &ShadingGrid,
        env: &ShadingEnv,
    ) -> (LightSamples, Vec<(String, Value)>) {
        self.run_light_with(grid, env, Messages::default())
    }

    /// [`SlInstance::run_light`] with what `surface()` (and the others) read.
    pub fn run_light_with(
        &self,
        grid: &ShadingGrid,
        env: &ShadingEnv,
        messages: Messages,
    ) -> (LightSamples, Vec<(String, Value)>) {
        // In a light shader P is the light's own position (its shader-space origin for a
        // non-area light), Ps the surface point.
        let origin = env
            .camera_from_shader
            .transform_point3(glam::DVec3::ZERO)
            .as_vec3();
        self.run_light_from(
            grid,
            env,
            messages,
            Value::triple(origin),
            Value::triple(Vec3::ZERO),
        )
    }

    /// One area-light sample: the light runs with `P`, `N` the point sampled on its geometry
    /// for each shaded point (`position[i]`, `normal[i]`), as the built-in `arealight` does;
    /// the caller weights the samples' `Cl`.
    pub fn run_area_light_sample(
        &self,
        grid: &ShadingGrid,
        env: &ShadingEnv,
        messages: Messages,
        position: Vec<Vec3>,
        normal: Vec<Vec3>,
    ) -> (LightSamples, Vec<(String, Value)>) {
        let (p, n) = (
            Value::Triple(crate::value::Slot::varying(position)),
            Value::Triple(crate::value::Slot::varying(normal)),
        );
        self.run_light_from(grid, env, messages, p, n)
    }

    fn run_light_from(
        &self,
        grid: &ShadingGrid,
        env: &ShadingEnv,
        messages: Messages,
        position: Value,
        normal: Value,
    ) -> (LightSamples, Vec<(String, Value)>) {
        let lights = Lights::default();
        let n = grid.len();
        let mut exec = Exec::new(&self.shader.program, grid, env, &lights);
        exec.messages = messages;
        exec.set_global(Global::P, position);
        exec.set_global(Global::N, normal);
        exec.set_global(Global::Cl, Value::triple(Vec3::ZERO));
        let params = self.params(&mut exec, grid);
        let out = exec.run_shader(self.shader.id, params);
        Self::report(&exec, env, self.name());
        let def = self.shader.program.shader(self.shader.id);
        let named: Vec<(String, Value)> = def
            .params
            .iter()
            .zip(out)
            .map(|(p, v)| (p.name.clone(), v))
            .collect();
        let (l, cl) = (exec.take_global(Global::L), exec.take_global(Global::Cl)).into_pair(n);
        let ol = triple_vec(exec.global(Global::Ol), n);
        let directional = exec.emission.directional;
        let lit = exec.emission.lit.take();
        let samples = LightSamples {
            ambient: !directional,
            // The light's L points from the light to the surface; the surface's toward it.
            l: l.iter().map(|v| -*v).collect(),
            cl: (0..n)
                .map(|i| {
                    let lit_i = lit.as_ref().is_none_or(|m| m.get(i));
                    if lit_i && cl[i].is_finite() {
                        cl[i]
                    } else {
                        Vec3::ZERO
                    }
                })
                .collect(),
            ol,
            lit: (0..n)
                .map(|i| lit.as_ref().is_none_or(|m| m.get(i)))
                .collect(),
            // An SL light exports `__shadow` as one of its outputs, not here.
            shadow: Vec::new(),
        };
        (samples, named)
    }
}

trait IntoPair {
    fn into_pair(self, n: usize) -> (Vec<Vec3>, Vec<Vec3>);
}

impl IntoPair for (Value, Value) {
    fn into_pair(self, n: usize) -> (Vec<Vec3>, Vec<Vec3>) {
        (owned_triple_vec(self.0, n), owned_triple_vec(self.1, n))
    }
}

/// [`triple_vec`] of a value the caller gives up: its lanes are moved out, not copied, when
/// nothing else holds them.
fn owned_triple_vec(v: Value, n: usize) -> Vec<Vec3> {
    match v {
        Value::Triple(Slot::Varying(lanes)) if lanes.len() == n => {
            Arc::try_unwrap(lanes).unwrap_or_else(|shared| shared.to_vec())
        }
        v => triple_vec(&v, n),
    }
}

pub(crate) fn triple_vec(v: &Value, n: usize) -> Vec<Vec3> {
    match v {
        Value::Triple(s) => s.to_varying(n),
        Value::Float(s) => s.to_varying(n).into_iter().map(Vec3::splat).collect(),
        _ => vec![Vec3::ZERO; n],
    }
}

/// Whether a RIB declaration type can bind to an SL parameter of `base`.
fn rib_type_fits(rib: illume_rib::Type, base: BaseType) -> bool {
    use illume_rib::Type as R;
    matches!(
        (rib, base),
        (R::Float | R::Integer, BaseType::Float)
            | (R::Color, BaseType::Color)
            | (R::Point, BaseType::Point)
            | (R::Vector, BaseType::Vector)
            | (R::Normal, BaseType::Normal)
            | (
                R::Point | R::Vector | R::Normal,
                BaseType::Point | BaseType::Vector | BaseType::Normal
            )
            | (R::String, BaseType::String)
            | (R::Matrix, BaseType::Matrix)
    )
}

/// A RIB value as an SL value of type `ty`; `None` on a count mismatch.
fn from_rib(value: &illume_rib::Value, ty: Type, camera_from_shader: &DMat4) -> Option<Value> {
    let count = ty.array_len().map_or(1, |n| n as usize);
    let elems: Vec<Value> = match (value, ty.base) {
        (illume_rib::Value::Strings(s), BaseType::String) if s.len() == count => {
            s.iter().map(|x| Value::string(x)).collect()
        }
        (illume_rib::Value::Strings(_), _) | (_, BaseType::String) => return None,
        (v, base) => {
            let f = v.as_floats()?;
            let comps = base.components();
            if comps == 0 || f.len() != comps * count {
                return None;
            }
            f.chunks(comps)
                .map(|c| match base {
                    BaseType::Float => Value::float(c[0]),
                    BaseType::Matrix => {
                        let mut m = [0.0f64; 16];
                        for (k, x) in c.iter().enumerate() {
                            m[k] = *x as f64;
                        }
                        Value::Matrix(Slot::Uniform(
                            *camera_from_shader * crate::geometric::matrix_from_rows(m),
                        ))
                    }
                    b => {
                        let p = Vec3::new(c[0], c[1], c[2]);
                        Value::triple(if b.is_geometric() {
                            apply(b, camera_from_shader, p)
                        } else {
                            p
                        })
                    }
                })
                .collect()
        }
    };
    Some(if ty.is_array() {
        Value::Array(elems)
    } else {
        elems.into_iter().next()?
    })
}

/// A primitive variable's values as a uniform or varying SL value.
fn primvar(var: &[f32], comps: usize, n: usize) -> Value {
    let one = var.len() == comps;
    if comps == 1 {
        return Value::Float(if one {
            Slot::Uniform(var[0])
        } else {
            Slot::varying(var[..n].to_vec())
        });
    }
    let at = |i: usize| Vec3::new(var[3 * i], var[3 * i + 1], var[3 * i + 2]);
    Value::Triple(if one {
        Slot::Uniform(at(0))
    } else {
        Slot::varying((0..n).map(at).collect())
    })
}

/// Makes an `Arc<str>` slot, used by callers building string parameters.
pub fn string_value(s: &str) -> Value {
    Value::String(Slot::Uniform(Arc::from(s)))
}
