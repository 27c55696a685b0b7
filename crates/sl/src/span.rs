//! Source locations. Every token, AST node and diagnostic carries a [`Span`] that names the
//! ORIGINAL file, line and column the text came from — not the position in the preprocessed
//! stream — so an error inside an `#include`d header or a macro body points at the line a user
//! can open in an editor.

use std::fmt;
use std::path::{Path, PathBuf};

/// Index of a file in a [`SourceMap`]. Kept small (`u32`) so a [`Span`] stays `Copy` and cheap.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(pub u32);

/// A position in an original source file: 1-based line and column (columns count characters,
/// not bytes, so a caret under a UTF-8 comment still lines up).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Loc {
    /// The file the text physically lives in.
    pub file: FileId,
    /// 1-based line.
    pub line: u32,
    /// 1-based column.
    pub col: u32,
}

/// Where a piece of syntax came from.
///
/// `loc` is the start of the text itself. When the text was produced by expanding a macro,
/// `expanded_at` is the location of the (outermost) macro invocation, so a diagnostic can say
/// both "in the body of ENVPARAMS" and "used here".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// Start of the syntax in its original file.
    pub loc: Loc,
    /// Outermost macro invocation that produced this text, if any.
    pub expanded_at: Option<Loc>,
}

impl Span {
    /// A span for text written directly in a file (not produced by a macro).
    pub fn at(file: FileId, line: u32, col: u32) -> Span {
        Span {
            loc: Loc { file, line, col },
            expanded_at: None,
        }
    }
}

/// One file known to the compiler: its path as the user named it (for messages) and its text.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Path as it should be printed in diagnostics.
    pub path: PathBuf,
    /// Full text of the file.
    pub text: String,
}

/// All files read during one compilation (the main file, its includes, and `<string>` sources
/// used by tests). A [`FileId`] indexes `files`.
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    /// Files in the order they were first read.
    pub files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> SourceMap {
        SourceMap::default()
    }

    /// Registers a file and returns its id. The same path read twice (an include guard's second
    /// visit) gets a second id; that is harmless and keeps this map append-only.
    pub fn add(&mut self, path: impl Into<PathBuf>, text: impl Into<String>) -> FileId {
        self.files.push(SourceFile {
            path: path.into(),
            text: text.into(),
        });
        FileId((self.files.len() - 1) as u32)
    }

    /// The path of a file, or `<unknown>` for an id from another map.
    pub fn path(&self, id: FileId) -> &Path {
        self.files
            .get(id.0 as usize)
            .map(|f| f.path.as_path())
            .unwrap_or_else(|| Path::new("<unknown>"))
    }

    /// Formats a location as `file:line:col`, the form editors and CI logs understand.
    pub fn display(&self, loc: Loc) -> LocDisplay<'_> {
        LocDisplay { map: self, loc }
    }
}

/// `file:line:col` rendering of a [`Loc`] (see [`SourceMap::display`]).
pub struct LocDisplay<'a> {
    map: &'a SourceMap,
    loc: Loc,
}

impl fmt::Display for LocDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}",
            self.map.path(self.loc.file).display(),
            self.loc.line,
            self.loc.col
        )
    }
}
