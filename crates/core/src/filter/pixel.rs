//! The pixel reconstruction filter of `PixelFilter` (RI Spec 3.2 §4.1.4), evaluated at an
//! offset (dx, dy) in pixels from the pixel centre. Weights are normalised per pixel by the
//! hider, so negative lobes (catmull-rom, sinc) keep flat regions flat.
//!
//! The spec's `RiGaussianFilter` and `RiCatmullRomFilter` are radial: the Gaussian's widths
//! scale its argument, Catmull–Rom is in pixel units (zero at radius 2). The other kernels are
//! the separable products of the 1-D kernels of [`super::FilterKind::eval`].
use super::FilterKind;
use std::sync::Arc;

/// A program's own filter function (the C binding's `RtFilterFunc`), tabulated once per frame:
/// `n`×`n` weights at the cell centres of the support `[-xwidth/2, xwidth/2]` ×
/// `[-ywidth/2, ywidth/2]`, row `j` (y) major. Looking weights up in a table keeps the hider
/// free of calls into foreign code (threads, panics) and its bits independent of them.
#[derive(Clone, Debug, PartialEq)]
pub struct FilterTable {
    pub n: usize,
    pub values: Vec<f32>,
}

impl FilterTable {
    /// Tabulates `f(x, y)` on an `n`×`n` grid over the support of the given full widths.
    pub fn tabulate(
        n: usize,
        xwidth: f32,
        ywidth: f32,
        mut f: impl FnMut(f32, f32) -> f32,
    ) -> Self {
        let n = n.max(1);
        let mut values = Vec::with_capacity(n * n);
        for j in 0..n {
            let y = ((j as f32 + 0.5) / n as f32 - 0.5) * ywidth;
            for i in 0..n {
                let x = ((i as f32 + 0.5) / n as f32 - 0.5) * xwidth;
                let w = f(x, y);
                values.push(if w.is_finite() { w } else { 0.0 });
            }
        }
        FilterTable { n, values }
    }

    /// The weight of the cell holding (u, v) in [0, 1]² of the support.
    fn lookup(&self, u: f32, v: f32) -> f32 {
        let cell = |t: f32| ((t * self.n as f32) as usize).min(self.n - 1);
        self.values[cell(v) * self.n + cell(u)]
    }
}

/// A pixel filter: a kernel and its full widths in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelFilter {
    pub kind: FilterKind,
    pub xwidth: f32,
    pub ywidth: f32,
    /// A program's filter function, which replaces `kind` (kept as its nearest standard kernel).
    pub table: Option<Arc<FilterTable>>,
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
            table: None,
        }
    }

    /// This filter with a program's tabulated function in place of its kernel.
    pub fn with_table(mut self, table: Option<Arc<FilterTable>>) -> PixelFilter {
        self.table = table;
        self
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
        if let Some(t) = &self.table {
            return t.lookup(0.5 + 0.5 * dx / rx, 0.5 + 0.5 * dy / ry);
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
            FilterKind::Sinc | FilterKind::Mitchell | FilterKind::Lanczos => {
                self.kind.eval(dx, self.xwidth) * self.kind.eval(dy, self.ywidth)
            }
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
    fn a_table_is_looked_up_by_cell_and_zero_outside_the_support() {
        // f(x, y) = x + 10 y at the cell centres of a 4×4 table over widths 4 × 2.
        let t = FilterTable::tabulate(4, 4.0, 2.0, |x, y| x + 10.0 * y);
        assert_eq!(t.values[0], -1.5 - 7.5);
        assert_eq!(t.values[15], 1.5 + 7.5);
        let f = PixelFilter::new("box", 4.0, 2.0).with_table(Some(Arc::new(t)));
        // (0.3, 0.6) lies in the cell centred on (0.5, 0.75).
        assert_eq!(f.weight(0.3, 0.6), 0.5 + 7.5);
        assert_eq!(f.weight(-2.0, -1.0), -1.5 - 7.5);
        assert_eq!(f.weight(2.0, 1.0), 1.5 + 7.5);
        assert_eq!(f.weight(2.01, 0.0), 0.0);
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
