//! Mip-mapped textures, cube and lat-long environments and shadow maps: building (`txmake`,
//! `MakeTexture`…), a shared tile cache, and filtered `texture`/`environment`/`shadow` lookups
//! with RenderMan semantics (chapter 9; DESIGN.md "Files").
//!
//! # Building
//! [`make_texture`], [`make_latlong_environment`], [`make_cube_face_environment`] (faces in
//! Table 9.1 orientation, written in OpenEXR's cube layout) and [`make_shadow`] (zfile depths +
//! matrices → `.sm` with a min/max pyramid) take `illume_imageio` images and [`MakeOptions`].
//!
//! # Looking up
//! One [`TextureCache`] per render, shared by all threads:
//! ```no_run
//! use illume_texture::{corners_from_derivatives, LookupOptions, TextureCache};
//! let cache = TextureCache::new(64 << 20); // Option "limits" "texturememory" (KB) × 1024
//! let st = corners_from_derivatives(0.5, 0.5, 1e-3, 0.0, 0.0, 1e-3);
//! match cache.texture("grid.tx", 0, 3, st, &LookupOptions::default()) {
//!     Ok(rgb) => println!("{rgb:?}"),
//!     Err(e) => eprintln!("warning: {e}"), // warn once, shade with black
//! }
//! println!("{:?}", cache.stats());
//! ```
#![forbid(unsafe_code)]

pub mod build;
pub mod cache;
pub mod cubeface;
pub mod environment;
pub mod filter;
mod header_order;
pub mod lookup;
pub mod mipmap;
pub mod request;
mod sampler;
pub mod shading;
mod shadow;
pub mod shadowmap;
mod texels;
mod texture;
pub mod texturelookup;
pub mod txfile;
pub mod wrapmode;

pub use build::{
    make_cube_face_environment, make_latlong_environment, make_shadow, make_texture, MakeOptions,
    Resize,
};
pub use cache::{CacheStats, TextureCache, TextureInfo, TextureKind};
pub use environment::{latlong_direction, latlong_st};
pub use filter::FilterKind;
pub use lookup::{corners_from_derivatives, vector_corners, LookupOptions};
pub use request::make_from_request;
pub use texturelookup::{InfoValue, ShadowOptions, TextureFilter, TextureLookup, TextureOptions};
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
