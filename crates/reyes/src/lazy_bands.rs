//! Lazy refinement (issue 21: memory that does not grow with the frame). As in PRMan and Aqsis,
//! a primitive is not split into dice-ready pieces up front: it waits, bound only, at the first
//! band of buckets (bucket row, in visiting order) its raster bound touches. When that band
//! comes, the primitive is split one level at a time; a child whose bound first touches a later
//! band waits there in turn, and only dice-ready pieces that reach this band stay. A piece lives
//! until the last band it overlaps is done, its grid only until the last bucket that needs it is
//! done ([`GridSlot`]). So the pieces, grids and bucket lists held at once are those of about one
//! band, whatever the image size.
//!
//! The image is the one an up-front refine of the whole frame gives, bit for bit: refining is
//! depth first and depends on the primitive and the camera only (`refine.rs`), so the same
//! pieces come out, diced the same; bucket lists hold the same pieces; and pieces keep the
//! frame-wide refine order ([`Piece::refine_order`]) that breaks depth ties between samples.
//! Each band's waiting items are refined in parallel and merged in order, so the result does
//! not depend on the thread count.
use crate::bucket::{BucketLayout, GridSlot, SideTask};
use crate::refine::{Item, Piece, PrimRef, RefineCounts, Refined, Refiner};
use illume_ri::Frame;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::time::Instant;

/// What refining the frame counted.
#[derive(Default)]
pub(crate) struct RefineReport {
    /// Dice-ready pieces made.
    pub pieces: u64,
    pub culled: u64,
    /// Per primitive (index), pieces dropped at the eye plane or the split depth limit.
    pub dropped: BTreeMap<usize, u64>,
    /// Wall time spent refining.
    pub split_ns: u64,
    /// The most pieces (dice-ready or waiting) held at once.
    pub peak_live_pieces: u64,
    /// Dice-ready pieces whose bound reached a band already rendered (a child bound outside its
    /// parent's): they miss those buckets. Zero for the primitives of this renderer.
    pub late_pieces: u64,
}

/// One band's waiting items refined: its dice-ready pieces in refine order, the items
/// deferred to later bands, and what refining them counted.
struct BandRefine<'f> {
    fresh: Vec<Piece<'f>>,
    deferred: Vec<(usize, Item<'f>)>,
    report: RefineReport,
}

impl RefineReport {
    /// Adds the counts of a refine done apart (peaks are the caller's).
    fn merge(&mut self, other: RefineReport) {
        self.pieces += other.pieces;
        self.culled += other.culled;
        for (prim, n) in other.dropped {
            *self.dropped.entry(prim).or_default() += n;
        }
        self.split_ns += other.split_ns;
        self.late_pieces += other.late_pieces;
    }

    /// Adds the report of another column block's render (of peaks, the larger).
    pub(crate) fn add_block(&mut self, other: RefineReport) {
        self.peak_live_pieces = self.peak_live_pieces.max(other.peak_live_pieces);
        self.merge(other);
    }

    fn add(&mut self, prim_index: usize, counts: &RefineCounts) {
        self.culled += counts.culled;
        if counts.eye_dropped > 0 {
            *self.dropped.entry(prim_index).or_default() += counts.eye_dropped;
        }
    }
}

/// The frame's primitives as refine items, moving primitives with the motion keys the shutter
/// sees.
fn frame_items<'f>(frame: &'f Frame) -> impl IndexedParallelIterator<Item = Item<'f>> + 'f {
    let [open, close] = frame.options.shutter;
    frame.primitives.par_iter().enumerate().map(move |(i, fp)| {
        // A moving primitive keeps its keys unless the shutter is closed at (or before) its
        // first key, where it is exactly its first key.
        let later = match &fp.motion {
            Some(m) if close > open || m.times.first().is_some_and(|&t| open > t) => m
                .later
                .iter()
                .map(|k| PrimRef::Borrowed(k.as_ref()))
                .collect(),
            _ => Vec::new(),
        };
        Item::primitive(PrimRef::Borrowed(fp.primitive.as_ref()), later, i)
    })
}

/// Whether some primitive moves over the open shutter (its pieces may then carry motion).
pub(crate) fn frame_moves(frame: &Frame) -> bool {
    let [open, close] = frame.options.shutter;
    frame.primitives.iter().any(|fp| {
        fp.motion.as_ref().is_some_and(|m| {
            !m.later.is_empty() && (close > open || m.times.first().is_some_and(|&t| open > t))
        })
    })
}

/// Refines `items` in parallel with `defer`, merging the results in item order.
fn refine_all<'f>(
    frame: &'f Frame,
    refiner: &Refiner,
    items: impl IndexedParallelIterator<Item = Item<'f>>,
    defer: &(dyn Fn(&[f32; 4]) -> Option<usize> + Sync),
    report: &mut RefineReport,
) -> (Vec<Piece<'f>>, Vec<(usize, Item<'f>)>) {
    let t = Instant::now();
    let refined: Vec<(usize, Refined)> = items
        .map(|item| {
            let prim_index = item.prim_index;
            let attrs = &frame.primitives[prim_index].attributes;
            let mut out = Refined::default();
            refiner.refine(item, attrs, defer, &mut out);
            (prim_index, out)
        })
        .collect();
    let (mut pieces, mut deferred) = (Vec::new(), Vec::new());
    for (prim_index, r) in refined {
        report.add(prim_index, &r.counts);
        report.pieces += r.pieces.len() as u64;
        pieces.extend(r.pieces);
        deferred.extend(r.deferred);
    }
    report.split_ns += t.elapsed().as_nanos() as u64;
    (pieces, deferred)
}

/// Every primitive of the frame refined up front into dice-ready pieces, in refine order (what
/// the displacement-bound loop needs: it may grow any piece and render the frame again).
pub(crate) fn refine_frame<'f>(
    frame: &'f Frame,
    refiner: &Refiner,
    report: &mut RefineReport,
) -> Vec<Piece<'f>> {
    let (pieces, _) = refine_all(frame, refiner, frame_items(frame), &|_| None, report);
    report.peak_live_pieces = pieces.len() as u64;
    pieces
}

/// A displaced grid left its bound while rendering lazily: the frame must be rendered by the
/// displacement-bound loop instead (`displacement_bound.rs`).
pub(crate) struct Overflowed;

/// The frame's refine state between bands.
pub(crate) struct LazyBands<'f, 'l> {
    frame: &'f Frame,
    refiner: &'l Refiner<'f>,
    layout: &'l BucketLayout,
    /// Per band, the items waiting for it.
    waiting: Vec<Vec<Item<'f>>>,
    waiting_count: usize,
    /// Dice-ready pieces that reach the current band or a later one, in refine order, and
    /// their grids.
    pieces: Vec<Piece<'f>>,
    grids: Vec<GridSlot>,
    pub report: RefineReport,
}

impl<'f, 'l> LazyBands<'f, 'l> {
    /// Every primitive bound and culled, split across the eye plane, and put to wait at its
    /// first band.
    pub fn new(
        frame: &'f Frame,
        refiner: &'l Refiner<'f>,
        layout: &'l BucketLayout,
    ) -> LazyBands<'f, 'l> {
        let mut bands = LazyBands {
            frame,
            refiner,
            layout,
            waiting: (0..layout.band_count()).map(|_| Vec::new()).collect(),
            waiting_count: 0,
            pieces: Vec::new(),
            grids: Vec::new(),
            report: RefineReport::default(),
        };
        let defer = |r: &[f32; 4]| Some(layout.band_of(r));
        let items = frame_items(frame);
        let (pieces, deferred) = refine_all(frame, refiner, items, &defer, &mut bands.report);
        debug_assert!(pieces.is_empty());
        bands.wait(deferred);
        bands
    }

    fn wait(&mut self, deferred: Vec<(usize, Item<'f>)>) {
        self.waiting_count += deferred.len();
        for (band, item) in deferred {
            self.waiting[band].push(item);
        }
    }

    /// Renders the frame band by band with `band` (given the live pieces, the band's bucket
    /// lists, the pieces' grids, the band index and work to do while the band renders).
    /// Stops with [`Overflowed`] after the first band in which a displaced grid left its bound.
    ///
    /// With `ahead`, the next band's waiting items are refined while a band renders (a side
    /// task of the band, [`BandRenderer::render`](crate::bucket::BandRenderer::render)): they
    /// are final by then, since refining band `by` defers items only to later bands, and their
    /// refine depends on the items alone. With one primitive or a few, a band's refine is one
    /// thread's work that held the others idle (`rib/sphere.rib` at 2×: 7% of the wall time
    /// at 2 threads). What it holds in addition
    /// is the next band's new pieces, not its grids: in a wide frame those are many (5120 ×
    /// 3840 `rib/bench/spotlight.rib`: 0.6 MB of a 12 MB heap), and a wide band has items
    /// enough to refine in parallel after it, so the caller turns it off there.
    pub fn render(
        mut self,
        ahead: bool,
        mut band: impl FnMut(&[Piece], &[Vec<usize>], &[GridSlot], usize, Vec<SideTask>),
    ) -> Result<RefineReport, Overflowed> {
        let count = self.layout.band_count();
        let mut next = None;
        for by in 0..count {
            // Refined during the band before, or now.
            let refined = match next.take() {
                Some(refined) => refined,
                None => {
                    let items = self.take_waiting(by);
                    self.refine_items(by, items)
                }
            };
            self.admit(by, refined);
            let lists = self.layout.band_lists(by, &self.pieces);
            let later = (ahead && by + 1 < count).then(|| self.take_waiting(by + 1));
            let this = &self;
            let mut side: Vec<SideTask> = Vec::new();
            if let Some(items) = later {
                let next = &mut next;
                side.push(Box::new(move || {
                    *next = Some(this.refine_items(by + 1, items))
                }));
            }
            band(&this.pieces, &lists, &this.grids, by, side);
            if self.grids.iter().any(|g| g.overflow.get().is_some()) {
                return Err(Overflowed);
            }
            let refined_ahead = next.as_ref().map_or(0, |r| r.fresh.len());
            let live = (self.pieces.len() + refined_ahead + self.waiting_count) as u64;
            self.report.peak_live_pieces = self.report.peak_live_pieces.max(live);
            self.retire(by);
        }
        Ok(self.report)
    }

    /// The items waiting for band `by`, taken.
    fn take_waiting(&mut self, by: usize) -> Vec<Item<'f>> {
        let items = std::mem::take(&mut self.waiting[by]);
        self.waiting_count -= items.len();
        items
    }

    /// Refines `items` (those waiting for band `by`) until every piece is dice-ready or waits
    /// for a later band.
    fn refine_items(&self, by: usize, items: Vec<Item<'f>>) -> BandRefine<'f> {
        let layout = self.layout;
        let defer = |r: &[f32; 4]| Some(layout.band_of(r)).filter(|&b| b > by);
        let mut report = RefineReport::default();
        let (mut fresh, deferred) = refine_all(
            self.frame,
            self.refiner,
            items.into_par_iter(),
            &defer,
            &mut report,
        );
        fresh.sort_by(|a, b| a.refine_order(b));
        BandRefine {
            fresh,
            deferred,
            report,
        }
    }

    /// Band `by`'s refine result taken in: deferred items wait for their bands, the
    /// dice-ready pieces that reach this band join the live pieces in refine order.
    fn admit(&mut self, by: usize, refined: BandRefine<'f>) {
        let BandRefine {
            fresh,
            deferred,
            report,
        } = refined;
        self.report.merge(report);
        self.wait(deferred);
        let layout = self.layout;
        let mut joining = Vec::with_capacity(fresh.len());
        for p in fresh {
            let Some([bx0, bx1, by0, by1]) = layout.buckets_of(&p.raster) else {
                continue;
            };
            if by1 < by {
                self.report.late_pieces += 1;
                continue;
            }
            if by0 < by {
                self.report.late_pieces += 1;
            }
            let buckets = (bx1 - bx0 + 1) * (by1 - by0.max(by) + 1);
            // Trimmed as each bucket row is done with it (`GridSlot::release`).
            joining.push((p, GridSlot::in_rows(buckets, bx1 - bx0 + 1)));
        }
        self.join(joining);
        let live = (self.pieces.len() + self.waiting_count) as u64;
        self.report.peak_live_pieces = self.report.peak_live_pieces.max(live);
    }

    /// Merges pieces (in refine order) into the live ones, keeping refine order.
    fn join(&mut self, joining: Vec<(Piece<'f>, GridSlot)>) {
        if joining.is_empty() {
            return;
        }
        let old = std::mem::take(&mut self.pieces)
            .into_iter()
            .zip(std::mem::take(&mut self.grids));
        let mut old = old.peekable();
        let mut new = joining.into_iter().peekable();
        let total = old.len() + new.len();
        let (mut pieces, mut grids) = (Vec::with_capacity(total), Vec::with_capacity(total));
        loop {
            let next = match (old.peek(), new.peek()) {
                (Some(a), Some(b)) if a.0.refine_order(&b.0).is_lt() => old.next(),
                (_, Some(_)) => new.next(),
                (Some(_), None) => old.next(),
                (None, None) => break,
            };
            let (p, g) = next.expect("peeked");
            pieces.push(p);
            grids.push(g);
        }
        self.pieces = pieces;
        self.grids = grids;
    }

    /// Drops the pieces whose last band is `by` (their grids are already freed).
    fn retire(&mut self, by: usize) {
        let layout = self.layout;
        let keep: Vec<bool> = self
            .pieces
            .iter()
            .map(|p| layout.buckets_of(&p.raster).is_some_and(|b| b[3] > by))
            .collect();
        let mut k = keep.iter();
        self.pieces
            .retain(|_| *k.next().expect("one flag per piece"));
        let mut k = keep.iter();
        self.grids
            .retain(|_| *k.next().expect("one flag per piece"));
    }
}
