//! Geometric primitives of the RenderMan Interface and the REYES operations on them:
//! **bound**, **split** and **dice** (Cook, Carpenter, Catmull 1987).
//!
//! # Contract with the hider (`illume-reyes`) and the RI state (`illume-ri`)
//! * `illume-ri` calls [`build`] with a geometry [`Request`] and a [`BuildContext`] (current
//!   transform, declarations, basis, texture coordinates). `build` resolves the parameter list
//!   into [`PrimVar`]s (checking counts per class against the primitive's topology — only geom
//!   knows how many uniform/varying/vertex values a primitive needs) and returns primitives.
//! * `illume-reyes` asks each [`Primitive`] for its camera-space [`Bound`], splits until it is
//!   [`Primitive::diceable`] at the size it measures, then calls [`Primitive::dice`].
//! * Everything a primitive hands out is in **camera space** (left-handed, +z forward).
//! * [`Grid::ng`] is `normalize(dPdu × dPdv)` as computed in camera space, never flipped:
//!   `Orientation`/`ReverseOrientation`/handedness flips are the hider's job (it knows the
//!   attributes). A user `N` is interpolated and transformed to camera space with the inverse
//!   transpose, into [`Grid::n`]; without one, `n == ng`.
//!
//! # What `build` returns
//! Every request builds a list of [`Parametric`] pieces (all diceable): one per quadric, one
//! per subpatch of a mesh (32 for the teapot), one per convex quad or ear-clipped triangle of a
//! polygon, one per non-empty knot rectangle of a NuPatch (all sharing one surface), one per
//! limit-mesh quad of a subdivision mesh, one disk per point, one ribbon per curve segment, one
//! isosurface triangle per marching-tetrahedra triangle of a Blobby. Their `(u, v)` run over `[0,1]²` of the piece's own surface; [`Grid::du`]/`dv` are
//! the steps in those units. Orientation of the raw `dPdu × dPdv`: outward for a quadric with
//! positive `thetamax` (inward when it is negative, as the u sweep reverses); along the
//! right-hand rule of the vertex order for polygons and of (u, v) for patches.
//!
//! # Numerics
//! Evaluation is analytic in f64 (quadrics in closed form, bicubic patches in power form,
//! bilinear pieces by interpolation), rounded to f32 only when stored in the [`Grid`]. Bounds
//! are conservative (quadrics: annular-sector boxes of the sub-range; bicubics: Bézier hull of
//! the sub-range) and padded by 1e-6 relative so every diced point lies inside.
#![forbid(unsafe_code)]

pub mod basis;
pub mod blobby;
pub mod blobby_field;
pub mod bound;
pub mod curves;
pub mod ear_clipping;
pub mod grid;
pub mod knots;
pub mod nupatch;
pub mod parametric;
pub mod patch;
pub mod points;
pub mod polygon;
pub mod polygonize;
pub mod primvar;
pub mod quadric;
pub mod subdivision;
pub mod teapot;
pub mod trimcurve;

pub use basis::basis_matrix;
pub use bound::Bound;
pub use grid::{Grid, GridVar};
pub use parametric::{Parametric, Surface};
pub use primvar::{ClassCounts, PrimVar, PrimVarData};
pub use trimcurve::{TrimCurveArgs, TrimCurves};

use glam::{DMat4, Vec3};
use illume_rib::{Declaration, Request};
use std::sync::Arc;
use thiserror::Error;

/// A piece of geometry the hider can bound, split and dice.
pub trait Primitive: Send + Sync + std::fmt::Debug {
    /// Camera-space bound of the surface (before displacement; the hider pads it).
    fn bound(&self) -> Bound;

    /// Whether [`Primitive::dice`] may be called. Aggregates (meshes, polygons with holes) say
    /// `false` until split into parametric pieces.
    fn diceable(&self) -> bool;

    /// Splits into smaller primitives that together cover exactly this one (parametric halves,
    /// mesh → faces, polygon → pieces). Never returns an empty list for a non-empty surface.
    fn split(&self) -> Vec<Box<dyn Primitive>>;

    /// Which way [`Primitive::split`] would cut this primitive, as an opaque tag. The motion
    /// keys of a deforming primitive must all be cut the same way (the hider interpolates their
    /// diced vertices one to one), so the hider asks the first key and cuts every key with
    /// [`Primitive::split_as`].
    fn split_choice(&self) -> u8 {
        0
    }

    /// Which way to cut a piece that crosses the eye plane ([`Primitive::split_choice`]'s
    /// tags): across its depth where the primitive can tell, so the parts in front of the eye
    /// separate from those behind it within the few eye splits allowed (a ground plane cut
    /// along its width instead ran out of eye splits and lost visible pieces).
    fn eye_split_choice(&self) -> u8 {
        self.split_choice()
    }

    /// [`Primitive::split`], cut the way `choice` (a [`Primitive::split_choice`] of a key of the
    /// same topology) says. Primitives whose split depends on topology only keep the default.
    fn split_as(&self, choice: u8) -> Vec<Box<dyn Primitive>> {
        let _ = choice;
        self.split()
    }

    /// Dices into a grid of `nu × nv` **vertices** (`nu, nv ≥ 2`), u varying fastest.
    /// Adjacent grids of one primitive share their edge vertices exactly (same parameter
    /// values evaluated the same way), so no crack opens between them.
    fn dice(&self, nu: usize, nv: usize) -> Grid;

    /// The vertex counts and positions of [`Primitive::dice`]`(nu, nv)`, bit for bit, and
    /// nothing else: what the hider's test dice (the dice rates) looks at. A primitive whose
    /// positions cost less on their own overrides it: a test dice of a parametric piece cost
    /// 26 000 instructions through `dice`, of which the normals, derivatives and variables
    /// the test never reads were two thirds.
    fn dice_positions(&self, nu: usize, nv: usize) -> (usize, usize, Vec<Vec3>) {
        let g = self.dice(nu, nv);
        (g.nu, g.nv, g.p)
    }

    /// The whole quadric this primitive is, with its camera-from-object transformation, for
    /// a ray tracer that intersects quadrics in closed form; `None` for anything else
    /// (including a piece of a quadric).
    fn quadric(&self) -> Option<(quadric::Shape, DMat4)> {
        None
    }
}

/// The graphics state `build` needs; everything else stays in `illume-ri`.
pub struct BuildContext<'a> {
    /// Object space → camera space, f64 (the current transformation matrix at the request).
    pub camera_from_object: DMat4,
    /// Looks up a variable name in the `Declare` table (including the spec's predeclared
    /// variables: P, Pz, Pw, N, Np, Cs, Os, s, t, st, …). Inline declarations in the parameter
    /// list take precedence.
    pub declarations: &'a dyn Fn(&str) -> Option<Declaration>,
    /// Current `Basis`: (u matrix, u step, v matrix, v step); matrices in RIB row order.
    pub basis: ([f32; 16], i32, [f32; 16], i32),
    /// Current `TextureCoordinates` s1 t1 s2 t2 s3 t3 s4 t4 (default 0 0 1 0 0 1 1 1).
    pub texture_coordinates: [f32; 8],
    /// Current `TrimCurve` loops (an attribute), applied to `NuPatch`.
    pub trim_curves: Option<Arc<TrimCurves>>,
    /// Where building reports what it repaired and carried on with (a primitive variable with
    /// the wrong number of values, cut to fit or dropped); `None` discards them.
    pub warnings: Option<&'a std::cell::RefCell<Vec<String>>>,
}

#[derive(Clone, Debug, PartialEq, Error)]
pub enum GeomError {
    /// A request this crate does not build (yet); `ri` warns once per kind and skips it.
    #[error("{0}: geometry not supported")]
    Unsupported(String),
    /// Wrong counts, bad indices, missing `P`, … with what was expected and found.
    #[error("{request}: {message}")]
    Invalid { request: String, message: String },
}

/// Builds the primitives of one geometry request. Non-geometry requests are a bug in the
/// caller and return [`GeomError::Unsupported`].
///
/// Built: the quadrics (Sphere, Cone, Cylinder, Hyperboloid, Paraboloid, Disk, Torus),
/// Polygon, GeneralPolygon, PointsPolygons, PointsGeneralPolygons (convex or not, with
/// holes), Patch and PatchMesh (bilinear, bicubic with `ctx.basis`), NuPatch (trimmed by
/// `ctx.trim_curves`), SubdivisionMesh "catmull-clark", Points, Curves (linear, cubic with the
/// v basis), `Geometry "teapot"`, Blobby (at [`blobby::DEFAULT_CELLS`]; `illume-ri` calls
/// [`blobby::build_blobby`] itself to size the lattice from the screen).
/// A zero-area surface (radius 0, `zmin == zmax`, `thetamax` 0) builds an empty list; a
/// non-finite parameter or transform is [`GeomError::Invalid`].
pub fn build(request: &Request, ctx: &BuildContext) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    if !ctx.camera_from_object.is_finite() {
        return Err(GeomError::Invalid {
            request: request.name().to_string(),
            message: "the current transformation is not finite".to_string(),
        });
    }
    match request {
        Request::Sphere { params, .. }
        | Request::Cone { params, .. }
        | Request::Cylinder { params, .. }
        | Request::Hyperboloid { params, .. }
        | Request::Paraboloid { params, .. }
        | Request::Disk { params, .. }
        | Request::Torus { params, .. } => quadric::build_quadric(request, params, ctx),
        Request::Polygon { .. }
        | Request::GeneralPolygon { .. }
        | Request::PointsPolygons { .. }
        | Request::PointsGeneralPolygons { .. } => polygon::build_polygons(request, ctx),
        Request::Patch { kind, params } => {
            let (bicubic, n) = patch_kind(request.name(), kind)?;
            let shape = patch::MeshShape {
                bicubic,
                nu: n,
                uwrap: "nonperiodic",
                nv: n,
                vwrap: "nonperiodic",
            };
            patch::build_mesh(request.name(), shape, &ctx.basis, params, ctx)
        }
        Request::PatchMesh {
            kind,
            nu,
            uwrap,
            nv,
            vwrap,
            params,
        } => {
            let (bicubic, _) = patch_kind(request.name(), kind)?;
            let shape = patch::MeshShape {
                bicubic,
                nu: *nu,
                uwrap,
                nv: *nv,
                vwrap,
            };
            patch::build_mesh(request.name(), shape, &ctx.basis, params, ctx)
        }
        Request::NuPatch {
            nu,
            uorder,
            uknot,
            umin,
            umax,
            nv,
            vorder,
            vknot,
            vmin,
            vmax,
            params,
        } => nupatch::build_nupatch(
            nupatch::NuPatchArgs {
                nu: *nu,
                uorder: *uorder,
                uknot,
                umin: *umin,
                umax: *umax,
                nv: *nv,
                vorder: *vorder,
                vknot,
                vmin: *vmin,
                vmax: *vmax,
            },
            params,
            ctx,
        ),
        Request::SubdivisionMesh {
            scheme,
            nvertices,
            vertices,
            tags,
            nargs,
            intargs,
            floatargs,
            params,
        } => subdivision::build_subdivision(
            subdivision::SubdivisionArgs {
                scheme,
                nvertices,
                vertices,
                tags,
                nargs,
                intargs,
                floatargs,
            },
            params,
            ctx,
        ),
        Request::Points { params } => points::build_points(params, ctx),
        Request::Curves {
            kind,
            nvertices,
            wrap,
            params,
        } => curves::build_curves(kind, nvertices, wrap, params, ctx),
        Request::Blobby {
            nleaf,
            code,
            floats,
            strings,
            params,
        } => blobby::build_blobby(
            &blobby::BlobbyArgs {
                nleaf: *nleaf,
                code,
                floats,
                strings,
            },
            params,
            ctx,
            &|_| blobby::DEFAULT_CELLS,
        )
        .map(|(prims, _warnings)| prims),
        Request::Geometry { kind, params } if kind == "teapot" => teapot::build_teapot(params, ctx),
        Request::Geometry { kind, .. } => {
            Err(GeomError::Unsupported(format!("Geometry \"{kind}\"")))
        }
        _ => Err(GeomError::Unsupported(request.name().to_string())),
    }
}

/// `"bilinear"` → (false, 2 control points per side), `"bicubic"` → (true, 4).
fn patch_kind(request: &str, kind: &str) -> Result<(bool, i32), GeomError> {
    match kind {
        "bilinear" => Ok((false, 2)),
        "bicubic" => Ok((true, 4)),
        _ => Err(GeomError::Invalid {
            request: request.to_string(),
            message: format!("type must be \"bilinear\" or \"bicubic\", found \"{kind}\""),
        }),
    }
}
