//! Messages for the user: `scene.rib:12:7: error: Sphere: expects 4 numbers, found 3`.
//!
//! Warnings are de-duplicated (same request, same message) so a scene with ten thousand
//! unsupported `Curves` says so once; errors are all kept because each one names its own line.
use illume_rib::Span;
use std::collections::HashSet;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Severity {
    Warning,
    Error,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub span: Span,
    /// The request the message is about (`"Sphere"`), when there is one.
    pub request: Option<String>,
    pub message: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let level = match self.severity {
            Severity::Warning => "warning",
            Severity::Error => "error",
        };
        write!(f, "{}: {level}: ", self.span)?;
        if let Some(r) = &self.request {
            write!(f, "{r}: ")?;
        }
        f.write_str(&self.message)
    }
}

/// Collects diagnostics in the order they happen; the caller drains and prints them.
#[derive(Debug, Default)]
pub struct Diagnostics {
    pending: Vec<Diagnostic>,
    seen_warnings: HashSet<(Option<String>, String)>,
    errors: usize,
    warnings: usize,
}

impl Diagnostics {
    pub fn push(&mut self, d: Diagnostic) {
        match d.severity {
            Severity::Error => self.errors += 1,
            Severity::Warning => {
                if !self
                    .seen_warnings
                    .insert((d.request.clone(), d.message.clone()))
                {
                    return;
                }
                self.warnings += 1;
            }
        }
        self.pending.push(d);
    }

    pub fn error(&mut self, span: &Span, request: &str, message: impl Into<String>) {
        self.push(Diagnostic {
            severity: Severity::Error,
            span: span.clone(),
            request: Some(request.to_string()),
            message: message.into(),
        });
    }

    pub fn warn(&mut self, span: &Span, request: &str, message: impl Into<String>) {
        self.push(Diagnostic {
            severity: Severity::Warning,
            span: span.clone(),
            request: Some(request.to_string()),
            message: message.into(),
        });
    }

    /// Messages since the last drain, in order.
    pub fn drain(&mut self) -> Vec<Diagnostic> {
        std::mem::take(&mut self.pending)
    }

    /// Errors reported so far (drained or not).
    pub fn error_count(&self) -> usize {
        self.errors
    }

    /// Distinct warnings reported so far.
    pub fn warning_count(&self) -> usize {
        self.warnings
    }
}
