//! What shaders need from the texture system lives with it, in
//! `illume_texture::texturelookup` (the texture crate does not depend on the shaders);
//! re-exported so the built-in shaders and their callers keep one path.
pub use illume_texture::{ShadowOptions, TextureFilter, TextureLookup, TextureOptions};
