//! Mip-mapped textures, cube and lat-long environments and shadow maps: building (`txmake`,
//! `MakeTexture`…), a shared tile cache, and filtered `texture`/`environment`/`shadow` lookups
//! with RenderMan semantics (chapter 9; DESIGN.md "Files").
#![forbid(unsafe_code)]

pub mod build;
pub mod cache;
pub mod cubeface;
pub mod environment;
pub mod filter;
pub mod lookup;
pub mod mipmap;
mod sampler;
mod shadow;
pub mod shadowmap;
mod texture;
pub mod txfile;
pub mod wrapmode;

pub use build::{
    make_cube_face_environment, make_latlong_environment, make_shadow, make_texture, MakeOptions,
    Resize,
};
pub use cache::{CacheStats, TextureCache, TextureInfo, TextureKind};
pub use environment::{latlong_direction, latlong_st};
pub use filter::FilterKind;
pub use lookup::LookupOptions;
pub use txfile::PixelFormat;
pub use wrapmode::WrapMode;

use thiserror::Error;

/// Errors of building and reading textures. A missing texture is [`TextureError::Missing`] so the
/// caller can warn once and use black.
#[derive(Debug, Error)]
pub enum TextureError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}: texture not found")]
    Missing { path: String },
    #[error("{path}: {message}")]
    Format { path: String, message: String },
    #[error("{path}: is a {found}, expected a {expected}")]
    WrongKind {
        path: String,
        expected: &'static str,
        found: &'static str,
    },
}
