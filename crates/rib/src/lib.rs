//! RIB, the RenderMan Interface Bytestream (RI Specification 3.2, chapter "RIB" and Appendix C).
//!
//! The crate turns bytes (ASCII, gzip or binary RIB, mixed freely) into a stream of typed
//! [`Request`]s, each with the [`Span`] it came from, and prints requests back as canonical RIB.
//! It knows the *shape* of every request (how many numbers `Sphere` takes) but not the scene
//! semantics: declarations, graphics state and geometry belong to `illume-ri`.
#![forbid(unsafe_code)]

pub mod declaration;
pub mod request;
pub mod span;

pub use declaration::{Class, Declaration, DeclarationError, Type};
pub use request::{BasisSpec, Handle, Param, ParamList, Request, Value};
pub use span::{Span, Spanned};
