//! Object instances that share their definition (RI Spec 3.2 §5.6) instead of copying it.
//!
//! Replaying an object's requests at every `ObjectInstance` builds every primitive of the
//! object again, in camera space, and keeps them all until the frame renders: 10⁴ instances of
//! a 10³-sphere object are 10⁷ primitives in memory before the first bucket. When the object
//! is plain geometry under nested transformations, an instance is instead one
//! [`InstancePrimitive`]: the shared definition, the instance's transformation and attributes,
//! and the object's bound. The hider splits it like any aggregate when a bucket first needs
//! it, and only then are the object's primitives built, under exactly the matrices (the same
//! `CTM · T` products, in the same order) and attributes that replaying would have used, so
//! the pixels are those of the replayed instance.
//!
//! Objects that do anything else (attributes, motion, solids, procedurals, absolute
//! transformations, primitives whose shape depends on the instance's attributes such as a
//! patch's basis, or any request that warns or fails when built) are replayed as before.
use crate::attributes::Attributes;
use crate::declarations::Declarations;
use crate::state::Ri;
use glam::{DMat4, DVec3};
use illume_geom::{Bound, BuildContext, Grid, Primitive};
use illume_rib::{Request, Spanned};
use std::sync::Arc;

/// One step of a shareable object: the block structure and transformations that place its
/// primitives, with the geometry itself as an index into the recorded requests.
#[derive(Debug)]
enum Step {
    Push,
    Pop,
    Concat(DMat4),
    Geometry(usize),
}

/// An object definition that instances share (see the module documentation).
#[derive(Debug)]
pub(crate) struct SharedObject {
    requests: Arc<Vec<Spanned<Request>>>,
    steps: Vec<Step>,
    /// The declarations when the object was defined (its parameter lists were read under them).
    declarations: Arc<Declarations>,
    /// Object-space bound of every primitive, padded for rounding.
    lo: DVec3,
    hi: DVec3,
    /// A deferred mesh's bound, already in camera space (its faces' own bounds).
    camera_bound: Option<Bound>,
    /// Whether the object's own transformations mirror (all agree, or it is not shared).
    mirrors: bool,
    /// The largest vertex count one of its requests declares (for `Option "limits"`).
    pub(crate) vertices: u64,
}

/// Geometry whose primitives do not depend on the attributes in effect (a patch's basis, a
/// curve's basis and a blobby's dicing do), so one definition serves every instance.
fn shareable_geometry(req: &Request) -> bool {
    use Request::*;
    matches!(
        req,
        Polygon { .. }
            | GeneralPolygon { .. }
            | PointsPolygons { .. }
            | PointsGeneralPolygons { .. }
            | NuPatch { .. }
            | Sphere { .. }
            | Cone { .. }
            | Cylinder { .. }
            | Hyperboloid { .. }
            | Paraboloid { .. }
            | Disk { .. }
            | Torus { .. }
            | Points { .. }
            | SubdivisionMesh { .. }
    )
}

/// The relative transformation a request concatenates, `None` for anything else (absolute
/// transformations such as `Transform` or `CoordSysTransform` depend on the instance's world).
fn relative_transform(req: &Request) -> Option<DMat4> {
    use Request::*;
    match req {
        Translate(t) => Some(DMat4::from_translation(DVec3::from(t.map(f64::from)))),
        Rotate { angle, axis } => crate::transform::rotate(*angle, *axis),
        Scale(s) => Some(DMat4::from_scale(DVec3::from(s.map(f64::from)))),
        Skew(a) => crate::transform::skew(a).ok(),
        ConcatTransform(m) => Some(crate::transform::from_rib(m)),
        _ => None,
    }
}

impl Ri {
    /// The declarations, shared until the next `Declare` changes them.
    pub(crate) fn shared_declarations(&mut self) -> Arc<Declarations> {
        self.declarations_shared
            .get_or_insert_with(|| Arc::new(self.declarations.clone()))
            .clone()
    }
}

impl SharedObject {
    /// Analyses a recorded object; `None` when it must be replayed (see the module docs).
    /// Each primitive is built once here, in object space, for the bound and to be sure that
    /// building it later (where nothing can be reported) neither warns nor fails.
    pub(crate) fn analyse(ri: &mut Ri, requests: Arc<Vec<Spanned<Request>>>) -> Option<Self> {
        // The trial builds report into a scratch list: any word from them means "replay".
        let saved = std::mem::take(&mut ri.diagnostics);
        let shared = Self::trial(ri, requests);
        let quiet = ri.diagnostics.error_count() + ri.diagnostics.warning_count() == 0;
        ri.diagnostics = saved;
        shared.filter(|_| quiet)
    }

    fn trial(ri: &mut Ri, requests: Arc<Vec<Spanned<Request>>>) -> Option<Self> {
        let mut steps = Vec::with_capacity(requests.len());
        let mut stack = Vec::new();
        let mut m = DMat4::IDENTITY;
        let mut signs = (false, false);
        let mut bound = Bound::EMPTY;
        let mut vertices = 0u64;
        for (k, r) in requests.iter().enumerate() {
            use Request::*;
            match &r.value {
                AttributeBegin | TransformBegin => {
                    stack.push(m);
                    steps.push(Step::Push);
                }
                AttributeEnd | TransformEnd => {
                    m = stack.pop()?;
                    steps.push(Step::Pop);
                }
                StructureComment(_) => {}
                g if shareable_geometry(g) => {
                    let prims = ri.build_geometry(g, &r.span, m)?;
                    for p in &prims {
                        bound = bound.union(p.bound());
                    }
                    let rh = m.determinant() < 0.0;
                    signs = (signs.0 || rh, signs.1 || !rh);
                    vertices = vertices.max(crate::options::declared_vertices(g));
                    steps.push(Step::Geometry(k));
                }
                other => {
                    let t = relative_transform(other)?;
                    m *= t;
                    steps.push(Step::Concat(t));
                }
            }
        }
        if !stack.is_empty() || bound.is_empty() || (signs.0 && signs.1) {
            return None;
        }
        let (lo, hi) = (bound.min.as_dvec3(), bound.max.as_dvec3());
        let pad = (hi - lo).max_element() * 1e-4 + 1e-6;
        Some(SharedObject {
            requests,
            steps,
            declarations: ri.shared_declarations(),
            lo: lo - DVec3::splat(pad),
            hi: hi + DVec3::splat(pad),
            camera_bound: None,
            mirrors: signs.0,
            vertices,
        })
    }

    /// One geometry request, built at `camera_from_object` into `built` (reported on already):
    /// the mesh is kept as its request and built again when the hider splits it, instead of
    /// as its faces (a 32×32-quad `PointsPolygons` is 1024 polygons of about 1 KB each, 25
    /// times the request's numbers). Returns the deferred primitive, `None` when `built` is
    /// empty.
    pub(crate) fn deferred(
        ri: &mut Ri,
        request: Spanned<Request>,
        camera_from_object: DMat4,
        built: &[Box<dyn Primitive>],
    ) -> Option<InstancePrimitive> {
        let bound = built.iter().fold(Bound::EMPTY, |b, p| b.union(p.bound()));
        if bound.is_empty() {
            return None;
        }
        let object = SharedObject {
            requests: Arc::new(vec![request]),
            steps: vec![Step::Geometry(0)],
            declarations: ri.shared_declarations(),
            lo: bound.min.as_dvec3(),
            hi: bound.max.as_dvec3(),
            camera_bound: Some(bound),
            mirrors: false,
            vertices: 0,
        };
        Some(InstancePrimitive::new(
            Arc::new(object),
            camera_from_object,
            ri.attributes.clone(),
        ))
    }

    /// The camera-space bound of an instance placed by `camera_from_object`.
    pub(crate) fn bound_at(&self, camera_from_object: &DMat4) -> Bound {
        if let Some(b) = self.camera_bound {
            return b;
        }
        Bound::of_transformed_box(camera_from_object, self.lo, self.hi)
    }

    /// Whether an instance placed by `camera_from_object` has a mirrored object space.
    pub(crate) fn mirrored(&self, camera_from_object: &DMat4) -> bool {
        (camera_from_object.determinant() < 0.0) != self.mirrors
    }

    /// Builds every primitive of the object as replaying it under `camera_from_object` with
    /// `attributes` would.
    fn build(&self, camera_from_object: DMat4, a: &Attributes) -> Vec<Box<dyn Primitive>> {
        let lookup = |n: &str| self.declarations.get(n);
        let mut out = Vec::new();
        let mut stack = Vec::new();
        let mut m = camera_from_object;
        for step in &self.steps {
            match step {
                Step::Push => stack.push(m),
                Step::Pop => m = stack.pop().unwrap_or(camera_from_object),
                Step::Concat(t) => m *= *t,
                Step::Geometry(k) => {
                    let ctx = BuildContext {
                        camera_from_object: m,
                        declarations: &lookup,
                        basis: a.basis,
                        texture_coordinates: a.texture_coordinates,
                        trim_curves: a.trim_curves.clone(),
                        warnings: None,
                    };
                    // It built without a word when the object was defined.
                    if let Ok(p) = illume_geom::build(&self.requests[*k].value, &ctx) {
                        out.extend(p);
                    }
                }
            }
        }
        out
    }
}

/// One `ObjectInstance` of a [`SharedObject`] (or one deferred mesh): an aggregate the hider
/// splits into the object's primitives when it first needs them.
#[derive(Debug)]
pub struct InstancePrimitive {
    object: Arc<SharedObject>,
    camera_from_object: DMat4,
    attributes: Arc<Attributes>,
}

impl InstancePrimitive {
    pub(crate) fn new(
        object: Arc<SharedObject>,
        camera_from_object: DMat4,
        attributes: Arc<Attributes>,
    ) -> Self {
        InstancePrimitive {
            object,
            camera_from_object,
            attributes,
        }
    }
}

impl Primitive for InstancePrimitive {
    fn bound(&self) -> Bound {
        self.object.bound_at(&self.camera_from_object)
    }

    fn diceable(&self) -> bool {
        false
    }

    fn split(&self) -> Vec<Box<dyn Primitive>> {
        self.object.build(self.camera_from_object, &self.attributes)
    }

    /// Never called (not diceable); an empty grid rather than a panic.
    fn dice(&self, _nu: usize, _nv: usize) -> Grid {
        Grid::default()
    }
}
