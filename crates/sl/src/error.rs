//! The crate's error type, for callers that want `Result` rather than a diagnostics list
//! (DESIGN.md: one error type per crate).

use thiserror::Error;

/// Why a shader could not be compiled.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum SlError {
    /// The source (or a file it includes) has errors. `rendered` holds every diagnostic,
    /// warnings included, as `file:line:col: error: message` lines.
    #[error("{errors} error(s) compiling {file}:\n{rendered}")]
    Source {
        /// The main file's name as given.
        file: String,
        /// How many diagnostics are errors.
        errors: usize,
        /// All diagnostics, rendered.
        rendered: String,
    },
}
