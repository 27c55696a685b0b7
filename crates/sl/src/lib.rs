//! `illume-sl`: the RenderMan Shading Language front end.
//!
//! Pipeline: preprocessor (`#include`, `#define`, `#if`, with a source map back to the
//! original file:line:col) → lexer → parser (recursive descent) → checker (scopes, types,
//! overload resolution, uniform/varying inference). Its output is a checked [`ast::Program`],
//! which `illume-slvm` executes over shading grids.
//!
//! [`ast`] and [`types`] are the ABI with the executor: they change only additively, and every
//! change is logged in `crates/sl/AST_CHANGES.md`.
#![forbid(unsafe_code)]

pub mod ast;
pub mod diagnostic;
pub mod span;
pub mod types;

pub use diagnostic::{Diagnostic, Severity};
pub use span::{FileId, Loc, SourceMap, Span};
