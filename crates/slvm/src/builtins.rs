//! The built-in functions of RI 3.2 chapter 15 over grid values, dispatched by the name and
//! overload the checker chose. Uniform arguments give uniform results (one evaluation per
//! grid); the per-point kernels live in the family files (`mathfunctions`, `noise`, …) or in
//! `illume_shade` where the built-in shaders already use them (so both agree bit for bit).
use crate::exec::{apply, zero_of, Exec};
use crate::value::{zip2, zip3, Mask, Slot, Value};
use crate::{colorspaces, geometric, mathfunctions as mf, noise, spline};
use glam::{DMat4, Vec3};
use illume_shade::{faceforward, fresnel, normalize_or_zero, reflect, refract};
use illume_sl::ast::{BuiltinCall, Expr, Global};
use illume_sl::types::{BaseType, Type};

fn fl(v: &Value) -> Slot<f32> {
    match v {
        Value::Float(s) => s.clone(),
        _ => Slot::Uniform(0.0),
    }
}

fn tr(v: &Value) -> Slot<Vec3> {
    match v {
        Value::Triple(s) => s.clone(),
        Value::Float(s) => s.map(|&x| Vec3::splat(x)),
        _ => Slot::Uniform(Vec3::ZERO),
    }
}

fn mx(v: &Value) -> Slot<DMat4> {
    match v {
        Value::Matrix(s) => s.clone(),
        _ => Slot::Uniform(DMat4::IDENTITY),
    }
}

/// A uniform string argument (SL names of spaces, maps, bases are uniform in practice; a
/// varying one is read at the first point).
fn st(v: &Value) -> String {
    match v {
        Value::String(s) => s.at(0).to_string(),
        _ => String::new(),
    }
}

/// `f` on a float, component-wise on a triple.
fn unary(v: &Value, f: impl Fn(f32) -> f32) -> Value {
    match v {
        Value::Triple(s) => Value::Triple(s.map(|p| Vec3::new(f(p.x), f(p.y), f(p.z)))),
        v => Value::Float(fl(v).map(|&x| f(x))),
    }
}

fn binary(a: &Value, b: &Value, n: usize, f: impl Fn(f32, f32) -> f32) -> Value {
    match (a, b) {
        (Value::Float(x), Value::Float(y)) => Value::Float(zip2(x, y, n, |&x, &y| f(x, y))),
        _ => Value::Triple(zip2(&tr(a), &tr(b), n, |p, q| {
            Vec3::new(f(p.x, q.x), f(p.y, q.y), f(p.z, q.z))
        })),
    }
}

fn ternary(a: &Value, b: &Value, c: &Value, n: usize, f: impl Fn(f32, f32, f32) -> f32) -> Value {
    match (a, b, c) {
        (Value::Float(x), Value::Float(y), Value::Float(z)) => {
            Value::Float(zip3(x, y, z, n, |&x, &y, &z| f(x, y, z)))
        }
        _ => Value::Triple(zip3(&tr(a), &tr(b), &tr(c), n, |p, q, r| {
            Vec3::new(f(p.x, q.x, r.x), f(p.y, q.y, r.y), f(p.z, q.z, r.z))
        })),
    }
}

/// The coordinates of a noise argument list (`float`, `float, float`, `point`, `point, float`).
fn noise_coords(args: &[Value], n: usize) -> Slot<[f32; 4]> {
    let mut acc: Slot<([f32; 4], usize)> = Slot::Uniform(([0.0; 4], 0));
    for a in args {
        acc = match a {
            Value::Triple(s) => zip2(&acc, s, n, |(c, k), p| {
                let mut c = *c;
                for (j, x) in [p.x, p.y, p.z].into_iter().enumerate() {
                    if k + j < 4 {
                        c[k + j] = x;
                    }
                }
                (c, k + 3)
            }),
            v => zip2(&acc, &fl(v), n, |(c, k), &x| {
                let mut c = *c;
                if *k < 4 {
                    c[*k] = x;
                }
                (c, k + 1)
            }),
        };
    }
    let dims: usize = args
        .iter()
        .map(|a| if matches!(a, Value::Triple(_)) { 3 } else { 1 })
        .sum::<usize>()
        .min(4);
    acc.map(move |(c, _)| {
        let mut c = *c;
        for x in c.iter_mut().skip(dims) {
            *x = 0.0;
        }
        c
    })
}

fn dims_of(args: &[Value]) -> usize {
    args.iter()
        .map(|a| if matches!(a, Value::Triple(_)) { 3 } else { 1 })
        .sum::<usize>()
        .clamp(1, 4)
}

/// A noise-family result of type `ret` from a per-point scalar kernel with a component seed.
fn noise_result(
    ret: BaseType,
    coords: &Slot<[f32; 4]>,
    f: impl Fn(&[f32; 4], u32) -> f32,
) -> Value {
    if ret == BaseType::Float {
        Value::Float(coords.map(|c| f(c, 0)))
    } else {
        Value::Triple(coords.map(|c| Vec3::new(f(c, 0), f(c, 1), f(c, 2))))
    }
}

impl Exec<'_> {
    pub(crate) fn call_builtin(
        &mut self,
        call: &BuiltinCall,
        args: &[Expr],
        mask: &Mask,
        ty: Type,
    ) -> Value {
        // Optional "name", value pairs (filterstep's "width", …) are not positional arguments.
        let positional = &args[..call.optional_from.unwrap_or(args.len()).min(args.len())];
        let vals: Vec<Value> = positional.iter().map(|a| self.eval(a, mask)).collect();
        match self.builtin(&call.name, ty.base, &vals, positional, mask) {
            Some(v) => v,
            None => {
                self.problem(format!(
                    "built-in `{}` is not implemented by the executor; it returns 0",
                    call.name
                ));
                zero_of(ty)
            }
        }
    }

    fn varying_global(&self, g: Global) -> Slot<Vec3> {
        tr(self.global(g))
    }

    /// `Du`/`Dv` of a float or triple, by grid differences.
    fn deriv(&self, v: &Value, along_u: bool) -> Value {
        let g = self.grid;
        match v {
            Value::Float(Slot::Varying(x)) => Value::Float(Slot::Varying(if along_u {
                g.deriv_u(x)
            } else {
                g.deriv_v(x)
            })),
            Value::Triple(Slot::Varying(x)) => Value::Triple(Slot::Varying(if along_u {
                g.deriv_u(x)
            } else {
                g.deriv_v(x)
            })),
            Value::Triple(_) => Value::triple(Vec3::ZERO),
            _ => Value::float(0.0),
        }
    }

    fn builtin(
        &mut self,
        name: &str,
        ret: BaseType,
        a: &[Value],
        exprs: &[Expr],
        mask: &Mask,
    ) -> Option<Value> {
        let n = self.n;
        Some(match (name, a.len()) {
            // ---- §15.1 mathematical ----
            ("PI", 0) => Value::float(std::f32::consts::PI),
            ("radians", 1) => unary(&a[0], f32::to_radians),
            ("degrees", 1) => unary(&a[0], f32::to_degrees),
            ("sin", 1) => unary(&a[0], f32::sin),
            ("cos", 1) => unary(&a[0], f32::cos),
            ("tan", 1) => unary(&a[0], f32::tan),
            ("asin", 1) => unary(&a[0], f32::asin),
            ("acos", 1) => unary(&a[0], f32::acos),
            ("atan", 1) => unary(&a[0], f32::atan),
            ("atan", 2) => binary(&a[0], &a[1], n, f32::atan2),
            ("pow", 2) => binary(&a[0], &a[1], n, f32::powf),
            ("exp", 1) => unary(&a[0], f32::exp),
            ("sqrt", 1) => unary(&a[0], f32::sqrt),
            ("inversesqrt", 1) => unary(&a[0], mf::inversesqrt),
            ("log", 1) => unary(&a[0], f32::ln),
            ("log", 2) => binary(&a[0], &a[1], n, mf::log_base),
            ("mod", 2) => binary(&a[0], &a[1], n, mf::sl_mod),
            ("abs", 1) => unary(&a[0], f32::abs),
            ("sign", 1) => unary(&a[0], mf::sign),
            ("floor", 1) => unary(&a[0], f32::floor),
            ("ceil", 1) => unary(&a[0], f32::ceil),
            ("round", 1) => unary(&a[0], mf::round),
            ("min", k) if k >= 1 => a[1..]
                .iter()
                .fold(a[0].clone(), |acc, x| binary(&acc, x, n, f32::min)),
            ("max", k) if k >= 1 => a[1..]
                .iter()
                .fold(a[0].clone(), |acc, x| binary(&acc, x, n, f32::max)),
            ("clamp", 3) => ternary(&a[0], &a[1], &a[2], n, mf::clamp),
            ("step", 2) => binary(&a[0], &a[1], n, mf::step),
            ("smoothstep", 3) => ternary(&a[0], &a[1], &a[2], n, illume_shade::smoothstep),
            ("mix", 3) => match (&a[0], &a[1], &a[2]) {
                (Value::Float(_), Value::Float(_), _) | (_, _, Value::Triple(_)) => {
                    ternary(&a[0], &a[1], &a[2], n, |x, y, t| x * (1.0 - t) + y * t)
                }
                _ => {
                    let t = fl(&a[2]);
                    let xy = zip2(&tr(&a[0]), &tr(&a[1]), n, |x, y| (*x, *y));
                    Value::Triple(zip2(&xy, &t, n, |(x, y), &t| *x * (1.0 - t) + *y * t))
                }
            },
            ("filterstep", 2) => {
                let x = fl(&a[1]);
                let w = self.filter_width(&x);
                Value::Float(zip3(&fl(&a[0]), &x, &w, n, |&e, &x, &w| {
                    mf::filterstep(e, x, w)
                }))
            }
            ("filterstep", 3) => {
                // filterstep(edge, s0, s1): the fraction of [s0, s1] at or above the edge.
                Value::Float(zip3(
                    &fl(&a[0]),
                    &fl(&a[1]),
                    &fl(&a[2]),
                    n,
                    |&e, &x0, &x1| {
                        let (lo, hi) = (x0.min(x1), x0.max(x1));
                        mf::filterstep(e, 0.5 * (lo + hi), hi - lo)
                    },
                ))
            }
            ("noise", _) => {
                let c = noise_coords(a, n);
                let d = dims_of(a);
                noise_result(ret, &c, |c, seed| noise::noise(&c[..d], seed))
            }
            ("cellnoise", _) => {
                let c = noise_coords(a, n);
                let d = dims_of(a);
                noise_result(ret, &c, |c, seed| noise::cellnoise(&c[..d], seed))
            }
            ("pnoise", k) if k >= 2 && k % 2 == 0 => {
                let half = k / 2;
                let c = noise_coords(&a[..half], n);
                let p = noise_coords(&a[half..], n);
                let d = dims_of(&a[..half]);
                let cp = zip2(&c, &p, n, |c, p| (*c, *p));
                if ret == BaseType::Float {
                    Value::Float(cp.map(|(c, p)| noise::pnoise(&c[..d], &p[..d], 0)))
                } else {
                    Value::Triple(cp.map(|(c, p)| {
                        Vec3::new(
                            noise::pnoise(&c[..d], &p[..d], 0),
                            noise::pnoise(&c[..d], &p[..d], 1),
                            noise::pnoise(&c[..d], &p[..d], 2),
                        )
                    }))
                }
            }
            ("random", 0) => {
                // Keyed by the point's undisplaced position (not its index in the grid, which
                // every grid shares), the call site and the frame: the same bits whatever the
                // dicing order or thread count.
                self.random_site += 1;
                let (site, seed) = (self.random_site, self.env.seed);
                let key = |i: usize| {
                    let p = self.grid.p[i];
                    illume_shade::lowbias32(
                        p.x.to_bits()
                            ^ illume_shade::lowbias32(
                                p.y.to_bits() ^ illume_shade::lowbias32(p.z.to_bits()),
                            ),
                    ) as usize
                };
                let f = |i: usize, c: u32| noise::random(key(i), site.wrapping_mul(3) + c, seed);
                if ret == BaseType::Float {
                    Value::Float(Slot::Varying((0..n).map(|i| f(i, 0)).collect()))
                } else {
                    Value::Triple(Slot::Varying(
                        (0..n)
                            .map(|i| Vec3::new(f(i, 0), f(i, 1), f(i, 2)))
                            .collect(),
                    ))
                }
            }
            ("spline", k) if k >= 2 => self.spline(ret, a)?,
            // ---- §15.2 geometric ----
            ("xcomp", 1) => Value::Float(tr(&a[0]).map(|p| p.x)),
            ("ycomp", 1) => Value::Float(tr(&a[0]).map(|p| p.y)),
            ("zcomp", 1) => Value::Float(tr(&a[0]).map(|p| p.z)),
            ("setxcomp" | "setycomp" | "setzcomp", 2) => {
                let k = match name {
                    "setxcomp" => 0,
                    "setycomp" => 1,
                    _ => 2,
                };
                let out = zip2(&tr(&a[0]), &fl(&a[1]), n, |p, &x| {
                    let mut p = *p;
                    p[k] = x;
                    p
                });
                self.write_back(&exprs[0], &Value::Triple(out), mask);
                Value::Void
            }
            ("comp", 2) => Value::Float(zip2(&tr(&a[0]), &fl(&a[1]), n, |p, &i| {
                p[(i.max(0.0) as usize).min(2)]
            })),
            ("comp", 3) => {
                Value::Float(zip3(&mx(&a[0]), &fl(&a[1]), &fl(&a[2]), n, |m, &r, &c| {
                    geometric::matrix_comp(m, r.max(0.0) as usize, c.max(0.0) as usize)
                }))
            }
            ("setcomp", 3) => {
                let out = zip3(&tr(&a[0]), &fl(&a[1]), &fl(&a[2]), n, |p, &i, &x| {
                    let mut p = *p;
                    p[(i.max(0.0) as usize).min(2)] = x;
                    p
                });
                self.write_back(&exprs[0], &Value::Triple(out), mask);
                Value::Void
            }
            ("setcomp", 4) => {
                let rc = zip2(&fl(&a[1]), &fl(&a[2]), n, |&r, &c| (r, c));
                let out = zip3(&mx(&a[0]), &rc, &fl(&a[3]), n, |m, (r, c), &x| {
                    let mut m = *m;
                    geometric::matrix_setcomp(&mut m, r.max(0.0) as usize, c.max(0.0) as usize, x);
                    m
                });
                self.write_back(&exprs[0], &Value::Matrix(out), mask);
                Value::Void
            }
            ("length", 1) => Value::Float(tr(&a[0]).map(|p| p.as_dvec3().length() as f32)),
            ("normalize", 1) => Value::Triple(tr(&a[0]).map(|p| normalize_or_zero(*p))),
            ("distance", 2) => Value::Float(zip2(&tr(&a[0]), &tr(&a[1]), n, |p, q| {
                geometric::distance(*p, *q)
            })),
            ("ptlined", 3) => {
                Value::Float(zip3(&tr(&a[0]), &tr(&a[1]), &tr(&a[2]), n, |p, q, r| {
                    geometric::ptlined(*p, *q, *r)
                }))
            }
            ("rotate", 4) if !matches!(a[0], Value::Matrix(_)) => {
                let qa = zip2(&tr(&a[0]), &fl(&a[1]), n, |q, &x| (*q, x));
                Value::Triple(zip3(&qa, &tr(&a[2]), &tr(&a[3]), n, |(q, ang), p0, p1| {
                    geometric::rotate_point(*q, *ang, *p0, *p1)
                }))
            }
            ("faceforward", 2) => {
                let ng = self.varying_global(Global::Ng);
                let ni = zip2(&tr(&a[0]), &tr(&a[1]), n, |a, b| (*a, *b));
                Value::Triple(zip2(&ni, &ng, n, |(nn, i), ng| faceforward(*nn, *i, *ng)))
            }
            ("faceforward", 3) => {
                Value::Triple(zip3(&tr(&a[0]), &tr(&a[1]), &tr(&a[2]), n, |x, i, r| {
                    faceforward(*x, *i, *r)
                }))
            }
            ("reflect", 2) => {
                Value::Triple(zip2(&tr(&a[0]), &tr(&a[1]), n, |i, nn| reflect(*i, *nn)))
            }
            ("refract", 3) => {
                Value::Triple(zip3(&tr(&a[0]), &tr(&a[1]), &fl(&a[2]), n, |i, nn, &e| {
                    refract(*i, *nn, e)
                }))
            }
            ("fresnel", 5 | 7) => {
                let fr = zip3(&tr(&a[0]), &tr(&a[1]), &fl(&a[2]), n, |i, nn, &e| {
                    fresnel(*i, *nn, e)
                });
                self.write_back(&exprs[3], &Value::Float(fr.map(|f| f.kr)), mask);
                self.write_back(&exprs[4], &Value::Float(fr.map(|f| f.kt)), mask);
                if a.len() == 7 {
                    self.write_back(&exprs[5], &Value::Triple(fr.map(|f| f.r)), mask);
                    self.write_back(&exprs[6], &Value::Triple(fr.map(|f| f.t)), mask);
                }
                Value::Void
            }
            ("transform" | "vtransform" | "ntransform", 2..=3) => {
                let kind = match name {
                    "transform" => BaseType::Point,
                    "vtransform" => BaseType::Vector,
                    _ => BaseType::Normal,
                };
                self.transform(kind, a)?
            }
            ("depth", 1) => {
                // RI 3.2 §15.2: the camera-space z mapped so the near plane is 0, the far 1. An
                // infinite far plane (the default) gives 0 everywhere, as (z−near)/∞ would.
                let (near, far) = self.env.clipping;
                let range = f64::from(far) - f64::from(near);
                Value::Float(tr(&a[0]).map(move |p| {
                    if range.is_finite() && range > 0.0 {
                        ((f64::from(p.z) - f64::from(near)) / range) as f32
                    } else {
                        0.0
                    }
                }))
            }
            ("calculatenormal", 1) => {
                let p = tr(&a[0]);
                let du = tr(&self.deriv(&Value::Triple(p.clone()), true));
                let dv = tr(&self.deriv(&Value::Triple(p), false));
                let ng = self.varying_global(Global::Ng);
                let c = zip2(&du, &dv, n, |a, b| a.cross(*b));
                // Oriented like Ng so that sidedness survives (as ShadingGrid::calculatenormal).
                Value::Triple(zip2(
                    &c,
                    &ng,
                    n,
                    |c, ng| if c.dot(*ng) < 0.0 { -*c } else { *c },
                ))
            }
            ("area", 1) => {
                let p = Value::Triple(tr(&a[0]));
                let (du, dv) = (tr(&self.deriv(&p, true)), tr(&self.deriv(&p, false)));
                let (gdu, gdv) = (self.grid.du, self.grid.dv);
                Value::Float(zip2(&du, &dv, n, |a, b| a.cross(*b).length() * gdu * gdv))
            }
            ("Du", 1) => self.deriv(&a[0], true),
            ("Dv", 1) => self.deriv(&a[0], false),
            ("Deriv", 2) => {
                // Deriv(num, den) = Du(num)/Du(den) + Dv(num)/Dv(den) (RI 3.2 §15.2).
                let (nu, nv) = (self.deriv(&a[0], true), self.deriv(&a[0], false));
                let (du, dv) = (self.deriv(&a[1], true), self.deriv(&a[1], false));
                let div = |x: f32, y: f32| if y == 0.0 { 0.0 } else { x / y };
                let u = binary(&nu, &du, n, div);
                let v = binary(&nv, &dv, n, div);
                binary(&u, &v, n, |x, y| x + y)
            }
            // ---- §15.3 colour ----
            ("ctransform", 2) => {
                let to = st(&a[0]);
                self.color_convert("rgb", &to, &a[1])
            }
            ("ctransform", 3) => {
                let (from, to) = (st(&a[0]), st(&a[1]));
                self.color_convert(&from, &to, &a[2])
            }
            // ---- §15.4 matrix ----
            ("determinant", 1) => Value::Float(mx(&a[0]).map(|m| m.determinant() as f32)),
            ("translate", 2) => Value::Matrix(zip2(&mx(&a[0]), &tr(&a[1]), n, |m, t| {
                geometric::translate(m, *t)
            })),
            ("scale", 2) => Value::Matrix(zip2(&mx(&a[0]), &tr(&a[1]), n, |m, s| {
                geometric::scale(m, *s)
            })),
            ("rotate", 3) => {
                Value::Matrix(zip3(&mx(&a[0]), &fl(&a[1]), &tr(&a[2]), n, |m, &x, ax| {
                    geometric::rotate(m, x, *ax)
                }))
            }
            // ---- §15.5 strings ----
            ("concat", _) => Value::string(&a.iter().map(st).collect::<String>()),
            ("format" | "printf", k) if k >= 1 => {
                let s = format_sl(&st(&a[0]), &a[1..]);
                if name == "printf" {
                    eprint!("{s}");
                    Value::Void
                } else {
                    Value::string(&s)
                }
            }
            ("match", 2) => {
                let (pat, subject) = (st(&a[0]), st(&a[1]));
                Value::float(subject.contains(pat.as_str()) as u8 as f32)
            }
            // ---- §15.6 shading and lighting ----
            ("ambient", 0) => {
                let l = self.lights;
                Value::Triple(Slot::Varying((0..n).map(|i| l.ambient(i)).collect()))
            }
            ("diffuse", 1) => {
                let (l, nn) = (self.lights, tr(&a[0]));
                Value::Triple(Slot::Varying(
                    (0..n)
                        .map(|i| l.diffuse(i, normalize_or_zero(*nn.at(i))))
                        .collect(),
                ))
            }
            ("specular", 3) => {
                let (l, nn, v, r) = (self.lights, tr(&a[0]), tr(&a[1]), fl(&a[2]));
                let model = self.env.specular_model;
                Value::Triple(Slot::Varying(
                    (0..n)
                        .map(|i| {
                            l.specular(i, normalize_or_zero(*nn.at(i)), *v.at(i), *r.at(i), model)
                        })
                        .collect(),
                ))
            }
            ("phong", 3) => {
                let (l, nn, v, s) = (self.lights, tr(&a[0]), tr(&a[1]), fl(&a[2]));
                Value::Triple(Slot::Varying(
                    (0..n)
                        .map(|i| l.phong(i, normalize_or_zero(*nn.at(i)), *v.at(i), *s.at(i)))
                        .collect(),
                ))
            }
            ("specularbrdf", 4) => {
                let model = self.env.specular_model;
                let ln = zip2(&tr(&a[0]), &tr(&a[1]), n, |l, nn| (*l, *nn));
                let vr = zip2(&tr(&a[2]), &fl(&a[3]), n, |v, &r| (*v, r));
                Value::Triple(zip2(&ln, &vr, n, |(l, nn), (v, r)| {
                    Vec3::splat(illume_shade::specularbrdf(*l, *nn, *v, *r, model))
                }))
            }
            ("lightsource", 2) => {
                let found = self
                    .current_light
                    .and_then(|k| self.lights.lights.get(k))
                    .and_then(|l| l.param(&st(&a[0])));
                match found {
                    Some(v) if same_kind(&v, &a[1]) => {
                        self.write_back(&exprs[1], &v, mask);
                        Value::float(1.0)
                    }
                    _ => Value::float(0.0),
                }
            }
            ("surface" | "displacement" | "atmosphere", 2) => {
                // The other shader's parameter values as the renderer handed them over (see
                // `Messages`); an unknown name or a type mismatch is "not found".
                let key = st(&a[0]);
                let list = match name {
                    "surface" => &self.messages.surface,
                    "displacement" => &self.messages.displacement,
                    _ => &self.messages.atmosphere,
                };
                let found = list.iter().find(|(k, _)| *k == key).map(|(_, v)| v.clone());
                match found {
                    Some(v) if same_kind(&v, &a[1]) => {
                        self.write_back(&exprs[1], &v, mask);
                        Value::float(1.0)
                    }
                    _ => Value::float(0.0),
                }
            }
            ("incident" | "opposite", 2) => {
                // Volume shaders do not run, so there is no volume to ask: "not found".
                Value::float(0.0)
            }
            ("attribute" | "option" | "rendererinfo", 2) => {
                let key = st(&a[0]);
                let found = match name {
                    "attribute" => self.env.attributes.and_then(|t| t.get(&key)).cloned(),
                    "option" => self.env.options.and_then(|t| t.get(&key)).cloned(),
                    _ => illume_shade::rendererinfo(&key),
                };
                self.answer_query(found, &a[1], &exprs[1], mask)
            }
            ("textureinfo", 3) => {
                let (map, key) = (st(&a[0]), st(&a[1]));
                let found = self.env.textures.and_then(|t| t.textureinfo(&map, &key));
                self.answer_query(found, &a[2], &exprs[2], mask)
            }
            ("trace", _) => Value::triple(Vec3::ZERO),
            _ => return None,
        })
    }

    /// Writes a queried value into the output argument when it fits the variable's type
    /// (float, triple, matrix, string, float array of the same length): 1, else 0 and the
    /// variable keeps its value (RI 3.2 §15.7).
    fn answer_query(
        &mut self,
        found: Option<illume_shade::InfoValue>,
        current: &Value,
        target: &Expr,
        mask: &Mask,
    ) -> Value {
        use illume_shade::InfoValue;
        let v = match (found, current) {
            (Some(InfoValue::String(s)), Value::String(_)) => Some(Value::string(&s)),
            (Some(InfoValue::Floats(f)), Value::Float(_)) if f.len() == 1 => {
                Some(Value::float(f[0]))
            }
            (Some(InfoValue::Floats(f)), Value::Triple(_)) if f.len() == 3 => {
                Some(Value::triple(Vec3::new(f[0], f[1], f[2])))
            }
            (Some(InfoValue::Floats(f)), Value::Matrix(_)) if f.len() == 16 => {
                let mut m = [0.0f64; 16];
                for (k, x) in f.iter().enumerate() {
                    m[k] = f64::from(*x);
                }
                Some(Value::Matrix(Slot::Uniform(geometric::matrix_from_rows(m))))
            }
            (Some(InfoValue::Floats(f)), Value::Array(e))
                if e.len() == f.len() && e.iter().all(|x| matches!(x, Value::Float(_))) =>
            {
                Some(Value::Array(f.iter().map(|&x| Value::float(x)).collect()))
            }
            _ => None,
        };
        match v {
            Some(v) => {
                self.write_back(target, &v, mask);
                Value::float(1.0)
            }
            None => Value::float(0.0),
        }
    }

    /// `filterstep`'s width: the change of `x` over one grid step in u plus one in v.
    fn filter_width(&self, x: &Slot<f32>) -> Slot<f32> {
        let (g, n) = (self.grid, self.n);
        match x {
            Slot::Uniform(_) => Slot::Uniform(0.0),
            Slot::Varying(v) => {
                let (du, dv) = (g.deriv_u(v), g.deriv_v(v));
                Slot::Varying(
                    (0..n)
                        .map(|i| (du[i] * g.du).abs() + (dv[i] * g.dv).abs())
                        .collect(),
                )
            }
        }
    }

    fn color_convert(&mut self, from: &str, to: &str, c: &Value) -> Value {
        if colorspaces::ctransform(from, to, Vec3::ZERO).is_none() {
            self.problem(format!(
                "ctransform: unknown colour space \"{from}\" or \"{to}\""
            ));
            return c.clone();
        }
        Value::Triple(tr(c).map(|c| colorspaces::ctransform(from, to, *c).unwrap_or(*c)))
    }

    /// `transform([from,] to, p)` and `transform([from,] m, p)` for points, vectors, normals.
    fn transform(&mut self, kind: BaseType, a: &[Value]) -> Option<Value> {
        let n = self.n;
        let p = tr(a.last()?);
        let (from, to): (Option<String>, &Value) = if a.len() == 3 {
            (Some(st(&a[0])), &a[1])
        } else {
            (None, &a[0])
        };
        let current_from_from = match &from {
            Some(s) => match self.current_from(s) {
                Some(m) => m,
                None => {
                    self.problem(format!("transform: unknown space \"{s}\""));
                    return Some(Value::Triple(p));
                }
            },
            None => DMat4::IDENTITY,
        };
        Some(match to {
            Value::Matrix(m) => Value::Triple(zip2(m, &p, n, |m, p| {
                apply(kind, &(*m * current_from_from), *p)
            })),
            v => {
                let space = st(v);
                let Some(current_from_to) = self.current_from(&space) else {
                    self.problem(format!("transform: unknown space \"{space}\""));
                    return Some(Value::Triple(p));
                };
                let m = current_from_to.inverse() * current_from_from;
                Value::Triple(p.map(|p| apply(kind, &m, *p)))
            }
        })
    }

    fn spline(&mut self, ret: BaseType, a: &[Value]) -> Option<Value> {
        let n = self.n;
        let (basis, rest) = match &a[0] {
            Value::String(s) => {
                let name = s.at(0).to_string();
                match spline::Basis::from_name(&name) {
                    Some(b) => (b, &a[1..]),
                    None => {
                        self.problem(format!("spline: unknown basis \"{name}\"; catmull-rom"));
                        (spline::Basis::CatmullRom, &a[1..])
                    }
                }
            }
            _ => (spline::Basis::CatmullRom, a),
        };
        let t = fl(rest.first()?);
        let knots: Vec<Value> = match rest.get(1..)? {
            [Value::Array(items)] => items.clone(),
            k => k.to_vec(),
        };
        Some(if ret == BaseType::Float {
            let ks: Vec<Slot<f32>> = knots.iter().map(fl).collect();
            let uniform = t.is_uniform() && ks.iter().all(Slot::is_uniform);
            let at = |i: usize| {
                let k: Vec<f32> = ks.iter().map(|s| *s.at(i)).collect();
                spline::spline(basis, *t.at(i), &k)
            };
            Value::Float(if uniform {
                Slot::Uniform(at(0))
            } else {
                Slot::Varying((0..n).map(at).collect())
            })
        } else {
            let ks: Vec<Slot<Vec3>> = knots.iter().map(tr).collect();
            let uniform = t.is_uniform() && ks.iter().all(Slot::is_uniform);
            let at = |i: usize| {
                let k: Vec<Vec3> = ks.iter().map(|s| *s.at(i)).collect();
                spline::spline(basis, *t.at(i), &k)
            };
            Value::Triple(if uniform {
                Slot::Uniform(at(0))
            } else {
                Slot::Varying((0..n).map(at).collect())
            })
        })
    }
}

fn same_kind(a: &Value, b: &Value) -> bool {
    std::mem::discriminant(a) == std::mem::discriminant(b)
}

/// SL `format`/`printf`: `%f`, `%d`, `%s`, `%p`/`%c` (triples), `%m` (matrix), `%%`, read at
/// the first grid point (uniform use is what scenes do).
fn format_sl(fmt: &str, args: &[Value]) -> String {
    let mut out = String::new();
    let mut it = args.iter();
    let mut chars = fmt.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        // Skip width/precision flags.
        while chars
            .peek()
            .is_some_and(|c| c.is_ascii_digit() || *c == '.' || *c == '-')
        {
            chars.next();
        }
        match chars.next() {
            Some('%') => out.push('%'),
            Some(_) => match it.next() {
                Some(Value::Float(s)) => out.push_str(&format!("{}", s.at(0))),
                Some(Value::Triple(s)) => {
                    let p = s.at(0);
                    out.push_str(&format!("{} {} {}", p.x, p.y, p.z))
                }
                Some(Value::String(s)) => out.push_str(s.at(0)),
                Some(Value::Matrix(s)) => out.push_str(&format!("{:?}", s.at(0).to_cols_array())),
                _ => {}
            },
            None => out.push('%'),
        }
    }
    out
}
