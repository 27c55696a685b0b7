//! A parametric sub-range `[u0,u1] × [v0,v1]` of a surface: the one primitive the hider splits
//! and dices. Quadrics, patches and polygon pieces are all [`Surface`]s with their primitive
//! variables ([`SurfaceVar`]); this file owns the shared REYES mechanics.
//!
//! * **split** halves the range that is longer *in camera space* (estimated from a few chords),
//!   so a thin sliver is cut across, not along.
//! * **dice** evaluates P, dPdu, dPdv analytically in f64 at parameters that are exactly `u0`
//!   and `u1` at the grid's ends, so two halves of a split evaluate their shared edge at the
//!   same parameters and produce bit-identical vertices (no cracks).
use crate::{Bound, Grid, GridVar, Primitive};
use glam::{DMat3, DMat4, DVec3, Vec3};
use illume_rib::Type;
use std::sync::Arc;

/// A surface over `(u, v) ∈ [0,1]²`, evaluated in camera space.
pub trait Surface: Send + Sync + std::fmt::Debug {
    /// Camera-space `(P, dP/du, dP/dv)` at `(u, v)`.
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3];
    /// [`Surface::eval`] at every `(u, v)` of `us × vs`, appended to `out` row by row (`u`
    /// fastest). A surface whose evaluation separates into a part in `u` and one in `v` (the
    /// quadrics) shares them along rows and columns; the values must be `eval`'s, bit for bit.
    fn eval_grid(&self, us: &[f64], vs: &[f64], out: &mut Vec<[DVec3; 3]>) {
        out.reserve(us.len() * vs.len());
        for &v in vs {
            out.extend(us.iter().map(|&u| self.eval(u, v)));
        }
    }
    /// A conservative camera-space bound of the sub-range `[u0,u1] × [v0,v1]`.
    fn bound(&self, u: [f64; 2], v: [f64; 2]) -> Bound;
    /// Whether the point `(u, v)` is cut away (a `TrimCurve` region of a NuPatch). Surfaces
    /// without trimming keep everything.
    fn trimmed(&self, _u: f64, _v: f64) -> bool {
        false
    }
    /// Whether [`Surface::trimmed`] can ever say `true` (saves the per-micropolygon test).
    fn has_trim(&self) -> bool {
        false
    }
    /// The quadric this surface is (see [`Primitive::quadric`]).
    fn quadric(&self) -> Option<(crate::quadric::Shape, glam::DMat4)> {
        None
    }
}

/// A primitive variable whose interpolation is not one of the closed forms of [`Interp`]
/// (NURBS bases, piecewise-bilinear varying values over knot spans). Values are already in
/// camera space when the field is built.
pub trait Field: Send + Sync + std::fmt::Debug {
    /// Writes the value at surface parameters `(u, v)` into `out` (`components` scalars).
    fn eval_into(&self, u: f64, v: f64, out: &mut [f64]);
}

/// A shared [`Field`], compared by identity (two fields are equal when they are the same one).
#[derive(Clone, Debug)]
pub struct FieldRef(pub Arc<dyn Field>);

impl PartialEq for FieldRef {
    fn eq(&self, other: &FieldRef) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// How a primitive variable varies over one surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Interp {
    /// Constant and uniform classes: one value over the whole surface.
    Constant(Vec<f64>),
    /// Varying (and, on bilinear surfaces, vertex/facevarying) values at the corners
    /// `(0,0), (1,0), (0,1), (1,1)`, interpolated bilinearly.
    Bilinear([Vec<f64>; 4]),
    /// Vertex values on a bicubic patch in power form: per component, `c[4·i + j]`
    /// multiplies `u^(3-i) · v^(3-j)` (so `c[15]` is the constant term).
    Bicubic(Vec<[f64; 16]>),
    /// Any other interpolation, already in camera space ([`SurfaceVar::to_camera`] leaves it).
    Field(FieldRef),
}

/// One primitive variable of a surface (everything but the position).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceVar {
    pub name: String,
    pub ty: Type,
    /// Scalars per value (`ty.components() × array_len`).
    pub components: usize,
    pub interp: Interp,
}

impl Interp {
    fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) {
        match self {
            Interp::Constant(c) => out.copy_from_slice(c),
            Interp::Bilinear([a, b, c, d]) => {
                let (w0, w1, w2, w3) = ((1.0 - u) * (1.0 - v), u * (1.0 - v), (1.0 - u) * v, u * v);
                for (k, o) in out.iter_mut().enumerate() {
                    *o = w0 * a[k] + w1 * b[k] + w2 * c[k] + w3 * d[k];
                }
            }
            Interp::Bicubic(coeffs) => {
                let uu = [u * u * u, u * u, u, 1.0];
                let vv = [v * v * v, v * v, v, 1.0];
                for (o, c) in out.iter_mut().zip(coeffs) {
                    *o = power_eval(c, &uu, &vv);
                }
            }
            Interp::Field(f) => f.0.eval_into(u, v, out),
        }
    }

    /// Applies `f` to every 3-component element (points, vectors, normals) of this variable,
    /// `constant_term` telling whether the value is a position (weights summing to one) or a
    /// difference (power-form coefficients other than the constant term).
    fn map_triples(&mut self, f: &dyn Fn(DVec3, bool) -> DVec3) {
        let map = |vals: &mut Vec<f64>, position: bool| {
            for e in vals.chunks_exact_mut(3) {
                let r = f(DVec3::new(e[0], e[1], e[2]), position);
                e.copy_from_slice(&r.to_array());
            }
        };
        match self {
            Interp::Constant(c) => map(c, true),
            Interp::Bilinear(corners) => corners.iter_mut().for_each(|c| map(c, true)),
            Interp::Bicubic(coeffs) => {
                for e in coeffs.chunks_exact_mut(3) {
                    let [x, y, z] = e else { continue };
                    for (k, ((x, y), z)) in
                        x.iter_mut().zip(y.iter_mut()).zip(z.iter_mut()).enumerate()
                    {
                        let r = f(DVec3::new(*x, *y, *z), k == 15);
                        (*x, *y, *z) = (r.x, r.y, r.z);
                    }
                }
            }
            Interp::Field(_) => {}
        }
    }
}

/// `Σ c[4i+j] · uu[i] · vv[j]`.
pub(crate) fn power_eval(c: &[f64; 16], uu: &[f64; 4], vv: &[f64; 4]) -> f64 {
    let mut s = 0.0;
    for i in 0..4 {
        let row = c[4 * i] * vv[0] + c[4 * i + 1] * vv[1] + c[4 * i + 2] * vv[2] + c[4 * i + 3];
        s += row * uu[i];
    }
    s
}

impl SurfaceVar {
    /// Moves point, vector and normal variables from object to camera space: points as
    /// points, vectors with the linear part, normals with its inverse transpose.
    pub fn to_camera(&mut self, camera_from_object: &DMat4) {
        let m = *camera_from_object;
        let normal_m = DMat3::from_mat4(m).inverse().transpose();
        match self.ty {
            Type::Point => self.interp.map_triples(&|p, position| {
                if position {
                    m.transform_point3(p)
                } else {
                    m.transform_vector3(p)
                }
            }),
            Type::Vector => self.interp.map_triples(&|p, _| m.transform_vector3(p)),
            Type::Normal => self.interp.map_triples(&|p, _| normal_m * p),
            _ => {}
        }
    }
}

/// Default `s`, `t` from `TextureCoordinates` (RI Spec 3.2 §4.3.3): the four (s,t) pairs sit at
/// the corners of the unit (u,v) square. `corners` are the surface's corners in those (u,v).
pub fn default_st(tc: &[f32; 8], corners: [[f64; 2]; 4]) -> [SurfaceVar; 2] {
    let at = |k: usize, [u, v]: [f64; 2]| {
        let c = |i: usize| tc[2 * i + k] as f64;
        (1.0 - u) * (1.0 - v) * c(0) + u * (1.0 - v) * c(1) + (1.0 - u) * v * c(2) + u * v * c(3)
    };
    let var = |k: usize, name: &str| SurfaceVar {
        name: name.to_string(),
        ty: Type::Float,
        components: 1,
        interp: Interp::Bilinear(corners.map(|c| vec![at(k, c)])),
    };
    [var(0, "s"), var(1, "t")]
}

/// Adds default `s`/`t` for any of the two the user did not give (as `s`, `t` or `st`).
pub fn with_default_st(mut vars: Vec<SurfaceVar>, defaults: [SurfaceVar; 2]) -> Vec<SurfaceVar> {
    let has = |n: &str| vars.iter().any(|v| v.name == n || v.name == "st");
    let [s, t] = defaults;
    let (need_s, need_t) = (!has("s"), !has("t"));
    if need_s {
        vars.push(s);
    }
    if need_t {
        vars.push(t);
    }
    vars
}

/// A sub-range of a [`Surface`] with its variables: bounded, split and diced by the hider.
#[derive(Clone, Debug)]
pub struct Parametric {
    surface: Arc<dyn Surface>,
    vars: Arc<Vec<SurfaceVar>>,
    u: [f64; 2],
    v: [f64; 2],
    /// The shader's (u, v) range that the surface's `[0,1]²` stands for: `[u0, u1, v0, v1]`.
    /// A subpatch of a `PatchMesh` reports u, v over the whole mesh (RI Spec 3.2 §5.2, as
    /// PRMan and Aqsis do), so its `du`, `dPdu` scale with it.
    span: [f64; 4],
}

impl Parametric {
    /// The whole surface `[0,1]²`.
    pub fn new(surface: Arc<dyn Surface>, vars: Arc<Vec<SurfaceVar>>) -> Parametric {
        Parametric {
            surface,
            vars,
            u: [0.0, 1.0],
            v: [0.0, 1.0],
            span: [0.0, 1.0, 0.0, 1.0],
        }
    }

    /// The same piece reporting u over `u` and v over `v` (a subpatch's share of its mesh).
    pub fn spanning(self, u: [f64; 2], v: [f64; 2]) -> Parametric {
        Parametric {
            span: [u[0], u[1], v[0], v[1]],
            ..self
        }
    }

    /// The parametric sub-range this piece covers.
    pub fn range(&self) -> ([f64; 2], [f64; 2]) {
        (self.u, self.v)
    }

    /// This piece restricted to `u`, `v` (sub-ranges of `[0,1]`).
    pub fn sub_range(&self, u: [f64; 2], v: [f64; 2]) -> Parametric {
        Parametric {
            u,
            v,
            ..self.clone()
        }
    }

    fn p(&self, u: f64, v: f64) -> DVec3 {
        self.surface.eval(u, v)[0]
    }

    /// Camera-space length of the piece along u (and along v): the longest of three
    /// two-chord polylines, enough to pick which direction to split.
    fn extents(&self) -> (f64, f64) {
        let [u0, u1] = self.u;
        let [v0, v1] = self.v;
        let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let chords = |a: DVec3, b: DVec3, c: DVec3| a.distance(b) + b.distance(c);
        let lu = [v0, vm, v1]
            .iter()
            .map(|&v| chords(self.p(u0, v), self.p(um, v), self.p(u1, v)))
            .fold(0.0, f64::max);
        let lv = [u0, um, u1]
            .iter()
            .map(|&u| chords(self.p(u, v0), self.p(u, vm), self.p(u, v1)))
            .fold(0.0, f64::max);
        (lu, lv)
    }
}

/// Parameter `i` of `n` evenly spaced over `[a, b]`, exactly `a` and `b` at the ends.
fn lerp_param([a, b]: [f64; 2], i: usize, n: usize) -> f64 {
    if i + 1 == n {
        b
    } else {
        a + (b - a) * (i as f64 / (n - 1) as f64)
    }
}

/// Splits `[a, b]` at its midpoint, or `None` when f64 cannot represent a point between them.
fn halve([a, b]: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    let m = 0.5 * (a + b);
    (m > a.min(b) && m < a.max(b)).then_some(([a, m], [m, b]))
}

impl Primitive for Parametric {
    fn bound(&self) -> Bound {
        self.surface.bound(self.u, self.v)
    }

    fn quadric(&self) -> Option<(crate::quadric::Shape, glam::DMat4)> {
        let whole = self.u == [0.0, 1.0] && self.v == [0.0, 1.0];
        whole.then(|| self.surface.quadric()).flatten()
    }

    fn diceable(&self) -> bool {
        true
    }

    /// Halves the longer camera-space direction. A range too small to halve in f64 is split
    /// the other way; one that can shrink in neither returns itself (the hider's split limit
    /// ends the recursion).
    fn split(&self) -> Vec<Box<dyn Primitive>> {
        self.split_as(self.split_choice())
    }

    /// 0: halve u, 1: halve v, 2: neither can be halved.
    fn split_choice(&self) -> u8 {
        let (lu, lv) = self.extents();
        // NaN extents (a degenerate surface) fall back to splitting u.
        let prefer_u = lv.partial_cmp(&lu) != Some(std::cmp::Ordering::Greater);
        match (halve(self.u), halve(self.v)) {
            (Some(_), _) if prefer_u => 0,
            (_, Some(_)) => 1,
            (Some(_), None) => 0,
            (None, None) => 2,
        }
    }

    /// Halves the direction along which camera depth changes most (when both can be halved).
    fn eye_split_choice(&self) -> u8 {
        let ([u0, u1], [v0, v1]) = (self.u, self.v);
        let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let dz = |a: DVec3, b: DVec3| (a.z - b.z).abs();
        let zu = [v0, vm, v1]
            .iter()
            .map(|&v| dz(self.p(u0, v), self.p(u1, v)))
            .fold(0.0, f64::max);
        let zv = [u0, um, u1]
            .iter()
            .map(|&u| dz(self.p(u, v0), self.p(u, v1)))
            .fold(0.0, f64::max);
        match (halve(self.u), halve(self.v)) {
            (Some(_), Some(_)) if zv > zu => 1,
            (Some(_), Some(_)) if zu > zv => 0,
            _ => self.split_choice(),
        }
    }

    fn split_as(&self, choice: u8) -> Vec<Box<dyn Primitive>> {
        match (choice, halve(self.u), halve(self.v)) {
            (0, Some((a, b)), _) => vec![
                Box::new(self.sub_range(a, self.v)),
                Box::new(self.sub_range(b, self.v)),
            ],
            (1, _, Some((a, b))) => vec![
                Box::new(self.sub_range(self.u, a)),
                Box::new(self.sub_range(self.u, b)),
            ],
            _ => vec![Box::new(self.clone())],
        }
    }

    fn dice(&self, nu: usize, nv: usize) -> Grid {
        dice(self, nu.max(2), nv.max(2))
    }

    fn dice_positions(&self, nu: usize, nv: usize) -> (usize, usize, Vec<Vec3>) {
        let (nu, nv) = (nu.max(2), nv.max(2));
        // The parameters and evaluation `dice` uses, so the same positions.
        let us: Vec<f64> = (0..nu).map(|i| lerp_param(self.u, i, nu)).collect();
        let vs: Vec<f64> = (0..nv).map(|j| lerp_param(self.v, j, nv)).collect();
        let mut evals = Vec::new();
        self.surface.eval_grid(&us, &vs, &mut evals);
        let p = evals
            .iter()
            .take(nu * nv)
            .map(|[p, _, _]| p.as_vec3())
            .collect();
        (nu, nv, p)
    }
}

fn dice(piece: &Parametric, nu: usize, nv: usize) -> Grid {
    let n = nu * nv;
    // The reported parameters: the surface's, mapped onto the piece's span.
    let [u0, u1, v0, v1] = piece.span;
    let (su, sv) = (u1 - u0, v1 - v0);
    let mut g = Grid {
        nu,
        nv,
        du: ((piece.u[1] - piece.u[0]) * su / (nu - 1) as f64) as f32,
        dv: ((piece.v[1] - piece.v[0]) * sv / (nv - 1) as f64) as f32,
        ..Grid::default()
    };
    for f in [&mut g.p, &mut g.n, &mut g.ng, &mut g.dpdu, &mut g.dpdv] {
        f.reserve_exact(n);
    }
    let us: Vec<f64> = (0..nu).map(|i| lerp_param(piece.u, i, nu)).collect();
    let vs: Vec<f64> = (0..nv).map(|j| lerp_param(piece.v, j, nv)).collect();
    let centre = [
        0.5 * (piece.u[0] + piece.u[1]),
        0.5 * (piece.v[0] + piece.v[1]),
    ];
    let mut evals = Vec::new();
    piece.surface.eval_grid(&us, &vs, &mut evals);
    let mut evals = evals.into_iter();
    for &v in &vs {
        for &u in &us {
            let Some([p, dpdu, dpdv]) = evals.next() else {
                break;
            };
            g.p.push(p.as_vec3());
            g.dpdu.push((dpdu / su).as_vec3());
            g.dpdv.push((dpdv / sv).as_vec3());
            g.ng.push(geometric_normal(&*piece.surface, u, v, dpdu, dpdv, centre));
            g.u.push((u0 + su * u) as f32);
            g.v.push((v0 + sv * v) as f32);
        }
    }
    g.n = g.ng.clone();
    fill_vars(&mut g, &piece.vars, &us, &vs);
    if piece.surface.has_trim() {
        g.hidden = trim_mask(&*piece.surface, &us, &vs);
    }
    g
}

/// Per micropolygon: whether its parametric centre is trimmed away. A centre test keeps the
/// expected covered area unbiased (micropolygons straddling the curve are kept or dropped
/// about half the time each), at an edge error below one micropolygon.
fn trim_mask(s: &dyn Surface, us: &[f64], vs: &[f64]) -> Vec<bool> {
    let mut mask = Vec::with_capacity((us.len() - 1) * (vs.len() - 1));
    for v in vs.windows(2) {
        for u in us.windows(2) {
            mask.push(s.trimmed(0.5 * (u[0] + u[1]), 0.5 * (v[0] + v[1])));
        }
    }
    mask
}

/// `normalize(dPdu × dPdv)`; where that vanishes (a pole, the collapsed edge of a triangle)
/// the normal of a point nudged toward the piece's centre, which is the limit normal there.
fn geometric_normal(
    s: &dyn Surface,
    u: f64,
    v: f64,
    dpdu: DVec3,
    dpdv: DVec3,
    centre: [f64; 2],
) -> Vec3 {
    let ok = |a: DVec3, b: DVec3| {
        let c = a.cross(b);
        let l = c.length();
        (l > 1e-12 * a.length() * b.length() && l.is_finite()).then(|| (c / l).as_vec3())
    };
    if let Some(n) = ok(dpdu, dpdv) {
        return n;
    }
    for t in [1e-4, 1e-2, 0.5] {
        let [_, a, b] = s.eval(u + t * (centre[0] - u), v + t * (centre[1] - v));
        if let Some(n) = ok(a, b) {
            return n;
        }
    }
    Vec3::Z
}

fn fill_vars(g: &mut Grid, vars: &[SurfaceVar], us: &[f64], vs: &[f64]) {
    let n = us.len() * vs.len();
    for var in vars {
        let c = var.components;
        let mut data = Vec::with_capacity(n * c);
        let mut tmp = vec![0.0f64; c];
        for &v in vs {
            for &u in us {
                var.interp.eval_into(u, v, &mut tmp);
                data.extend(tmp.iter().map(|&x| x as f32));
            }
        }
        let triples =
            |d: &[f32]| -> Vec<Vec3> { d.chunks_exact(3).map(Vec3::from_slice).collect() };
        match (var.name.as_str(), var.ty, c) {
            (name @ ("N" | crate::grid::SMOOTH_N), Type::Normal, 3) => {
                g.user_normals = name == "N";
                g.n = triples(&data)
                    .into_iter()
                    .zip(&g.ng)
                    .map(|(n, &ng)| n.try_normalize().unwrap_or(ng))
                    .collect()
            }
            ("Cs", Type::Color, 3) => g.cs = Some(triples(&data)),
            ("Os", Type::Color, 3) => g.os = Some(triples(&data)),
            (crate::grid::PARAM_U, Type::Float, 1) => g.u = data,
            (crate::grid::PARAM_V, Type::Float, 1) => g.v = data,
            ("s", Type::Float, 1) => g.s = data,
            ("t", Type::Float, 1) => g.t = data,
            ("st", Type::Float, 2) => {
                if g.s.is_empty() {
                    g.s = data.iter().step_by(2).copied().collect();
                }
                if g.t.is_empty() {
                    g.t = data.iter().skip(1).step_by(2).copied().collect();
                }
            }
            _ => g.vars.push(GridVar {
                name: var.name.clone(),
                ty: var.ty,
                components: c,
                data,
            }),
        }
    }
    if g.s.is_empty() {
        g.s = vec![0.0; n];
    }
    if g.t.is_empty() {
        g.t = vec![0.0; n];
    }
}
