//! Grid-at-a-time built-in shading for Illume: the shading context (a structure-of-arrays grid),
//! the Shading Language built-in functions, light shaders and the material shaders of
//! *Advanced RenderMan* chapter 9 (“Illumination Models and Lights”), written in native Rust.
//!
//! The hider calls [`surface`], [`light`] and [`displacement`] once per `Surface` /
//! `LightSource` / `Displacement` request to bind the RIB parameters, then for every diced grid
//! [`displace`] and [`shade_surface`]. Lights run once per grid ([`LightCache`]) and every
//! illuminance loop of the surface (diffuse, then specular, …) reuses their `L`, `Cl`, `Ol`.
//!
//! ```
//! use glam::{DMat4, Vec3};
//! use illume_rib::{Param, Value};
//! use illume_shade::{light, shade_surface, surface, ShadingEnv, ShadingGrid, SpecularModel};
//!
//! let kd = Param { name: "uniform float Kd".into(), value: Value::Floats(vec![0.6]) };
//! let (plastic, warnings) = surface("plastic", &[kd]).unwrap();
//! assert!(warnings.is_empty());
//! let (sun, _) = light("distantlight", &[], DMat4::IDENTITY).unwrap(); // shines along +z
//!
//! let mut grid = ShadingGrid::new(2, 2); // the hider fills P, N, Ng, dPdu, dPdv, s, t, Cs, Os…
//! grid.p.iter_mut().for_each(|p| *p = Vec3::new(0.0, 0.0, 5.0));
//! grid.set_incident_from_p(false);
//! let env = ShadingEnv { specular_model: SpecularModel::Blinn, ..ShadingEnv::new() };
//! let stats = shade_surface(&plastic, &mut grid, &[&sun], &env);
//! assert_eq!(stats.nonfinite, 0);
//! // N faces the light head-on: Kd·1 + Ks·1.
//! assert!((grid.ci[0] - Vec3::splat(0.6 + 0.5)).length() < 1e-6);
//! ```
#![forbid(unsafe_code)]

mod areaemitter;
mod displacement;
mod error;
mod geometric;
mod hash;
mod illuminance;
mod imager;
mod light;
mod lighting;
mod lights;
mod materials;
mod mathfunctions;
mod noise;
mod occlusion;
mod parameters;
mod renderstate;
mod shadingenv;
mod shadinggrid;
mod surface;
mod texturelookup;
mod tracing;
mod volume;

pub use areaemitter::AreaEmitter;
pub use displacement::{displace, displacement, Displacement};
pub use error::ShadeError;
pub use geometric::{faceforward, fresnel, normalize_or_zero, reflect, refract, Fresnel};
pub use hash::lowbias32;
pub use illuminance::{category_matches, Illuminance};
pub use imager::{imager, Imager};
pub use light::{light, AreaSample, Light, LightCache, LightSamples};
pub use lighting::{
    blinn_phong, diffuse_term, glossy_term, oren_nayar_term, phong_term, specularbrdf,
    ward_anisotropic_term,
};
pub use materials::environment::{raysphere, RaySphere};
pub use materials::{surface_components, Components, COMPONENT_NAMES};
pub use mathfunctions::{mix, smoothstep};
pub use noise::noise;
pub use occlusion::{stratified_sample, Occlusion};
pub use parameters::ParamValue;
pub use renderstate::{rendererinfo, InfoValue, RenderInfo};
pub use shadingenv::{Located, ShadingEnv, SourceAt, SpecularModel, WarnOnce, WarningSink};
pub use shadinggrid::ShadingGrid;
pub use surface::{shade_surface, shade_surface_with, surface, ShadeStats, Surface};
pub use texturelookup::{ShadowOptions, TextureFilter, TextureLookup, TextureOptions};
pub use tracing::{
    blocked_by_transmission, cosine_direction, segment, CosinePattern, RayDifferential, RayStart,
    RayTracer, TraceHit,
};
pub use volume::{run_volume, volume, Volume};
