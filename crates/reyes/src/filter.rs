//! The pixel reconstruction filters of RI Spec 3.2 §4.1.4 live with the other filter kernels
//! and their one name table in [`illume_core::filter`]; re-exported for the hider. Here: the
//! frame's filter as the film evaluates it, tabulated once per frame (issue 21 part 3), and how
//! one sample spreads over the pixels its weight reaches ([`FilterWeights::splat`]).
//!
//! Why a table: samples are jittered per sample, so no two share an offset and weights cannot
//! be precomputed per subpixel position; the separable 1-D factors are instead tabulated finely
//! over the filter's half-width and interpolated linearly, which replaces an `expf` (Gaussian),
//! `sinf` (sinc, Lanczos) or cubic per factor by a load and a multiply-add. The support test
//! `|d| > r` stays exact, so a box or a windowed sinc keeps its hard edge.
//!
//! Error (checked by `tests::tables_stay_within_their_stated_error`): with at least
//! [`ENTRIES_PER_PIXEL`] entries per pixel of half-width and never fewer than [`MIN_ENTRIES`],
//! the linear interpolant is within `h²/8 · max|f''|` of each factor; for every kernel at
//! widths 0.5–16 that is below [`TABLE_ERROR`] (2e-6 of the kernel's peak of 1), so a weight
//! (a product of two factors, each at most 1 in magnitude) is within 4e-6 of the exact one.
//! Summed over a pixel's samples that stays under 1e-4 of the pixel's weight sum (the issue's
//! bound; `tests::a_pixels_weights_stay_within_1e_4_of_their_sum`, at one sample per pixel and
//! any width from the kernel's default up; the sum is of |w|, since a negative lobe can cancel
//! a pixel's signed sum to nearly zero whatever the weights' accuracy). The per-pixel
//! normalisation divides by the sum of the same tabulated weights, so a flat field stays
//! exactly flat. The tables cost 16–64 KB per frame.
pub use illume_core::filter::{FilterKind, PixelFilter};

/// Entries per pixel of a factor's half-width.
pub(crate) const ENTRIES_PER_PIXEL: usize = 1024;
/// Entries over a factor's half-width at least (a narrow filter's curvature grows as its
/// width shrinks; the table's resolution follows the width, not the pixel grid).
pub(crate) const MIN_ENTRIES: usize = 2048;
/// The largest difference between a tabulated factor and the exact one, for the kernels and
/// widths the tests sweep (the peak of every factor is 1).
pub const TABLE_ERROR: f32 = 2e-6;

/// One separable factor, `f(|d|)` sampled at `n + 1` evenly spaced offsets over `[0, r]`
/// (plus a copy of the last, so the interpolation at `|d| = r` reads in bounds).
#[derive(Clone, Debug)]
struct Factor {
    radius: f32,
    /// Entries per unit of offset: `n / r`.
    scale: f32,
    /// `f` at offsets `i·r/n` (`i` in `0..=n`) and at `i + 1` (the last repeated): the two
    /// ends of the interval a lookup interpolates in, one bounds check and one load instead
    /// of two of each.
    pairs: Vec<[f32; 2]>,
}

impl Factor {
    fn new(radius: f32, exact: impl Fn(f32) -> f32) -> Factor {
        let pixels = radius.ceil().max(1.0) as usize;
        Factor::with_entries(radius, (pixels * ENTRIES_PER_PIXEL).max(MIN_ENTRIES), exact)
    }

    /// `n` intervals over `[0, radius]`.
    fn with_entries(radius: f32, n: usize, exact: impl Fn(f32) -> f32) -> Factor {
        let mut values: Vec<f32> = (0..=n)
            .map(|i| exact((i as f32 * radius / n as f32).min(radius)))
            .collect();
        values.push(values[n]);
        Factor {
            radius,
            scale: n as f32 / radius,
            pairs: values.windows(2).map(|w| [w[0], w[1]]).collect(),
        }
    }

    /// The factor at offset `d`: zero outside the support and for a NaN offset, else the
    /// linear interpolant of the table. Written for the instruction count, since the splat
    /// calls it six times per sample (callgrind, `rib/sphere.rib` at 2×: 45 instructions a
    /// call before, 25 after): one compare that a NaN also fails, an `i32` index and its
    /// `f32` (a `usize` one converts back to float through an unsigned-overflow branch), one
    /// bounds-checked pair. The arithmetic is the same, so the same bits.
    #[inline(always)]
    fn at(&self, d: f32) -> f32 {
        let a = d.abs();
        if a <= self.radius {
            let t = a * self.scale;
            // `t` is in `[0, n]`; the cast saturates like any `as`, so any `t` is safe.
            let i = (t as i32).min(self.pairs.len() as i32 - 1);
            let f = t - i as f32;
            let [v0, v1] = self.pairs[i as usize];
            v0 + f * (v1 - v0)
        } else {
            0.0
        }
    }
}

/// How the factors are evaluated.
#[derive(Clone, Debug)]
enum Eval {
    /// Tabulated separable factors (the frame's default).
    Table(Factor, Factor),
    /// `RiCatmullRomFilter`, radial: its profile tabulated over the squared distance.
    Radial(Factor),
    /// The exact kernel: [`PixelFilter::weight`] (a filter that is not separable, or the
    /// reference the tests compare the tables with).
    Exact,
}

/// A pixel filter ready for the film: its kernel, tabulated once per frame.
#[derive(Clone, Debug)]
pub(crate) struct FilterWeights {
    pub filter: PixelFilter,
    eval: Eval,
    /// Whether every weight the splat can hand out is `≥ 0` (tabulated separable factors with
    /// no negative entry): then a pixel whose samples are all black develops to `+0.0`
    /// whatever its weight sum, so [`FilterWeights::splat`] may skip such samples.
    nonneg: bool,
}

/// Reused per-bucket storage of [`FilterWeights::splat`]: one sample's nonzero column and row
/// factors (pixel index in the block, factor).
#[derive(Default)]
pub(crate) struct SplatScratch {
    xs: Vec<(usize, f32)>,
    ys: Vec<(usize, f32)>,
}

impl FilterWeights {
    /// `filter` tabulated (separable kernels per factor, the radial Catmull–Rom over r²) or
    /// evaluated exactly (a program's 2-D filter table, already a table).
    pub fn new(filter: &PixelFilter) -> FilterWeights {
        let mut nonneg = false;
        let eval = if filter.is_separable() {
            let (rx, ry) = filter.radius();
            let (fx, fy) = (
                Factor::new(rx, |d| filter.factor_x(d)),
                Factor::new(ry, |d| filter.factor_y(d)),
            );
            nonneg = (fx.pairs.iter().chain(&fy.pairs)).all(|p| p[0] >= 0.0 && p[1] >= 0.0);
            Eval::Table(fx, fy)
        } else if filter.kind == FilterKind::CatmullRom && filter.table.is_none() {
            Eval::Radial(radial_profile(filter))
        } else {
            Eval::Exact
        };
        FilterWeights {
            filter: filter.clone(),
            eval,
            nonneg,
        }
    }

    /// `filter` evaluated exactly, factor by factor: the reference for the tables.
    pub fn exact(filter: &PixelFilter) -> FilterWeights {
        FilterWeights {
            filter: filter.clone(),
            eval: Eval::Exact,
            nonneg: false,
        }
    }

    /// The horizontal and vertical factors at offsets `dx`, `dy` (the tests; separable).
    #[cfg(test)]
    fn factors(&self, dx: f32, dy: f32) -> (f32, f32) {
        match &self.eval {
            Eval::Table(fx, fy) => (fx.at(dx), fy.at(dy)),
            _ => (self.filter.factor_x(dx), self.filter.factor_y(dy)),
        }
    }

    /// Spreads every sample of `region` over the pixels of `rect` (x0 x1 y0 y1) its weight
    /// reaches: calls `add(pixel, sample, weight)` for each nonzero weight, pixel index rows
    /// first within `rect`. Samples are visited in order, so each pixel sums its samples in
    /// the same order as a gather over the sample cells around it would, and the sums are
    /// the same bits for any bucket order or thread count.
    ///
    /// A separable weight is the product of a column and a row factor, so each sample
    /// evaluates its factors once per column (row) it may reach, keeps the nonzero ones, and
    /// visits only the pixels where both are nonzero (a radius-1 filter: 2×2 pixels per
    /// sample instead of the 3×3 cells' samples per pixel of a gather).
    ///
    /// A sample counts by its position, not its pixel: the one case where that differs from
    /// a gather is a sample whose jittered position rounded onto its pixel's far edge
    /// (`px + 1.0` in f32) under a kernel with a hard edge at a half-integer radius (box 1,
    /// a 3-wide Gaussian), where a gather skipped it for the neighbour it touches. A kernel
    /// that is not separable is gathered (`splat_2d`).
    pub fn splat(
        &self,
        rect: [u32; 4],
        region: &crate::film::SampleRegion,
        scratch: &mut SplatScratch,
        add: impl FnMut(usize, usize, f32),
    ) {
        self.splat_live(rect, region, scratch, None, add)
    }

    /// Whether every weight is `≥ 0`, so samples may be skipped as [`Self::splat_live`] says.
    pub fn nonneg(&self) -> bool {
        self.nonneg
    }

    /// [`Self::splat`] over the sample cells (pixels of `region`) `live` marks, all of them
    /// for `None`. A tabulated separable kernel visits only the live cells' samples (the
    /// gathers ignore `live`); the caller marks dead only cells whose skipped weights
    /// cannot change what it develops (black samples around black pixels, [`Self::nonneg`]).
    pub fn splat_live(
        &self,
        rect: [u32; 4],
        region: &crate::film::SampleRegion,
        scratch: &mut SplatScratch,
        live: Option<&[bool]>,
        add: impl FnMut(usize, usize, f32),
    ) {
        let [px0, px1, py0, py1] = rect;
        if px1 <= px0 || py1 <= py0 {
            return;
        }
        let f = &self.filter;
        match &self.eval {
            Eval::Table(fx, fy) => splat_separable(
                f,
                rect,
                region,
                scratch,
                live,
                |d| fx.at(d),
                |d| fy.at(d),
                add,
            ),
            Eval::Exact if f.is_separable() => splat_separable(
                f,
                rect,
                region,
                scratch,
                None,
                |d| f.factor_x(d),
                |d| f.factor_y(d),
                add,
            ),
            Eval::Radial(profile) => {
                let (rx, ry) = f.radius();
                let w = |dx: f32, dy: f32| {
                    if dx.abs() > rx || dy.abs() > ry {
                        0.0
                    } else {
                        profile.at(dx * dx + dy * dy)
                    }
                };
                splat_2d(f, rect, region, w, add)
            }
            Eval::Exact => splat_2d(f, rect, region, |dx, dy| f.weight(dx, dy), add),
        }
    }
}

/// Intervals of the radial Catmull–Rom's profile over the squared distance `[0, 4]`: in `t =
/// r²` the profile `1 − 2.5t + 1.5t^{3/2}` has unbounded curvature at 0, where linear
/// interpolation errs by about `0.22·h^{3/2}`; 16384 intervals (64 KB) keep that under 1e-6.
const RADIAL_ENTRIES: usize = 16384;

/// The radial Catmull–Rom's profile over the squared distances its box `rx × ry` holds (at
/// most 4, where it ends): no square root per weight. Each entry is the exact weight at an
/// offset of that length inside the box.
fn radial_profile(f: &PixelFilter) -> Factor {
    let (rx, ry) = f.radius();
    let reach = (rx * rx + ry * ry).min(4.0);
    Factor::with_entries(reach, RADIAL_ENTRIES, |t| {
        let r = t.max(0.0).sqrt();
        let a = r.min(rx);
        f.weight(a, (r * r - a * a).max(0.0).sqrt().min(ry))
    })
}

/// `⌊v⌋` without a libm call (the default x86-64 target has no `roundss`); exact for the
/// raster positions a frame holds.
#[inline]
fn floor(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) > v {
        t - 1
    } else {
        t
    }
}

/// `⌈v⌉`, as [`floor`].
#[inline]
fn ceil(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) < v {
        t + 1
    } else {
        t
    }
}

/// Candidate pixels of a sample at `c` along one axis for a filter reaching `r`, clipped to
/// `lo..hi`: the pixels whose centre `x + ½` lies within `r` of `c`, grown by a margin of a
/// few float ulps of `c` (and 1/64 pixel), since the factor's own `|d| ≤ r` test on the
/// offset `c − (x + ½)` (the one a gather computes) decides. The margin rarely adds a pixel.
#[inline]
fn span(c: f32, r: f32, lo: u32, hi: u32) -> std::ops::RangeInclusive<i64> {
    let eps = 1.0 / 64.0 + c.abs() * 4.0 * f32::EPSILON;
    ceil(c - 0.5 - r - eps).max(lo as i64)..=floor(c - 0.5 + r + eps).min(hi as i64 - 1)
}

/// The most columns (rows) a cell's samples may reach for the cell-wise splat: a filter up to
/// about 7 pixels wide. A wider one takes [`splat_sample_spans`].
const MAX_CELL_REACH: usize = 8;

/// The pixels along one axis that samples between two positions may reach: the union of
/// their [`span`]s (`span` grows monotonically with its centre), as the block's first index,
/// a count (0: none; above [`MAX_CELL_REACH`]: too many for the cell-wise splat) and the
/// pixel centres the per-sample spans compute (`x as f32 + 0.5`).
#[derive(Clone, Copy)]
struct Reach {
    first: usize,
    n: usize,
    centre: [f32; MAX_CELL_REACH],
}

impl Reach {
    fn new(lo: f32, hi: f32, r: f32, px0: u32, px1: u32) -> Reach {
        let (start, end) = (*span(lo, r, px0, px1).start(), *span(hi, r, px0, px1).end());
        let mut reach = Reach {
            first: 0,
            n: 0,
            centre: [0.0; MAX_CELL_REACH],
        };
        // Both ends lie in the block when the range is not empty, so nothing overflows.
        if lo <= hi && start <= end {
            reach.first = (start - px0 as i64) as usize;
            reach.n = (end - start + 1) as usize;
            for (k, c) in reach.centre.iter_mut().enumerate().take(reach.n) {
                *c = (start + k as i64) as f32 + 0.5;
            }
        }
        reach
    }
}

/// Whether every sample of `region` lies in its own cell (pixel), edges included: then a
/// cell's samples reach what its edges' spans reach, the same for a whole column (row) of
/// cells. Sample positions are made so ([`crate::sampling`]); anything else (a NaN) makes
/// the splat bound each cell by its samples instead.
fn samples_in_cells(region: &crate::film::SampleRegion) -> bool {
    let [ox, oy] = region.origin;
    let (w, n_per) = (region.size[0].max(1), region.per_pixel.max(1));
    region.pos.chunks(n_per).enumerate().all(|(c, cell)| {
        let (x0, y0) = ((ox + (c % w) as i32) as f32, (oy + (c / w) as i32) as f32);
        cell.iter()
            .all(|&(x, y)| x >= x0 && x <= x0 + 1.0 && y >= y0 && y <= y0 + 1.0)
    })
}

/// [`FilterWeights::splat`] for a separable kernel with factors `fx`, `fy`.
///
/// Why cell by cell: the pixels a sample may reach depend on its position only through the
/// ends of its [`span`]s, and the samples of one cell (pixel) lie in that pixel, so the
/// union of their spans is known per column and per row of cells ([`Reach`]). Each sample
/// then evaluates its factor at the few columns and rows of that union instead of finding its
/// own spans (two floors and two ceilings per axis) and collecting the nonzero factors; a
/// column outside the sample's own span gets a factor of zero (its offset exceeds the radius
/// by the span's margin) and is skipped as before. So the same weights reach the same pixels
/// in the same sample order, bit for bit. Measured (callgrind, `rib/sphere.rib` at 2×): the
/// splat went from 744 M to 454 M instructions (with the table lookup of [`Factor::at`] and the
/// film's four-lane accumulation, the frame from 3.56 G to 3.27 G).
#[allow(clippy::too_many_arguments)]
fn splat_separable(
    f: &PixelFilter,
    rect: [u32; 4],
    region: &crate::film::SampleRegion,
    scratch: &mut SplatScratch,
    live: Option<&[bool]>,
    fx: impl Fn(f32) -> f32,
    fy: impl Fn(f32) -> f32,
    mut add: impl FnMut(usize, usize, f32),
) {
    let [px0, px1, py0, py1] = rect;
    let bw = (px1 - px0) as usize;
    let (rx, ry) = f.radius();
    let n_per = region.per_pixel.max(1);
    let ([ox, oy], w) = (region.origin, region.size[0].max(1));
    let in_cells = samples_in_cells(region);
    let (cols, rows): (Vec<Reach>, Vec<Reach>) = if in_cells {
        let edge = |o: i32, k: usize| (o + k as i32) as f32;
        (
            (0..w)
                .map(|i| Reach::new(edge(ox, i), edge(ox, i) + 1.0, rx, px0, px1))
                .collect(),
            (0..region.size[1])
                .map(|j| Reach::new(edge(oy, j), edge(oy, j) + 1.0, ry, py0, py1))
                .collect(),
        )
    } else {
        (Vec::new(), Vec::new())
    };
    for (c, cell) in region.pos.chunks(n_per).enumerate() {
        if live.is_some_and(|l| !l.get(c).copied().unwrap_or(true)) {
            continue;
        }
        let (cx, cy) = if in_cells {
            (cols[c % w], rows[c / w])
        } else {
            // `min`/`max` skip a NaN position (its factors are all zero).
            let [x_lo, x_hi, y_lo, y_hi] = cell.iter().fold(
                [
                    f32::INFINITY,
                    f32::NEG_INFINITY,
                    f32::INFINITY,
                    f32::NEG_INFINITY,
                ],
                |b, &(x, y)| [b[0].min(x), b[1].max(x), b[2].min(y), b[3].max(y)],
            );
            (
                Reach::new(x_lo, x_hi, rx, px0, px1),
                Reach::new(y_lo, y_hi, ry, py0, py1),
            )
        };
        if cx.n == 0 || cy.n == 0 {
            continue;
        }
        let first = c * n_per;
        if cx.n > MAX_CELL_REACH || cy.n > MAX_CELL_REACH {
            let samples = (first, first + cell.len());
            splat_sample_spans(
                (rx, ry),
                rect,
                region,
                samples,
                scratch,
                (&fx, &fy),
                &mut add,
            );
            continue;
        }
        // A cell that reaches at most 3 × 3 pixels (every filter of radius up to 1, the
        // default `gaussian 2 2` among them) takes loops of a fixed length the compiler
        // unrolls (`rib/sphere.rib` at 2×: −2.1% instructions; the splat took 186 per sample).
        let reach = (&cx, &cy);
        if cx.n <= 3 && cy.n <= 3 {
            splat_cell::<3>(cell, first, reach, bw, (&fx, &fy), &mut add);
        } else {
            splat_cell::<MAX_CELL_REACH>(cell, first, reach, bw, (&fx, &fy), &mut add);
        }
    }
}

/// [`splat_separable`]'s loop over one cell's samples (the first at `first`), for a cell that
/// reaches at most `R × R` pixels: each sample's column factors, then per row its factor and
/// the nonzero products. The columns and rows beyond the cell's reach are never added to.
#[inline]
fn splat_cell<const R: usize>(
    cell: &[(f32, f32)],
    first: usize,
    (cx, cy): (&Reach, &Reach),
    bw: usize,
    (fx, fy): (&impl Fn(f32) -> f32, &impl Fn(f32) -> f32),
    add: &mut impl FnMut(usize, usize, f32),
) {
    for (j, &(sx, sy)) in cell.iter().enumerate() {
        let wx: [f32; R] =
            std::array::from_fn(|k| if k < cx.n { fx(sx - cx.centre[k]) } else { 0.0 });
        if wx == [0.0; R] {
            continue;
        }
        for ky in 0..R {
            if ky == cy.n {
                break;
            }
            let wyk = fy(sy - cy.centre[ky]);
            if wyk == 0.0 {
                continue;
            }
            let row = (cy.first + ky) * bw + cx.first;
            for (kx, &wxk) in wx.iter().enumerate().take(cx.n) {
                let w = wxk * wyk;
                if w != 0.0 {
                    add(row + kx, first + j, w);
                }
            }
        }
    }
}

/// The splat of samples `from..to` sample by sample, each over its own [`span`]s: for a
/// filter too wide for [`splat_separable`]'s cell-wise arrays.
fn splat_sample_spans(
    (rx, ry): (f32, f32),
    [px0, px1, py0, py1]: [u32; 4],
    region: &crate::film::SampleRegion,
    (from, to): (usize, usize),
    scratch: &mut SplatScratch,
    (fx, fy): (&impl Fn(f32) -> f32, &impl Fn(f32) -> f32),
    add: &mut impl FnMut(usize, usize, f32),
) {
    let bw = (px1 - px0) as usize;
    let SplatScratch { xs, ys } = scratch;
    for (s, &(sx, sy)) in region.pos[from..to]
        .iter()
        .enumerate()
        .map(|(j, p)| (from + j, p))
    {
        xs.clear();
        for x in span(sx, rx, px0, px1) {
            let w = fx(sx - (x as f32 + 0.5));
            if w != 0.0 {
                xs.push(((x - px0 as i64) as usize, w));
            }
        }
        if xs.is_empty() {
            continue;
        }
        ys.clear();
        for y in span(sy, ry, py0, py1) {
            let w = fy(sy - (y as f32 + 0.5));
            if w != 0.0 {
                ys.push(((y - py0 as i64) as usize * bw, w));
            }
        }
        for &(row, wy) in ys.iter() {
            for &(col, wx) in xs.iter() {
                let w = wx * wy;
                if w != 0.0 {
                    add(row + col, s, w);
                }
            }
        }
    }
}

/// [`FilterWeights::splat`] for a kernel that is not a product of factors (the radial
/// Catmull–Rom, a program's 2-D table): a gather, pixel by pixel over the sample cells within
/// the filter's box, since a 2-D weight has no per-axis factors to share between pixels and
/// a pixel's sums stay in registers (measured: the splat was 10% slower here).
fn splat_2d(
    f: &PixelFilter,
    [px0, px1, py0, py1]: [u32; 4],
    region: &crate::film::SampleRegion,
    weight: impl Fn(f32, f32) -> f32,
    mut add: impl FnMut(usize, usize, f32),
) {
    let (rx, ry) = f.radius();
    let [sx0, sy0] = region.origin;
    let (sw, n_per) = (region.size[0], region.per_pixel);
    let (sx1, sy1) = (sx0 + sw as i32, sy0 + region.size[1] as i32);
    let mut k = 0;
    for y in py0..py1 {
        for x in px0..px1 {
            let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
            let qx0 = (floor(cx - rx) as i32).max(sx0);
            let qx1 = (floor(cx + rx) as i32).min(sx1 - 1);
            for qy in (floor(cy - ry) as i32).max(sy0)..=(floor(cy + ry) as i32).min(sy1 - 1) {
                let row = ((qy - sy0) as usize) * sw;
                let first = (row + (qx0 - sx0) as usize) * n_per;
                let last = (row + (qx1 - sx0) as usize + 1) * n_per;
                for s in first..last.max(first) {
                    let (sx, sy) = region.pos[s];
                    let w = weight(sx - cx, sy - cy);
                    if w != 0.0 {
                        add(k, s, w);
                    }
                }
            }
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use illume_core::filter::FILTER_NAMES;

    #[test]
    fn tables_stay_within_their_stated_error() {
        for &(name, _) in FILTER_NAMES {
            for width in [0.5f32, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 16.0] {
                let f = PixelFilter::new(name, width, width * 0.75);
                let w = FilterWeights::new(&f);
                let exact = FilterWeights::exact(&f);
                if !f.is_separable() {
                    continue;
                }
                let mut worst = 0.0f32;
                // Dense offsets across and beyond the support, off the table's nodes.
                for i in -20_000..=20_000 {
                    let d = i as f32 * width * 0.6 / 20_000.0 + 1.3e-6;
                    let (a, b) = w.factors(d, d * 0.75);
                    let (ea, eb) = exact.factors(d, d * 0.75);
                    worst = worst.max((a - ea).abs()).max((b - eb).abs());
                }
                assert!(worst <= TABLE_ERROR, "{name} width {width}: {worst:e}");
            }
        }
    }

    #[test]
    fn the_radial_catmull_rom_profile_stays_within_the_stated_error() {
        for (xw, yw) in [(4.0f32, 4.0f32), (2.0, 3.0), (6.0, 5.0)] {
            let f = PixelFilter::new("catmull-rom", xw, yw);
            let Eval::Radial(profile) = FilterWeights::new(&f).eval else {
                panic!("catmull-rom {xw}x{yw} is not tabulated radially");
            };
            let mut worst = 0.0f32;
            for i in -400..=400 {
                for j in -400..=400 {
                    let (dx, dy) = (i as f32 * xw * 0.0013 + 1e-5, j as f32 * yw * 0.0013);
                    let w = if dx.abs() > xw / 2.0 || dy.abs() > yw / 2.0 {
                        0.0
                    } else {
                        profile.at(dx * dx + dy * dy)
                    };
                    worst = worst.max((w - f.weight(dx, dy)).abs());
                }
            }
            assert!(worst <= TABLE_ERROR, "catmull-rom {xw}x{yw}: {worst:e}");
        }
    }

    #[test]
    fn a_table_keeps_the_hard_edge_and_the_peak() {
        let f = PixelFilter::new("box", 1.0, 1.0);
        let w = FilterWeights::new(&f);
        assert_eq!(w.factors(0.5, -0.5), (1.0, 1.0));
        assert_eq!(w.factors(0.500_001, 0.0).0, 0.0);
        let g = FilterWeights::new(&PixelFilter::new("gaussian", 2.0, 2.0));
        assert_eq!(g.factors(0.0, 0.0), (1.0, 1.0));
        assert!((g.factors(1.0, 0.0).0 - (-2.0f32).exp()).abs() < 1e-6);
        assert_eq!(g.factors(1.01, f32::NAN), (0.0, 0.0));
    }

    /// The splat hands out exactly the weights a brute force over every pixel of the block
    /// finds with the same factors, in the same order (sample by sample, pixels rows first):
    /// samples inside their cells (the cell-wise reach), outside them and NaN (each cell
    /// bounded by its samples), and filters too wide for the cell-wise arrays.
    #[test]
    fn the_splat_gives_every_nonzero_weight_a_brute_force_finds() {
        let mut h = 0x2545_f491u32;
        let mut unit = move || {
            h ^= h << 13;
            h ^= h >> 17;
            h ^= h << 5;
            (h >> 8) as f32 / 16_777_216.0
        };
        for (name, width) in [
            ("box", 1.0f32),
            ("box", 2.0),
            ("gaussian", 2.0),
            ("gaussian", 3.0),
            ("triangle", 2.5),
            ("sinc", 4.0),
            ("mitchell", 4.0),
            ("lanczos", 6.0),
            ("gaussian", 20.0),
        ] {
            let f = PixelFilter::new(name, width, width * 0.75);
            let w = FilterWeights::new(&f);
            assert!(matches!(w.eval, Eval::Table(..)), "{name}");
            let (n_per, size) = (4usize, [14usize, 11usize]);
            for layout in 0..3 {
                let pos: Vec<(f32, f32)> = (0..size[0] * size[1] * n_per)
                    .map(|i| {
                        let c = i / n_per;
                        let (x, y) = ((c % size[0]) as f32 - 3.0, (c / size[0]) as f32 - 2.0);
                        match (layout, i % 7) {
                            // On the cell's edges now and then (jitter 0 and 1).
                            (0, 0) => (x, y + 1.0),
                            (0, _) | (1, 1..) => (x + unit(), y + unit()),
                            (1, _) => (x + 3.0 * unit() - 1.0, y - unit()),
                            (_, 3) => (f32::NAN, y),
                            _ => (x + unit(), y + unit()),
                        }
                    })
                    .collect();
                let region = crate::film::SampleRegion {
                    origin: [-3, -2],
                    size,
                    per_pixel: n_per,
                    pos: &pos,
                };
                let rect = [0u32, 8, 0, 7];
                let mut got = Vec::new();
                w.splat(rect, &region, &mut SplatScratch::default(), |k, s, w| {
                    got.push((k, s, w.to_bits()))
                });
                let mut want = Vec::new();
                for (s, &(sx, sy)) in pos.iter().enumerate() {
                    for y in rect[2]..rect[3] {
                        for x in rect[0]..rect[1] {
                            let (a, b) = w.factors(sx - (x as f32 + 0.5), sy - (y as f32 + 0.5));
                            let k = ((y - rect[2]) * (rect[1] - rect[0]) + x - rect[0]) as usize;
                            if a != 0.0 && a * b != 0.0 {
                                want.push((k, s, (a * b).to_bits()));
                            }
                        }
                    }
                }
                assert!(!want.is_empty());
                assert_eq!(got, want, "{name} {width} layout {layout}");
            }
        }
    }

    #[test]
    fn a_pixels_weights_stay_within_1e_4_of_their_sum() {
        use std::collections::HashMap;
        // One sample per pixel (the smallest weight sums) at jittered positions.
        let pos: Vec<(f32, f32)> = (0..24 * 24)
            .map(|i| {
                let (x, y) = ((i % 24) as f32 - 8.0, (i / 24) as f32 - 8.0);
                let h = (i as u32).wrapping_mul(2_654_435_761);
                (
                    x + (h >> 8 & 1023) as f32 / 1024.0,
                    y + (h >> 18) as f32 / 16384.0,
                )
            })
            .collect();
        let region = crate::film::SampleRegion {
            origin: [-8, -8],
            size: [24, 24],
            per_pixel: 1,
            pos: &pos,
        };
        let rect = [0, 8, 0, 8];
        for &(name, kind) in FILTER_NAMES {
            for scale in [1.0f32, 1.5, 3.0] {
                let width = kind.default_width() * scale;
                let f = PixelFilter::new(name, width, width);
                let weights = |w: FilterWeights| {
                    let mut m = HashMap::new();
                    w.splat(rect, &region, &mut SplatScratch::default(), |k, s, w| {
                        m.insert((k, s), w);
                    });
                    m
                };
                let (table, exact) = (
                    weights(FilterWeights::new(&f)),
                    weights(FilterWeights::exact(&f)),
                );
                let mut err = [0.0f64; 64];
                let mut sum = [0.0f64; 64];
                for (&(k, s), &w) in &exact {
                    sum[k] += w.abs() as f64;
                    err[k] += (table.get(&(k, s)).copied().unwrap_or(0.0) - w).abs() as f64;
                }
                for (&(k, s), &w) in &table {
                    if !exact.contains_key(&(k, s)) {
                        err[k] += w.abs() as f64;
                    }
                }
                for k in 0..64 {
                    assert!(
                        err[k] <= 1e-4 * sum[k],
                        "{name} {width}: pixel {k}: error {:e} of sum {}",
                        err[k],
                        sum[k]
                    );
                }
            }
        }
    }
}
