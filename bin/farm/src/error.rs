//! farm's one error type: each variant says which exit code it means (see `main`).

use crate::scene::SceneError;

#[derive(Debug, thiserror::Error)]
pub enum FarmError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// A command line or job directory farm cannot work with.
    #[error("{0}")]
    Usage(String),
    /// The RIB has errors (already printed, each with its line); nothing was submitted.
    #[error("{scene}: {count} error(s) in the RIB; nothing submitted (fix them, or pass --allow-errors to render anyway)")]
    SceneErrors { scene: String, count: usize },
    /// `sbatch` missing or refusing a job.
    #[error("{0}")]
    Slurm(String),
}

pub fn io_error(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> FarmError + '_ {
    move |source| FarmError::Io {
        path: path.display().to_string(),
        source,
    }
}
