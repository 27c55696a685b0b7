//! A program's own pixel filter function (`RiPixelFilter(myfilter, w, h)`): the binding
//! tabulates it ([`FilterTable`]); the in-process renderer filters with the table, and RIB,
//! which can only name a filter, gets the standard kernel closest to it.
use illume_core::filter::{FilterKind, FilterTable, PixelFilter, FILTER_NAMES};

/// The canonical name of the standard kernel nearest to `table` at the same widths: least
/// squared difference of the weights normalised to sum 1 (the hider normalises per pixel, so
/// scale does not matter). Ties go to the earlier name in [`FILTER_NAMES`].
pub fn nearest_standard(table: &FilterTable, xwidth: f32, ywidth: f32) -> &'static str {
    let normalised = |v: &[f32]| -> Vec<f64> {
        let sum: f64 = v.iter().map(|&w| f64::from(w)).sum();
        let s = if sum.abs() > 1e-30 { sum } else { 1.0 };
        v.iter().map(|&w| f64::from(w) / s).collect()
    };
    let user = normalised(&table.values);
    let mut best: Option<(f64, FilterKind)> = None;
    for &(_, kind) in FILTER_NAMES {
        let std = PixelFilter::new(kind.name(), xwidth, ywidth);
        let t = FilterTable::tabulate(table.n, xwidth, ywidth, |x, y| std.weight(x, y));
        let d: f64 = normalised(&t.values)
            .iter()
            .zip(&user)
            .map(|(a, b)| (a - b) * (a - b))
            .sum();
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, kind));
        }
    }
    best.map_or("gaussian", |(_, k)| k.name())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_standard_kernel_is_its_own_nearest() {
        for kind in [
            FilterKind::Box,
            FilterKind::Triangle,
            FilterKind::Gaussian,
            FilterKind::CatmullRom,
            FilterKind::Sinc,
        ] {
            let f = PixelFilter::new(kind.name(), 4.0, 3.0);
            // Scaled by 3: the scale must not matter.
            let t = FilterTable::tabulate(64, 4.0, 3.0, |x, y| 3.0 * f.weight(x, y));
            assert_eq!(nearest_standard(&t, 4.0, 3.0), kind.name());
        }
    }

    #[test]
    fn a_cone_is_nearest_to_the_triangle() {
        let t = FilterTable::tabulate(64, 2.0, 2.0, |x, y| (1.0 - (x * x + y * y).sqrt()).max(0.0));
        assert_eq!(nearest_standard(&t, 2.0, 2.0), "triangle");
    }
}
