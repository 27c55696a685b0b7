//! The bucket stage: the crop window cut into buckets, each listing the pieces that reach it,
//! and one bucket rendered from its list. A piece's grid is shared by every bucket it reaches
//! and freed when the last one is done.
use crate::aov::AovLayout;
use crate::csg::{SolidResolver, NO_SOLID};
use crate::dice::{dice_and_shade, ShadedGrid};
use crate::displacement_bound::Overflow;
use crate::film::{blank_rows, paste, Film, PixelBlock};
use crate::hider::{ns, Counters};
use crate::lens::Lens;
use crate::motion::sample_moving_grid;
use crate::refine::Piece;
use crate::sample_buffer::{SampleBuffer, SampleSetup};
use crate::shader::GridShader;
use crate::visible::{composite, empty_sample};
use illume_ri::Frame;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// The bucket grid over the crop region.
pub(crate) struct BucketLayout {
    /// Crop window x0 x1 y0 y1 (pixels).
    crop: [u32; 4],
    /// Bucket width and height (pixels).
    size: [u32; 2],
    count: [usize; 2],
    /// Filter reach (pixels) added around each piece's raster bound.
    margin: f32,
}

impl BucketLayout {
    pub fn new(crop: [u32; 4], bucket_size: [u32; 2], margin: f32) -> BucketLayout {
        let [cx0, cx1, cy0, cy1] = crop;
        let [bw, bh] = bucket_size.map(|b| b.max(1));
        let nbx = (cx1 - cx0).div_ceil(bw).max(1) as usize;
        let nby = (cy1 - cy0).div_ceil(bh).max(1) as usize;
        BucketLayout {
            crop,
            size: [bw, bh],
            count: [nbx, nby],
            margin,
        }
    }

    /// The crop window x0 x1 y0 y1 (pixels) the buckets cover.
    pub fn crop(&self) -> [u32; 4] {
        self.crop
    }

    /// The height of a bucket (pixels): a band's rows.
    pub fn bucket_height(&self) -> u32 {
        self.size[1]
    }

    /// The number of buckets.
    pub fn bucket_count(&self) -> usize {
        self.count[0] * self.count[1]
    }

    /// The buckets of bucket row `by` (buckets are numbered row by row), and the pixel rows
    /// y0 y1 they cover. Rendering band after band lets the film print whole pixel rows and
    /// hand them on while the next band renders, and frees grids in the order the rows go.
    pub fn band(&self, by: usize) -> (std::ops::Range<usize>, [u32; 2]) {
        let nbx = self.count[0];
        let r = self.rect(by * nbx);
        (by * nbx..(by + 1) * nbx, [r[2], r[3]])
    }

    /// The number of bucket rows.
    pub fn band_count(&self) -> usize {
        self.count[1]
    }

    /// The pixels x0 x1 y0 y1 of bucket `b` (buckets row by row).
    pub fn rect(&self, b: usize) -> [u32; 4] {
        let [cx0, cx1, cy0, cy1] = self.crop;
        let [bw, bh] = self.size;
        let nbx = self.count[0];
        let (bx, by) = ((b % nbx) as u32, (b / nbx) as u32);
        let px0 = cx0 + bx * bw;
        let py0 = cy0 + by * bh;
        [px0, (px0 + bw).min(cx1), py0, (py0 + bh).min(cy1)]
    }

    /// The buckets bx0 bx1 by0 by1 (inclusive) a raster bound grown by the filter margin
    /// overlaps; `None` when it misses the bucket grid.
    pub fn buckets_of(&self, raster: &[f32; 4]) -> Option<[usize; 4]> {
        let [nbx, nby] = self.count;
        let [ox, oy] = [self.crop[0] as f32, self.crop[2] as f32];
        let [bw, bh] = self.size.map(|s| s as f32);
        let m = self.margin;
        let bx0 = ((raster[0] - m - ox) / bw).floor().max(0.0) as usize;
        let bx1 = ((raster[1] + m - ox) / bw).floor();
        let by0 = ((raster[2] - m - oy) / bh).floor().max(0.0) as usize;
        let by1 = ((raster[3] + m - oy) / bh).floor();
        if bx1 < 0.0 || by1 < 0.0 {
            return None;
        }
        let (bx1, by1) = ((bx1 as usize).min(nbx - 1), (by1 as usize).min(nby - 1));
        (bx0 <= bx1 && by0 <= by1).then_some([bx0, bx1, by0, by1])
    }

    /// The first band (bucket row) a raster bound grown by the filter margin reaches, clamped
    /// to the bucket grid: where a lazy refine picks up a piece with that bound.
    pub fn band_of(&self, raster: &[f32; 4]) -> usize {
        let oy = self.crop[2] as f32;
        let bh = self.size[1] as f32;
        let by0 = ((raster[2] - self.margin - oy) / bh).floor().max(0.0) as usize;
        by0.min(self.count[1] - 1)
    }

    /// A raster y above which no sample of band `by` (or of a later band) lies: its first pixel
    /// row less the filter margin (a bucket's samples reach that far out) and a pixel to spare.
    pub fn samples_top(&self, by: usize) -> f32 {
        let (_, [y0, _]) = self.band(by);
        y0 as f32 - self.margin - 1.0
    }

    /// Per bucket of band `band`, the pieces (of `pieces`, in refine order) whose padded raster
    /// bound overlaps it, nearest first.
    pub fn band_lists(&self, band: usize, pieces: &[Piece]) -> Vec<Vec<usize>> {
        let mut lists: Vec<Vec<usize>> = vec![Vec::new(); self.count[0]];
        for (id, p) in pieces.iter().enumerate() {
            if let Some([bx0, bx1, by0, by1]) = self.buckets_of(&p.raster) {
                if (by0..=by1).contains(&band) {
                    for list in &mut lists[bx0..=bx1] {
                        list.push(id);
                    }
                }
            }
        }
        sort_nearest_first(&mut lists, pieces);
        lists
    }

    /// Per bucket, the pieces whose padded raster bound overlaps it, nearest first.
    pub fn lists(&self, pieces: &[Piece]) -> Vec<Vec<usize>> {
        let nbx = self.count[0];
        let mut lists: Vec<Vec<usize>> = vec![Vec::new(); self.bucket_count()];
        for (id, p) in pieces.iter().enumerate() {
            let Some([bx0, bx1, by0, by1]) = self.buckets_of(&p.raster) else {
                continue;
            };
            for by in by0..=by1 {
                for list in &mut lists[by * nbx + bx0..=by * nbx + bx1] {
                    list.push(id);
                }
            }
        }
        sort_nearest_first(&mut lists, pieces);
        lists
    }
}

/// Nearest piece first; at equal depth the earlier piece in refine order (`pieces` are in it).
fn sort_nearest_first(lists: &mut [Vec<usize>], pieces: &[Piece]) {
    for l in lists {
        l.sort_by(|&a, &b| pieces[a].zmin.total_cmp(&pieces[b].zmin).then(a.cmp(&b)));
    }
}

/// A piece's grid, shared by the buckets it overlaps: diced and shaded by the first bucket
/// that needs it, dropped when the last one is done (DESIGN.md, "Parallelism and memory").
pub(crate) struct GridSlot {
    grid: Mutex<Option<Option<Arc<ShadedGrid>>>>,
    /// Buckets that still have to visit this piece.
    remaining: AtomicUsize,
    /// The piece's buckets in each bucket row it reaches when buckets are visited row by row
    /// (0 otherwise): when `remaining` falls to a multiple of it, a row is done with the grid
    /// and it can drop what only that row needed ([`GridSlot::release`]).
    row_buckets: usize,
    /// The grid's [`Overflow`], kept after the grid is freed for the re-bucketing pass.
    pub(crate) overflow: OnceLock<Overflow>,
    /// Whether some bucket diced and shaded the piece (not all culled it as occluded).
    pub(crate) shaded: AtomicBool,
}

impl GridSlot {
    pub(crate) fn new(remaining: usize) -> GridSlot {
        GridSlot::in_rows(remaining, 0)
    }

    /// The slot of a piece whose buckets are visited row by row, `row_buckets` in each row.
    pub(crate) fn in_rows(remaining: usize, row_buckets: usize) -> GridSlot {
        GridSlot {
            grid: Mutex::new(None),
            remaining: AtomicUsize::new(remaining),
            row_buckets,
            overflow: OnceLock::new(),
            shaded: AtomicBool::new(false),
        }
    }

    fn get(
        &self,
        make: impl FnOnce() -> Option<Arc<ShadedGrid>>,
        counters: &Counters,
    ) -> Option<Arc<ShadedGrid>> {
        let mut g = self.grid.lock().unwrap_or_else(|e| e.into_inner());
        let g = g
            .get_or_insert_with(|| {
                let g = make();
                if g.is_some() {
                    let live = counters.live_grids.fetch_add(1, Relaxed) + 1;
                    counters.peak_grids.fetch_max(live, Relaxed);
                }
                g
            })
            .clone();
        self.shaded.store(true, Relaxed);
        if let Some(o) = g.as_ref().and_then(|g| g.overflow) {
            let _ = self.overflow.set(o);
        }
        g
    }

    /// Drops the rows of the grid (if it is held) that no bucket whose samples lie at or below
    /// raster `y` samples ([`ShadedGrid::trim_above`]), when no bucket holds it.
    fn trim_above(&self, y: f32) {
        let mut g = self.grid.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(grid) = g.as_mut().and_then(|g| g.as_mut()).and_then(Arc::get_mut) {
            grid.trim_above(y);
        }
    }

    /// One overlapping bucket is done; the last one frees the grid. The last one of a bucket
    /// row trims it to the rows that buckets whose samples lie at or below `next_top` (the next
    /// row's) may sample: a grid reaching the next row is held until that row is done, most
    /// of it lies in the row just rendered, and trimming it as soon as its own row is done
    /// (not when the whole row of buckets is) keeps a row's worth of whole grids from piling
    /// up (5120×3840 `rib/bench/spotlight.rib`: the held grids' share of the peak heap 4.1 →
    /// 3.1 MB, heaptrack). A bucket releases its grids after dropping its own references, and
    /// the buckets of the next row start after the band, so the trim finds the grid unshared.
    fn release(&self, counters: &Counters, next_top: Option<f32>) {
        let left = self.remaining.fetch_sub(1, Relaxed) - 1;
        if left == 0 {
            let freed = self.grid.lock().unwrap_or_else(|e| e.into_inner()).take();
            if freed.flatten().is_some() {
                counters.live_grids.fetch_sub(1, Relaxed);
            }
        } else if let Some(y) = next_top.filter(|_| self.row_buckets > 0) {
            if left % self.row_buckets == 0 {
                self.trim_above(y);
            }
        }
    }
}

/// Renders one bucket: its pieces nearest first (skipping those behind everything opaque so
/// far), each grid diced and shaded once for all buckets through `grids`, sampled, then the
/// samples composited and developed into the bucket's pixels.
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_bucket(
    frame: &Frame,
    shader: &dyn GridShader,
    pieces: &[Piece],
    grids: &[GridSlot],
    list: &[usize],
    rect: [u32; 4],
    film: &Film,
    setup: &SampleSetup,
    lens: Option<&Lens>,
    counters: &Counters,
    aov: &AovLayout,
    next_top: Option<f32>,
) -> PixelBlock {
    // No piece reaches the bucket: its pixels are what empty samples develop to, made without
    // the samples where that is the same bits (`Film::develop_empty`); the imager still runs.
    if list.is_empty() && aov.stride == 0 {
        let t = Instant::now();
        let n_per = (setup.spp[0] * setup.spp[1]) as usize;
        if let Some(mut block) = film.develop_empty(rect, n_per, empty_sample()) {
            shader.image(&mut block);
            counters.filter_ns.fetch_add(ns(t), Relaxed);
            return block;
        }
    }
    // Samples as far out as the widest filter reaches (an AOV display may filter wider).
    let mut buf = SampleBuffer::new(rect, aov.reach(film.filter.radius()), setup);
    let t_sample = Instant::now();
    let mut shade_elapsed = 0u64;
    for &id in list {
        let piece = &pieces[id];
        if piece.zmin > buf.max_opaque_z() {
            counters.occluded.fetch_add(1, Relaxed);
            continue;
        }
        let t = Instant::now();
        let grid = grids[id].get(|| dice_and_shade(frame, shader, piece, counters), counters);
        shade_elapsed += ns(t);
        let Some(g) = grid.as_deref() else { continue };
        let hits = match &g.motion {
            Some(m) if setup.blur => sample_moving_grid(g, m, id, &frame.camera, lens, &mut buf),
            _ => buf.sample_still_grid(g, id),
        };
        counters.samples.fetch_add(hits, Relaxed);
    }
    counters
        .sample_ns
        .fetch_add(ns(t_sample).saturating_sub(shade_elapsed), Relaxed);
    for &id in list {
        grids[id].release(counters, next_top);
    }
    // Composite each sample front to back, then filter into pixels.
    let t = Instant::now();
    let solids = SolidResolver::new(&frame.solids, &setup.eye_in_solids);
    let solid_of = |order: u64| {
        let prim = pieces[(order >> 32) as usize].prim_index;
        let solid = frame.primitives.get(prim).and_then(|fp| fp.solid);
        solid.unwrap_or(NO_SOLID)
    };
    let aov_in = (aov.stride > 0).then_some((aov, &buf.aov_store[..]));
    counters
        .aov_peak_bytes
        .fetch_max((buf.aov_store.len() * 4) as u64, Relaxed);
    let (composited, aov_samples) =
        composite(&buf.lists, &buf.opaque_z, solids.as_ref(), solid_of, aov_in);
    let mut block = film.develop(rect, &buf.region(), &composited, (&aov_samples, aov.stride));
    // The imager (RI Spec 3.2 `RiImager`) sees filtered pixels before exposure (`Film::print`).
    shader.image(&mut block);
    counters.filter_ns.fetch_add(ns(t), Relaxed);
    block
}

/// Work done while a band renders that is not one of its buckets (see [`BandRenderer::render`]).
pub(crate) type SideTask<'t> = Box<dyn FnOnce() + Send + 't>;

/// One item of a band's parallel loop ([`BandRenderer::render`]).
enum BandWork<'t> {
    Side(SideTask<'t>),
    /// A bucket's index in the layout.
    Bucket(usize),
}

/// Everything a bucket needs besides its pieces: renders one band of buckets at a time (the
/// buckets of a band in parallel) into whole pixel rows.
pub(crate) struct BandRenderer<'a> {
    pub frame: &'a Frame,
    pub shader: &'a dyn GridShader,
    pub layout: &'a BucketLayout,
    pub film: &'a Film,
    pub setup: &'a SampleSetup,
    pub lens: Option<&'a Lens>,
    pub counters: &'a Counters,
    pub aov: &'a AovLayout,
    /// Called after each bucket with (buckets done, buckets to do).
    pub progress: Option<&'a (dyn Fn(usize, usize) + Sync)>,
    pub done: AtomicUsize,
    pub total: AtomicUsize,
}

impl BandRenderer<'_> {
    /// Band `by`'s buckets rendered from `lists` (one per bucket of the band, indices into
    /// `pieces` and `grids`), printed into the band's rows; the `side` tasks (writing the band
    /// before, refining the band after) are run meanwhile.
    ///
    /// The side tasks are items of the band's one parallel loop, ahead of the buckets. They
    /// were a `rayon::join` and a scope's `spawn` around the loop; as items of it, 10
    /// interleaved pairs at 2× Format and 2 threads: wall −5% `sphere`, −4% `teapot`, −8%
    /// `specular_models`, −6% `vase`, +2% `geometry`, CPU −4 to −9% (less time waiting in the
    /// join). Placed after the buckets, for a thread that runs out of buckets to take (the
    /// band's end waits for its slowest bucket), they were 2–5% slower than ahead: a side task
    /// then became the band's last item.
    pub fn render(
        &self,
        by: usize,
        pieces: &[Piece],
        lists: &[Vec<usize>],
        grids: &[GridSlot],
        side: Vec<SideTask>,
    ) -> crate::row_sink::PixelRows {
        let (buckets, rows) = self.layout.band(by);
        let first = buckets.start;
        let [cx0, cx1, _, _] = self.layout.crop;
        let stride = self.aov.stride;
        // Each bucket pastes its pixels as it finishes; every pixel belongs to one bucket, so
        // the rows do not depend on the order buckets finish in.
        let out = Mutex::new(blank_rows([cx0, cx1], rows, stride));
        let next_top = (by + 1 < self.layout.band_count()).then(|| self.layout.samples_top(by + 1));
        let work: Vec<BandWork> = (side.into_iter().map(BandWork::Side))
            .chain(buckets.map(BandWork::Bucket))
            .collect();
        work.into_par_iter().for_each(|w| {
            let b = match w {
                BandWork::Side(task) => return task(),
                BandWork::Bucket(b) => b,
            };
            let block = render_bucket(
                self.frame,
                self.shader,
                pieces,
                grids,
                &lists[b - first],
                self.layout.rect(b),
                self.film,
                self.setup,
                self.lens,
                self.counters,
                self.aov,
                next_top,
            );
            paste(
                &mut out.lock().unwrap_or_else(|e| e.into_inner()),
                &block,
                stride,
            );
            drop(block);
            let n = self.done.fetch_add(1, Relaxed) + 1;
            if let Some(p) = self.progress {
                p(n, self.total.load(Relaxed));
            }
        });
        let mut out = out.into_inner().unwrap_or_else(|e| e.into_inner());
        self.film.expose_rows(&mut out);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_tile_the_crop_window_exactly_once() {
        for (crop, size) in [
            ([0, 64, 0, 48], [16, 16]),
            ([5, 70, 3, 40], [16, 7]),
            ([10, 11, 10, 11], [32, 32]),
        ] {
            let layout = BucketLayout::new(crop, size, 1.0);
            let [cx0, cx1, cy0, cy1] = crop;
            let mut hits = vec![0u32; ((cx1 - cx0) * (cy1 - cy0)) as usize];
            for b in 0..layout.bucket_count() {
                let [x0, x1, y0, y1] = layout.rect(b);
                for y in y0..y1 {
                    for x in x0..x1 {
                        hits[((y - cy0) * (cx1 - cx0) + x - cx0) as usize] += 1;
                    }
                }
            }
            assert!(hits.iter().all(|&h| h == 1), "crop {crop:?} size {size:?}");
        }
    }
}
