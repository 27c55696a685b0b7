//! What the parser tells the user: `scene.rib:12:7: error: Sphere: expected 4 numbers, found 3`,
//! then the offending line and a caret under the column (the format of compilers and PRMan).
use crate::span::Span;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Severity {
    /// The stream goes on unchanged (unknown vendor requests, ignored oddities).
    Warning,
    /// A request (or part of the stream) was dropped; the parser resynchronised after it.
    Error,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Warning => "warning",
            Severity::Error => "error",
        })
    }
}

/// One problem found in a RIB stream, located at `span` (1-based line and column).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub span: Span,
    /// The request being read when the problem was found (`Some("Sphere")`), if any.
    pub request: Option<String>,
    pub message: String,
    /// The source line the span points into (without its newline); empty when unknown (binary
    /// RIB, or the line was too long to keep).
    pub source_line: String,
}

impl Diagnostic {
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// The first line only: `file:line:col: severity: Request: message`.
    pub fn headline(&self) -> String {
        match &self.request {
            Some(r) => format!("{}: {}: {}: {}", self.span, self.severity, r, self.message),
            None => format!("{}: {}: {}", self.span, self.severity, self.message),
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.headline())?;
        if self.source_line.is_empty() || self.span.col == 0 {
            return Ok(());
        }
        // Copy tabs from the line so the caret lines up however the terminal expands them.
        let before: String = self
            .source_line
            .chars()
            .take(self.span.col as usize - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        write!(f, "\n{}\n{}^", self.source_line, before)
    }
}

impl std::error::Error for Diagnostic {}
