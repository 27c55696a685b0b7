//! `Curves` (RI Spec 3.2 §5.7 "Curves"): linear or cubic (the current v `Basis` and v step),
//! periodic or not, as flat ribbons of `width` (varying) or `constantwidth` (default 1).
//!
//! Each segment is one [`Parametric`] piece: `v` runs along the curve, `u` across the ribbon
//! (u = 0.5 on the curve). Without `N` the ribbon is **camera-facing**: its width direction
//! is perpendicular to the tangent in the image plane (`d = (−Ty, Tx, 0)/|…|`, so the normal
//! `dPdu × dPdv` points back at the camera). That is exact in orthographic views and, in
//! perspective, wherever the tangent has no depth component. With `N` (varying, per segment
//! end) the ribbon is oriented: its width direction is `T × N`, so its normal is `N`.
//!
//! Primitive-variable counts per curve (§5.7): vertex `nvertices`; varying (and facevarying)
//! one per segment end (`segments + 1` nonperiodic, `segments` periodic); uniform one per curve.
use crate::basis::{bezier_of_range, BasisMatrix};
use crate::parametric::{default_st, with_default_st, Interp, Parametric, Surface};
use crate::points::{count_of_p, width_scale};
use crate::primvar::{camera_values, element64, resolve, surface_vars, ClassCounts, PrimVar};
use crate::{Bound, BuildContext, GeomError, Primitive};
use glam::{DMat4, DVec3};
use illume_rib::{Class, ParamList};
use std::sync::Arc;

/// One ribbon segment in camera space.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveSegment {
    /// Power form of the centre line: `C(v) = Σ c[a]·v^(3−a)`.
    pub c: [DVec3; 4],
    /// Camera-space widths at v = 0 and v = 1 (linear between).
    pub width: [f64; 2],
    /// Ribbon normals at v = 0 and v = 1, when oriented.
    pub normal: Option<[DVec3; 2]>,
}

impl CurveSegment {
    fn centre(&self, v: f64) -> (DVec3, DVec3) {
        let c = &self.c;
        let p = ((c[0] * v + c[1]) * v + c[2]) * v + c[3];
        let t = (3.0 * c[0] * v + 2.0 * c[1]) * v + c[2];
        (p, t)
    }

    fn across(&self, v: f64, t: DVec3) -> DVec3 {
        let d = match self.normal {
            Some([a, b]) => t.cross(a.lerp(b, v)),
            None => DVec3::new(-t.y, t.x, 0.0),
        };
        d.try_normalize().unwrap_or(DVec3::X)
    }
}

impl Surface for CurveSegment {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        let (p, t) = self.centre(v);
        let d = self.across(v, t);
        let w = self.width[0] + (self.width[1] - self.width[0]) * v;
        let dw = self.width[1] - self.width[0];
        // The change of d along v is left out of dP/dv: ribbons are narrow.
        [p + (u - 0.5) * w * d, w * d, t + (u - 0.5) * dw * d]
    }

    /// The Bézier hull of the centre line over the sub-range, padded by the half width.
    fn bound(&self, _u: [f64; 2], v: [f64; 2]) -> Bound {
        let axis = |k: usize| {
            let mut c = [0.0; 16];
            for a in 0..4 {
                c[12 + a] = self.c[a][k];
            }
            bezier_of_range(&c, [0.0, 1.0], v)
        };
        let (x, y, z) = (axis(0), axis(1), axis(2));
        let half = 0.5 * self.width[0].max(self.width[1]);
        let b = Bound::from_dpoints((12..16).map(|n| DVec3::new(x[n], y[n], z[n])));
        b.padded((half * (1.0 + 1e-6)) as f32)
    }
}

/// One curve's segment layout.
#[derive(Clone, Copy, Debug)]
struct Layout {
    nverts: usize,
    segments: usize,
    varying: usize,
    step: usize,
    span: usize,
}

/// Builds a `Curves` request.
pub fn build_curves(
    kind: &str,
    nvertices: &[i32],
    wrap: &str,
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    let invalid = |message: String| GeomError::Invalid {
        request: "Curves".to_string(),
        message,
    };
    let cubic = match kind {
        "linear" => false,
        "cubic" => true,
        _ => {
            return Err(invalid(format!(
                "type must be \"linear\" or \"cubic\", found \"{kind}\""
            )))
        }
    };
    let periodic = match wrap {
        "periodic" => true,
        "nonperiodic" => false,
        _ => {
            return Err(invalid(format!(
                "wrap must be \"periodic\" or \"nonperiodic\", found \"{wrap}\""
            )))
        }
    };
    let step = if cubic {
        ctx.basis.3.max(1) as usize
    } else {
        1
    };
    let span = if cubic { 4 } else { 2 };
    let layouts: Vec<Layout> = nvertices
        .iter()
        .enumerate()
        .map(|(i, &n)| {
            let n = n.max(0) as usize;
            let segments = match (periodic, n) {
                (true, n) if n >= span.min(2) && n % step == 0 => n / step,
                (false, n) if n >= span && (n - span) % step == 0 => (n - span) / step + 1,
                _ => {
                    return Err(invalid(format!(
                        "curve {i}: {n} vertices do not make whole segments ({kind}, {wrap}, step {step})"
                    )))
                }
            };
            let varying = if periodic { segments } else { segments + 1 };
            Ok(Layout {
                nverts: n,
                segments,
                varying,
                step,
                span,
            })
        })
        .collect::<Result<_, _>>()?;
    let vertex: usize = layouts.iter().map(|l| l.nverts).sum();
    let varying: usize = layouts.iter().map(|l| l.varying).sum();
    if count_of_p(params) != vertex {
        return Err(invalid(format!(
            "\"P\" has {} points, nvertices adds up to {vertex}",
            count_of_p(params)
        )));
    }
    let counts = ClassCounts {
        uniform: layouts.len(),
        varying,
        vertex,
        facevarying: varying,
    };
    let vars = resolve("Curves", params, ctx.declarations, &counts, ctx.warnings)?;
    let m = &ctx.camera_from_object;
    let p = vars
        .iter()
        .find(|v| v.name == "P")
        .ok_or_else(|| invalid("needs \"P\"".to_string()))?;
    let pts: Vec<DVec3> = p
        .floats()
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0].into(), c[1].into(), c[2].into()))
        .collect();
    if pts.iter().any(|p| !p.is_finite()) {
        return Err(invalid("a control point is not finite".to_string()));
    }
    let widths = varying_widths(&vars, varying, width_scale(m)).map_err(invalid)?;
    let normals = vars
        .iter()
        .find(|v| v.name == "N" && v.element_size() == 3)
        .map(|n| (n.class, camera_values(n, m)));
    let basis = ctx.basis.2;
    let mut out: Vec<Box<dyn Primitive>> = Vec::new();
    let (mut v0, mut y0) = (0usize, 0usize);
    for (ci, l) in layouts.iter().enumerate() {
        for s in 0..l.segments {
            let ctrl = |k: usize| v0 + (s * l.step + k) % l.nverts;
            let ends = [y0 + s, y0 + (s + 1) % l.varying];
            let g: Vec<DVec3> = (0..l.span).map(|k| pts[ctrl(k)]).collect();
            let c = power_form(&g, &basis, m);
            let normal = normals.as_ref().and_then(|(class, n)| {
                let at = |i: usize| DVec3::new(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
                match class {
                    Class::Varying | Class::FaceVarying | Class::FaceVertex => Some(ends.map(at)),
                    Class::Vertex if !cubic => Some([at(ctrl(0)), at(ctrl(1))]),
                    Class::Uniform => Some([at(ci), at(ci)]),
                    Class::Constant => Some([at(0), at(0)]),
                    Class::Vertex => None,
                }
            });
            let segment = CurveSegment {
                c,
                width: ends.map(|e| widths[e]),
                normal,
            };
            let svars = segment_vars(&vars, (ci, ends), &ctrl, cubic, &basis, m);
            let (a, b) = (
                s as f64 / l.segments as f64,
                (s + 1) as f64 / l.segments as f64,
            );
            let st = default_st(
                &ctx.texture_coordinates,
                [[0.0, a], [1.0, a], [0.0, b], [1.0, b]],
            );
            out.push(Box::new(Parametric::new(
                Arc::new(segment),
                Arc::new(with_default_st(svars, st)),
            )));
        }
        v0 += l.nverts;
        y0 += l.varying;
    }
    Ok(out)
}

/// Camera-space power form of a segment's centre line: linear from 2 points, cubic from 4
/// with the v basis (`[v³ v² v 1]·M·G`).
fn power_form(g: &[DVec3], basis: &BasisMatrix, m: &DMat4) -> [DVec3; 4] {
    let obj = if g.len() == 2 {
        [DVec3::ZERO, DVec3::ZERO, g[1] - g[0], g[0]]
    } else {
        std::array::from_fn(|a| (0..4).map(|k| f64::from(basis[4 * a + k]) * g[k]).sum())
    };
    // The constant term is a position, the others are differences.
    std::array::from_fn(|a| {
        if a == 3 {
            m.transform_point3(obj[a])
        } else {
            m.transform_vector3(obj[a])
        }
    })
}

/// The variables of one segment (everything but P, width and N), by class.
fn segment_vars(
    vars: &[PrimVar],
    (curve, ends): (usize, [usize; 2]),
    ctrl: &dyn Fn(usize) -> usize,
    cubic: bool,
    basis: &BasisMatrix,
    m: &DMat4,
) -> Vec<crate::parametric::SurfaceVar> {
    let kept: Vec<PrimVar> = vars
        .iter()
        .filter(|v| !matches!(v.name.as_str(), "width" | "constantwidth"))
        .cloned()
        .collect();
    let along = |a: Vec<f64>, b: Vec<f64>| Interp::Bilinear([a.clone(), a, b.clone(), b]);
    surface_vars(&kept, m, |v| match v.class {
        Class::Constant => Interp::Constant(element64(v, 0)),
        Class::Uniform => Interp::Constant(element64(v, curve)),
        Class::Varying | Class::FaceVarying | Class::FaceVertex => {
            along(element64(v, ends[0]), element64(v, ends[1]))
        }
        Class::Vertex if !cubic => along(element64(v, ctrl(0)), element64(v, ctrl(1))),
        Class::Vertex => {
            let size = v.element_size();
            Interp::Bicubic(
                (0..size)
                    .map(|k| {
                        // A curve along v only: the u^0 row of the power form.
                        let mut c = [0.0; 16];
                        for a in 0..4 {
                            c[12 + a] = (0..4)
                                .map(|j| {
                                    f64::from(basis[4 * a + j])
                                        * f64::from(v.floats()[ctrl(j) * size + k])
                                })
                                .sum();
                        }
                        c
                    })
                    .collect(),
            )
        }
    })
}

/// Camera-space widths at every varying position: `width` or `constantwidth` (default 1).
fn varying_widths(vars: &[PrimVar], n: usize, scale: f64) -> Result<Vec<f64>, String> {
    crate::points::widths(vars, n, scale)
}

#[cfg(test)]
mod tests {
    use super::*;
    use illume_rib::{Declaration, Param, Value};

    fn no_decls(_: &str) -> Option<Declaration> {
        None
    }

    fn build(kind: &str, nv: &[i32], wrap: &str, n: usize, step: i32) -> Result<usize, GeomError> {
        let b = crate::basis::basis_matrix("b-spline").unwrap().0;
        let ctx = BuildContext {
            camera_from_object: DMat4::IDENTITY,
            declarations: &no_decls,
            basis: (b, step, b, step),
            texture_coordinates: [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            trim_curves: None,
            warnings: None,
        };
        let p: Vec<f32> = (0..3 * n).map(|k| (k * k % 7) as f32).collect();
        let params = vec![Param {
            name: "P".to_string(),
            value: Value::Floats(p),
        }];
        build_curves(kind, nv, wrap, &params, &ctx).map(|v| v.len())
    }

    #[test]
    fn segment_counts_follow_wrap_and_step() {
        assert_eq!(build("linear", &[4, 2], "nonperiodic", 6, 1), Ok(3 + 1));
        assert_eq!(build("linear", &[4], "periodic", 4, 1), Ok(4));
        assert_eq!(build("cubic", &[7], "nonperiodic", 7, 1), Ok(4));
        assert_eq!(build("cubic", &[6], "periodic", 6, 1), Ok(6));
        assert_eq!(build("cubic", &[7], "nonperiodic", 7, 3), Ok(2));
        assert!(build("cubic", &[6], "nonperiodic", 6, 3).is_err());
        assert!(build("cubic", &[3], "nonperiodic", 3, 1).is_err());
        assert!(build("linear", &[4], "nonperiodic", 5, 1).is_err());
        assert!(build("quadratic", &[4], "nonperiodic", 4, 1).is_err());
    }
}
