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

/// What kind of problem a diagnostic reports, as the RenderMan Interface classifies errors
/// (RI Spec 3.2 Appendix C, `RIE_*` in `ri.h`): the C binding's error handler gets
/// [`ErrorKind::code`], so each report site says what it is instead of the binding guessing
/// from the words.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    NoMem,
    System,
    NoFile,
    BadFile,
    Version,
    /// An optional RI feature this renderer does not have.
    Incapable,
    /// A feature not implemented (the default for warnings).
    #[default]
    Unimplemented,
    Limit,
    Bug,
    NotStarted,
    Nesting,
    NotOptions,
    NotAttribs,
    NotPrims,
    IllState,
    BadMotion,
    BadSolid,
    BadToken,
    Range,
    /// Arguments that contradict each other (the default for errors).
    Consistency,
    BadHandle,
    NoShader,
    MissingData,
    Syntax,
    Math,
}

impl ErrorKind {
    /// The `RIE_*` code of `ri.h`.
    pub fn code(self) -> i32 {
        use ErrorKind::*;
        match self {
            NoMem => 1,
            System => 2,
            NoFile => 3,
            BadFile => 4,
            Version => 5,
            Incapable => 11,
            Unimplemented => 12,
            Limit => 13,
            Bug => 14,
            NotStarted => 23,
            Nesting => 24,
            NotOptions => 25,
            NotAttribs => 26,
            NotPrims => 27,
            IllState => 28,
            BadMotion => 29,
            BadSolid => 30,
            BadToken => 41,
            Range => 42,
            Consistency => 43,
            BadHandle => 44,
            NoShader => 45,
            MissingData => 46,
            Syntax => 47,
            Math => 61,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    /// The RI error class ([`ErrorKind::code`] is the `RIE_*` code).
    pub kind: ErrorKind,
    pub span: Span,
    /// The request the message is about (`"Sphere"`), when there is one.
    pub request: Option<String>,
    pub message: String,
}

impl Diagnostic {
    /// The `RIE_*` code of the problem.
    pub fn code(&self) -> i32 {
        self.kind.code()
    }
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

    /// An error of the most common kind: arguments that make no sense together
    /// ([`ErrorKind::Consistency`]).
    pub fn error(&mut self, span: &Span, request: &str, message: impl Into<String>) {
        self.report(
            Severity::Error,
            ErrorKind::Consistency,
            span,
            request,
            message,
        );
    }

    /// A warning of the most common kind: something not supported, ignored or approximated
    /// ([`ErrorKind::Unimplemented`]).
    pub fn warn(&mut self, span: &Span, request: &str, message: impl Into<String>) {
        self.report(
            Severity::Warning,
            ErrorKind::Unimplemented,
            span,
            request,
            message,
        );
    }

    /// An error of a stated kind (nesting, handles, files…).
    pub fn error_kind(
        &mut self,
        kind: ErrorKind,
        span: &Span,
        request: &str,
        message: impl Into<String>,
    ) {
        self.report(Severity::Error, kind, span, request, message);
    }

    /// A warning of a stated kind.
    pub fn warn_kind(
        &mut self,
        kind: ErrorKind,
        span: &Span,
        request: &str,
        message: impl Into<String>,
    ) {
        self.report(Severity::Warning, kind, span, request, message);
    }

    fn report(
        &mut self,
        severity: Severity,
        kind: ErrorKind,
        span: &Span,
        request: &str,
        message: impl Into<String>,
    ) {
        self.push(Diagnostic {
            severity,
            kind,
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
