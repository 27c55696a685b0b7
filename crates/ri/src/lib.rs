//! The RenderMan Interface state machine (RI Specification 3.2, chapter 4): options, the
//! attribute and transformation stacks, declarations, coordinate systems, archives, object
//! instances and frames.
//!
//! Feed it [`Spanned`](illume_rib::Spanned) [`Request`](illume_rib::Request)s with
//! [`Ri::request`]; at every `WorldEnd` a complete [`Frame`] is queued for the hider
//! ([`Ri::take_frames`]). Problems are collected as [`Diagnostic`]s (`file:line:col: error:
//! Request: message`), drained with [`Ri::drain_diagnostics`]; the state always recovers.
#![forbid(unsafe_code)]

mod archive;
pub mod attributes;
pub mod camera;
pub mod declarations;
pub mod diagnostic;
pub mod frame;
mod geometry;
mod instance;
pub mod instance_batch;
mod lights;
mod make_texture;
pub mod memory;
pub mod motion;
pub mod options;
pub mod paramlist;
mod procedural;
pub mod solid;
pub mod state;
pub mod transform;

pub use attributes::{Attributes, Light, Shader};
pub use camera::Camera;
pub use declarations::Declarations;
pub use diagnostic::{Diagnostic, Diagnostics, ErrorKind, Severity};
pub use frame::{Frame, FramePrimitive};
pub use instance::InstancePrimitive;
pub use motion::{MotionKeys, MovingTransform};
pub use options::{
    declared_vertices, DepthFilter, DisplayChannel, DisplaySpec, Limits, Options, Projection,
    QuantizeSpec,
};
pub use solid::{SolidNode, SolidOp, SolidTree};
pub use state::{from_rib_diagnostic, RequestSource, Ri, StreamParser, TextureMaker};
