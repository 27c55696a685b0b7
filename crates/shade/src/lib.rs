//! Grid-at-a-time built-in shading for Illume: the shading context (a structure-of-arrays grid),
//! the Shading Language built-in functions, light shaders and the material shaders of
//! *Advanced RenderMan* chapter 9 (“Illumination Models and Lights”), written in native Rust.
//!
//! The hider calls [`surface`], [`light`] and [`displacement`] once per `Surface` /
//! `LightSource` / `Displacement` request to bind the RIB parameters, then for every diced grid
//! [`displace`] and [`shade_surface`]. Lights run once per grid ([`LightCache`]) and every
//! illuminance loop of the surface (diffuse, then specular, …) reuses their `L`, `Cl`, `Ol`.
#![forbid(unsafe_code)]

mod displacement;
mod error;
mod geometric;
mod illuminance;
mod light;
mod lighting;
mod lights;
mod materials;
mod mathfunctions;
mod parameters;
mod shadingenv;
mod shadinggrid;
mod surface;
mod texturelookup;

pub use displacement::{displace, displacement, Displacement};
pub use error::ShadeError;
pub use geometric::{faceforward, fresnel, normalize_or_zero, reflect, refract, Fresnel};
pub use illuminance::{category_matches, Illuminance};
pub use light::{light, AreaSample, Light, LightCache, LightSamples};
pub use lighting::{
    blinn_phong, diffuse_term, glossy_term, oren_nayar_term, phong_term, specularbrdf,
    ward_anisotropic_term,
};
pub use materials::environment::{raysphere, RaySphere};
pub use mathfunctions::{mix, smoothstep};
pub use parameters::ParamValue;
pub use shadingenv::{ShadingEnv, SpecularModel, WarnOnce, WarningSink};
pub use shadinggrid::ShadingGrid;
pub use surface::{shade_surface, shade_surface_with, surface, ShadeStats, Surface};
pub use texturelookup::{ShadowOptions, TextureFilter, TextureLookup, TextureOptions};
