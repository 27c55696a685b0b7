//! The Shading Language runtime of Illume: executes the checked ASTs of `illume-sl` over whole
//! shading grids. Values are structure-of-arrays over the grid and either uniform (computed once)
//! or varying ([`Slot`]); varying control flow runs under running-state masks ([`Mask`]).
//! The built-in function library of RI 3.2 chapter 15 lives in one file per family.
#![forbid(unsafe_code)]

mod builtins;
pub mod colorspaces;
mod exec;
pub mod frontend;
pub mod geometric;
mod instance;
pub mod library;
mod lights;
pub mod mathfunctions;
pub mod noise;
pub mod operators;
pub mod spline;
mod value;
mod volume;

pub use exec::{zero_of, CompiledShader, Exec, Messages};
pub use instance::{string_value, SlInstance, SlStats};
pub use lights::{in_cone, LightSource, LightView, Lights};
pub use value::{zip2, zip3, Mask, Slot, Value};
pub use volume::Relight;
