//! See Cargo.toml description; contract in progress.
