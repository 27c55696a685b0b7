//! The crate's one error type.
use thiserror::Error;

/// Errors binding a shader. Bad *parameters* are not errors: they come back as warnings next to
/// the shader and are ignored (the shader keeps its listing default).
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum ShadeError {
    /// No built-in shader of that kind has this name. The caller warns once and falls back to
    /// `defaultsurface` (surfaces), no light, or no displacement.
    #[error("unknown {kind} shader `{name}` (built-in {kind} shaders: {known})")]
    UnknownShader {
        kind: &'static str,
        name: String,
        /// The names searched, comma separated, for the warning.
        known: String,
    },
}
