//! The pixel reconstruction filter of `PixelFilter` (RI Spec 3.2 §4.1.4), evaluated at an
//! offset (dx, dy) in pixels from the pixel centre. Weights are normalised per pixel by the
//! hider, so negative lobes (catmull-rom, sinc) keep flat regions flat.
//!
//! The spec's `RiGaussianFilter` and `RiCatmullRomFilter` are radial: the Gaussian's widths
//! scale its argument (and, being a Gaussian, it is also the product of an x and a y factor,
//! which is how it is evaluated), Catmull–Rom is in pixel units (zero at radius 2). The other
//! kernels are the separable products of the 1-D kernels of [`super::FilterKind::eval`].
use super::FilterKind;

/// A pixel filter: a kernel and its full widths in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelFilter {
    pub kind: FilterKind,
    pub xwidth: f32,
    pub ywidth: f32,
}

impl PixelFilter {
    /// The filter named `name` ([`super::FILTER_NAMES`]). The RIB front end has already warned
    /// about an unknown name and replaced it by `gaussian`, the default; a caller that did not
    /// gets the default too.
    pub fn new(name: &str, xwidth: f32, ywidth: f32) -> PixelFilter {
        PixelFilter {
            kind: FilterKind::parse(name).unwrap_or(FilterKind::Gaussian),
            xwidth: xwidth.max(1e-3),
            ywidth: ywidth.max(1e-3),
        }
    }

    /// Half-widths: a sample farther than this from a pixel centre has no weight.
    pub fn radius(&self) -> (f32, f32) {
        (self.xwidth * 0.5, self.ywidth * 0.5)
    }

    pub fn weight(&self, dx: f32, dy: f32) -> f32 {
        if self.is_separable() {
            return self.factor_x(dx) * self.factor_y(dy);
        }
        let (rx, ry) = self.radius();
        if dx.abs() > rx || dy.abs() > ry {
            return 0.0;
        }
        // RiCatmullRomFilter is radial in pixel units.
        let r2 = dx * dx + dy * dy;
        let r = r2.sqrt();
        if r < 1.0 {
            1.5 * r * r2 - 2.5 * r2 + 1.0
        } else if r < 2.0 {
            -0.5 * r * r2 + 2.5 * r2 - 4.0 * r + 2.0
        } else {
            0.0
        }
    }

    /// Whether the weight is the product `factor_x(dx) · factor_y(dy)`: every kernel but the
    /// radial Catmull–Rom. The hider then evaluates each factor once per sample and pixel
    /// column (row) instead of the 2-D weight once per sample and pixel (issue 21 part 3).
    pub fn is_separable(&self) -> bool {
        self.kind != FilterKind::CatmullRom
    }

    /// The horizontal factor of a separable weight at offset `dx` (zero outside the width).
    pub fn factor_x(&self, dx: f32) -> f32 {
        self.factor(dx, self.xwidth)
    }

    /// The vertical factor of a separable weight at offset `dy` (zero outside the width).
    pub fn factor_y(&self, dy: f32) -> f32 {
        self.factor(dy, self.ywidth)
    }

    fn factor(&self, d: f32, width: f32) -> f32 {
        let r = width * 0.5;
        if d.abs() > r {
            return 0.0;
        }
        match self.kind {
            FilterKind::Box => 1.0,
            FilterKind::Triangle => 1.0 - d.abs() / r,
            // The spec's RiGaussianFilter, exp(-2·((dx/rx)² + (dy/ry)²)) as the product of
            // its two factors: widths scale the argument so it reaches exp(-2) at the edge.
            FilterKind::Gaussian => {
                let u = d / r;
                (-2.0 * u * u).exp()
            }
            _ => self.kind.eval(d, width),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::FILTER_NAMES;

    #[test]
    fn gaussian_reaches_exp_minus_two_at_its_edge() {
        let f = PixelFilter::new("gaussian", 2.0, 2.0);
        assert!((f.weight(1.0, 0.0) - (-2.0f32).exp()).abs() < 1e-6);
        assert_eq!(f.weight(1.01, 0.0), 0.0);
        assert_eq!(f.weight(0.0, 0.0), 1.0);
    }

    #[test]
    fn catmull_rom_is_zero_at_integer_radii() {
        for name in ["catmull-rom", "catrom", "separable-catmull-rom"] {
            let f = PixelFilter::new(name, 4.0, 4.0);
            assert_eq!(f.kind, FilterKind::CatmullRom, "{name}");
            assert!(f.weight(1.0, 0.0).abs() < 1e-6);
            assert!(f.weight(0.0, 2.0).abs() < 1e-6);
            assert!(f.weight(1.5, 0.0) < 0.0);
        }
    }

    #[test]
    fn triangle_and_box_shapes() {
        let t = PixelFilter::new("triangle", 2.0, 2.0);
        assert!((t.weight(0.5, 0.0) - 0.5).abs() < 1e-6);
        let b = PixelFilter::new("box", 1.0, 1.0);
        assert_eq!(b.weight(0.49, -0.49), 1.0);
        assert_eq!(b.weight(0.51, 0.0), 0.0);
    }

    #[test]
    fn every_name_gives_its_kernel_peaking_at_the_centre() {
        for &(name, kind) in FILTER_NAMES {
            let f = PixelFilter::new(name, 4.0, 4.0);
            assert_eq!(f.kind, kind, "{name}");
            // Mitchell is the lowest: (8/9)² ≈ 0.79.
            assert!(f.weight(0.0, 0.0) > 0.75, "{name}");
            assert_eq!(f.weight(2.01, 0.0), 0.0, "{name}");
        }
        // Sinc is in pixel units: zero at every integer offset inside the width.
        let s = PixelFilter::new("sinc", 6.0, 6.0);
        assert!(s.weight(1.0, 0.0).abs() < 1e-6 && s.weight(0.0, 2.0).abs() < 1e-6);
    }
}
