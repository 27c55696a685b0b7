//! Patch and PatchMesh, bilinear and bicubic (RI Spec 3.2 §5.2), with every basis of
//! [`crate::basis`] and periodic or nonperiodic wrap.
//!
//! A mesh builds one [`Parametric`] per subpatch. Subpatch `(i, j)` takes control points
//! `i·ustep … i·ustep+3` (mod `nu` when periodic) and its varying values at varying corners
//! `i, i+1` (mod the varying count when periodic); uniform values are one per subpatch.
//! Vertex variables are interpolated with the same basis as the position.
use crate::basis::{bezier_of_range, power_coefficients, BasisMatrix};
use crate::parametric::{default_st, with_default_st, Interp, Parametric, Surface, SurfaceVar};
use crate::primvar::{element64, resolve, surface_vars, ClassCounts, PrimVar};
use crate::{Bound, BuildContext, GeomError, Primitive};
use glam::{DMat4, DVec3};
use illume_rib::{Class, ParamList};
use std::sync::Arc;

/// A bicubic patch in camera space, in power form: `c[4a + b]` multiplies `u^(3−a) v^(3−b)`.
#[derive(Clone, Debug, PartialEq)]
pub struct BicubicSurface {
    pub c: [DVec3; 16],
}

impl BicubicSurface {
    /// From object-space control points `g[j·4 + i]` (RIB order, u fastest) and the bases.
    pub fn new(
        g: &[DVec3; 16],
        mu: &BasisMatrix,
        mv: &BasisMatrix,
        camera_from_object: &DMat4,
    ) -> BicubicSurface {
        let axis = |k: usize| power_coefficients(mu, mv, &std::array::from_fn(|n| g[n][k]));
        let (x, y, z) = (axis(0), axis(1), axis(2));
        let c = std::array::from_fn(|n| {
            let p = DVec3::new(x[n], y[n], z[n]);
            // Only the constant term is a position; the others are differences.
            if n == 15 {
                camera_from_object.transform_point3(p)
            } else {
                camera_from_object.transform_vector3(p)
            }
        });
        BicubicSurface { c }
    }
}

impl Surface for BicubicSurface {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        let uu = [u * u * u, u * u, u, 1.0];
        let vv = [v * v * v, v * v, v, 1.0];
        let du = [3.0 * u * u, 2.0 * u, 1.0, 0.0];
        let dv = [3.0 * v * v, 2.0 * v, 1.0, 0.0];
        let (mut p, mut pu, mut pv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for a in 0..4 {
            let row = |w: &[f64; 4]| {
                self.c[4 * a] * w[0]
                    + self.c[4 * a + 1] * w[1]
                    + self.c[4 * a + 2] * w[2]
                    + self.c[4 * a + 3] * w[3]
            };
            let (rv, rdv) = (row(&vv), row(&dv));
            p += rv * uu[a];
            pu += rv * du[a];
            pv += rdv * uu[a];
        }
        [p, pu, pv]
    }

    fn bound(&self, u: [f64; 2], v: [f64; 2]) -> Bound {
        let axis = |k: usize| bezier_of_range(&std::array::from_fn(|n| self.c[n][k]), u, v);
        let (x, y, z) = (axis(0), axis(1), axis(2));
        Bound::from_dpoints((0..16).map(|n| DVec3::new(x[n], y[n], z[n])))
    }
}

/// A bilinear patch in camera space, corners at `(0,0), (1,0), (0,1), (1,1)`. Also the piece
/// polygons are diced as (a triangle is the patch with its last two corners equal).
#[derive(Clone, Debug, PartialEq)]
pub struct BilinearSurface {
    pub p: [DVec3; 4],
}

impl Surface for BilinearSurface {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        let [a, b, c, d] = self.p;
        [
            (1.0 - v) * ((1.0 - u) * a + u * b) + v * ((1.0 - u) * c + u * d),
            (1.0 - v) * (b - a) + v * (d - c),
            (1.0 - u) * (c - a) + u * (d - b),
        ]
    }

    /// A bilinear patch lies in the hull of its corners, also over any sub-range.
    fn bound(&self, [u0, u1]: [f64; 2], [v0, v1]: [f64; 2]) -> Bound {
        Bound::from_dpoints(
            [(u0, v0), (u1, v0), (u0, v1), (u1, v1)].map(|(u, v)| self.eval(u, v)[0]),
        )
    }
}

/// Subpatch counts of one parametric direction of a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Direction {
    /// Control points.
    n: usize,
    periodic: bool,
    /// Control points a subpatch spans (2 or 4) and advances by.
    span: usize,
    step: usize,
    patches: usize,
    varying: usize,
}

impl Direction {
    fn new(
        request: &str,
        axis: &str,
        n: i32,
        wrap: &str,
        bicubic: bool,
        step: i32,
    ) -> Result<Direction, GeomError> {
        let invalid = |message: String| GeomError::Invalid {
            request: request.to_string(),
            message,
        };
        let periodic = match wrap {
            "periodic" => true,
            "nonperiodic" => false,
            _ => {
                return Err(invalid(format!(
                    "{axis}wrap must be \"periodic\" or \"nonperiodic\", found \"{wrap}\""
                )))
            }
        };
        let (span, step) = if bicubic { (4, step) } else { (2, 1) };
        if step < 1 {
            return Err(invalid(format!(
                "{axis}step must be at least 1, found {step}"
            )));
        }
        let (n, step) = (n.max(0) as usize, step as usize);
        let patches = match (periodic, n) {
            (true, n) if n >= 1 && n % step == 0 => n / step,
            (false, n) if n >= span && (n - span) % step == 0 => (n - span) / step + 1,
            _ => {
                return Err(invalid(format!(
                    "n{axis} = {n} does not make whole {} patches ({}, {axis}step {step})",
                    if bicubic { "bicubic" } else { "bilinear" },
                    if periodic {
                        "periodic: a multiple of the step"
                    } else {
                        "nonperiodic: 4 + k·step"
                    }
                )))
            }
        };
        let varying = if periodic { patches } else { patches + 1 };
        Ok(Direction {
            n,
            periodic,
            span,
            step,
            patches,
            varying,
        })
    }

    fn control(&self, patch: usize, k: usize) -> usize {
        (patch * self.step + k) % self.n
    }

    fn varying_index(&self, patch: usize, k: usize) -> usize {
        (patch + k) % self.varying
    }
}

/// The mesh's control points in object space from `P`, `Pw` (divided by w) or `Pz` (heights
/// over the evenly spaced unit square).
fn positions(
    request: &str,
    vars: &[PrimVar],
    u: &Direction,
    v: &Direction,
) -> Result<Vec<DVec3>, GeomError> {
    let find = |n: &str| vars.iter().find(|x| x.name == n);
    let pts: Vec<DVec3> = if let Some(p) = find("P") {
        p.floats()
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64))
            .collect()
    } else if let Some(p) = find("Pw") {
        p.floats()
            .chunks_exact(4)
            .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) / c[3] as f64)
            .collect()
    } else if let Some(p) = find("Pz") {
        let spacing = |d: &Direction| if d.periodic { d.n } else { d.n - 1 }.max(1) as f64;
        p.floats()
            .iter()
            .enumerate()
            .map(|(k, &z)| {
                DVec3::new(
                    (k % u.n) as f64 / spacing(u),
                    (k / u.n) as f64 / spacing(v),
                    z as f64,
                )
            })
            .collect()
    } else {
        return Err(GeomError::Invalid {
            request: request.to_string(),
            message: "needs \"P\", \"Pw\" or \"Pz\"".to_string(),
        });
    };
    if let Some(k) = pts.iter().position(|p| !p.is_finite()) {
        return Err(GeomError::Invalid {
            request: request.to_string(),
            message: format!("control point {k} is not finite: {}", pts[k]),
        });
    }
    Ok(pts)
}

/// Bicubic bases for a mesh: (u matrix, u step, v matrix, v step).
pub type Bases = (BasisMatrix, i32, BasisMatrix, i32);

/// A mesh's shape as the request gives it.
#[derive(Clone, Copy, Debug)]
pub struct MeshShape<'a> {
    pub bicubic: bool,
    pub nu: i32,
    pub uwrap: &'a str,
    pub nv: i32,
    pub vwrap: &'a str,
}

/// Builds `Patch` and `PatchMesh` requests (a `Patch` is a 2×2 or 4×4 nonperiodic mesh).
pub fn build_mesh(
    request: &str,
    shape: MeshShape,
    bases: &Bases,
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    let u = Direction::new(request, "u", shape.nu, shape.uwrap, shape.bicubic, bases.1)?;
    let v = Direction::new(request, "v", shape.nv, shape.vwrap, shape.bicubic, bases.3)?;
    let patches = u.patches * v.patches;
    let counts = ClassCounts {
        uniform: patches,
        varying: u.varying * v.varying,
        vertex: u.n * v.n,
        facevarying: patches.saturating_mul(4),
    };
    let vars = resolve(request, params, ctx.declarations, &counts, ctx.warnings)?;
    let pts = positions(request, &vars, &u, &v)?;
    let m = &ctx.camera_from_object;
    let mut out: Vec<Box<dyn Primitive>> = Vec::with_capacity(patches);
    for j in 0..v.patches {
        for i in 0..u.patches {
            let ctrl = |ku: usize, kv: usize| v.control(j, kv) * u.n + u.control(i, ku);
            let surface: Arc<dyn Surface> = if shape.bicubic {
                let g = std::array::from_fn(|n| pts[ctrl(n % 4, n / 4)]);
                Arc::new(BicubicSurface::new(&g, &bases.0, &bases.2, m))
            } else {
                let corner = |n: usize| m.transform_point3(pts[ctrl(n % 2, n / 2)]);
                Arc::new(BilinearSurface {
                    p: std::array::from_fn(corner),
                })
            };
            let svars = subpatch_vars(&vars, shape.bicubic, bases, (i, j), (&u, &v), m);
            let (nu, nv) = (u.patches as f64, v.patches as f64);
            let (i0, i1) = (i as f64 / nu, (i + 1) as f64 / nu);
            let (j0, j1) = (j as f64 / nv, (j + 1) as f64 / nv);
            let st = default_st(
                &ctx.texture_coordinates,
                [[i0, j0], [i1, j0], [i0, j1], [i1, j1]],
            );
            // u, v run over the whole mesh, as s, t do.
            out.push(Box::new(
                Parametric::new(surface, Arc::new(with_default_st(svars, st)))
                    .spanning([i0, i1], [j0, j1]),
            ));
        }
    }
    Ok(out)
}

/// The variables of subpatch `(i, j)`: each class picks its values as RI Spec 3.2 §5.2 says.
fn subpatch_vars(
    vars: &[PrimVar],
    bicubic: bool,
    bases: &Bases,
    (i, j): (usize, usize),
    (u, v): (&Direction, &Direction),
    m: &DMat4,
) -> Vec<SurfaceVar> {
    let corners = |index: &dyn Fn(usize, usize) -> usize, var: &PrimVar| {
        Interp::Bilinear([(0, 0), (1, 0), (0, 1), (1, 1)].map(|(a, b)| element64(var, index(a, b))))
    };
    surface_vars(vars, m, |var| match var.class {
        Class::Constant => Interp::Constant(element64(var, 0)),
        Class::Uniform => Interp::Constant(element64(var, j * u.patches + i)),
        Class::Varying => corners(
            &|a, b| v.varying_index(j, b) * u.varying + u.varying_index(i, a),
            var,
        ),
        Class::FaceVarying | Class::FaceVertex => {
            corners(&|a, b| 4 * (j * u.patches + i) + 2 * b + a, var)
        }
        Class::Vertex if !bicubic => corners(&|a, b| v.control(j, b) * u.n + u.control(i, a), var),
        Class::Vertex => {
            let size = var.element_size();
            Interp::Bicubic(
                (0..size)
                    .map(|k| {
                        let g = std::array::from_fn(|n| {
                            let idx = v.control(j, n / 4) * u.n + u.control(i, n % 4);
                            var.floats()[idx * size + k] as f64
                        });
                        power_coefficients(&bases.0, &bases.2, &g)
                    })
                    .collect(),
            )
        }
    })
}
