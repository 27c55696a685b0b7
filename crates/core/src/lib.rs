//! The conventions several Illume crates share, each with exactly one home so that two crates
//! can never disagree about them: a scene's NDC, a filter's name, a basis matrix, a hash value
//! or a noise pattern means the same thing in the RIB front end, the hider, the texture tools,
//! the built-in shaders and the Shading Language VM.
//!
//! * [`spaces`]: camera → screen → NDC → raster (RI Spec 3.2 §4.1.1), the default screen
//!   window, and the zfile `Np` / OpenEXR `worldToNDC` matrices.
//! * [`filter`]: the filter kernels and the one table of their RIB names (`PixelFilter`,
//!   `MakeTexture`, `txmake -filter`).
//! * [`basis`]: the spline basis matrices (`Basis`, SL `spline()`) and the power form.
//! * [`hash`]: `lowbias32` and `splitmix64`, the integer hashes behind every deterministic
//!   random stream.
//! * [`noise`]: the one gradient noise (SL `noise`/`pnoise`/`cellnoise` and the built-in
//!   shaders).
//! * [`searchpath`]: finding a file on an `Option "searchpath"` list.
//!
//! Everything here is a leaf: it depends on `glam` only, so any crate may use it.
#![forbid(unsafe_code)]

pub mod basis;
pub mod filter;
pub mod hash;
pub mod noise;
pub mod searchpath;
pub mod spaces;
