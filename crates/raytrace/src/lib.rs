//! Ray-traced visibility for Illume's BMRT-style shadows (`shadow("raytrace", …)`,
//! `Attribute "light" "shadows" ["on"]`) and area lights: a bounding volume hierarchy over
//! triangles with any-hit occlusion queries.
//!
//! * [`Triangle`]: the watertight ray-triangle test of Woop, Benthin and Wald (JCGT 2013) as
//!   pbrt-v4 writes it, evaluated in `f64` so the rounding error (≈1e-16 relative) is far below
//!   the offsets the caller uses against self-intersection: rays through shared edges and
//!   vertices never slip between two triangles.
//! * [`Bvh`]: binned surface-area-heuristic build (16 bins per axis, deterministic: no
//!   threads, ties broken by index), collapsed into four-wide nodes whose four child boxes
//!   one `f32` SIMD test checks at once; any-hit traversal for shadow rays, nearest-first for
//!   the closest hit.
//!
//! * [`Quadric`]: spheres, disks, cylinders and cones intersected in closed form, leaves of
//!   the same tree ([`Bvh::with_quadrics`]): one test instead of a tessellated subtree.
//!
//! The crate knows nothing of primitives or shading: the hider dices the scene into triangles
//! and the lights ask [`Bvh::occluded`] through a trait object, so `illume-shade` never depends
//! on this crate.
#![forbid(unsafe_code)]

mod bvh;
mod quadric;
mod slab;
mod triangle;
mod wide;

pub use bvh::{Bvh, BvhStats, Hit, TraversalStack, NO_GROUP};
pub use quadric::{Quadric, QuadricShape};
pub use triangle::Triangle;
