//! The predeclared global variables (RI 3.2 §11.3) and which shader kinds may read or write
//! them.

use crate::types::{Detail, ShaderKind, Type};

/// The predeclared global variables (RI 3.2 §11.3, tables 11.1–11.6). Which are readable and
/// writable depends on the [`ShaderKind`]; the checker enforces that.
#[allow(non_camel_case_types)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Global {
    /// `point P`: surface position (light shaders: point on the light's area geometry).
    P,
    /// `vector dPdu`: derivative of P along u.
    dPdu,
    /// `vector dPdv`: derivative of P along v.
    dPdv,
    /// `normal N`: shading normal.
    N,
    /// `normal Ng`: geometric normal.
    Ng,
    /// `float u`: surface parameter.
    u,
    /// `float v`: surface parameter.
    v,
    /// `float du`: change in u between adjacent grid points.
    du,
    /// `float dv`: change in v between adjacent grid points.
    dv,
    /// `float s`: texture coordinate.
    s,
    /// `float t`: texture coordinate.
    t,
    /// `vector L`: direction to (surface shaders) or from (light shaders) the light.
    L,
    /// `color Cl`: light colour.
    Cl,
    /// `color Ol`: light opacity.
    Ol,
    /// `color Cs`: surface colour attribute.
    Cs,
    /// `color Os`: surface opacity attribute.
    Os,
    /// `color Ci`: resulting colour.
    Ci,
    /// `color Oi`: resulting opacity.
    Oi,
    /// `vector I`: incident ray direction, from the eye to P.
    I,
    /// `point E`: eye position (uniform).
    E,
    /// `point Ps`: the surface point being illuminated (light shaders).
    Ps,
    /// `uniform float ncomps`: number of colour components (3).
    ncomps,
    /// `uniform float time`: current shutter time.
    time,
    /// `uniform float dtime`: shutter interval (PRMan extension, widely used).
    dtime,
    /// `vector dPdtime`: motion of P over the shutter (PRMan extension).
    dPdtime,
    /// `float alpha`: pixel coverage (imager shaders).
    alpha,
}

impl Global {
    /// Every global, in declaration order.
    pub const ALL: [Global; 26] = [
        Global::P,
        Global::dPdu,
        Global::dPdv,
        Global::N,
        Global::Ng,
        Global::u,
        Global::v,
        Global::du,
        Global::dv,
        Global::s,
        Global::t,
        Global::L,
        Global::Cl,
        Global::Ol,
        Global::Cs,
        Global::Os,
        Global::Ci,
        Global::Oi,
        Global::I,
        Global::E,
        Global::Ps,
        Global::ncomps,
        Global::time,
        Global::dtime,
        Global::dPdtime,
        Global::alpha,
    ];

    /// The name as written in source.
    pub fn name(self) -> &'static str {
        match self {
            Global::P => "P",
            Global::dPdu => "dPdu",
            Global::dPdv => "dPdv",
            Global::N => "N",
            Global::Ng => "Ng",
            Global::u => "u",
            Global::v => "v",
            Global::du => "du",
            Global::dv => "dv",
            Global::s => "s",
            Global::t => "t",
            Global::L => "L",
            Global::Cl => "Cl",
            Global::Ol => "Ol",
            Global::Cs => "Cs",
            Global::Os => "Os",
            Global::Ci => "Ci",
            Global::Oi => "Oi",
            Global::I => "I",
            Global::E => "E",
            Global::Ps => "Ps",
            Global::ncomps => "ncomps",
            Global::time => "time",
            Global::dtime => "dtime",
            Global::dPdtime => "dPdtime",
            Global::alpha => "alpha",
        }
    }

    /// The global with this name, if any.
    pub fn from_name(name: &str) -> Option<Global> {
        Global::ALL.into_iter().find(|g| g.name() == name)
    }

    /// Its type.
    pub fn ty(self) -> Type {
        match self {
            Global::P | Global::E | Global::Ps => Type::POINT,
            Global::dPdu | Global::dPdv | Global::L | Global::I | Global::dPdtime => Type::VECTOR,
            Global::N | Global::Ng => Type::NORMAL,
            Global::Cl | Global::Ol | Global::Cs | Global::Os | Global::Ci | Global::Oi => {
                Type::COLOR
            }
            Global::u
            | Global::v
            | Global::du
            | Global::dv
            | Global::s
            | Global::t
            | Global::ncomps
            | Global::time
            | Global::dtime
            | Global::alpha => Type::FLOAT,
        }
    }

    /// Its detail: `E`, `ncomps`, `time` and `dtime` are uniform, everything else varying.
    pub fn detail(self) -> Detail {
        match self {
            Global::E | Global::ncomps | Global::time | Global::dtime => Detail::Uniform,
            _ => Detail::Varying,
        }
    }
}

/// How a shader kind may use a global (RI 3.2 tables 11.1–11.6, with the common renderer
/// leniencies: surface shaders may write `P` and `N`, light shaders may write `L`, as
/// Listing 9.14's `L = 0` does, imager shaders may read `s` and `t`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Access {
    /// Not defined in this kind of shader.
    None,
    /// Readable only.
    Read,
    /// Readable and writable.
    ReadWrite,
}

impl Global {
    /// How a shader of `kind` may use this global. In surface and volume shaders `L`, `Cl` and
    /// `Ol` are additionally only meaningful inside `illuminance` (the checker enforces that).
    pub fn access(self, kind: ShaderKind) -> Access {
        use Access::{None as No, Read as R, ReadWrite as RW};
        use Global as G;
        match kind {
            ShaderKind::Surface => match self {
                G::P | G::N | G::Ci | G::Oi => RW,
                G::Ps | G::alpha => No,
                _ => R,
            },
            ShaderKind::Light => match self {
                G::L | G::Cl | G::Ol => RW,
                G::Cs | G::Os | G::Ci | G::Oi | G::I | G::alpha => No,
                _ => R,
            },
            ShaderKind::Displacement => match self {
                G::P | G::N => RW,
                G::L | G::Cl | G::Ol | G::Ci | G::Oi | G::Ps | G::alpha => No,
                _ => R,
            },
            ShaderKind::Volume => match self {
                G::Ci | G::Oi => RW,
                G::P | G::I | G::E | G::L | G::Cl | G::Ol | G::ncomps | G::time | G::dtime => R,
                _ => No,
            },
            // `s`, `t` in imagers: not in RI 3.2's table 11.6, but peers define them (the
            // pixel's position across the image) and imager shaders read them.
            ShaderKind::Imager => match self {
                G::Ci | G::Oi | G::alpha => RW,
                G::P | G::s | G::t | G::ncomps | G::time | G::dtime => R,
                _ => No,
            },
            ShaderKind::Transformation => match self {
                G::P => RW,
                G::time | G::dtime => R,
                _ => No,
            },
        }
    }
}
