//! `Blobby` (RI Spec 3.2 §5.6): an implicit surface, the level set of the field that
//! [`BlobbyField`] decodes, turned into pieces the hider dices like any surface.
//!
//! # Pipeline
//! 1. The field's object-space bound (the union of its leaves' regions of influence) is cut
//!    into a lattice of cubic cells, `cells` along its longest side; `illume-ri` chooses
//!    `cells` from the bound's raster size and the ShadingRate ([`cells_for_raster_size`]).
//! 2. Marching tetrahedra ([`crate::polygonize`]) gives triangles whose vertices lie on the
//!    exact isosurface (root found along each lattice edge).
//! 3. Each triangle becomes a [`Parametric`] piece over a [`BlobTriangle`]: a point of the flat
//!    triangle is moved along its interpolated normal onto the isosurface (root finding again),
//!    so every *diced* vertex lies on the true surface and the hider's dice rates, not the
//!    lattice, decide micropolygon size. Shading normals are the field gradient there, and
//!    varying values are blended by the leaves' fields there.
//!
//! Why a lattice and not an adaptive octree: the lattice only has to resolve the topology
//! (the dicing puts the vertices on the surface), a few cells per blob suffice for that, and a
//! uniform lattice of marching tetrahedra is crack-free by construction, which an octree of
//! mixed cell sizes is not without stitching.
//!
//! A lattice cell is `CELL_PIXELS` (16) pixels at ShadingRate 1. Since dicing puts every
//! vertex on the surface, the lattice only has to get the topology right, and coarse cells
//! keep the piece count (and the hider's per-piece cost) low: 4-pixel cells made 218k pieces
//! of ~4 micropolygons for rib/blobby.rib and spent 57 s splitting them. Features thinner
//! than a cell (a bridge just closing) can be missed; a field that is above the threshold
//! far from every leaf (a large constant) is cut at the bound.
use crate::blobby_field::{BlobbyField, THRESHOLD};
use crate::parametric::{
    default_st, with_default_st, Field, FieldRef, Interp, Parametric, Surface, SurfaceVar,
};
use crate::polygonize::{marching_tetrahedra, Lattice, TriangleMesh};
use crate::primvar::{camera_values, is_position, resolve, ClassCounts, PrimVarData};
use crate::{Bound, BuildContext, GeomError, Primitive};
use glam::{DMat3, DMat4, DVec3};
use illume_rib::{Class, ParamList, Type};
use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::Arc;

/// Lattice cell size in pixels at ShadingRate 1 (it scales with √ShadingRate).
pub const CELL_PIXELS: f64 = 16.0;
/// Lattice resolution limits along the longest side of the bound.
pub const MIN_CELLS: usize = 16;
pub const MAX_CELLS: usize = 128;
/// Resolution when the raster size is unknown (`geom::build` without a camera).
pub const DEFAULT_CELLS: usize = 48;

/// The pieces of a built `Blobby` and its warnings (parts not supported).
pub type Built = (Vec<Box<dyn Primitive>>, Vec<String>);

/// The raw arguments of a `Blobby` request.
pub struct BlobbyArgs<'a> {
    pub nleaf: i32,
    pub code: &'a [i32],
    pub floats: &'a [f32],
    pub strings: &'a [String],
}

/// Lattice cells along the bound's longest side for a bound `raster_extent` pixels long at
/// `shading_rate` (`None`: the bound reaches behind the eye): cells of `CELL_PIXELS·√rate`.
pub fn cells_for_raster_size(raster_extent: Option<f64>, shading_rate: f64) -> usize {
    match raster_extent {
        Some(l) if l.is_finite() => {
            let cell = CELL_PIXELS * shading_rate.max(1e-3).sqrt();
            ((l / cell).ceil() as usize).clamp(MIN_CELLS, MAX_CELLS)
        }
        _ => MAX_CELLS,
    }
}

/// Builds a `Blobby`. `cells_for` maps the object-space bound `[x0 x1 y0 y1 z0 z1]` of the
/// field to the lattice resolution. Returns the pieces and any warnings (unsupported parts).
pub fn build_blobby(
    args: &BlobbyArgs,
    params: &ParamList,
    ctx: &BuildContext,
    cells_for: &dyn Fn([f32; 6]) -> usize,
) -> Result<Built, GeomError> {
    let invalid = |message: String| GeomError::Invalid {
        request: "Blobby".to_string(),
        message,
    };
    let field =
        BlobbyField::decode(args.nleaf, args.code, args.floats, args.strings).map_err(invalid)?;
    let nleaf = field.leaves.len();
    let counts = ClassCounts {
        uniform: 1,
        varying: nleaf,
        vertex: nleaf,
        facevarying: nleaf,
    };
    let vars = resolve("Blobby", params, ctx.declarations, &counts, ctx.warnings)?;
    let mut warnings = Vec::new();
    if field.has_repeller() {
        warnings.push(
            "repelling planes (opcode 1003) are not supported: they add no field".to_string(),
        );
    }
    let Some((lo, hi)) = field.influence_box() else {
        return Ok((Vec::new(), warnings));
    };
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(invalid("the bound of the leaves is not finite".to_string()));
    }
    let cells = cells_for([lo.x, hi.x, lo.y, hi.y, lo.z, hi.z].map(|x| x as f32));
    let field = Arc::new(field);
    let Some((mesh, h)) = isosurface_mesh(&field, cells) else {
        return Ok((Vec::new(), warnings));
    };

    let m = ctx.camera_from_object;
    let user = user_vars(&vars, &m, nleaf);
    let shared = Arc::new(Shared {
        field,
        camera_from_object: m,
        // Signed like the camera-space `dPdu × dPdv` of the triangles (a mirroring transform
        // reverses their winding), so the hider's orientation flip treats both alike.
        normal_to_camera: DMat3::from_mat4(m).inverse().transpose() * m.determinant().signum(),
        reach: h,
        blend: user
            .iter()
            .any(|u| matches!(u.values, UserValues::PerLeaf(_))),
    });
    let outward = |p: DVec3| -> DVec3 {
        let (_, g) = shared.field.eval(p, None);
        (-g).try_normalize().unwrap_or(DVec3::Z)
    };
    let normals: Vec<DVec3> = mesh.positions.iter().map(|&p| outward(p)).collect();
    let st = default_st(
        &ctx.texture_coordinates,
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
    );
    let mut out: Vec<Box<dyn Primitive>> = Vec::with_capacity(mesh.triangles.len());
    for t in &mesh.triangles {
        let tri = Arc::new(BlobTriangle {
            id: NEXT_TRIANGLE.fetch_add(1, Relaxed),
            shared: shared.clone(),
            p: t.map(|i| mesh.positions[i as usize]),
            n: t.map(|i| normals[i as usize]),
        });
        let mut svars = vec![SurfaceVar {
            name: crate::grid::SMOOTH_N.to_string(),
            ty: Type::Normal,
            components: 3,
            interp: Interp::Field(FieldRef(Arc::new(TriangleVar {
                tri: tri.clone(),
                what: VarKind::Normal,
            }))),
        }];
        for u in &user {
            svars.push(SurfaceVar {
                name: u.name.clone(),
                ty: u.ty,
                components: u.components,
                interp: match &u.values {
                    UserValues::Constant(c) => Interp::Constant(c.clone()),
                    UserValues::PerLeaf(v) => Interp::Field(FieldRef(Arc::new(TriangleVar {
                        tri: tri.clone(),
                        what: VarKind::Blend {
                            values: v.clone(),
                            components: u.components,
                        },
                    }))),
                },
            });
        }
        out.push(Box::new(Parametric::new(
            tri,
            Arc::new(with_default_st(svars, st.clone())),
        )));
    }
    Ok((out, warnings))
}

/// The object-space marching-tetrahedra mesh of `field = THRESHOLD` on a lattice of `cells`
/// cells along the longest side of the influence box (plus one cell of margin all round, so
/// the surface never touches the lattice boundary), with the cell size; `None` without a
/// geometric leaf or for an empty bound.
pub fn isosurface_mesh(field: &Arc<BlobbyField>, cells: usize) -> Option<(TriangleMesh, f64)> {
    let (lo, hi) = field.influence_box()?;
    let extent = (hi - lo).max_element();
    if !(extent > 0.0 && extent.is_finite()) {
        return None;
    }
    let h = extent / cells.clamp(1, MAX_CELLS) as f64;
    let n = ((hi - lo) / h).ceil().to_array().map(|c| c as usize + 3);
    let lattice = Lattice {
        origin: lo - DVec3::splat(h),
        h,
        n,
    };
    let f = field.clone();
    Some((
        marching_tetrahedra(&lattice, &move |p| f.value(p), THRESHOLD),
        h,
    ))
}

/// A user primitive variable, in camera space.
struct UserVar {
    name: String,
    ty: Type,
    components: usize,
    values: UserValues,
}

enum UserValues {
    Constant(Vec<f64>),
    /// One value per leaf, blended by the leaves' fields.
    PerLeaf(Arc<Vec<f64>>),
}

fn user_vars(vars: &[crate::PrimVar], m: &DMat4, nleaf: usize) -> Vec<UserVar> {
    vars.iter()
        .filter(|v| !is_position(v) && v.name != "N" && matches!(v.data, PrimVarData::Floats(_)))
        .map(|v| {
            let values = camera_values(v, m);
            let components = v.element_size();
            UserVar {
                name: v.name.clone(),
                ty: v.ty,
                components,
                values: if matches!(v.class, Class::Constant | Class::Uniform) || nleaf == 0 {
                    UserValues::Constant(values[..components].to_vec())
                } else {
                    UserValues::PerLeaf(Arc::new(values))
                },
            }
        })
        .collect()
}

/// What every triangle of one blobby shares.
#[derive(Debug)]
struct Shared {
    field: Arc<BlobbyField>,
    camera_from_object: DMat4,
    /// Object-space normals to camera space, times the sign of the determinant: the smooth
    /// normal is a default `N`, oriented like `dPdu × dPdv`.
    normal_to_camera: DMat3,
    /// How far (object space) a point may move onto the isosurface: one lattice cell (half a
    /// cell missed the groove of a `max` union on a 16-cell lattice). The
    /// bound is padded by it, so it is conservative by construction.
    reach: f64,
    /// Whether some primitive variable is blended per leaf (the grid memo then keeps the
    /// leaves' field values too).
    blend: bool,
}

/// One marching-tetrahedra triangle, its corners on the isosurface with their outward field
/// normals (object space). `(u, v)` map to the flat triangle as a bilinear patch with corners
/// `p0, p1, p2, p2`, and each point is then projected onto the isosurface.
#[derive(Debug)]
pub struct BlobTriangle {
    /// Unique among the triangles of the process: names it in the [`GridMemo`].
    id: u64,
    shared: Arc<Shared>,
    p: [DVec3; 3],
    n: [DVec3; 3],
}

impl BlobTriangle {
    fn flat(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3, DVec3) {
        let [a, b, c] = self.p;
        let [na, nb, nc] = self.n;
        let edge = a + (b - a) * u;
        let p = edge + (c - edge) * v;
        let n = (na + (nb - na) * u) * (1.0 - v) + nc * v;
        (p, n, (b - a) * (1.0 - v), c - edge)
    }

    /// The object-space point of `(u, v)` on the isosurface and the flat derivatives.
    ///
    /// The projection runs along the interpolated vertex normal. Where that finds no surface
    /// within reach (a triangle spanning the crease of a `max` union, whose vertex normals
    /// point away from each other), it tries the flat triangle's normal, then the field
    /// gradient at the point. Those fallbacks depend on the triangle, so at such creases two
    /// neighbours may place a shared edge point differently (a crack the width of the crease
    /// error); elsewhere edge points depend on the edge's end points only.
    pub fn surface_point(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let (p0, n, dpdu, dpdv) = self.flat(u, v);
        let [a, b, c] = self.p;
        let flat_normal = (b - a).cross(c - a);
        // The field gradient only when both normals fail (it costs a field evaluation).
        let gradient = || -self.shared.field.eval(p0, None).1;
        let directions = [n, flat_normal]
            .into_iter()
            .chain(std::iter::once_with(gradient));
        for d in directions {
            if let Some(p) = d.try_normalize().and_then(|d| self.project(p0, d)) {
                return (p, dpdu, dpdv);
            }
        }
        (p0, dpdu, dpdv)
    }

    /// Moves `p0` along `d` onto the isosurface within ±`reach`; `None` without a bracket.
    /// Safeguarded Newton on `g(t) = field(p0 + t·d) − ½` (the gradient comes with the value):
    /// a Newton step that leaves the bracket is replaced by bisection.
    fn project(&self, p0: DVec3, d: DVec3) -> Option<DVec3> {
        let f = &self.shared.field;
        let g = |t: f64| {
            let (v, grad) = f.eval(p0 + d * t, None);
            (v - THRESHOLD, grad.dot(d))
        };
        let (g0, dg0) = g(0.0);
        if g0 == 0.0 {
            return Some(p0);
        }
        // Outward along d the field falls: search forward from inside, backward from outside.
        let r = if g0 > 0.0 {
            self.shared.reach
        } else {
            -self.shared.reach
        };
        // The first crossing: steps doubling from twice the Newton distance to `reach`. Near a
        // concave crease the outside is a thin wedge, which a fixed step jumps over.
        let newton = (g0 / dg0).abs();
        let mut step = if newton.is_finite() && newton > 0.0 {
            (2.0 * newton).clamp(r.abs() / 4096.0, r.abs())
        } else {
            r.abs() / 8.0
        };
        let mut bracket = None;
        let mut prev = (0.0, g0, dg0);
        loop {
            let tk = step.min(r.abs()) * r.signum();
            let (gk, dgk) = g(tk);
            if (gk > 0.0) != (g0 > 0.0) || gk == 0.0 {
                bracket = Some((prev, tk));
                break;
            }
            if step >= r.abs() {
                break;
            }
            prev = (tk, gk, dgk);
            step *= 2.0;
        }
        let ((t, gt, dgt), t_far) = bracket?;
        // Bracket [inside, outside] in t: g(inside) > 0 ≥ g(outside).
        let (mut t_in, mut t_out) = if g0 > 0.0 { (t, t_far) } else { (t_far, t) };
        let (mut t, mut gt, mut dgt) = (t, gt, dgt);
        // A step that did not halve |g| is followed by a bisection, so a Newton ping-pong at a
        // max/min crease still converges. (Bisecting every third step instead undid the
        // converging Newton steps on the smooth surface: 13 field evaluations per point.)
        let mut bisect = false;
        for _ in 0..100 {
            let newton = t - gt / dgt;
            let (a, b) = (t_in.min(t_out), t_in.max(t_out));
            let next = if !bisect && dgt != 0.0 && newton > a && newton < b {
                newton
            } else {
                0.5 * (t_in + t_out)
            };
            let done = (next - t).abs() <= 1e-14 * self.shared.reach;
            let before = gt.abs();
            t = next;
            (gt, dgt) = g(t);
            if gt > 0.0 {
                t_in = t;
            } else {
                t_out = t;
            }
            bisect = gt.abs() > 0.5 * before;
            if done || gt == 0.0 || (t_in - t_out).abs() <= 1e-15 * self.shared.reach {
                break;
            }
        }
        Some(p0 + d * t)
    }
}

impl BlobTriangle {
    /// The field gradient at the isosurface point of `(u, v)` ([`BlobTriangle::surface_point`])
    /// and, when `leaves` is given, each leaf's field there; and the camera-space
    /// `(P, dP/du, dP/dv)` of [`Surface::eval`].
    fn on_surface(&self, u: f64, v: f64, leaves: Option<&mut Vec<f64>>) -> (DVec3, [DVec3; 3]) {
        let (p, dpdu, dpdv) = self.surface_point(u, v);
        let (_, gradient) = self.shared.field.eval(p, leaves);
        // Tangent to the isosurface: the flat derivatives with their normal part removed.
        let (dpdu, dpdv) = match (-gradient).try_normalize() {
            Some(n) => (dpdu - n * n.dot(dpdu), dpdv - n * n.dot(dpdv)),
            None => (dpdu, dpdv),
        };
        let m = &self.shared.camera_from_object;
        let camera = [
            m.transform_point3(p),
            m.transform_vector3(dpdu),
            m.transform_vector3(dpdv),
        ];
        (gradient, camera)
    }
}

impl Surface for BlobTriangle {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        self.on_surface(u, v, None).1
    }

    /// [`Surface::eval`] at every point, remembered in this thread's [`GridMemo`] for the
    /// primitive variables that `dice` evaluates next at the same points.
    fn eval_grid(&self, us: &[f64], vs: &[f64], out: &mut Vec<[DVec3; 3]>) {
        GRID_MEMO.with(|memo| {
            let mut memo = memo.borrow_mut();
            let GridMemo {
                triangle,
                us: mus,
                vs: mvs,
                gradients,
                leaves,
                nleaf,
            } = &mut *memo;
            *triangle = None;
            mus.clear();
            mus.extend_from_slice(us);
            mvs.clear();
            mvs.extend_from_slice(vs);
            gradients.clear();
            leaves.clear();
            out.reserve(us.len() * vs.len());
            let mut leaf = Vec::new();
            for &v in vs {
                for &u in us {
                    let blend = self.shared.blend.then_some(&mut leaf);
                    let (gradient, camera) = self.on_surface(u, v, blend);
                    gradients.push(gradient);
                    leaves.extend_from_slice(&leaf);
                    out.push(camera);
                }
            }
            *nleaf = leaf.len();
            *triangle = Some(self.id);
        });
    }

    fn bound(&self, u: [f64; 2], v: [f64; 2]) -> Bound {
        let corners = [(u[0], v[0]), (u[1], v[0]), (u[0], v[1]), (u[1], v[1])]
            .map(|(u, v)| self.flat(u, v).0);
        let pad = DVec3::splat(self.shared.reach);
        let lo = corners.iter().fold(DVec3::INFINITY, |a, &p| a.min(p)) - pad;
        let hi = corners.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p)) + pad;
        Bound::of_transformed_box(&self.shared.camera_from_object, lo, hi)
    }
}

#[derive(Debug)]
enum VarKind {
    /// The outward field gradient, as a camera-space normal.
    Normal,
    /// Per-leaf camera-space values blended by the leaves' fields.
    Blend {
        values: Arc<Vec<f64>>,
        components: usize,
    },
}

/// A primitive variable evaluated at the projected point of a [`BlobTriangle`].
#[derive(Debug)]
struct TriangleVar {
    tri: Arc<BlobTriangle>,
    what: VarKind,
}

impl Field for TriangleVar {
    fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) {
        let shared = &self.tri.shared;
        let mut leaf = Vec::new();
        let blend = matches!(self.what, VarKind::Blend { .. });
        let remembered = GRID_MEMO.with(|m| m.borrow().find(self.tri.id, u, v, &mut leaf));
        let gradient = remembered.unwrap_or_else(|| {
            let leaves = blend.then_some(&mut leaf);
            self.tri.on_surface(u, v, leaves).0
        });
        match &self.what {
            VarKind::Normal => {
                let n = (-gradient)
                    .try_normalize()
                    .unwrap_or_else(|| self.tri.flat(u, v).1);
                let c = shared.normal_to_camera * n;
                out.copy_from_slice(&c.to_array()[..out.len().min(3)]);
            }
            VarKind::Blend { values, components } => {
                let w = BlobbyField::blend_weights(&leaf);
                out.fill(0.0);
                for (k, wk) in w.iter().enumerate() {
                    for (c, o) in out.iter_mut().enumerate().take(*components) {
                        *o += wk * values[k * components + c];
                    }
                }
            }
        }
    }
}

/// The source of [`BlobTriangle::id`].
static NEXT_TRIANGLE: AtomicU64 = AtomicU64::new(0);

/// What the primitive variables need of the last grid a [`BlobTriangle`] evaluated on this
/// thread ([`Surface::eval_grid`]). `dice` evaluates a grid's positions, then each primitive
/// variable at the same parameters; each needs the field at the point on the isosurface (a
/// root find of several field evaluations), which was found three times per vertex with a
/// smooth normal and a blended `Cs` (`rib/blobby.rib`). The remembered values are the ones
/// found again, bit for bit; a lookup for another triangle or parameter finds nothing and
/// computes.
#[derive(Default)]
struct GridMemo {
    triangle: Option<u64>,
    us: Vec<f64>,
    vs: Vec<f64>,
    /// The field gradient per point, row by row.
    gradients: Vec<DVec3>,
    /// `nleaf` field values per point when the blobby blends a variable (else empty).
    leaves: Vec<f64>,
    nleaf: usize,
}

thread_local! {
    static GRID_MEMO: RefCell<GridMemo> = RefCell::default();
}

impl GridMemo {
    /// The gradient remembered for triangle `id` at `(u, v)`, with its leaves' fields (when
    /// remembered) in `leaf`.
    fn find(&self, id: u64, u: f64, v: f64, leaf: &mut Vec<f64>) -> Option<DVec3> {
        if self.triangle != Some(id) {
            return None;
        }
        let i = self.us.iter().position(|x| x.to_bits() == u.to_bits())?;
        let j = self.vs.iter().position(|x| x.to_bits() == v.to_bits())?;
        let k = j * self.us.len() + i;
        leaf.clear();
        leaf.extend_from_slice(self.leaves.get(k * self.nleaf..(k + 1) * self.nleaf)?);
        self.gradients.get(k).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_memo_answers_only_for_its_triangle_and_parameters() {
        let (us, vs) = (vec![0.0, 0.5, 1.0], vec![0.25, 0.75]);
        let memo = GridMemo {
            triangle: Some(7),
            us: us.clone(),
            vs: vs.clone(),
            gradients: (0..6).map(|k| DVec3::splat(f64::from(k))).collect(),
            leaves: (0..12).map(f64::from).collect(),
            nleaf: 2,
        };
        let mut leaf = Vec::new();
        // Row by row, u fastest: (u 1.0, v 0.75) is point 5, its leaves 10 and 11.
        assert_eq!(memo.find(7, 1.0, 0.75, &mut leaf), Some(DVec3::splat(5.0)));
        assert_eq!(leaf, [10.0, 11.0]);
        assert_eq!(memo.find(7, 0.5, 0.25, &mut leaf), Some(DVec3::splat(1.0)));
        assert_eq!(leaf, [2.0, 3.0]);
        assert_eq!(memo.find(8, 0.5, 0.25, &mut leaf), None, "another triangle");
        assert_eq!(memo.find(7, 0.4, 0.25, &mut leaf), None, "a u off the grid");
        assert_eq!(memo.find(7, 0.5, -0.0, &mut leaf), None, "a v off the grid");
        let empty = GridMemo::default();
        assert_eq!(empty.find(0, 0.0, 0.25, &mut leaf), None);
    }
}
