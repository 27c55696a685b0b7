//! RIB, the RenderMan Interface Bytestream (RI Specification 3.2, chapter "RIB" and Appendix C).
//!
//! The crate turns bytes (ASCII, gzip or binary RIB, mixed freely) into a stream of typed
//! [`Request`]s, each with the [`Span`] it came from, and prints requests back as canonical RIB.
//! It knows the *shape* of every request (how many numbers `Sphere` takes) but not the scene
//! semantics: declarations, graphics state and geometry belong to `illume-ri`.
//!
//! ```
//! let rib = "Sphere 1 -1 1 360 \"Cs\" [1 0 0]\n";
//! let mut parser = illume_rib::Parser::new(rib.as_bytes(), "scene.rib");
//! let sphere = parser.next().unwrap().unwrap();
//! assert_eq!(sphere.value.name(), "Sphere");
//! assert_eq!(illume_rib::to_ascii(&sphere.value), "Sphere 1 -1 1 360 \"Cs\" [1 0 0]");
//! ```
#![forbid(unsafe_code)]

mod binary;
mod classification;
pub mod declaration;
mod diagnostic;
mod lexer;
mod parser;
mod printer;
pub mod request;
mod signature;
pub mod span;

pub use binary::{write_binary, BinaryWriter};
pub use declaration::{Class, Declaration, DeclarationError, Type};
pub use diagnostic::{Diagnostic, Severity};
pub use parser::{decompress, open, Item, Parser};
pub use printer::{to_ascii, write_ascii};
pub use request::{BasisSpec, Handle, Param, ParamList, Request, Value};
pub use span::{Span, Spanned};
