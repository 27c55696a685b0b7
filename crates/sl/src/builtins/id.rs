//! [`BuiltinId`]: one variant per built-in function of the table, shared by the checker (which
//! resolves a call's name to its id once) and the executor (which dispatches on the id and its
//! [`Family`], never on the name).
//!
//! The texture-access calls (`texture`, `environment`, `shadow`, `bump`) are not here: the
//! parser already turns them into [`crate::ast::TextureCall`] with a
//! [`crate::ast::TextureKind`], which is their id.

/// The family a built-in belongs to: which part of the executor implements it. Follows RI 3.2
/// chapter 15's sections, except that the noise functions and the ones computed from grid
/// differences (derivatives, `filterstep`, `area`, `calculatenormal`) have their own families,
/// because they need the grid rather than one point at a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// §15.1 mathematical functions of one point (`sin`, `mix`, `spline`, …), and PRMan's
    /// `arraylength`.
    Math,
    /// `noise`, `pnoise`, `cellnoise`, `random`.
    Noise,
    /// Computed from differences across the grid: `Du`, `Dv`, `Deriv`, `filterstep`, `area`,
    /// `calculatenormal`.
    Derivative,
    /// §15.2 geometric functions and component access (`xcomp`, `comp`, `setcomp`, also of
    /// colours and matrices), `transform` and friends, `depth`.
    Geometric,
    /// §15.3 colour: `ctransform`.
    Color,
    /// §15.4 matrix: `determinant`, `translate`, `scale` (the matrix `rotate` shares the id of
    /// the point `rotate`, [`BuiltinId::Rotate`], which is [`Family::Geometric`]).
    Matrix,
    /// §15.5 strings: `concat`, `printf`, `format`, `match`.
    String,
    /// §15.6 shading and lighting: `ambient`, `diffuse`, `specular`, …, and the ray-tracing
    /// calls of BMRT (`trace`, `visibility`, `rayhittest`, `fulltrace`) and PRMan
    /// (`transmission`, `occlusion`).
    Shading,
    /// §15.8 message passing and information: `surface()`, `lightsource()`, `attribute()`,
    /// `textureinfo()`, ….
    Message,
}

/// Declares [`BuiltinId`] with its SL name and family per variant, in one list so that the
/// three can never disagree.
macro_rules! builtin_ids {
    ($($family:ident { $($variant:ident = $name:literal),* $(,)? })*) => {
        /// A built-in function of the table, independent of its overload (the chosen
        /// overload is the call's [`crate::ast::Signature`]).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum BuiltinId {
            $($(
                #[doc = concat!("`", $name, "`")]
                $variant,
            )*)*
        }

        impl BuiltinId {
            /// Every built-in, grouped by family.
            pub const ALL: &'static [BuiltinId] = &[$($(BuiltinId::$variant,)*)*];

            /// The name as written in SL.
            pub fn name(self) -> &'static str {
                match self {
                    $($(BuiltinId::$variant => $name,)*)*
                }
            }

            /// The executor family that implements it.
            pub fn family(self) -> Family {
                match self {
                    $($(BuiltinId::$variant => Family::$family,)*)*
                }
            }
        }
    };
}

builtin_ids! {
    Math {
        Radians = "radians", Degrees = "degrees", Sin = "sin", Asin = "asin", Cos = "cos",
        Acos = "acos", Tan = "tan", Atan = "atan", Pow = "pow", Exp = "exp", Sqrt = "sqrt",
        InverseSqrt = "inversesqrt", Log = "log", Mod = "mod", Abs = "abs", Sign = "sign",
        Floor = "floor", Ceil = "ceil", Round = "round", Min = "min", Max = "max",
        Clamp = "clamp", Mix = "mix", Step = "step", SmoothStep = "smoothstep",
        Spline = "spline", ArrayLength = "arraylength",
    }
    Noise {
        Noise = "noise", PNoise = "pnoise", CellNoise = "cellnoise", Random = "random",
    }
    Derivative {
        FilterStep = "filterstep", Du = "Du", Dv = "Dv", Deriv = "Deriv", Area = "area",
        CalculateNormal = "calculatenormal",
    }
    Geometric {
        XComp = "xcomp", YComp = "ycomp", ZComp = "zcomp", SetXComp = "setxcomp",
        SetYComp = "setycomp", SetZComp = "setzcomp", Comp = "comp", SetComp = "setcomp",
        Length = "length", Normalize = "normalize", Distance = "distance",
        PtLineD = "ptlined", Rotate = "rotate", FaceForward = "faceforward",
        Reflect = "reflect", Refract = "refract", Fresnel = "fresnel",
        Transform = "transform", VTransform = "vtransform", NTransform = "ntransform",
        Depth = "depth",
    }
    Color {
        CTransform = "ctransform",
    }
    Matrix {
        Determinant = "determinant", Translate = "translate", Scale = "scale",
    }
    String {
        Concat = "concat", Printf = "printf", Format = "format", Match = "match",
    }
    Shading {
        Ambient = "ambient", Diffuse = "diffuse", Specular = "specular",
        SpecularBrdf = "specularbrdf", Phong = "phong", Trace = "trace",
        Visibility = "visibility", RayHitTest = "rayhittest", FullTrace = "fulltrace",
        Transmission = "transmission", Occlusion = "occlusion",
    }
    Message {
        TextureInfo = "textureinfo", Surface = "surface", Displacement = "displacement",
        LightSource = "lightsource", Atmosphere = "atmosphere", Incident = "incident",
        Opposite = "opposite", Attribute = "attribute", Option = "option",
        RendererInfo = "rendererinfo",
    }
}

impl BuiltinId {
    /// The built-in with this SL name, if any.
    pub fn from_name(name: &str) -> Option<BuiltinId> {
        BuiltinId::ALL.iter().copied().find(|id| id.name() == name)
    }

    /// True when the result varies over the grid whatever the arguments: the built-in reads
    /// the lights, the grid's neighbours, random numbers, or another shader's values.
    pub fn is_inherently_varying(self) -> bool {
        use BuiltinId as B;
        matches!(
            self,
            B::Ambient
                | B::Diffuse
                | B::Specular
                | B::SpecularBrdf
                | B::Phong
                | B::Trace
                | B::Visibility
                | B::RayHitTest
                | B::FullTrace
                | B::Transmission
                | B::Occlusion
                | B::Random
                | B::Du
                | B::Dv
                | B::Deriv
                | B::Area
                | B::CalculateNormal
                | B::Depth
                | B::FilterStep
                | B::Surface
                | B::Displacement
                | B::LightSource
                | B::Atmosphere
                | B::Incident
                | B::Opposite
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_round_trip() {
        for &id in BuiltinId::ALL {
            assert_eq!(BuiltinId::from_name(id.name()), Some(id));
        }
        let mut names: Vec<&str> = BuiltinId::ALL.iter().map(|id| id.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), BuiltinId::ALL.len());
        assert_eq!(BuiltinId::from_name("bake"), None);
    }
}
