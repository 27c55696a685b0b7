//! `illume-sl`: the RenderMan Shading Language front end.
//!
//! Pipeline: preprocessor (`#include`, `#define`, `#if`, with a source map back to the
//! original file:line:col) → lexer → parser (recursive descent) → checker (scopes, types,
//! overload resolution) → uniform/varying inference. Its output is a checked [`ast::Program`],
//! which `illume-slvm` executes over shading grids.
//!
//! [`ast`] and [`types`] are the ABI with the executor: they change only additively, and every
//! change is logged in `crates/sl/AST_CHANGES.md`.
//!
//! ```
//! let out = illume_sl::compile_str(
//!     "matte.sl",
//!     "surface matte (float Ka = 1, Kd = 1;) {
//!          normal Nf = faceforward (normalize(N), I);
//!          Oi = Os; Ci = Os * Cs * (Ka*ambient() + Kd*diffuse(Nf));
//!      }",
//!     &illume_sl::PpOptions::default(),
//! );
//! assert!(!out.has_errors(), "{}", out.render_diagnostics());
//! assert_eq!(out.program.shaders[0].params.len(), 2);
//! ```
#![forbid(unsafe_code)]

pub mod ast;
pub mod builtins;
pub mod checker;
mod detail;
pub mod diagnostic;
mod error;
pub mod lexer;
pub mod parser;
pub mod preprocess;
pub mod span;
pub mod types;

pub use diagnostic::{Diagnostic, Severity};
pub use error::SlError;
pub use preprocess::PpOptions;
pub use span::{FileId, Loc, SourceMap, Span};

use std::path::Path;

/// The result of compiling one source file.
#[derive(Debug, Clone)]
pub struct Compiled {
    /// The checked program (complete only when [`Compiled::has_errors`] is false).
    pub program: ast::Program,
    /// Every file read (the main file first), for rendering spans.
    pub sources: SourceMap,
    /// Errors and warnings in the order found.
    pub diagnostics: Vec<Diagnostic>,
}

impl Compiled {
    /// True when any diagnostic is an error (the program must not be run).
    pub fn has_errors(&self) -> bool {
        diagnostic::has_errors(&self.diagnostics)
    }

    /// All diagnostics as `file:line:col: error: message` lines.
    pub fn render_diagnostics(&self) -> String {
        self.diagnostics
            .iter()
            .map(|d| format!("{}\n", d.render(&self.sources)))
            .collect()
    }

    /// The checked program, or [`SlError::Source`] when there were errors. Warnings are
    /// dropped; read [`Compiled::diagnostics`] first to show them.
    pub fn into_program(self) -> Result<ast::Program, SlError> {
        if !self.has_errors() {
            return Ok(self.program);
        }
        let errors = self
            .diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .count();
        Err(SlError::Source {
            file: self
                .sources
                .files
                .first()
                .map_or_else(String::new, |f| f.path.display().to_string()),
            errors,
            rendered: self.render_diagnostics(),
        })
    }
}

/// Compiles source text; `name` is the file name used in diagnostics and the directory
/// searched first for `#include "…"`.
pub fn compile_str(name: &str, text: &str, opts: &PpOptions) -> Compiled {
    let mut sources = SourceMap::new();
    let id = sources.add(name, text);
    compile_registered(sources, id, opts)
}

/// Reads and compiles a file (bytes that are not UTF-8 read as U+FFFD). An unreadable file is
/// reported as a diagnostic, not a panic.
pub fn compile_file(path: &Path, opts: &PpOptions) -> Compiled {
    // Lossy: old shaders carry Latin-1 bytes in comments (author names, ©), which must not
    // stop compilation; such bytes can only matter inside string literals.
    match std::fs::read(path).map(|b| String::from_utf8_lossy(&b).into_owned()) {
        Ok(text) => {
            let mut sources = SourceMap::new();
            let id = sources.add(path, text);
            compile_registered(sources, id, opts)
        }
        Err(e) => {
            let mut sources = SourceMap::new();
            let id = sources.add(path, "");
            Compiled {
                program: ast::Program::default(),
                sources,
                diagnostics: vec![Diagnostic::error(
                    Span::at(id, 1, 1),
                    format!("cannot read {}: {e}", path.display()),
                )],
            }
        }
    }
}

fn compile_registered(mut sources: SourceMap, id: FileId, opts: &PpOptions) -> Compiled {
    let mut diagnostics = Vec::new();
    let tokens = preprocess::preprocess(&mut sources, id, opts, &mut diagnostics);
    let mut program = parser::parse(&tokens, &mut diagnostics);
    if !diagnostic::has_errors(&diagnostics) {
        checker::check(&mut program, &mut diagnostics);
    }
    Compiled {
        program,
        sources,
        diagnostics,
    }
}
