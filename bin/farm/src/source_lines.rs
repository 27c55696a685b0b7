//! The RIB's diagnostics as the user should see them from `farm submit`: the parser's own form
//! (`file:line:col: error: Request: message`, the line, a caret under the column). Parse errors
//! bring their line with them; errors the RI state finds later (a `WorldEnd` without
//! `WorldBegin`, a bad parameter) carry only a span, so their line is read back from the file.

use illume_rib::{Diagnostic, Severity, Span};
use std::collections::HashMap;
use std::sync::Arc;

/// Longest line quoted under a message (the parser's limit: longer lines are data, not code).
const MAX_LINE: usize = 200;

#[derive(Default)]
pub struct SourceLines {
    /// Every diagnostic so far, in the order the RI state reported it.
    pub diagnostics: Vec<Diagnostic>,
    /// Lines the parser already quoted, by span.
    parsed: HashMap<Span, String>,
    /// Files read back for a line (`None`: unreadable, compressed or binary).
    files: HashMap<Arc<str>, Option<Vec<String>>>,
}

impl SourceLines {
    /// Notes the line of a parser diagnostic (it comes back through the RI state's queue).
    pub fn remember(&mut self, d: &Diagnostic) {
        if !d.source_line.is_empty() {
            self.parsed.insert(d.span.clone(), d.source_line.clone());
        }
    }

    /// Keeps the RI state's diagnostics, each with its source line when one can be found.
    pub fn keep(&mut self, drained: Vec<illume_ri::Diagnostic>) {
        for d in drained {
            let source_line = match self.parsed.get(&d.span) {
                Some(line) => line.clone(),
                None => self.line_of(&d.span).unwrap_or_default(),
            };
            self.diagnostics.push(Diagnostic {
                severity: match d.severity {
                    illume_ri::Severity::Warning => Severity::Warning,
                    illume_ri::Severity::Error => Severity::Error,
                },
                span: d.span,
                request: d.request,
                message: d.message,
                source_line,
            });
        }
    }

    fn line_of(&mut self, span: &Span) -> Option<String> {
        if span.line == 0 {
            return None;
        }
        let lines = self
            .files
            .entry(span.file.clone())
            .or_insert_with(|| text_lines(&span.file))
            .as_ref()?;
        lines.get(span.line as usize - 1).cloned()
    }
}

/// The lines of a plain-text RIB; `None` for gzip or binary RIB (no caret would line up).
fn text_lines(file: &str) -> Option<Vec<String>> {
    let bytes = std::fs::read(file).ok()?;
    if bytes.starts_with(&[0x1f, 0x8b]) {
        return None;
    }
    let text = String::from_utf8(bytes).ok()?;
    Some(
        text.lines()
            .map(|l| {
                let l = l.trim_end_matches('\r');
                let control = l.chars().any(|c| c.is_control() && c != '\t');
                if control || l.len() > MAX_LINE {
                    String::new()
                } else {
                    l.to_string()
                }
            })
            .collect(),
    )
}
