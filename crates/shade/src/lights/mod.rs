//! The built-in light shaders (chapter 9 §9.6, Listings 9.14–9.19, plus `shadowdistant` and
//! `shadowpoint` as users expect them). Each file runs one light over a grid.
mod ambientlight;
mod arealight;
mod distantlight;
mod pointlight;
mod shadow;
mod spotlight;

use crate::light::{Light, LightSamples};
use crate::parameters::ParamValue;
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LightKind {
    Ambient,
    Distant,
    Point,
    Spot,
    ShadowSpot,
    ShadowDistant,
    ShadowPoint,
    Area,
}

impl LightKind {
    pub const NAMES: [&'static str; 8] = [
        "ambientlight",
        "distantlight",
        "pointlight",
        "spotlight",
        "shadowspot",
        "shadowdistant",
        "shadowpoint",
        "arealight",
    ];

    pub fn from_name(name: &str) -> Option<LightKind> {
        Some(match name {
            "ambientlight" => LightKind::Ambient,
            "distantlight" => LightKind::Distant,
            "pointlight" => LightKind::Point,
            "spotlight" => LightKind::Spot,
            "shadowspot" => LightKind::ShadowSpot,
            "shadowdistant" => LightKind::ShadowDistant,
            "shadowpoint" => LightKind::ShadowPoint,
            "arealight" => LightKind::Area,
            _ => return None,
        })
    }

    /// Parameter names and listing defaults.
    pub fn params(self) -> Vec<(&'static str, ParamValue)> {
        let mut p = vec![
            ("intensity", ParamValue::Float(1.0)),
            ("lightcolor", ParamValue::Color(Vec3::ONE)),
        ];
        let from = ("from", ParamValue::Point(Vec3::ZERO));
        let to = ("to", ParamValue::Point(Vec3::Z));
        let cone = [
            ("coneangle", ParamValue::Float(30f32.to_radians())),
            ("conedeltaangle", ParamValue::Float(5f32.to_radians())),
            ("beamdistribution", ParamValue::Float(2.0)),
        ];
        let shadow = [
            ("shadowname", ParamValue::String(String::new())),
            ("samples", ParamValue::Float(16.0)),
            ("blur", ParamValue::Float(0.01)),
            ("bias", ParamValue::Float(0.01)),
            ("width", ParamValue::Float(1.0)),
        ];
        match self {
            LightKind::Ambient | LightKind::Area => {}
            LightKind::Distant | LightKind::Point => {
                p.push(from);
                if self == LightKind::Distant {
                    p.push(to);
                }
            }
            LightKind::Spot => {
                p.extend([from, to]);
                p.extend(cone);
            }
            LightKind::ShadowSpot => {
                p.extend([from, to]);
                p.extend(cone);
                p.extend(shadow);
            }
            LightKind::ShadowDistant => {
                p.extend([from, to]);
                p.extend(shadow);
            }
            LightKind::ShadowPoint => {
                p.push(from);
                p.extend(shadow);
                for face in ["sfpx", "sfnx", "sfpy", "sfny", "sfpz", "sfnz"] {
                    p.push((face, ParamValue::String(String::new())));
                }
            }
        }
        p
    }
}

/// Runs `light` over every point of `grid` (one result per area-light sample).
pub(crate) fn run(light: &Light, grid: &ShadingGrid, env: &ShadingEnv) -> Vec<LightSamples> {
    match light.kind {
        LightKind::Ambient => vec![ambientlight::run(light, grid)],
        LightKind::Distant | LightKind::ShadowDistant => vec![distantlight::run(light, grid, env)],
        LightKind::Point | LightKind::ShadowPoint => vec![pointlight::run(light, grid, env)],
        LightKind::Spot | LightKind::ShadowSpot => vec![spotlight::run(light, grid, env)],
        LightKind::Area => arealight::run(light, grid, env),
    }
}

/// `value / (L·L)`, finite for every `L`: `L·L` is taken in `f64` (it underflows in `f32` below
/// r ≈ 1e-19), a light exactly at the shaded point (`r = 0`, no direction) contributes nothing,
/// and `1/r²` saturates at `f32::MAX` instead of overflowing.
pub(crate) fn inverse_square(value: Vec3, l: Vec3) -> Vec3 {
    let r2 = l.as_dvec3().length_squared();
    if (r2.is_nan() || r2 <= 0.0) || !r2.is_finite() {
        return Vec3::ZERO;
    }
    let c = value.as_dvec3() / r2;
    c.clamp(
        glam::DVec3::splat(-(f32::MAX as f64)),
        glam::DVec3::splat(f32::MAX as f64),
    )
    .as_vec3()
}
