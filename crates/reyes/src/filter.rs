//! Pixel reconstruction filters of RI Spec 3.2 §4.1.4 (`RiBoxFilter`, `RiTriangleFilter`,
//! `RiCatmullRomFilter`, `RiGaussianFilter`, `RiSincFilter`), evaluated at an offset (dx, dy) in
//! pixels from the pixel centre. Weights are normalised per pixel by the hider, so negative lobes
//! (catmull-rom, sinc) keep flat regions flat.
use std::f32::consts::PI;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterKind {
    Box,
    Triangle,
    CatmullRom,
    Gaussian,
    Sinc,
    Mitchell,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelFilter {
    pub kind: FilterKind,
    pub xwidth: f32,
    pub ywidth: f32,
}

impl PixelFilter {
    pub fn new(name: &str, xwidth: f32, ywidth: f32) -> PixelFilter {
        let kind = match name {
            "box" => FilterKind::Box,
            "triangle" => FilterKind::Triangle,
            "catmull-rom" | "separable-catmull-rom" => FilterKind::CatmullRom,
            "sinc" => FilterKind::Sinc,
            "mitchell" => FilterKind::Mitchell,
            _ => FilterKind::Gaussian,
        };
        PixelFilter {
            kind,
            xwidth: xwidth.max(1e-3),
            ywidth: ywidth.max(1e-3),
        }
    }

    /// Half-widths: a sample farther than this from a pixel centre has no weight.
    pub fn radius(&self) -> (f32, f32) {
        (self.xwidth * 0.5, self.ywidth * 0.5)
    }

    pub fn weight(&self, dx: f32, dy: f32) -> f32 {
        let (rx, ry) = self.radius();
        if dx.abs() > rx || dy.abs() > ry {
            return 0.0;
        }
        match self.kind {
            FilterKind::Box => 1.0,
            FilterKind::Triangle => (1.0 - dx.abs() / rx) * (1.0 - dy.abs() / ry),
            // The spec's RiGaussianFilter: widths scale the argument so the filter reaches
            // exp(-2) at its edge.
            FilterKind::Gaussian => {
                let x = dx / rx;
                let y = dy / ry;
                (-2.0 * (x * x + y * y)).exp()
            }
            // RiCatmullRomFilter is radial in pixel units.
            FilterKind::CatmullRom => {
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
            FilterKind::Sinc => sinc(dx) * sinc(dy),
            FilterKind::Mitchell => mitchell(dx / rx * 2.0) * mitchell(dy / ry * 2.0),
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

/// Mitchell–Netravali with B = C = 1/3, on [-2, 2].
fn mitchell(x: f32) -> f32 {
    let (b, c) = (1.0 / 3.0, 1.0 / 3.0);
    let x = x.abs();
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x * x * x
            + (-18.0 + 12.0 * b + 6.0 * c) * x * x
            + (6.0 - 2.0 * b)
    } else if x < 2.0 {
        (-b - 6.0 * c) * x * x * x
            + (6.0 * b + 30.0 * c) * x * x
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
    fn gaussian_reaches_exp_minus_two_at_its_edge() {
        let f = PixelFilter::new("gaussian", 2.0, 2.0);
        assert!((f.weight(1.0, 0.0) - (-2.0f32).exp()).abs() < 1e-6);
        assert_eq!(f.weight(1.01, 0.0), 0.0);
        assert_eq!(f.weight(0.0, 0.0), 1.0);
    }

    #[test]
    fn catmull_rom_is_zero_at_integer_radii() {
        let f = PixelFilter::new("catmull-rom", 4.0, 4.0);
        assert!(f.weight(1.0, 0.0).abs() < 1e-6);
        assert!(f.weight(0.0, 2.0).abs() < 1e-6);
        assert!(f.weight(1.5, 0.0) < 0.0);
    }

    #[test]
    fn triangle_and_box_shapes() {
        let t = PixelFilter::new("triangle", 2.0, 2.0);
        assert!((t.weight(0.5, 0.0) - 0.5).abs() < 1e-6);
        let b = PixelFilter::new("box", 1.0, 1.0);
        assert_eq!(b.weight(0.49, -0.49), 1.0);
        assert_eq!(b.weight(0.51, 0.0), 0.0);
    }
}
