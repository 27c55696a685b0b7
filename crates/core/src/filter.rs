//! The filter kernels and the one table of their names. `PixelFilter` (RI Spec 3.2 §4.1.4),
//! `MakeTexture` and friends (§8) and `txmake -filter` all look names up in [`FILTER_NAMES`],
//! so a name either means the same kernel everywhere or is unknown everywhere (and the caller
//! warns or fails; it never silently becomes another filter).
//!
//! Each kernel is a function of an offset `x` in destination pixels and a full width `w`, zero
//! for `|x| > w/2`. Shapes follow the RI specification's filter functions: box; triangle
//! `1 − |x|/(w/2)`; Gaussian `exp(−2·(2x/w)²)` (`exp(−2)` at the edge); Catmull–Rom and
//! Mitchell–Netravali (B = C = 1/3) cubics stretched so their `[−2,2]` support spans the width;
//! Lanczos-2 likewise; sinc in pixel units, windowed by the width. The pixel filter's 2-D
//! forms are in [`pixel`].

use std::f32::consts::PI;

pub mod pixel;
pub use pixel::{FilterTable, PixelFilter};

/// A filter kernel.
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

/// Every accepted filter name (lower case; lookups ignore case) and its kernel. The first name
/// of each kernel is its canonical name ([`FilterKind::name`]). PRMan and BMRT spellings are
/// aliases: `catrom` and `catmullrom` (BMRT, txmake), `separable-catmull-rom` (PRMan; here the
/// one Catmull–Rom), `tent`/`bilinear` for the triangle, `lanczos3` for Lanczos.
pub const FILTER_NAMES: &[(&str, FilterKind)] = &[
    ("box", FilterKind::Box),
    ("triangle", FilterKind::Triangle),
    ("gaussian", FilterKind::Gaussian),
    ("catmull-rom", FilterKind::CatmullRom),
    ("lanczos", FilterKind::Lanczos),
    ("mitchell", FilterKind::Mitchell),
    ("sinc", FilterKind::Sinc),
    ("tent", FilterKind::Triangle),
    ("bilinear", FilterKind::Triangle),
    ("catmullrom", FilterKind::CatmullRom),
    ("catrom", FilterKind::CatmullRom),
    ("separable-catmull-rom", FilterKind::CatmullRom),
    ("lanczos3", FilterKind::Lanczos),
];

/// The accepted names as a message lists them: `box, triangle, …`.
pub fn filter_names_list() -> String {
    let names: Vec<&str> = FILTER_NAMES.iter().map(|(n, _)| *n).collect();
    names.join(", ")
}

impl FilterKind {
    /// The kernel a name means ([`FILTER_NAMES`], case-insensitive); `None` for an unknown
    /// name, which the caller reports.
    pub fn parse(name: &str) -> Option<FilterKind> {
        FILTER_NAMES
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|&(_, k)| k)
    }

    /// The canonical name (written into a `.tx` file's `filter` attribute).
    pub fn name(self) -> &'static str {
        FILTER_NAMES
            .iter()
            .find(|&&(_, k)| k == self)
            .map(|&(n, _)| n)
            .unwrap_or("box")
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

    /// The separable 1-D kernel at offset `x` (destination pixels) for full width `width`.
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

/// `sin(πx)/(πx)`, 1 at 0.
pub fn sinc(x: f32) -> f32 {
    if x.abs() < 1e-6 {
        1.0
    } else {
        (PI * x).sin() / (PI * x)
    }
}

/// The Mitchell–Netravali family on `|x| ∈ [0,2]` (B=0, C=½ is Catmull–Rom).
pub fn cubic(x: f32, b: f32, c: f32) -> f32 {
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
        for &(name, f) in FILTER_NAMES {
            let w = f.default_width();
            assert!(f.eval(0.0, w) > 0.6, "{name}");
            assert_eq!(f.eval(w * 0.51, w), 0.0, "{name}");
            assert_eq!(FilterKind::parse(name), Some(f));
            assert_eq!(FilterKind::parse(&name.to_uppercase()), Some(f));
            // The canonical name round-trips.
            assert_eq!(FilterKind::parse(f.name()), Some(f));
        }
        assert!(FilterKind::parse("bogus").is_none());
        assert_eq!(FilterKind::CatmullRom.name(), "catmull-rom");
    }

    #[test]
    fn catmull_rom_interpolates_integer_points() {
        // Width 4 → unit spacing in the cubic's own domain: 1 at 0, 0 at ±1, ±2.
        let f = FilterKind::CatmullRom;
        assert!((f.eval(0.0, 4.0) - 1.0).abs() < 1e-6);
        assert!(f.eval(1.0, 4.0).abs() < 1e-6);
        assert!(f.eval(1.5, 4.0) < 0.0);
    }

    #[test]
    fn mitchell_matches_its_closed_form() {
        // B = C = 1/3: k(0) = (6 − 2B)/6 = 8/9 and k(1) = B/6 = 1/18 (Mitchell & Netravali).
        let f = FilterKind::Mitchell;
        assert!((f.eval(0.0, 4.0) - 8.0 / 9.0).abs() < 1e-6);
        assert!((f.eval(1.0, 4.0) - 1.0 / 18.0).abs() < 1e-6);
    }
}
