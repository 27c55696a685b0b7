//! Geometry requests (RI Spec 3.2 chapter 5) in the RI state: built under the current
//! transformation (at every key when it moves), culled by `DetailRange`, and queued with the
//! attributes they were made under for the frame.
use crate::frame::FramePrimitive;
use crate::instance::SharedObject;
use crate::motion::MotionKeys;
use crate::state::Ri;
use glam::{DMat4, DVec3};
use illume_geom::{BuildContext, GeomError};
use illume_rib::{Request, Span};

/// Requests that build into this many primitives or more (mesh faces) are kept as their
/// request until the hider needs them: their faces take about 25 times the request's numbers.
const DEFER_AT: usize = 16;

impl Ri {
    pub(crate) fn geometry(&mut self, req: &Request, span: &Span) {
        if !self.in_world() {
            self.diagnostics.error_kind(
                crate::ErrorKind::NotPrims,
                span,
                req.name(),
                "geometry is only valid inside WorldBegin/WorldEnd (ignored)",
            );
            return;
        }
        if !self.world_active || self.memory_exceeded || !self.detail_visible() {
            return;
        }
        if !crate::options::check_vertices(&self.options.limits, req, span, &mut self.diagnostics) {
            return;
        }
        if let Some(m) = &self.motion {
            // One key of a deforming primitive, built under the transform at its time.
            let ctm = match (m.times.get(m.geometry.len()), &self.ctm_motion) {
                (Some(&t), Some(mm)) => mm.at(t),
                _ => self.ctm,
            };
            let prims = self.build_geometry(req, span, ctm).unwrap_or_default();
            let bytes = crate::memory::request_bytes(req, prims.len());
            if !self.charge_memory(bytes, span, req.name()) {
                return;
            }
            let m = self.motion.as_mut().expect("checked above");
            m.first
                .get_or_insert((span.clone(), req.name().to_string()));
            m.geometry.push(prims);
            return;
        }
        match self.ctm_motion.clone() {
            None => {
                let prims = self.build_geometry(req, span, self.ctm).unwrap_or_default();
                // A deferred request is one primitive until the hider splits it (its faces
                // then live only while their band of buckets renders).
                let deferred = prims.len() >= DEFER_AT && self.open_solids.is_empty();
                let counted = if deferred { 1 } else { prims.len() };
                let bytes = crate::memory::request_bytes(req, counted);
                if !self.charge_memory(bytes, span, req.name()) {
                    return;
                }
                if deferred {
                    self.defer(req, span, &prims);
                    return;
                }
                self.push_primitives(vec![0.0], vec![prims], span, req.name());
            }
            Some(mm) => {
                // A moving transform (or camera): the primitive is built at every key.
                let mut keys = Vec::new();
                for m in &mm.mats {
                    match self.build_geometry(req, span, *m) {
                        Some(p) => keys.push(p),
                        None => return,
                    }
                }
                let n: usize = keys.iter().map(Vec::len).sum();
                if !self.charge_memory(crate::memory::request_bytes(req, n), span, req.name()) {
                    return;
                }
                self.push_primitives(mm.times.clone(), keys, span, req.name());
            }
        }
    }

    /// Keeps a request that built into many primitives as one deferred primitive (see
    /// [`SharedObject::deferred`]); its faces are built again, identically, when the hider
    /// splits it.
    fn defer(&mut self, req: &Request, span: &Span, built: &[Box<dyn illume_geom::Primitive>]) {
        let request = illume_rib::Spanned {
            span: span.clone(),
            value: req.clone(),
        };
        let Some(p) = SharedObject::deferred(self, request, self.ctm, built) else {
            return;
        };
        self.push_frame_primitive(FramePrimitive {
            primitive: Box::new(p),
            attributes: self.attributes.clone(),
            span: span.clone(),
            solid: None,
            motion: None,
            mirrored: self.current_is_rh(),
        });
    }

    /// Builds a geometry request under `camera_from_object`; `None` (reported) when it fails.
    pub(crate) fn build_geometry(
        &mut self,
        req: &Request,
        span: &Span,
        camera_from_object: DMat4,
    ) -> Option<Vec<Box<dyn illume_geom::Primitive>>> {
        let decls = &self.declarations;
        let lookup = |n: &str| decls.get(n);
        let a = &self.attributes;
        let mut blobby_warnings = Vec::new();
        let repaired = std::cell::RefCell::new(Vec::new());
        let ctx = BuildContext {
            camera_from_object,
            declarations: &lookup,
            basis: a.basis,
            texture_coordinates: a.texture_coordinates,
            trim_curves: a.trim_curves.clone(),
            warnings: Some(&repaired),
        };
        let built = match req {
            Request::Blobby {
                nleaf,
                code,
                floats,
                strings,
                params,
            } => {
                let args = illume_geom::blobby::BlobbyArgs {
                    nleaf: *nleaf,
                    code,
                    floats,
                    strings,
                };
                let rate = f64::from(a.shading_rate);
                let cells_for = |b: [f32; 6]| {
                    let extent = self
                        .raster_bound(&b, camera_from_object)
                        .map(|r| (r[1] - r[0]).max(r[3] - r[2]));
                    illume_geom::blobby::cells_for_raster_size(extent, rate)
                };
                illume_geom::blobby::build_blobby(&args, params, &ctx, &cells_for).map(
                    |(prims, warnings)| {
                        blobby_warnings = warnings;
                        prims
                    },
                )
            }
            _ => illume_geom::build(req, &ctx),
        };
        for w in repaired.into_inner().into_iter().chain(blobby_warnings) {
            self.diagnostics.warn(span, req.name(), w);
        }
        match built {
            Ok(prims) => Some(prims),
            Err(GeomError::Unsupported(what)) => {
                self.diagnostics.warn(
                    span,
                    req.name(),
                    format!("{what} not supported yet (skipped)"),
                );
                None
            }
            Err(GeomError::Invalid { message, .. }) => {
                self.diagnostics.error(span, req.name(), message);
                None
            }
        }
    }

    /// Adds the primitives of one request: `keys[k]` is what it built at `times[k]`. Keys of
    /// different topology (another primitive count) can not be interpolated: an error, and the
    /// first key is used.
    pub(crate) fn push_primitives(
        &mut self,
        times: Vec<f64>,
        keys: Vec<Vec<Box<dyn illume_geom::Primitive>>>,
        span: &Span,
        name: &str,
    ) {
        let mut keys = keys.into_iter();
        let Some(first) = keys.next() else { return };
        let mut later: Vec<Vec<Box<dyn illume_geom::Primitive>>> = keys.collect();
        if later.iter().any(|k| k.len() != first.len()) {
            self.diagnostics.error(
                span,
                name,
                "the motion keys differ in topology (not interpolated: the first key is used)",
            );
            later.clear();
        }
        let mut later: Vec<_> = later.into_iter().map(Vec::into_iter).collect();
        let solid = self.solid_leaf();
        let mirrored = self.current_is_rh();
        for p in first {
            let motion = (!later.is_empty()).then(|| MotionKeys {
                times: times.iter().map(|&t| t as f32).collect(),
                later: later
                    .iter_mut()
                    .map(|k| k.next().expect("same length checked"))
                    .collect(),
            });
            self.push_frame_primitive(FramePrimitive {
                primitive: p,
                attributes: self.attributes.clone(),
                span: span.clone(),
                solid,
                motion,
                mirrored,
            });
        }
    }

    /// Raster-space bound of an object-space box, for level of detail and delayed archives;
    /// `None` when the box reaches behind the eye (treated as "large and on screen").
    pub(crate) fn raster_bound(&self, b: &[f32; 6], camera_from_object: DMat4) -> Option<[f64; 4]> {
        let cam = self.camera.as_ref()?;
        let mut r = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for i in 0..8 {
            let p = DVec3::new(
                b[i & 1].into(),
                b[2 + ((i >> 1) & 1)].into(),
                b[4 + ((i >> 2) & 1)].into(),
            );
            let c = camera_from_object.transform_point3(p);
            if cam.is_perspective() && c.z <= cam.near {
                return None;
            }
            let q = cam.raster_from_camera(c)?;
            r = [r[0].min(q.x), r[1].max(q.x), r[2].min(q.y), r[3].max(q.y)];
        }
        Some(r)
    }

    /// `DetailRange` (RI Spec 3.2 §4.2.9) as a hard switch: the primitive is drawn when the
    /// raster area of the `Detail` bound lies in `[minvisible, maxvisible)`.
    pub(crate) fn detail_visible(&self) -> bool {
        let (Some((bound, m)), Some(range)) =
            (self.attributes.detail, self.attributes.detail_range)
        else {
            return true;
        };
        let area = match self.raster_bound(&bound, m) {
            Some(r) => (r[1] - r[0]) * (r[3] - r[2]),
            None => f64::INFINITY,
        };
        area >= f64::from(range[0]) && area < f64::from(range[3])
    }
}
