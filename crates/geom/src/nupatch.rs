//! `NuPatch` (RI Spec 3.2 §5.5): a tensor-product non-uniform rational B-spline surface, with
//! the current `TrimCurve` loops.
//!
//! The control points are moved to camera space **as homogeneous points** (`Pw`, or `P` with
//! w = 1): an affine map commutes with the rational combination, so evaluating in camera space
//! is exact. Evaluation is Cox–de Boor in f64 ([`crate::knots`]) with the quotient rule for
//! derivatives. The surface's `(u, v) ∈ [0,1]²` maps linearly onto `[umin,umax] × [vmin,vmax]`.
//!
//! A patch builds one [`Parametric`] piece per non-empty knot rectangle inside that range, all
//! sharing one surface: neighbouring pieces evaluate their shared edge with the same function
//! at the same parameters, so it is bit-identical (no cracks). Primitive variables follow §5.5:
//! uniform one per segment (`(nu−uorder+1)·(nv−vorder+1)`, empty segments included), varying
//! one per segment corner (`(nu−uorder+2)·(nv−vorder+2)`, bilinear inside a segment), vertex
//! one per control point (the same rational basis as P), facevarying four per segment.
use crate::knots::KnotVector;
use crate::parametric::{default_st, with_default_st, Field, FieldRef, Interp, Parametric};
use crate::parametric::{Surface, SurfaceVar};
use crate::primvar::{
    camera_values, element64, is_position, resolve, ClassCounts, PrimVar, PrimVarData,
};
use crate::trimcurve::TrimCurves;
use crate::{Bound, BuildContext, GeomError, Primitive};
use glam::{DMat4, DVec3, DVec4};
use illume_rib::{Class, ParamList};
use std::sync::Arc;

/// The knot vectors and parameter ranges of one `NuPatch` request, as the RIB gives them.
#[derive(Clone, Copy, Debug)]
pub struct NuPatchArgs<'a> {
    pub nu: i32,
    pub uorder: i32,
    pub uknot: &'a [f32],
    pub umin: f32,
    pub umax: f32,
    pub nv: i32,
    pub vorder: i32,
    pub vknot: &'a [f32],
    pub vmin: f32,
    pub vmax: f32,
}

/// One direction of the patch: knots and the clamped parameter range.
#[derive(Clone, Debug, PartialEq)]
struct Axis {
    knots: KnotVector,
    range: [f64; 2],
}

impl Axis {
    /// Knot parameter of the surface parameter `s ∈ [0,1]`.
    fn param(&self, s: f64) -> f64 {
        self.range[0] + s * (self.range[1] - self.range[0])
    }

    /// Surface parameter of the knot parameter `t`, exactly 0 and 1 at the range's ends.
    fn local(&self, t: f64) -> f64 {
        let [a, b] = self.range;
        if t <= a {
            0.0
        } else if t >= b {
            1.0
        } else {
            (t - a) / (b - a)
        }
    }

    fn scale(&self) -> f64 {
        self.range[1] - self.range[0]
    }

    /// Non-empty segments inside the range: (segment index, local sub-range).
    fn pieces(&self) -> Vec<(usize, [f64; 2])> {
        let first = self.knots.order() - 1;
        let [lo, hi] = self.range;
        self.knots
            .segments()
            .filter_map(|(i, [a, b])| {
                let (a, b) = (a.max(lo), b.min(hi));
                (b > a).then(|| (i - first, [self.local(a), self.local(b)]))
            })
            .collect()
    }

    /// The span a local parameter evaluates in and its basis functions.
    fn basis(&self, s: f64, n: &mut [f64], dn: &mut [f64]) -> usize {
        let t = self.param(s);
        let span = self.knots.span(t);
        self.knots.basis(span, t, n, dn);
        span
    }

    /// Knot parameters of a local range.
    fn params(&self, [s0, s1]: [f64; 2]) -> [f64; 2] {
        [self.param(s0), self.param(s1)]
    }
}

/// A NURBS surface in camera space (homogeneous control points, u fastest).
#[derive(Debug)]
pub struct NurbsSurface {
    u: Axis,
    v: Axis,
    pw: Vec<DVec4>,
    trim: Option<Arc<TrimCurves>>,
    /// Derivatives shorter than this are rounding noise of a collapsed edge (a pole whose
    /// control points coincide with different weights) and are zeroed, so the normal falls
    /// back to the limit normal instead of taking the noise's direction.
    tiny: f64,
}

/// The basis functions of both directions at one point, and where they start.
struct Weights {
    iu: usize,
    iv: usize,
    nu: Vec<f64>,
    dnu: Vec<f64>,
    nv: Vec<f64>,
    dnv: Vec<f64>,
}

impl NurbsSurface {
    fn weights(&self, u: f64, v: f64) -> Weights {
        let (ou, ov) = (self.u.knots.order(), self.v.knots.order());
        let mut w = Weights {
            iu: 0,
            iv: 0,
            nu: vec![0.0; ou],
            dnu: vec![0.0; ou],
            nv: vec![0.0; ov],
            dnv: vec![0.0; ov],
        };
        w.iu = self.u.basis(u, &mut w.nu, &mut w.dnu) + 1 - ou;
        w.iv = self.v.basis(v, &mut w.nv, &mut w.dnv) + 1 - ov;
        w
    }

    fn ctrl(&self, i: usize, j: usize) -> DVec4 {
        self.pw[j * self.u.knots.len() + i]
    }
}

impl Surface for NurbsSurface {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        let w = self.weights(u, v);
        let (mut a, mut au, mut av) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for (b, (&nv, &dnv)) in w.nv.iter().zip(&w.dnv).enumerate() {
            let (mut row, mut drow) = (DVec4::ZERO, DVec4::ZERO);
            for (k, (&nu, &dnu)) in w.nu.iter().zip(&w.dnu).enumerate() {
                let c = self.ctrl(w.iu + k, w.iv + b);
                row += nu * c;
                drow += dnu * c;
            }
            a += nv * row;
            au += nv * drow;
            av += dnv * row;
        }
        let p = a.truncate() / a.w;
        // Quotient rule for (xyz/w)', then the chain rule into the surface's [0,1] units.
        let pu = (au.truncate() - p * au.w) / a.w * self.u.scale();
        let pv = (av.truncate() - p * av.w) / a.w * self.v.scale();
        let clean = |d: DVec3| {
            if d.length() < self.tiny {
                DVec3::ZERO
            } else {
                d
            }
        };
        [p, clean(pu), clean(pv)]
    }

    /// Convex hull property: with positive weights the sub-range lies in the hull of its
    /// Bézier control points (homogeneous, one set per knot rectangle it crosses), which
    /// shrink with the range: the B-spline control points alone bound a whole knot span,
    /// so the pieces of a split bilinear floor would all keep the floor's bound and never be
    /// culled off screen (issue 21).
    fn bound(&self, u: [f64; 2], v: [f64; 2]) -> Bound {
        let (pu, pv) = (self.u.knots.order() - 1, self.v.knots.order() - 1);
        let (tu, tv) = (self.u.params(u), self.v.params(v));
        let mut points = Vec::new();
        for (su, ru) in self.u.knots.spans_of_range(tu[0], tu[1]) {
            let mu = self.u.knots.bezier_of_range(su, ru);
            for (sv, rv) in self.v.knots.spans_of_range(tv[0], tv[1]) {
                let mv = self.v.knots.bezier_of_range(sv, rv);
                // Rows of the span's control points converted to Bézier form in u …
                let rows: Vec<Vec<DVec4>> = (0..=pv)
                    .map(|b| {
                        mu.iter()
                            .map(|w| {
                                w.iter()
                                    .enumerate()
                                    .map(|(k, &x)| x * self.ctrl(su + k - pu, sv + b - pv))
                                    .sum()
                            })
                            .collect()
                    })
                    .collect();
                // … then in v.
                for w in &mv {
                    for i in 0..=pu {
                        let c: DVec4 = w.iter().zip(&rows).map(|(&x, r)| x * r[i]).sum();
                        points.push(c.truncate() / c.w);
                    }
                }
            }
        }
        Bound::from_dpoints(points)
    }

    fn trimmed(&self, u: f64, v: f64) -> bool {
        self.trim
            .as_ref()
            .is_some_and(|t| !t.keeps(self.u.param(u), self.v.param(v)))
    }

    fn has_trim(&self) -> bool {
        self.trim.is_some()
    }
}

/// A vertex variable: the surface's rational basis applied to per-control-point values.
#[derive(Debug)]
struct VertexField {
    surface: Arc<NurbsSurface>,
    values: Vec<f64>,
    components: usize,
}

impl Field for VertexField {
    fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) {
        let s = &self.surface;
        let w = s.weights(u, v);
        out.fill(0.0);
        let mut wsum = 0.0;
        for (b, &nv) in w.nv.iter().enumerate() {
            for (k, &nu) in w.nu.iter().enumerate() {
                let (i, j) = (w.iu + k, w.iv + b);
                let weight = nu * nv * s.ctrl(i, j).w;
                wsum += weight;
                let idx = (j * s.u.knots.len() + i) * self.components;
                for (o, x) in out.iter_mut().zip(&self.values[idx..idx + self.components]) {
                    *o += weight * x;
                }
            }
        }
        out.iter_mut().for_each(|o| *o /= wsum);
    }
}

/// Varying and facevarying variables: four corner values per segment, bilinear in the
/// segment's own knot interval.
#[derive(Debug)]
struct SegmentField {
    surface: Arc<NurbsSurface>,
    /// Per segment (u fastest), corners (0,0) (1,0) (0,1) (1,1), `components` each.
    corners: Vec<f64>,
    components: usize,
}

impl Field for SegmentField {
    fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) {
        let s = &self.surface;
        let frac = |axis: &Axis, x: f64| {
            let t = axis.param(x);
            let span = axis.knots.span(t);
            let (a, b) = (axis.knots.knot(span), axis.knots.knot(span + 1));
            (
                span + 1 - axis.knots.order(),
                ((t - a) / (b - a)).clamp(0.0, 1.0),
            )
        };
        let ((su, fu), (sv, fv)) = (frac(&s.u, u), frac(&s.v, v));
        let segs_u = s.u.knots.len() + 1 - s.u.knots.order();
        let c = self.components;
        let base = (sv * segs_u + su) * 4 * c;
        let w = [
            (1.0 - fu) * (1.0 - fv),
            fu * (1.0 - fv),
            (1.0 - fu) * fv,
            fu * fv,
        ];
        for (k, o) in out.iter_mut().enumerate() {
            *o = (0..4).map(|n| w[n] * self.corners[base + n * c + k]).sum();
        }
    }
}

/// Builds a `NuPatch`, cut by `trim` when the attribute state holds trim curves.
pub fn build_nupatch(
    a: NuPatchArgs,
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    let invalid = |message: String| GeomError::Invalid {
        request: "NuPatch".to_string(),
        message,
    };
    let axis = |name: &str, knots: &[f32], order: i32, n: i32, min: f32, max: f32| {
        let knots =
            KnotVector::new(knots, order, n).map_err(|e| invalid(format!("{name}: {e}")))?;
        if !min.is_finite() || !max.is_finite() {
            return Err(invalid(format!("{name}min/{name}max must be finite")));
        }
        let [d0, d1] = knots.domain();
        let range = [f64::from(min).max(d0), f64::from(max).min(d1)];
        Ok(Axis { knots, range })
    };
    let u = axis("u", a.uknot, a.uorder, a.nu, a.umin, a.umax)?;
    let v = axis("v", a.vknot, a.vorder, a.nv, a.vmin, a.vmax)?;
    if u.range[1] <= u.range[0] || v.range[1] <= v.range[0] {
        return Ok(Vec::new());
    }
    let (nu, nv) = (a.nu as usize, a.nv as usize);
    let segs_u = nu + 1 - a.uorder as usize;
    let segs_v = nv + 1 - a.vorder as usize;
    let counts = ClassCounts {
        uniform: segs_u * segs_v,
        varying: (segs_u + 1) * (segs_v + 1),
        vertex: nu * nv,
        facevarying: 4 * segs_u * segs_v,
    };
    let vars = resolve("NuPatch", params, ctx.declarations, &counts, ctx.warnings)?;
    let pw = homogeneous_points(&vars, &ctx.camera_from_object).map_err(invalid)?;
    let trim = ctx.trim_curves.clone().filter(|t| !t.is_empty());
    // The control net's extent sets the noise floor of the derivatives (f64 rounding of
    // coordinates of that size, with a wide margin).
    let extent = pw
        .iter()
        .map(|c| (c.truncate() / c.w).abs().max_element())
        .fold(0.0, f64::max);
    let tiny = extent * 1e-9;
    let surface = Arc::new(NurbsSurface {
        u,
        v,
        pw,
        trim,
        tiny,
    });
    let shared = shared_vars(&vars, &surface, ctx, (segs_u, segs_v));
    let st = default_st(
        &ctx.texture_coordinates,
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
    );
    let dyn_surface: Arc<dyn Surface> = surface.clone();
    let mut out: Vec<Box<dyn Primitive>> = Vec::new();
    for (sv, rv) in surface.v.pieces() {
        for (su, ru) in surface.u.pieces() {
            let mut pv = shared.clone();
            for var in vars.iter().filter(|x| x.class == Class::Uniform) {
                if let Some(sv) = uniform_var(var, sv * segs_u + su, &ctx.camera_from_object) {
                    pv.push(sv);
                }
            }
            let pv = with_default_st(pv, st.clone());
            let whole = Parametric::new(dyn_surface.clone(), Arc::new(pv));
            out.push(Box::new(whole.sub_range(ru, rv)));
        }
    }
    Ok(out)
}

/// Camera-space homogeneous control points from `Pw` (or `P` with w = 1). Weights must be
/// positive: the convex-hull bound and the rational quotient need it.
fn homogeneous_points(vars: &[PrimVar], m: &DMat4) -> Result<Vec<DVec4>, String> {
    let find = |n: &str| vars.iter().find(|x| x.name == n);
    let pw: Vec<DVec4> = if let Some(p) = find("Pw") {
        p.floats()
            .chunks_exact(4)
            .map(|c| DVec4::new(c[0].into(), c[1].into(), c[2].into(), c[3].into()))
            .collect()
    } else if let Some(p) = find("P") {
        p.floats()
            .chunks_exact(3)
            .map(|c| DVec4::new(c[0].into(), c[1].into(), c[2].into(), 1.0))
            .collect()
    } else {
        return Err("needs \"P\" or \"Pw\"".to_string());
    };
    if let Some(k) = pw.iter().position(|p| !p.is_finite() || p.w <= 0.0) {
        return Err(format!(
            "control point {k} must be finite with a positive weight, found {}",
            pw[k]
        ));
    }
    Ok(pw.into_iter().map(|p| *m * p).collect())
}

/// The variables every piece shares: constant, varying, facevarying and vertex ones.
fn shared_vars(
    vars: &[PrimVar],
    surface: &Arc<NurbsSurface>,
    ctx: &BuildContext,
    (segs_u, segs_v): (usize, usize),
) -> Vec<SurfaceVar> {
    let mut out = Vec::new();
    for var in vars
        .iter()
        .filter(|v| !is_position(v) && matches!(v.data, PrimVarData::Floats(_)))
    {
        let c = var.element_size();
        let values = camera_values(var, &ctx.camera_from_object);
        let interp = match var.class {
            Class::Uniform => continue,
            Class::Constant => Interp::Constant(values),
            Class::Vertex => Interp::Field(FieldRef(Arc::new(VertexField {
                surface: surface.clone(),
                values,
                components: c,
            }))),
            Class::Varying => {
                let at = |i: usize, j: usize| &values[(j * (segs_u + 1) + i) * c..][..c];
                let mut corners = Vec::with_capacity(segs_u * segs_v * 4 * c);
                for j in 0..segs_v {
                    for i in 0..segs_u {
                        for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            corners.extend_from_slice(at(i + a, j + b));
                        }
                    }
                }
                segment_field(surface, corners, c)
            }
            Class::FaceVarying | Class::FaceVertex => segment_field(surface, values, c),
        };
        out.push(SurfaceVar {
            name: var.name.clone(),
            ty: var.ty,
            components: c,
            interp,
        });
    }
    out
}

fn segment_field(surface: &Arc<NurbsSurface>, corners: Vec<f64>, components: usize) -> Interp {
    Interp::Field(FieldRef(Arc::new(SegmentField {
        surface: surface.clone(),
        corners,
        components,
    })))
}

fn uniform_var(var: &PrimVar, segment: usize, m: &DMat4) -> Option<SurfaceVar> {
    if is_position(var) || !matches!(var.data, PrimVarData::Floats(_)) {
        return None;
    }
    let mut sv = SurfaceVar {
        name: var.name.clone(),
        ty: var.ty,
        components: var.element_size(),
        interp: Interp::Constant(element64(var, segment)),
    };
    sv.to_camera(m);
    Some(sv)
}
