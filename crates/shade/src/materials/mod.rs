//! The surface shaders: the chapter's materials (Listings 9.1–9.13) and the standard RI 3.2
//! surfaces, each a function from the grid and the cached lights to the unpremultiplied colour
//! (`surface.rs` then applies `Oi = Os; Ci *= Oi` as every listing ends).
pub mod environment;

mod components;
pub use components::{surface_components, Components, COMPONENT_NAMES};

mod constant;
mod defaultsurface;
mod glossy;
mod matte;
mod metal;
mod orennayar;
mod plastic;
mod shinymetal;
mod shinyplastic;
mod thinplastic;
mod wardanisotropic;

use crate::geometric::{faceforward, normalize_or_zero};
use crate::light::LightCache;
use crate::parameters::{FloatParam, ParamValue, ShaderParams};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::Vec3;

/// Everything a surface needs for one grid: the globals, the bound parameters, the lights run
/// once, and the two vectors every listing starts from.
pub(crate) struct SurfaceContext<'a> {
    pub grid: &'a ShadingGrid,
    pub lights: &'a LightCache<'a>,
    pub env: &'a ShadingEnv<'a>,
    pub params: &'a ShaderParams,
    /// `Nf = faceforward(normalize(N), I)` (against `Ng`).
    pub nf: Vec<Vec3>,
    /// `V = -normalize(I)`.
    pub v: Vec<Vec3>,
}

impl<'a> SurfaceContext<'a> {
    pub fn new(
        grid: &'a ShadingGrid,
        lights: &'a LightCache<'a>,
        env: &'a ShadingEnv<'a>,
        params: &'a ShaderParams,
    ) -> SurfaceContext<'a> {
        let nf = (0..grid.len())
            .map(|i| faceforward(normalize_or_zero(grid.n[i]), grid.i[i], grid.ng[i]))
            .collect();
        let v = grid.i.iter().map(|&i| -normalize_or_zero(i)).collect();
        SurfaceContext {
            grid,
            lights,
            env,
            params,
            nf,
            v,
        }
    }

    /// `Ka`, `Kd`, `Ks` and `roughness` read per point: the parameters the plastic and metal
    /// family (plastic, metal, shinymetal, shinyplastic) share.
    pub fn ka_kd_ks_roughness(&self) -> [FloatParam<'a>; 4] {
        ["Ka", "Kd", "Ks", "roughness"].map(|name| self.params.float_on(self.grid, name))
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SurfaceKind {
    Constant,
    DefaultSurface,
    Matte,
    Plastic,
    PaintedPlastic,
    Metal,
    RoughMetal,
    ThinPlastic,
    ShinyMetal,
    ShinyPlastic,
    OrenNayar,
    WardAnisotropic,
    Glossy,
}

impl SurfaceKind {
    pub const NAMES: [&'static str; 13] = [
        "constant",
        "defaultsurface",
        "matte",
        "plastic",
        "paintedplastic",
        "metal",
        "roughmetal",
        "thinplastic",
        "shinymetal",
        "shinyplastic",
        "orennayar",
        "wardanisotropic",
        "glossy",
    ];
    const KINDS: [SurfaceKind; 13] = [
        SurfaceKind::Constant,
        SurfaceKind::DefaultSurface,
        SurfaceKind::Matte,
        SurfaceKind::Plastic,
        SurfaceKind::PaintedPlastic,
        SurfaceKind::Metal,
        SurfaceKind::RoughMetal,
        SurfaceKind::ThinPlastic,
        SurfaceKind::ShinyMetal,
        SurfaceKind::ShinyPlastic,
        SurfaceKind::OrenNayar,
        SurfaceKind::WardAnisotropic,
        SurfaceKind::Glossy,
    ];

    pub fn from_name(name: &str) -> Option<SurfaceKind> {
        Self::NAMES
            .iter()
            .position(|&n| n == name)
            .map(|k| Self::KINDS[k])
    }

    /// Parameter names and defaults (see each shader's file for the table and its source).
    pub fn params(self) -> Vec<(&'static str, ParamValue)> {
        match self {
            SurfaceKind::Constant => vec![],
            SurfaceKind::DefaultSurface => defaultsurface::params(),
            SurfaceKind::Matte => matte::params(),
            SurfaceKind::Plastic => plastic::params(false),
            SurfaceKind::PaintedPlastic => plastic::params(true),
            SurfaceKind::Metal => metal::params(false),
            SurfaceKind::RoughMetal => metal::params(true),
            SurfaceKind::ThinPlastic => thinplastic::params(),
            SurfaceKind::ShinyMetal => shinymetal::params(),
            SurfaceKind::ShinyPlastic => shinyplastic::params(),
            SurfaceKind::OrenNayar => orennayar::params(),
            SurfaceKind::WardAnisotropic => wardanisotropic::params(),
            SurfaceKind::Glossy => glossy::params(),
        }
    }

    /// The unpremultiplied surface colour at every grid point: the sum of the
    /// [`components`](Self::components), so each formula exists once and the AOVs add up to
    /// `Ci` by construction.
    pub fn shade(self, ctx: &SurfaceContext) -> Vec<Vec3> {
        self.components(ctx).total()
    }

    /// The material's lighting terms apart (`__ambient`, `__diffuse`, `__specular`,
    /// `__reflection`), unpremultiplied.
    pub fn components(self, ctx: &SurfaceContext) -> Components {
        match self {
            SurfaceKind::Constant => constant::components(ctx),
            SurfaceKind::DefaultSurface => defaultsurface::components(ctx),
            SurfaceKind::Matte => matte::components(ctx),
            SurfaceKind::Plastic | SurfaceKind::PaintedPlastic => plastic::components(ctx),
            SurfaceKind::Metal => metal::components(ctx, false),
            SurfaceKind::RoughMetal => metal::components(ctx, true),
            SurfaceKind::ThinPlastic => thinplastic::components(ctx),
            SurfaceKind::ShinyMetal => shinymetal::components(ctx),
            SurfaceKind::ShinyPlastic => shinyplastic::components(ctx),
            SurfaceKind::OrenNayar => orennayar::components(ctx),
            SurfaceKind::WardAnisotropic => wardanisotropic::components(ctx),
            SurfaceKind::Glossy => glossy::components(ctx),
        }
    }
}

fn f(v: f32) -> ParamValue {
    ParamValue::Float(v)
}

fn c(v: f32) -> ParamValue {
    ParamValue::Color(Vec3::splat(v))
}

fn s(v: &str) -> ParamValue {
    ParamValue::String(v.to_string())
}

/// `DECLARE_DEFAULTED_ENVPARAMS` of Listing 9.7.
fn envparams() -> [(&'static str, ParamValue); 3] {
    [
        ("envname", s("")),
        ("envspace", s("world")),
        ("envrad", f(100.0)),
    ]
}
