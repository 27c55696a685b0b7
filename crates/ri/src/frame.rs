//! What the RI state hands the hider at `WorldEnd`.
use crate::attributes::{Attributes, Light};
use crate::camera::Camera;
use crate::options::Options;
use crate::solid::SolidTree;
use crate::state::{BlockKind, Ri};
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
    /// Whether its object-to-camera transformation mirrors (negative determinant, at the
    /// first motion key): its object space then has the other handedness than camera space.
    pub mirrored: bool,
}

impl FramePrimitive {
    /// The sign that turns the camera-space `dPdu × dPdv` into the surface's geometric normal
    /// `Ng` (and the default `N`): camera space is left-handed, so the raw cross product is the
    /// left-handed normal; it is flipped when the orientation is "inside" relative to the
    /// object's own handedness, or "outside" in a mirrored (right-handed) object space. A
    /// user-supplied `N` is never flipped (see [`illume_geom::Grid::user_normals`]).
    pub fn normal_sign(&self) -> f32 {
        if self.attributes.orientation_inside != self.mirrored {
            -1.0
        } else {
            1.0
        }
    }
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

// ---- WorldBegin/WorldEnd: a frame's world block ----------------------------------

impl Ri {
    pub(crate) fn world_begin(&mut self, span: &Span) {
        if self.in_world() {
            self.diagnostics.error_kind(
                crate::ErrorKind::Nesting,
                span,
                "WorldBegin",
                "already inside a world block (ignored)",
            );
            return;
        }
        self.push_block(BlockKind::World, span);
        let mut options = self.options.clone();
        if let Some(c) = self.crop_override {
            options.crop = c;
        }
        self.camera = Some(Camera::new(&options, self.ctm));
        self.camera_from_world = Some(self.ctm);
        self.camera_motion = self.ctm_motion.clone();
        self.coordinate_systems
            .insert("world".to_string(), self.ctm);
        self.world_active = match (self.frame_range, self.frame_number) {
            (Some((a, b)), Some(n)) => (a..=b).contains(&n),
            _ => true,
        };
        self.primitives.clear();
        self.instance_run = None;
        self.frame_bytes = 0;
        self.memory_exceeded = false;
    }

    pub(crate) fn world_end(&mut self) {
        let Some(camera) = self.camera.take() else {
            return;
        };
        let mut options = self.options.clone();
        if let Some(c) = self.crop_override {
            options.crop = c;
        }
        self.end_instance_run();
        let primitives = std::mem::take(&mut self.primitives);
        let solids = std::mem::take(&mut self.solids);
        self.open_solids.clear();
        if self.world_active {
            self.frames.push(Frame {
                number: self.frame_number,
                options,
                camera,
                lights: self.lights.clone(),
                primitives,
                solids,
                coordinate_systems: self
                    .coordinate_systems
                    .iter()
                    .map(|(k, v)| (k.clone(), *v))
                    .collect(),
            });
        }
        self.lights.clear();
        self.camera_from_world = None;
        self.camera_motion = None;
        self.coordinate_systems.remove("world");
        self.world_active = true;
    }
}
