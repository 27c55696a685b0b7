//! Compiler diagnostics: errors and warnings with an original-source location.
//!
//! Every stage (preprocessor, lexer, parser, checker) pushes [`Diagnostic`]s into a list instead
//! of stopping at the first problem, so one `slc` run reports every error it can find (the parser
//! recovers at `;` and `}`).

use crate::span::{SourceMap, Span};
use std::fmt;

/// How bad a diagnostic is. Only errors make compilation fail (and `slc` exit 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Severity {
    /// Compilation continues and the shader is usable (e.g. an unused parameter, a
    /// point assigned to a normal).
    Warning,
    /// The shader cannot be run.
    Error,
}

/// One message about the source.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Where the problem is (original file:line:col).
    pub span: Span,
    /// The message, lower case, no trailing period, in the form `expected X, found Y` where
    /// that fits (the convention of rustc and gcc).
    pub message: String,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            span,
            message: message.into(),
        }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            span,
            message: message.into(),
        }
    }

    /// Renders `file:line:col: error: message` (plus `(expanded from macro at file:line:col)`
    /// when the text came from a macro), resolving file names through `map`.
    pub fn render<'a>(&'a self, map: &'a SourceMap) -> DiagnosticDisplay<'a> {
        DiagnosticDisplay { diag: self, map }
    }
}

/// Display adapter returned by [`Diagnostic::render`].
pub struct DiagnosticDisplay<'a> {
    diag: &'a Diagnostic,
    map: &'a SourceMap,
}

impl fmt::Display for DiagnosticDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.diag.severity {
            Severity::Warning => "warning",
            Severity::Error => "error",
        };
        write!(
            f,
            "{}: {}: {}",
            self.map.display(self.diag.span.loc),
            kind,
            self.diag.message
        )?;
        if let Some(at) = self.diag.span.expanded_at {
            write!(f, " (in macro expanded at {})", self.map.display(at))?;
        }
        Ok(())
    }
}

/// True when any diagnostic in the list is an error.
pub fn has_errors(diags: &[Diagnostic]) -> bool {
    diags.iter().any(|d| d.severity == Severity::Error)
}
