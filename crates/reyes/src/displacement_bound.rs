//! The displacement-bound loop. A piece is bucketed by its bound padded by the primitive's
//! `displacementbound`; a displacement shader that moves the surface farther than that leaves
//! the piece's grids outside the buckets that listed it. Rather than clip, the hider measures
//! where each displaced grid really is, grows its piece to the measured bound, re-lists the
//! buckets and renders again exactly the buckets whose lists changed, until no new grid
//! overflows. Each pass shades a deterministic set of grids, so the image does not depend on
//! the thread count, and it equals the image a large enough bound gives (the same pieces,
//! diced the same). One warning per primitive says what it cost.
use crate::bucket::{BucketLayout, GridSlot};
use crate::film::PixelBlock;
use crate::refine::{Piece, Refiner};
use glam::Vec3;
use illume_ri::{Diagnostic, Frame, Severity};
use std::sync::atomic::Ordering::Relaxed;

/// Where a displaced grid really is, when displacement moved it farther than the piece's
/// `displacementbound` said (so the piece may have been bucketed too tightly).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Overflow {
    /// Raster x0 x1 y0 y1 of the displaced vertices, grown by the seams' reach.
    pub(crate) raster: [f32; 4],
    /// Nearest camera depth of the displaced vertices.
    pub(crate) zmin: f32,
    /// Largest distance (camera space) a vertex moved.
    pub(crate) displacement: f32,
}

/// Renders every bucket with `pass` (given the pieces, every bucket's list, the buckets to
/// render and one [`GridSlot`] per piece; it returns their blocks in that order), then again
/// the buckets a grown piece reaches, until no piece grows. Returns every bucket's block and
/// the overflow warnings.
pub(crate) fn render_until_bounded(
    frame: &Frame,
    refiner: &Refiner,
    layout: &BucketLayout,
    pieces: &mut [Piece],
    mut pass: impl FnMut(&[Piece], &[Vec<usize>], &[usize], &[GridSlot]) -> Vec<PixelBlock>,
) -> (Vec<PixelBlock>, Vec<Diagnostic>) {
    let mut lists = layout.lists(pieces);
    let mut buckets: Vec<PixelBlock> = vec![Default::default(); layout.bucket_count()];
    let mut todo: Vec<usize> = (0..layout.bucket_count()).collect();
    let mut bounds = Measured::new(pieces);
    while !todo.is_empty() {
        let mut overlaps = vec![0usize; pieces.len()];
        for &b in &todo {
            for &id in &lists[b] {
                overlaps[id] += 1;
            }
        }
        let grids: Vec<GridSlot> = overlaps.into_iter().map(GridSlot::new).collect();
        let out = pass(pieces, &lists, &todo, &grids);
        for (&b, o) in todo.iter().zip(out) {
            buckets[b] = o;
        }
        let Some(nearer) = bounds.grow(frame, refiner, pieces, &grids) else {
            break;
        };
        let relisted = layout.lists(pieces);
        todo = (0..layout.bucket_count())
            .filter(|&b| relisted[b] != lists[b] || relisted[b].iter().any(|&id| nearer[id]))
            .collect();
        lists = relisted;
        bounds.rerendered += todo.len();
    }
    let warnings = overflow_warnings(frame, pieces, &bounds.overflows, bounds.rerendered);
    (buckets, warnings)
}

/// What the loop has learnt about each piece so far.
struct Measured {
    /// The measured overflow of each piece's grid (`None`: within its bound, or not shaded).
    overflows: Vec<Option<Overflow>>,
    /// Whether some pass shaded the piece.
    shaded: Vec<bool>,
    /// The displacement each piece's bound is padded by.
    padded_by: Vec<f32>,
    /// Buckets rendered again.
    rerendered: usize,
}

impl Measured {
    fn new(pieces: &[Piece]) -> Measured {
        Measured {
            overflows: vec![None; pieces.len()],
            shaded: vec![false; pieces.len()],
            padded_by: pieces.iter().map(|p| p.attrs.displacement_bound).collect(),
            rerendered: 0,
        }
    }

    /// Grows the pieces whose grids overflowed in the pass just rendered (and the unshaded
    /// pieces of their primitives). `None` when nothing grew; else, per piece, whether it is
    /// now nearer than its old bound said.
    fn grow(
        &mut self,
        frame: &Frame,
        refiner: &Refiner,
        pieces: &mut [Piece],
        grids: &[GridSlot],
    ) -> Option<Vec<bool>> {
        let (overflows, shaded, padded_by) =
            (&mut self.overflows, &mut self.shaded, &mut self.padded_by);
        let mut grown = false;
        // Pieces now nearer than their old bound said: a bucket may have culled them as
        // occluded, so every bucket listing one renders again.
        let mut nearer = vec![false; pieces.len()];
        for (id, slot) in grids.iter().enumerate() {
            if let (None, Some(o)) = (overflows[id], slot.overflow.get()) {
                nearer[id] = o.zmin < pieces[id].zmin;
                let p = &mut pieces[id];
                p.raster = [
                    p.raster[0].min(o.raster[0]),
                    p.raster[1].max(o.raster[1]),
                    p.raster[2].min(o.raster[2]),
                    p.raster[3].max(o.raster[3]),
                ];
                p.zmin = p.zmin.min(o.zmin);
                overflows[id] = Some(*o);
                grown = true;
            }
        }
        // A piece no bucket shaded (all culled it as occluded, by its undisplaced depth) is
        // not measured: pad it by the most its primitive's measured grids moved, so the
        // next pass shades it where it may now show (and measures it, if it moves farther).
        for (id, slot) in grids.iter().enumerate() {
            shaded[id] |= slot.shaded.load(Relaxed);
        }
        let mut moved = vec![0.0f32; frame.primitives.len()];
        for (p, o) in pieces.iter().zip(overflows.iter()) {
            if let Some(o) = o {
                moved[p.prim_index] = moved[p.prim_index].max(o.displacement);
            }
        }
        for (id, p) in pieces.iter_mut().enumerate() {
            let m = moved[p.prim_index];
            if shaded[id] || m <= padded_by[id] {
                continue;
            }
            let b = p.prim.get().bound().padded(m);
            let r = refiner.raster_bound(&b);
            p.raster = [
                p.raster[0].min(r[0]),
                p.raster[1].max(r[1]),
                p.raster[2].min(r[2]),
                p.raster[3].max(r[3]),
            ];
            nearer[id] |= b.min.z < p.zmin;
            p.zmin = p.zmin.min(b.min.z);
            padded_by[id] = m;
            grown = true;
        }
        grown.then_some(nearer)
    }
}

/// The grid's [`Overflow`] if some vertex moved (diced `before` → displaced `after`, camera
/// space) farther than `bound`: then the displaced grid may lie outside the piece's padded
/// bound. The tolerance absorbs f32 rounding of `P + a·N` for a displacement exactly at the
/// bound.
pub(crate) fn measure_overflow(
    before: &[Vec3],
    after: &[Vec3],
    pos: &[Vec3],
    seam: &[Vec<f64>; 4],
    bound: f32,
) -> Option<Overflow> {
    let mut moved = 0.0f32;
    let mut scale = 0.0f32;
    for (b, a) in before.iter().zip(after) {
        let d = (*a - *b).length();
        if d.is_finite() {
            moved = moved.max(d);
        }
        scale = scale.max(b.abs().max_element());
    }
    if moved <= bound * (1.0 + 1e-4) + 1e-6 * scale {
        return None;
    }
    let reach = seam.iter().flatten().copied().fold(0.0f64, f64::max) as f32;
    let mut raster = [
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    let mut zmin = f32::INFINITY;
    for q in pos.iter().filter(|q| q.is_finite()) {
        raster = [
            raster[0].min(q.x - reach),
            raster[1].max(q.x + reach),
            raster[2].min(q.y - reach),
            raster[3].max(q.y + reach),
        ];
        zmin = zmin.min(q.z);
    }
    Some(Overflow {
        raster,
        zmin,
        displacement: moved,
    })
}

/// One warning per primitive whose displaced grids left their `displacementbound`, at the
/// primitive's request, with the bound given and the largest displacement measured.
fn overflow_warnings(
    frame: &Frame,
    pieces: &[Piece],
    overflows: &[Option<Overflow>],
    rerendered: usize,
) -> Vec<Diagnostic> {
    let mut worst: Vec<Option<f32>> = vec![None; frame.primitives.len()];
    for (p, o) in pieces.iter().zip(overflows) {
        if let (Some(o), Some(w)) = (o, worst.get_mut(p.prim_index)) {
            *w = Some(w.map_or(o.displacement, |w| w.max(o.displacement)));
        }
    }
    worst
        .iter()
        .zip(&frame.primitives)
        .filter_map(|(w, fp)| {
            let w = (*w)?;
            Some(Diagnostic {
                severity: Severity::Warning,
                kind: illume_ri::ErrorKind::Unimplemented,
                span: fp.span.clone(),
                request: None,
                message: format!(
                    "displacement moved the surface {w:.4} (camera space) but its \"displacementbound\" \"sphere\" is {:.4} there; rendered correctly by re-rendering {rerendered} bucket(s) with the measured bound (raise the bound to avoid the cost)",
                    fp.attributes.displacement_bound
                ),
            })
        })
        .collect()
}
