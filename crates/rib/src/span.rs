//! Source positions, so that every error a user sees names `file:line:col`.
use std::fmt;
use std::sync::Arc;

/// Where a request (or a token) starts in its source: 1-based line and column.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Span {
    /// The file name as the user gave it (`-` for stdin, the archive path for `ReadArchive`).
    pub file: Arc<str>,
    pub line: u32,
    pub col: u32,
    /// Byte offset from the start of the (decompressed) stream.
    pub offset: u64,
}

impl Span {
    pub fn new(file: Arc<str>, line: u32, col: u32, offset: u64) -> Self {
        Span {
            file,
            line,
            col,
            offset,
        }
    }

    /// A span for requests that were not read from a file (made by code, tests).
    pub fn synthetic() -> Self {
        Span {
            file: Arc::from("<internal>"),
            line: 0,
            col: 0,
            offset: 0,
        }
    }
}

impl fmt::Display for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.col)
    }
}

/// A value together with the source position it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    pub span: Span,
    pub value: T,
}
