//! What the RI state hands the hider at `WorldEnd`.
use crate::attributes::{Attributes, Light};
use crate::camera::Camera;
use crate::options::Options;
use crate::solid::SolidTree;
use illume_geom::Primitive;
use illume_rib::Span;
use std::sync::Arc;

/// One primitive with the attributes it was made under.
#[derive(Debug)]
pub struct FramePrimitive {
    pub primitive: Box<dyn Primitive>,
    pub attributes: Arc<Attributes>,
    /// The request that made it, for the hider's warnings.
    pub span: Span,
    /// The primitive solid (a leaf of [`Frame::solids`]) whose boundary this surface is part
    /// of, `None` outside `SolidBegin`/`SolidEnd`.
    pub solid: Option<u32>,
    /// Its later positions when it moves (a motion block, a moving transform or camera).
    pub motion: Option<crate::motion::MotionKeys>,
}

/// A complete frame: camera, options, lights, and every primitive of the world block.
#[derive(Debug)]
pub struct Frame {
    /// `FrameBegin n`, if the world was inside a frame block.
    pub number: Option<i32>,
    pub options: Options,
    pub camera: Camera,
    /// Every light declared in the world (a re-used handle replaced the older light in place).
    pub lights: Vec<Light>,
    pub primitives: Vec<FramePrimitive>,
    /// The CSG solids the primitives' `solid` leaves belong to (empty without `SolidBegin`).
    pub solids: SolidTree,
    /// Named coordinate systems (`CoordinateSystem`), camera from that space.
    pub coordinate_systems: Vec<(String, glam::DMat4)>,
}
