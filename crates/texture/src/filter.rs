//! Reconstruction/decimation filters named as `txmake -filter` and `MakeTexture` name them.
//!
//! Each filter is evaluated at an offset `x` measured in *destination* pixels and is zero outside
//! `|x| > width/2`. Shapes follow the RI specification's filter functions (Gaussian
//! `exp(-2·(2x/w)²)`, Catmull–Rom, Mitchell–Netravali B=C=1/3, Lanczos-2, windowed sinc).

use std::f32::consts::PI;

/// A named decimation filter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FilterKind {
    Box,
    Triangle,
    Gaussian,
    CatmullRom,
    Lanczos,
    Mitchell,
    Sinc,
}

impl FilterKind {
    /// Parses `box`, `triangle`, `gaussian`, `catmull-rom`, `lanczos`, `mitchell`, `sinc`
    /// (case-insensitive; `catmullrom`, `bessel`-less PRMan spellings accepted).
    pub fn parse(name: &str) -> Option<FilterKind> {
        Some(match name.to_ascii_lowercase().as_str() {
            "box" => FilterKind::Box,
            "triangle" | "tent" | "bilinear" => FilterKind::Triangle,
            "gaussian" => FilterKind::Gaussian,
            "catmull-rom" | "catmullrom" | "catrom" => FilterKind::CatmullRom,
            "lanczos" | "lanczos3" => FilterKind::Lanczos,
            "mitchell" => FilterKind::Mitchell,
            "sinc" => FilterKind::Sinc,
            _ => return None,
        })
    }

    /// The name written into the `.tx` `filter` attribute.
    pub fn name(self) -> &'static str {
        match self {
            FilterKind::Box => "box",
            FilterKind::Triangle => "triangle",
            FilterKind::Gaussian => "gaussian",
            FilterKind::CatmullRom => "catmull-rom",
            FilterKind::Lanczos => "lanczos",
            FilterKind::Mitchell => "mitchell",
            FilterKind::Sinc => "sinc",
        }
    }

    /// Default full width in destination pixels (box 1 gives the exact 2×2 average).
    pub fn default_width(self) -> f32 {
        match self {
            FilterKind::Box => 1.0,
            FilterKind::Triangle | FilterKind::Gaussian => 2.0,
            FilterKind::CatmullRom
            | FilterKind::Lanczos
            | FilterKind::Mitchell
            | FilterKind::Sinc => 4.0,
        }
    }

    /// Filter weight at offset `x` (destination pixels) for full width `width`.
    pub fn eval(self, x: f32, width: f32) -> f32 {
        let half = 0.5 * width;
        let ax = x.abs();
        if ax > half {
            return 0.0;
        }
        match self {
            FilterKind::Box => 1.0,
            FilterKind::Triangle => 1.0 - ax / half,
            FilterKind::Gaussian => {
                let u = ax / half;
                (-2.0 * u * u).exp()
            }
            FilterKind::CatmullRom => cubic(2.0 * ax / half, 0.0, 0.5),
            FilterKind::Mitchell => cubic(2.0 * ax / half, 1.0 / 3.0, 1.0 / 3.0),
            FilterKind::Lanczos => {
                let u = 2.0 * ax / half;
                sinc(u) * sinc(u / 2.0)
            }
            FilterKind::Sinc => sinc(ax),
        }
    }
}

fn sinc(x: f32) -> f32 {
    if x.abs() < 1e-6 {
        1.0
    } else {
        (PI * x).sin() / (PI * x)
    }
}

/// Mitchell–Netravali family on `|x| ∈ [0,2]` (B=0, C=½ is Catmull–Rom).
fn cubic(x: f32, b: f32, c: f32) -> f32 {
    let x2 = x * x;
    let x3 = x2 * x;
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else if x < 2.0 {
        (-b - 6.0 * c) * x3
            + (6.0 * b + 30.0 * c) * x2
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c)
    } else {
        0.0
    };
    v / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_filter_peaks_at_zero_and_vanishes_outside_its_width() {
        for name in [
            "box",
            "triangle",
            "gaussian",
            "catmull-rom",
            "lanczos",
            "mitchell",
            "sinc",
        ] {
            let f = FilterKind::parse(name).unwrap();
            let w = f.default_width();
            assert!(f.eval(0.0, w) > 0.6, "{name}");
            assert_eq!(f.eval(w * 0.51, w), 0.0, "{name}");
            assert_eq!(f.name(), name);
        }
        assert!(FilterKind::parse("bogus").is_none());
    }

    #[test]
    fn catmull_rom_interpolates_integer_points() {
        // width 4 → unit spacing in the cubic's own domain.
        let f = FilterKind::CatmullRom;
        assert!((f.eval(0.0, 4.0) - 1.0).abs() < 1e-6);
        assert!(f.eval(1.0, 4.0).abs() < 1e-6);
    }
}
