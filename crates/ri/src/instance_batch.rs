//! Runs of object instances kept as one frame primitive (issue 23: 10⁷ instances in bounded
//! memory).
//!
//! A shared instance ([`InstancePrimitive`]) is small, but as one [`FramePrimitive`] each it
//! still costs about 300 bytes (the frame's entry, its span, the boxed instance with its
//! matrix) and one refine item per instance before the first bucket: 10⁷ instances were 3.1
//! GB before the hider started. Consecutive `ObjectInstance`s of the same object under the
//! same attributes (the usual way a scatter of copies is written: `TransformBegin`, a
//! placement, `ObjectInstance`, `TransformEnd`) are instead gathered into one
//! [`InstanceBatch`] that keeps only each placement's matrix (96 bytes, an affine f64 matrix).
//!
//! The hider splits a batch like any aggregate: into at most [`FANOUT`] batches of contiguous
//! placements, each with the bound of its own placements, and a batch of a few placements into
//! one [`InstancePrimitive`] each, built with the very matrix the placement had. So a batch
//! whose part of the screen is not reached yet waits, as one item, for its band of buckets
//! (`lazy_bands.rs`), and only the instances of the band being rendered exist at once. The
//! children keep the placements' order, so the hider's depth-first refine order (which breaks
//! depth ties between samples) is the order the instances were given in, and the pixels are
//! those of one primitive per instance (checked bit for bit in `tests/big_scenes.rs`).
//!
//! What differs from one primitive per instance: the frame counts one primitive per batch,
//! and a hider warning about an instance (a piece dropped at the eye plane) names the first
//! `ObjectInstance` of its run.
use crate::attributes::Attributes;
use crate::frame::FramePrimitive;
use crate::instance::{InstancePrimitive, SharedObject};
use crate::state::Ri;
use glam::{DAffine3, DMat4, DVec4};
use illume_geom::{Bound, Grid, Primitive};
use illume_rib::Span;
use std::sync::Arc;

/// Children of one split: a 10⁷-instance batch is split 6 levels deep before its instances.
pub const FANOUT: usize = 16;

/// Instances gathered while the world is read, not yet a frame primitive.
pub(crate) struct InstanceRun {
    object: Arc<SharedObject>,
    attributes: Arc<Attributes>,
    mirrored: bool,
    /// The first `ObjectInstance` of the run (what a batch's warnings name).
    span: Span,
    placements: Vec<DAffine3>,
    bound: Bound,
}

/// The matrix as an affine one when it is exactly affine (its last row is 0 0 0 1), so that
/// turning it back into a `DMat4` gives the same numbers.
fn affine(m: &DMat4) -> Option<DAffine3> {
    (m.row(3) == DVec4::W).then(|| DAffine3::from_mat4(*m))
}

impl Ri {
    /// Adds one shared instance at the current transformation to the open run, or starts a
    /// new run (pushing the open one to the frame) when the object, the attributes or the
    /// handedness differ or the matrix is not affine.
    /// The frame's memory estimate is charged a placement for an instance that joins a run,
    /// a whole frame primitive for one that does not (`memory.rs`).
    pub(crate) fn add_instance(&mut self, object: &Arc<SharedObject>, span: &Span) {
        let mirrored = object.mirrored(&self.ctm);
        let placement = affine(&self.ctm);
        let joins = placement.is_some()
            && self.instance_run.as_ref().is_some_and(|run| {
                Arc::ptr_eq(&run.object, object)
                    && Arc::ptr_eq(&run.attributes, &self.attributes)
                    && run.mirrored == mirrored
                    && run.placements.len() < u32::MAX as usize
            });
        let bytes = if joins {
            crate::memory::PER_PLACEMENT
        } else {
            crate::memory::PER_PRIMITIVE
        };
        if !self.charge_memory(bytes, span, "ObjectInstance") {
            return;
        }
        let Some(placement) = placement else {
            let primitive =
                InstancePrimitive::new(object.clone(), self.ctm, self.attributes.clone());
            self.push_frame_primitive(FramePrimitive {
                primitive: Box::new(primitive),
                attributes: self.attributes.clone(),
                span: span.clone(),
                solid: None,
                motion: None,
                mirrored,
            });
            return;
        };
        let bound = object.bound_at(&self.ctm);
        if let Some(run) = self.instance_run.as_mut().filter(|_| joins) {
            run.placements.push(placement);
            run.bound = run.bound.union(bound);
            return;
        }
        self.end_instance_run();
        self.instance_run = Some(InstanceRun {
            object: object.clone(),
            attributes: self.attributes.clone(),
            mirrored,
            span: span.clone(),
            placements: vec![placement],
            bound,
        });
    }

    /// Pushes the open run of instances to the frame: one instance as itself, more as one
    /// [`InstanceBatch`].
    pub(crate) fn end_instance_run(&mut self) {
        let Some(run) = self.instance_run.take() else {
            return;
        };
        let primitive: Box<dyn Primitive> = if let [one] = run.placements[..] {
            Box::new(InstancePrimitive::new(
                run.object,
                DMat4::from(one),
                run.attributes.clone(),
            ))
        } else {
            let mut placements = run.placements;
            placements.shrink_to_fit();
            let end = placements.len() as u32;
            Box::new(InstanceBatch {
                object: run.object,
                attributes: run.attributes.clone(),
                placements: Arc::new(placements),
                start: 0,
                end,
                bound: run.bound,
            })
        };
        self.primitives.push(FramePrimitive {
            primitive,
            attributes: run.attributes,
            span: run.span,
            solid: None,
            motion: None,
            mirrored: run.mirrored,
        });
    }

    /// Adds a frame primitive after the open run of instances (keeping the request order).
    pub(crate) fn push_frame_primitive(&mut self, fp: FramePrimitive) {
        self.end_instance_run();
        self.primitives.push(fp);
    }
}

/// Contiguous placements of one shared object under one set of attributes: an aggregate the
/// hider splits into smaller batches and then into the instances (see the module docs).
pub struct InstanceBatch {
    object: Arc<SharedObject>,
    attributes: Arc<Attributes>,
    /// Every placement of the run (shared by all the batches split from it).
    placements: Arc<Vec<DAffine3>>,
    /// This batch's placements: `placements[start..end]`.
    start: u32,
    end: u32,
    /// The union of its instances' bounds.
    bound: Bound,
}

impl std::fmt::Debug for InstanceBatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InstanceBatch")
            .field("instances", &(self.end - self.start))
            .field("bound", &self.bound)
            .finish()
    }
}

impl InstanceBatch {
    /// The placements `start..end` as a batch of their own.
    fn part(&self, start: u32, end: u32) -> InstanceBatch {
        let bound = self.placements[start as usize..end as usize]
            .iter()
            .fold(Bound::EMPTY, |b, m| {
                b.union(self.object.bound_at(&DMat4::from(*m)))
            });
        InstanceBatch {
            object: self.object.clone(),
            attributes: self.attributes.clone(),
            placements: self.placements.clone(),
            start,
            end,
            bound,
        }
    }

    /// How many instances it holds.
    pub fn len(&self) -> usize {
        (self.end - self.start) as usize
    }

    /// Never true (a batch holds two instances or more); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.end == self.start
    }
}

impl Primitive for InstanceBatch {
    fn bound(&self) -> Bound {
        self.bound
    }

    fn diceable(&self) -> bool {
        false
    }

    fn split(&self) -> Vec<Box<dyn Primitive>> {
        let n = self.len();
        if n <= FANOUT {
            return self.placements[self.start as usize..self.end as usize]
                .iter()
                .map(|m| {
                    Box::new(InstancePrimitive::new(
                        self.object.clone(),
                        DMat4::from(*m),
                        self.attributes.clone(),
                    )) as Box<dyn Primitive>
                })
                .collect();
        }
        // FANOUT parts of (nearly) equal size, in order.
        (0..FANOUT)
            .map(|k| {
                let a = self.start + (n * k / FANOUT) as u32;
                let b = self.start + (n * (k + 1) / FANOUT) as u32;
                Box::new(self.part(a, b)) as Box<dyn Primitive>
            })
            .collect()
    }

    /// Never called (not diceable); an empty grid rather than a panic.
    fn dice(&self, _nu: usize, _nv: usize) -> Grid {
        Grid::default()
    }
}
