//! The film: what happens to composited samples on their way to pixels. Each bucket's samples
//! are filtered into a [`PixelBlock`] (pixel filter for colour, depth filter for `z`), each
//! sample splatted over the pixels its weight reaches through the frame's tabulated filter
//! ([`crate::filter::FilterWeights`]); the blocks of one band of buckets are pasted into whole rows and exposed (RI Spec 3.2 `RiExposure`).
//! Quantization and dithering are the displays' business (`illume-imageio`, through the
//! driver): the film hands over premultiplied float RGBA and depth.
//!
//! Why a stage of its own: streaming output (each band of buckets printed into whole rows and
//! handed to a [`crate::RowSink`] while later bands render) and arbitrary output variables both
//! extend what a bucket hands over, not how it is rendered.
use crate::aov::AovLayout;
use crate::filter::{FilterWeights, PixelFilter, SplatScratch};
use crate::row_sink::PixelRows;
use glam::Vec4;
use illume_ri::{DepthFilter, Options};
use std::ops::Range;

/// One sample after visible-point compositing.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Composited {
    /// Premultiplied colour and alpha.
    pub rgba: [f32; 4],
    /// Depth of the nearest visible point (`f32::MAX` for none).
    pub z: f32,
    /// Halfway between the nearest and the second-nearest visible point (`depthfilter
    /// "midpoint"`; the nearest when there is one).
    pub z_mid: f32,
}

/// The samples of a bucket as the film sees them: a rectangle of pixels (grown by the
/// filter's reach) with `per_pixel` samples each, pixel by pixel, rows first.
pub(crate) struct SampleRegion<'s> {
    /// First pixel (x, y) and size (pixels) of the region.
    pub origin: [i32; 2],
    pub size: [usize; 2],
    pub per_pixel: usize,
    /// Raster position of each sample.
    pub pos: &'s [(f32, f32)],
}

/// One bucket's finished pixels: the unit streaming output and AOVs extend.
#[derive(Clone, Debug, Default)]
pub struct PixelBlock {
    /// Pixel rectangle x0 x1 y0 y1 (exclusive ends) in the full frame.
    pub rect: [u32; 4],
    /// Filtered premultiplied RGBA per pixel, top row first.
    pub rgba: Vec<[f32; 4]>,
    /// Camera-space depth per pixel after the depth filter (`f32::MAX` where nothing was hit).
    pub z: Vec<f32>,
    /// Filtered AOV records per pixel (`stride` floats each; empty without AOVs).
    pub aov: Vec<f32>,
}

/// The frame's film settings.
pub(crate) struct Film {
    pub filter: PixelFilter,
    /// The pixel filter as the film evaluates it (tabulated once per frame).
    weights: FilterWeights,
    /// The record floats of each output variable with its own filter, and that filter.
    own_filters: Vec<(Range<usize>, FilterWeights)>,
    /// Whether filters are evaluated exactly ([`Film::use_exact_filter`]).
    exact: bool,
    depth_filter: DepthFilter,
    /// `RiExposure` gain and gamma.
    exposure: (f32, f32),
}

impl Film {
    pub fn new(opts: &Options) -> Film {
        let filter = PixelFilter::new(&opts.filter.0, opts.filter.1, opts.filter.2)
            .with_table(opts.filter_table.clone());
        Film {
            weights: FilterWeights::new(&filter),
            filter,
            own_filters: Vec::new(),
            exact: false,
            depth_filter: opts.depth_filter,
            exposure: opts.exposure,
        }
    }

    /// Gives the output variables whose display names its own filter ([`crate::AovChannel`]'s
    /// `filter`) their tabulated weights; the others develop with the pixel filter's.
    pub fn set_aovs(&mut self, layout: &AovLayout) {
        let exact = self.exact;
        self.own_filters = layout
            .channels
            .iter()
            .zip(&layout.offsets)
            .filter_map(|(c, &off)| {
                let f = c.filter.as_ref()?;
                let weights = if exact {
                    FilterWeights::exact(f)
                } else {
                    FilterWeights::new(f)
                };
                Some((off..off + c.components, weights))
            })
            .collect();
    }

    /// Evaluates every filter exactly instead of through its table: the reference path the
    /// tables are checked against (`illume_render::render_with_exact_filter`).
    pub fn use_exact_filter(&mut self) {
        self.exact = true;
        self.weights = FilterWeights::exact(&self.filter);
        for (_, w) in &mut self.own_filters {
            *w = FilterWeights::exact(&w.filter);
        }
    }

    /// Filters the samples of `region` into the pixels of `rect` (x0 x1 y0 y1): colour by the
    /// pixel filter over every sample within its reach, depth by the depth filter over the
    /// pixel's own samples. `aov` holds `stride` composited AOV floats per sample, filtered
    /// with the same weights as the colour (or a channel's own filter, [`Film::set_aovs`]).
    pub fn develop(
        &self,
        rect: [u32; 4],
        region: &SampleRegion,
        samples: &[Composited],
        (aov, stride): (&[f32], usize),
    ) -> PixelBlock {
        let [px0, px1, py0, py1] = rect;
        let pixels = (px1.saturating_sub(px0) * py1.saturating_sub(py0)) as usize;
        // Per pixel its weighted colour, four lanes at once (the same products and sums as
        // channel by channel, so the same bits), and its weight sum beside it: one bounds
        // check per weight, and the closures own their slices, so the splat keeps the
        // pointers in registers. The accumulation took 29 instructions per weight, now 12.
        let mut acc = vec![(Vec4::ZERO, 0.0f32); pixels];
        let mut aov_px = vec![0.0f32; pixels * stride];
        let mut scratch = SplatScratch::default();
        let colour = |acc: &mut (Vec4, f32), s: usize, w: f32| {
            acc.1 += w;
            acc.0 += Vec4::from_array(samples[s].rgba) * w;
        };
        if stride == 0 {
            let live = self
                .weights
                .nonneg()
                .then(|| live_cells(region, samples, self.filter.radius()));
            let acc = &mut acc[..];
            self.weights.splat_live(
                rect,
                region,
                &mut scratch,
                live.as_deref(),
                move |k, s, w| colour(&mut acc[k], s, w),
            );
        } else {
            let (acc, aov_px) = (&mut acc[..], &mut aov_px[..]);
            self.weights
                .splat(rect, region, &mut scratch, move |k, s, w| {
                    colour(&mut acc[k], s, w);
                    let rec = &aov[s * stride..(s + 1) * stride];
                    for (a, v) in aov_px[k * stride..(k + 1) * stride].iter_mut().zip(rec) {
                        *a += w * v;
                    }
                });
        }
        let mut rgba = Vec::with_capacity(pixels);
        for (k, &(px, ws)) in acc.iter().enumerate() {
            if ws != 0.0 {
                rgba.push((px / ws).to_array());
                aov_px[k * stride..(k + 1) * stride]
                    .iter_mut()
                    .for_each(|v| *v /= ws);
            } else {
                rgba.push(px.to_array());
            }
        }
        for (span, weights) in &self.own_filters {
            own_filter(
                weights,
                rect,
                region,
                (aov, stride),
                span.clone(),
                &mut aov_px,
            );
        }
        PixelBlock {
            rect,
            rgba,
            z: self.depths(rect, region, samples),
            aov: aov_px,
        }
    }

    /// What [`Film::develop`] makes of `rect` when every sample is `empty` (what
    /// [`crate::visible::empty_sample`] composites) and nothing has output variables, or
    /// `None` where that could differ in a bit: only weights `≥ 0` are sure to develop black
    /// to `+0.0` (a negative weight sum turns it into `−0.0`). Why: a bucket that no piece
    /// reaches (the sky around a model) then costs no sample positions, compositing or
    /// splat: `rib/sphere.rib` at 2× took 10% fewer instructions, `rib/teapot.rib` 14%.
    pub fn develop_empty(
        &self,
        rect: [u32; 4],
        per_pixel: usize,
        empty: Composited,
    ) -> Option<PixelBlock> {
        if !self.weights.nonneg() {
            return None;
        }
        let [px0, px1, py0, py1] = rect;
        let pixels = (px1.saturating_sub(px0) * py1.saturating_sub(py0)) as usize;
        let depth = self.depth(&vec![empty; per_pixel]);
        Some(PixelBlock {
            rect,
            rgba: vec![[0.0; 4]; pixels],
            z: vec![depth; pixels],
            aov: Vec::new(),
        })
    }

    /// The depth filter over each pixel's own samples, pixels of `rect` rows first.
    fn depths(&self, rect: [u32; 4], region: &SampleRegion, samples: &[Composited]) -> Vec<f32> {
        let [px0, px1, py0, py1] = rect;
        let [sx0, sy0] = region.origin;
        let (sw, n_per) = (region.size[0], region.per_pixel);
        let mut depth =
            Vec::with_capacity((px1.saturating_sub(px0) * py1.saturating_sub(py0)) as usize);
        for y in py0..py1 {
            for x in px0..px1 {
                let base = (((y as i32 - sy0) as usize) * sw + (x as i32 - sx0) as usize) * n_per;
                depth.push(self.depth(&samples[base..base + n_per]));
            }
        }
        depth
    }

    /// `RiDepthFilter` over one pixel's own samples.
    fn depth(&self, own: &[Composited]) -> f32 {
        let zs = own.iter().map(|c| {
            if self.depth_filter == DepthFilter::Midpoint {
                c.z_mid
            } else {
                c.z
            }
        });
        match self.depth_filter {
            DepthFilter::Min | DepthFilter::Midpoint => zs.fold(f32::MAX, f32::min),
            DepthFilter::Max => zs.fold(f32::MIN, f32::max),
            DepthFilter::Average => {
                let (sum, n) = zs
                    .filter(|&z| z < f32::MAX)
                    .fold((0.0f32, 0u32), |(s, n), z| (s + z, n + 1));
                if n == 0 {
                    f32::MAX
                } else {
                    sum / n as f32
                }
            }
        }
    }

    /// Exposes one band's rows once every bucket's block is pasted in ([`blank_rows`],
    /// [`paste`]): premultiplied RGBA, depth and AOV records (not exposed), top row first.
    pub fn expose_rows(&self, rows: &mut PixelRows) {
        self.expose(&mut rows.rgba);
    }

    /// Exposure (RI Spec 3.2 `RiExposure`): c' = (gain·c)^(1/gamma) on colour, not alpha.
    fn expose(&self, rgba: &mut [f32]) {
        let (gain, gamma) = self.exposure;
        if gain != 1.0 || gamma != 1.0 {
            for px in rgba.chunks_exact_mut(4) {
                for c in &mut px[..3] {
                    *c = (*c * gain).max(0.0).powf(1.0 / gamma);
                }
            }
        }
    }
}

/// Rows `y0..y1` of columns `x0..x1` before any block is pasted in: black, depth `f32::MAX`.
pub(crate) fn blank_rows([x0, x1]: [u32; 2], [y0, y1]: [u32; 2], stride: usize) -> PixelRows {
    let (width, height) = (x1 - x0, y1 - y0);
    PixelRows {
        x0,
        y0,
        width,
        height,
        rgba: vec![0.0f32; (width * height * 4) as usize],
        z: vec![f32::MAX; (width * height) as usize],
        aov: vec![0.0f32; (width * height) as usize * stride],
    }
}

/// Copies one bucket's developed pixels into the rows (`stride` AOV floats per pixel). A
/// bucket pastes its block as soon as it is done, so a band's blocks are never all held
/// beside its rows (at 5120 pixels wide, 1.6 MB).
pub(crate) fn paste(rows: &mut PixelRows, b: &PixelBlock, stride: usize) {
    let (x0, y0, width) = (rows.x0, rows.y0, rows.width);
    let [bx0, bx1, by0, _] = b.rect;
    let bwid = bx1 - bx0;
    for (k, (pc, pz)) in b.rgba.iter().zip(&b.z).enumerate() {
        let (x, y) = (bx0 - x0 + k as u32 % bwid, by0 - y0 + k as u32 / bwid);
        let o = (y * width + x) as usize;
        rows.rgba[o * 4..o * 4 + 4].copy_from_slice(pc);
        rows.z[o] = *pz;
        if let Some(rec) = b.aov.get(k * stride..(k + 1) * stride) {
            rows.aov[o * stride..(o + 1) * stride].copy_from_slice(rec);
        }
    }
}

/// The sample cells (pixels of `region`, rows first) whose samples a splat with weights
/// `≥ 0` must visit: those within twice the filter's reach (in whole cells) of a cell holding
/// a sample that is not black. Every other sample is black and reaches only pixels whose
/// samples are all black; such a pixel sums `+0.0` (a weight `≥ 0` times `±0.0`, added to
/// `+0.0`) and develops to `+0.0` whatever its weight sum, so skipping them leaves the same
/// bits. A pixel with some sample that is not black within reach gets all its samples, in
/// the same order. The empty sky around a model costs no filtering.
fn live_cells(region: &SampleRegion, samples: &[Composited], (rx, ry): (f32, f32)) -> Vec<bool> {
    let [w, h] = region.size;
    let n_per = region.per_pixel.max(1);
    let cells = w * h;
    if samples.len() < cells * n_per || region.pos.len() < cells * n_per {
        return vec![true; cells];
    }
    // How far a sample's pixels can lie from its cell: its offset from the cell's centre
    // plus the filter's reach, plus the margin `span` (filter.rs) grows by.
    let [ox, oy] = region.origin;
    let mut dev = 0.0f32;
    let mut big = 0.0f32;
    let mut black = vec![true; cells];
    for (c, b) in black.iter_mut().enumerate() {
        let (cx, cy) = (
            (ox + (c % w) as i32) as f32 + 0.5,
            (oy + (c / w) as i32) as f32 + 0.5,
        );
        let cell = c * n_per..(c + 1) * n_per;
        for (&(sx, sy), sample) in region.pos[cell.clone()].iter().zip(&samples[cell]) {
            dev = dev.max((sx - cx).abs()).max((sy - cy).abs());
            big = big.max(sx.abs()).max(sy.abs());
            *b &= sample.rgba.iter().all(|&v| v == 0.0);
        }
    }
    let eps = 1.0 / 32.0 + (big + 2.0) * 8.0 * f32::EPSILON;
    let reach = dev + rx.max(ry) + eps;
    if !reach.is_finite() || reach > (w.max(h)) as f32 {
        return vec![true; cells];
    }
    let r = 2 * reach as usize;
    // Dilate the cells that are not black by `r` cells, rows then columns.
    let mut rows = vec![false; cells];
    for y in 0..h {
        let line = &black[y * w..(y + 1) * w];
        for x in 0..w {
            rows[y * w + x] = line[x.saturating_sub(r)..(x + r + 1).min(w)]
                .iter()
                .any(|&b| !b);
        }
    }
    let mut live = vec![false; cells];
    for y in 0..h {
        for x in 0..w {
            live[y * w + x] = (y.saturating_sub(r)..(y + r + 1).min(h)).any(|v| rows[v * w + x]);
        }
    }
    live
}

/// Re-develops the record floats `span` of every pixel of `rect` with a channel's own filter
/// (a display's `"filter"`/`"filterwidth"`), over what the pixel filter left in `pixels`.
fn own_filter(
    weights: &FilterWeights,
    rect: [u32; 4],
    region: &SampleRegion,
    (aov, stride): (&[f32], usize),
    span: Range<usize>,
    pixels: &mut [f32],
) {
    let n = span.len();
    let count = pixels.len() / stride.max(1);
    let mut acc = vec![0.0f32; count * n];
    let mut wsum = vec![0.0f32; count];
    weights.splat(rect, region, &mut SplatScratch::default(), |k, s, w| {
        wsum[k] += w;
        let rec = &aov[s * stride + span.start..s * stride + span.end];
        for (a, v) in acc[k * n..(k + 1) * n].iter_mut().zip(rec) {
            *a += w * v;
        }
    });
    for (k, (values, &ws)) in acc.chunks_mut(n.max(1)).zip(&wsum).enumerate() {
        if ws != 0.0 {
            values.iter_mut().for_each(|v| *v /= ws);
        }
        pixels[k * stride + span.start..k * stride + span.end].copy_from_slice(values);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options(filter: &str, depth: DepthFilter, exposure: (f32, f32)) -> Options {
        Options {
            filter: (filter.to_string(), 2.0, 2.0),
            depth_filter: depth,
            exposure,
            ..Options::default()
        }
    }

    /// A 4×4-pixel sample region at (−1, −1), 2 samples per pixel, with `f(s)` per sample.
    fn develop(film: &Film, f: impl Fn(usize) -> Composited) -> PixelBlock {
        let pos: Vec<(f32, f32)> = (0..32)
            .map(|s| {
                let (p, k) = (s / 2, s % 2);
                let (x, y) = ((p % 4) as f32 - 1.0, (p / 4) as f32 - 1.0);
                (x + 0.25 + 0.5 * k as f32, y + 0.25 + 0.5 * k as f32)
            })
            .collect();
        let samples: Vec<Composited> = (0..32).map(f).collect();
        let region = SampleRegion {
            origin: [-1, -1],
            size: [4, 4],
            per_pixel: 2,
            pos: &pos,
        };
        film.develop([0, 2, 0, 2], &region, &samples, (&[], 0))
    }

    #[test]
    fn a_flat_field_stays_flat_through_any_filter() {
        for name in ["box", "triangle", "gaussian", "catmull-rom", "sinc"] {
            let film = Film::new(&options(name, DepthFilter::Min, (1.0, 1.0)));
            let rgba = [0.25, 0.5, 0.75, 1.0];
            let block = develop(&film, |_| Composited {
                rgba,
                z: 1.0,
                z_mid: 1.0,
            });
            for px in &block.rgba {
                for (a, b) in px.iter().zip(rgba) {
                    assert!((a - b).abs() < 1e-6, "{name}: {px:?}");
                }
            }
        }
    }

    /// The empty-bucket shortcut is the bits `develop` makes of empty samples, for every
    /// filter whose weights are `≥ 0` and every depth filter; the filters with negative lobes
    /// are not given it.
    #[test]
    fn an_empty_bucket_develops_to_the_same_bits_without_its_samples() {
        let empty = crate::visible::empty_sample();
        let bits = |b: &PixelBlock| {
            let rgba = b.rgba.iter().flatten().map(|v| v.to_bits());
            (
                rgba.collect::<Vec<_>>(),
                b.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            )
        };
        for depth in [
            DepthFilter::Min,
            DepthFilter::Max,
            DepthFilter::Average,
            DepthFilter::Midpoint,
        ] {
            for name in ["box", "triangle", "gaussian", "catmull-rom", "sinc"] {
                let film = Film::new(&options(name, depth, (1.0, 1.0)));
                let shortcut = film.develop_empty([0, 2, 0, 2], 2, empty);
                match (film.weights.nonneg(), shortcut) {
                    (true, Some(b)) => assert_eq!(bits(&b), bits(&develop(&film, |_| empty))),
                    (false, None) => {}
                    (nonneg, b) => panic!("{name}: weights ≥ 0 {nonneg}, shortcut {b:?}"),
                }
            }
        }
        let film = Film::new(&options("gaussian", DepthFilter::Min, (1.0, 1.0)));
        assert!(film.develop_empty([0, 2, 0, 2], 2, empty).is_some());
        assert_eq!(
            film.develop_empty([0, 2, 0, 2], 2, empty).unwrap().z,
            vec![f32::MAX; 4]
        );
    }

    #[test]
    fn depth_filters_reduce_a_pixels_own_samples() {
        // Sample s has depth 10 + s, except sample 11, which hit nothing.
        let z = |s: usize| if s == 11 { f32::MAX } else { 10.0 + s as f32 };
        let sample = |s: usize| Composited {
            rgba: [0.0; 4],
            z: z(s),
            z_mid: z(s) + 0.5,
        };
        // Pixel (0, 0) is region pixel (1, 1) = index 5: samples 10 and 11.
        let depth = |f| develop(&Film::new(&options("box", f, (1.0, 1.0))), sample).z[0];
        assert_eq!(depth(DepthFilter::Min), 20.0);
        assert_eq!(depth(DepthFilter::Max), f32::MAX);
        assert_eq!(depth(DepthFilter::Average), 20.0);
        assert_eq!(depth(DepthFilter::Midpoint), 20.5);
    }

    #[test]
    fn exposure_is_gain_then_gamma_on_colour_only() {
        let film = Film::new(&options("box", DepthFilter::Min, (2.0, 2.0)));
        let block = PixelBlock {
            rect: [0, 1, 0, 1],
            rgba: vec![[0.125, 0.5, 0.0, 0.5]],
            z: vec![3.0],
            aov: Vec::new(),
        };
        let mut rows = blank_rows([0, 1], [0, 1], 0);
        paste(&mut rows, &block, 0);
        film.expose_rows(&mut rows);
        for (a, b) in rows.rgba.iter().zip([0.5, 1.0, 0.0, 0.5]) {
            assert!((a - b).abs() < 1e-6, "{:?}", rows.rgba);
        }
        assert_eq!(rows.z, vec![3.0]);
    }

    /// A jittered sample region around `rect` grown by `reach` pixels, `n_per` samples per
    /// pixel from a fixed LCG, with colours and `stride` AOV floats per sample in [0, 1].
    struct Jittered {
        pos: Vec<(f32, f32)>,
        samples: Vec<Composited>,
        aov: Vec<f32>,
        origin: [i32; 2],
        size: [usize; 2],
        n_per: usize,
    }

    fn jittered(rect: [u32; 4], reach: i32, n_per: usize, stride: usize) -> Jittered {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let origin = [rect[0] as i32 - reach, rect[2] as i32 - reach];
        let size = [
            (rect[1] - rect[0]) as usize + 2 * reach as usize,
            (rect[3] - rect[2]) as usize + 2 * reach as usize,
        ];
        let (mut pos, mut samples, mut aov) = (Vec::new(), Vec::new(), Vec::new());
        for y in 0..size[1] as i32 {
            for x in 0..size[0] as i32 {
                for _ in 0..n_per {
                    let p = (
                        (origin[0] + x) as f32 + rnd(),
                        (origin[1] + y) as f32 + rnd(),
                    );
                    pos.push(p);
                    let a = rnd();
                    samples.push(Composited {
                        rgba: [rnd() * a, rnd() * a, rnd() * a, a],
                        z: 1.0,
                        z_mid: 1.0,
                    });
                    aov.extend((0..stride).map(|_| rnd()));
                }
            }
        }
        Jittered {
            pos,
            samples,
            aov,
            origin,
            size,
            n_per,
        }
    }

    /// The gather the splat replaced (one pixel at a time over the sample cells within the
    /// filter's radius, [`PixelFilter::weight`] per sample), colour and AOVs.
    fn gather(f: &PixelFilter, rect: [u32; 4], j: &Jittered, stride: usize) -> Vec<f32> {
        let (rx, ry) = f.radius();
        let [sx0, sy0] = j.origin;
        let (sx1, sy1) = (sx0 + j.size[0] as i32, sy0 + j.size[1] as i32);
        let mut out = Vec::new();
        for y in rect[2]..rect[3] {
            for x in rect[0]..rect[1] {
                let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
                let mut acc = vec![0.0f32; 4 + stride];
                let mut wsum = 0.0f32;
                for qy in
                    ((cy - ry).floor() as i32).max(sy0)..=((cy + ry).floor() as i32).min(sy1 - 1)
                {
                    for qx in ((cx - rx).floor() as i32).max(sx0)
                        ..=((cx + rx).floor() as i32).min(sx1 - 1)
                    {
                        let q = ((qy - sy0) as usize) * j.size[0] + (qx - sx0) as usize;
                        for s in q * j.n_per..(q + 1) * j.n_per {
                            let w = f.weight(j.pos[s].0 - cx, j.pos[s].1 - cy);
                            if w != 0.0 {
                                wsum += w;
                                let rec = j.samples[s].rgba.iter();
                                let rec = rec.chain(&j.aov[s * stride..(s + 1) * stride]);
                                for (a, v) in acc.iter_mut().zip(rec) {
                                    *a += w * v;
                                }
                            }
                        }
                    }
                }
                if wsum != 0.0 {
                    acc.iter_mut().for_each(|a| *a /= wsum);
                }
                out.extend(acc);
            }
        }
        out
    }

    fn developed(film: &Film, rect: [u32; 4], j: &Jittered, stride: usize) -> Vec<f32> {
        let region = SampleRegion {
            origin: j.origin,
            size: j.size,
            per_pixel: j.n_per,
            pos: &j.pos,
        };
        let block = film.develop(rect, &region, &j.samples, (&j.aov, stride));
        let recs = block.aov.chunks(stride.max(1));
        block
            .rgba
            .iter()
            .zip(recs)
            .flat_map(|(c, r)| c.iter().chain(&r[..stride]).copied().collect::<Vec<_>>())
            .collect()
    }

    const FILTERS: [(&str, f32, f32); 8] = [
        ("box", 1.0, 1.0),
        ("triangle", 2.0, 2.0),
        ("gaussian", 2.0, 2.0),
        ("gaussian", 3.3, 1.7),
        ("catmull-rom", 4.0, 4.0),
        ("mitchell", 4.0, 4.0),
        ("sinc", 6.0, 6.0),
        ("lanczos", 4.0, 3.0),
    ];

    #[test]
    fn the_exact_splat_is_the_gather_it_replaced_bit_for_bit() {
        // Same weights, same per-pixel summation order (samples in index order): same bits.
        let rect = [5, 13, 7, 12];
        for (name, xw, yw) in FILTERS {
            let mut opts = options(name, DepthFilter::Min, (1.0, 1.0));
            opts.filter = (name.to_string(), xw, yw);
            let mut film = Film::new(&opts);
            film.use_exact_filter();
            let j = jittered(rect, 4, 5, 2);
            let old = gather(&film.filter, rect, &j, 2);
            assert_eq!(developed(&film, rect, &j, 2), old, "{name} {xw}x{yw}");
        }
    }

    #[test]
    fn tabulated_weights_stay_within_1e_4_of_the_exact_image() {
        // Colours in [0, 1]; each weight within 4e-6 of the exact one (`filter.rs`), so a
        // normalised sum of many weights of order 0.1–1 moves by far less than 1e-4.
        let rect = [5, 13, 7, 12];
        for (name, xw, yw) in FILTERS {
            let mut opts = options(name, DepthFilter::Min, (1.0, 1.0));
            opts.filter = (name.to_string(), xw, yw);
            let film = Film::new(&opts);
            for n_per in [1, 4, 16] {
                let j = jittered(rect, 4, n_per, 1);
                let old = gather(&film.filter, rect, &j, 1);
                let new = developed(&film, rect, &j, 1);
                let worst = old
                    .iter()
                    .zip(&new)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0f32, f32::max);
                assert!(worst <= 1e-4, "{name} {xw}x{yw}, {n_per} spp: {worst:e}");
            }
        }
    }
}
