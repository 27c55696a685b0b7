//! The hider's stages for one frame, in order: bucket layout (`bucket.rs`), refine (bound, cull,
//! eye-split, split, `refine.rs`; lazily, each piece when the band of buckets its bound first
//! touches comes, `lazy_bands.rs`), per bucket dice and shade (`dice.rs`,
//! through the [`GridShader`]), sample (`sample_buffer.rs`, `motion.rs`), composite
//! (`visible.rs`, `csg.rs`) and develop (`film.rs`), repeated for the buckets a displacement
//! overflow reaches (`displacement_bound.rs`); each band of buckets is printed into exposed rows
//! that go straight to a [`RowSink`] (`row_sink.rs`), so the film holds one band at a time.
use crate::aov::AovLayout;
use crate::bucket::{BandRenderer, BucketLayout, GridSlot, SideTask};
use crate::column_blocks::column_blocks;
use crate::displacement_bound::render_until_bounded;
use crate::film::Film;
use crate::lazy_bands::{frame_moves, refine_frame, LazyBands, Overflowed, RefineReport};
use crate::lens::Lens;
use crate::refine::{Piece, Refiner};
use crate::row_sink::{FrameCollector, PixelRows, RowSink};
use crate::sample_buffer::SampleSetup;
use crate::shader::GridShader;
use crate::{Rendered, Stats};
use illume_ri::{Diagnostic, Frame, Severity};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

/// Per-stage counts and times, summed over the buckets (threads) that add to them.
#[derive(Default)]
pub(crate) struct Counters {
    pub(crate) grids: AtomicU64,
    pub(crate) micropolygons: AtomicU64,
    pub(crate) samples: AtomicU64,
    pub(crate) occluded: AtomicU64,
    pub(crate) dice_ns: AtomicU64,
    pub(crate) shade_ns: AtomicU64,
    pub(crate) sample_ns: AtomicU64,
    pub(crate) filter_ns: AtomicU64,
    /// The largest AOV store a bucket held (bytes).
    pub(crate) aov_peak_bytes: AtomicU64,
    /// Shaded grids held now, and the most held at once.
    pub(crate) live_grids: AtomicU64,
    pub(crate) peak_grids: AtomicU64,
}

/// Nanoseconds since `t`.
pub(crate) fn ns(t: Instant) -> u64 {
    t.elapsed().as_nanos() as u64
}

/// One frame's hider: set up from the frame ([`Hider::new`]), then run over the buckets with a
/// shader ([`Hider::render`]), refining the primitives as the buckets reach them.
pub struct Hider<'f> {
    frame: &'f Frame,
    refiner: Refiner<'f>,
    film: Film,
    /// Filter reach (pixels) around each piece's raster bound.
    margin: f32,
    /// Where the refine stage's own warnings go in [`Hider::warnings`] (after the hider's
    /// setup warnings, before the driver's), though refining happens while rendering.
    refine_warnings_at: usize,
    /// The arbitrary output variables the displays ask for ([`Hider::set_aovs`]).
    aov: AovLayout,
    /// Problems found so far, in the order they arose. A driver appends its own (e.g. shader
    /// binding) here before [`Hider::render`], which adds the rest and hands them all back.
    pub warnings: Vec<Diagnostic>,
}

impl<'f> Hider<'f> {
    /// The hider for `frame`: its film, and the refiner that culls against the crop region
    /// (grown by the filter's reach). Refining waits for [`Hider::render_to`].
    pub fn new(frame: &'f Frame) -> Hider<'f> {
        let opts = &frame.options;
        let cam = &frame.camera;
        let film = Film::new(opts);
        // Geometry as far out as the widest pixel or display filter reaches.
        let (rx, ry) = crate::aov::frame_reach(opts, &film.filter);
        let [cx0, cx1, cy0, cy1] = cam.crop;
        let margin = rx.max(ry) + 1.0;
        let region = [
            cx0 as f32 - margin,
            cx1 as f32 + margin,
            cy0 as f32 - margin,
            cy1 as f32 + margin,
        ];
        let frame_region = [
            -margin,
            opts.xres as f32 + margin,
            -margin,
            opts.yres as f32 + margin,
        ];
        let mut warnings = Vec::new();
        let samples = opts.pixel_samples;
        let lens = Lens::new(opts.depth_of_field, cam)
            .map(|l| l.with_strata(samples, frame.number.unwrap_or(0)));
        if opts.depth_of_field.is_some() && !cam.is_perspective() {
            warnings.push(Diagnostic {
                severity: Severity::Warning,
                kind: illume_ri::ErrorKind::Incapable,
                span: illume_rib::Span::synthetic(),
                request: Some("DepthOfField".to_string()),
                message: "depth of field needs a perspective camera (ignored)".to_string(),
            });
        }
        let refiner = Refiner {
            camera: cam,
            region,
            frame_region,
            eye_splits: opts.eye_splits,
            grid_size: opts.grid_size.max(1) as usize,
            lens,
        };
        Hider {
            frame,
            refiner,
            film,
            margin,
            refine_warnings_at: warnings.len(),
            aov: AovLayout::default(),
            warnings,
        }
    }

    /// Asks the hider to carry these output variables; the [`GridShader`] must then hand back
    /// `layout.stride` floats per vertex in [`crate::Shaded::aov`].
    pub fn set_aovs(&mut self, layout: AovLayout) {
        self.film.set_aovs(&layout);
        self.aov = layout;
    }

    /// Evaluates the pixel filter (and every display's own filter) exactly instead of through
    /// the film's per-frame tables: the reference the tables are checked against.
    #[doc(hidden)]
    pub fn use_exact_filter(&mut self) {
        self.film.use_exact_filter();
    }

    /// The bucket stage into memory: [`Hider::render_to`] with a sink that keeps the whole
    /// crop window, for callers that want the image (tests, the library API, farm tiles).
    pub fn render(
        self,
        shader: &dyn GridShader,
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    ) -> Rendered {
        let mut frame = FrameCollector::new(self.frame.camera.crop, self.aov.stride);
        let mut r = self.render_to(shader, progress, &mut frame);
        r.rgba = frame.rgba;
        r.z = frame.z;
        r.aov = frame.aov;
        r
    }

    /// The bucket stage: every bucket's pieces diced, shaded by `shader`, sampled, composited
    /// and developed, one band of buckets after the other (the buckets of a band in
    /// parallel); each finished band's rows go to `sink`. `progress` is called after each
    /// bucket with (buckets done, bucket count). The [`Rendered`] returned has the frame's
    /// size, statistics and warnings but empty pixel buffers: the pixels went to `sink`.
    pub fn render_to(
        self,
        shader: &dyn GridShader,
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
        sink: &mut (dyn RowSink + Send),
    ) -> Rendered {
        let Hider {
            frame,
            refiner,
            film,
            margin,
            refine_warnings_at,
            aov,
            mut warnings,
        } = self;
        let opts = &frame.options;
        let cam = &frame.camera;
        let lens = refiner.lens.clone();
        let layout = BucketLayout::new(cam.crop, opts.bucket_size, margin);
        let setup = SampleSetup {
            spp: opts.pixel_samples,
            frame: frame.number.unwrap_or(0),
            jitter: opts.jitter,
            // Times and lens positions, only when something in the frame moves or a lens blurs.
            blur: lens.is_some() || frame_moves(frame),
            lens: lens.is_some(),
            shutter: opts.shutter,
            near_far: [cam.near as f32, cam.far as f32],
            perspective: cam.is_perspective(),
            aov_stride: aov.stride,
            eye_in_solids: crate::csg_eye::solids_containing_eye(frame),
            drop_hidden: frame.solids.is_empty()
                && opts.depth_filter != illume_ri::DepthFilter::Midpoint,
        };
        let counters = Counters::default();
        let blocks = column_blocks(cam.crop);
        let total = (blocks.iter())
            .map(|b| BucketLayout::new(*b, opts.bucket_size, margin).bucket_count())
            .sum();
        // The frame's band renderer; each block's is this with the block's layout.
        let whole = BandRenderer {
            frame,
            shader,
            layout: &layout,
            film: &film,
            setup: &setup,
            lens: lens.as_ref(),
            counters: &counters,
            aov: &aov,
            progress,
            done: AtomicUsize::new(0),
            total: AtomicUsize::new(total),
        };
        sink.begin_pass();
        let (mut report, mut done, mut lazy) = (RefineReport::default(), 0, Ok(()));
        for block in blocks {
            let layout = BucketLayout::new(block, opts.bucket_size, margin);
            // The block refined as its own crop window: pieces outside it are culled.
            let mut block_refiner = refiner.clone();
            let [bx0, bx1, by0, by1] = block.map(|v| v as f32);
            block_refiner.region = [bx0 - margin, bx1 + margin, by0 - margin, by1 + margin];
            let bands = BandRenderer {
                layout: &layout,
                done: AtomicUsize::new(done),
                total: AtomicUsize::new(total),
                ..whole
            };
            let rendered = render_block(frame, &block_refiner, &bands, &aov, sink);
            done = bands.done.load(Relaxed);
            match rendered {
                Ok(r) => report.add_block(r),
                Err(o) => {
                    lazy = Err(o);
                    break;
                }
            }
        }
        // A displaced grid that left its bound needs the displacement-bound loop, which may
        // grow any piece and render again: refine the whole frame up front and start over
        // (in bands as wide as the crop window).
        if let Err(Overflowed) = lazy {
            // Progress counts the lazy pass's buckets as done; the loop adds its own passes.
            let bands = whole;
            bands.done.store(done, Relaxed);
            bands.total.store(done, Relaxed);
            report = RefineReport::default();
            let mut pieces = refine_frame(frame, &refiner, &mut report);
            warnings.extend(render_until_bounded(
                frame,
                &refiner,
                &layout,
                &mut pieces,
                |pieces: &[Piece], lists: &[Vec<usize>], grids: &[GridSlot]| {
                    bands.total.fetch_add(layout.bucket_count(), Relaxed);
                    sink.begin_pass();
                    for by in 0..layout.band_count() {
                        let (buckets, _) = layout.band(by);
                        sink.rows(bands.render(by, pieces, &lists[buckets], grids, Vec::new()));
                    }
                },
            ));
        }
        let mut dropped = dropped_warnings(frame, &report);
        if report.late_pieces > 0 {
            dropped.push(Diagnostic {
                severity: Severity::Warning,
                kind: illume_ri::ErrorKind::Limit,
                span: illume_rib::Span::synthetic(),
                request: None,
                message: format!(
                    "{} split piece(s) had a bound outside their parent's and may miss buckets rendered before them",
                    report.late_pieces
                ),
            });
        }
        warnings.splice(refine_warnings_at..refine_warnings_at, dropped);
        let [cx0, cx1, cy0, cy1] = cam.crop;
        let stats = frame_stats(frame, &report, &counters, aov.stride);
        Rendered {
            x0: cx0,
            y0: cy0,
            width: cx1 - cx0,
            height: cy1 - cy0,
            rgba: Vec::new(),
            z: Vec::new(),
            aov_layout: aov,
            aov: Vec::new(),
            stats,
            warnings,
        }
    }
}

/// The frame's statistics from what refining reported and the buckets counted.
fn frame_stats(frame: &Frame, report: &RefineReport, counters: &Counters, stride: usize) -> Stats {
    let [cx0, cx1, cy0, cy1] = frame.camera.crop;
    let aov_image_bytes = ((cx1 - cx0) as u64) * ((cy1 - cy0) as u64) * stride as u64 * 4;
    Stats {
        primitives: frame.primitives.len() as u64,
        pieces: report.pieces,
        grids: counters.grids.load(Relaxed),
        micropolygons: counters.micropolygons.load(Relaxed),
        samples: counters.samples.load(Relaxed),
        culled_pieces: report.culled,
        occluded_grids: counters.occluded.load(Relaxed),
        split_seconds: report.split_ns as f64 * 1e-9,
        dice_seconds: counters.dice_ns.load(Relaxed) as f64 * 1e-9,
        shade_seconds: counters.shade_ns.load(Relaxed) as f64 * 1e-9,
        sample_seconds: counters.sample_ns.load(Relaxed) as f64 * 1e-9,
        filter_seconds: counters.filter_ns.load(Relaxed) as f64 * 1e-9,
        // The hider does not see shaded values: the driver counts them.
        nonfinite: 0,
        aov_stride: stride as u64,
        aov_bucket_peak_bytes: counters.aov_peak_bytes.load(Relaxed),
        aov_image_bytes,
        peak_live_pieces: report.peak_live_pieces,
        peak_live_grids: counters.peak_grids.load(Relaxed),
    }
}

/// One crop window (the frame's, or a column block of it) rendered band by band with lazy
/// refinement into `sink`. A band's rows go to the sink while the next band renders, when they
/// are small enough to hold that long ([`OVERLAP_BYTES`]; larger ones are written at once), and
/// the next band's pieces are refined meanwhile only then: both overlaps hold a band's worth of
/// memory more. [`Overflowed`] when a displaced grid left its bound (the pass is then void).
fn render_block(
    frame: &Frame,
    refiner: &Refiner,
    bands: &BandRenderer,
    aov: &AovLayout,
    sink: &mut (dyn RowSink + Send),
) -> Result<RefineReport, Overflowed> {
    let layout = bands.layout;
    let [x0, x1, _, _] = layout.crop();
    let band_bytes = (x1 - x0) as usize
        * layout.bucket_height() as usize
        * (5 + aov.stride)
        * std::mem::size_of::<f32>();
    let ahead = band_bytes <= OVERLAP_BYTES;
    let mut written: Option<PixelRows> = None;
    let band = |pieces: &[Piece],
                lists: &[Vec<usize>],
                grids: &[GridSlot],
                by,
                side: Vec<SideTask<'_>>| {
        // Re-bound to a lifetime as short as this call, so it can hold the sink's borrow.
        let mut side: Vec<SideTask> = side;
        if let Some(prev) = written.take() {
            // The band before written while this one renders (a side task of the band).
            let sink = &mut *sink;
            side.push(Box::new(move || sink.rows(prev)));
        }
        let rows = bands.render(by, pieces, lists, grids, side);
        if rows_bytes(&rows) <= OVERLAP_BYTES {
            written = Some(rows);
        } else {
            sink.rows(rows);
        }
    };
    let lazy = LazyBands::new(frame, refiner, layout).render(ahead, band);
    // The last band, unless the pass is void (the caller starts the files over).
    if let (Ok(_), Some(rows)) = (&lazy, written.take()) {
        sink.rows(rows);
    }
    lazy
}

/// The largest band of rows [`Hider::render_to`] holds while the next band renders, to write
/// it meanwhile (and the widest band, in these bytes, whose next band's pieces are refined
/// while it renders: [`LazyBands::render`]). Writing (display channels, quantizing, compressing) was serial work between
/// bands that left the other threads idle: 12% of `rib/sphere.rib`'s wall time at 2× and 2
/// threads. Holding a band longer costs its rows once more (a 960-pixel-wide band of 16 rows
/// is 300 KB); above this a band is written at once, so the peak does not grow with the
/// frame's width (a 5120-pixel band is 1.6 MB).
const OVERLAP_BYTES: usize = 1 << 20;

/// The bytes a band of rows holds.
fn rows_bytes(rows: &PixelRows) -> usize {
    (rows.rgba.len() + rows.z.len() + rows.aov.len()) * std::mem::size_of::<f32>()
}

/// One warning per primitive some of whose pieces were dropped at the eye plane (or at the
/// split depth limit), in primitive order.
fn dropped_warnings(frame: &Frame, report: &RefineReport) -> Vec<Diagnostic> {
    report
        .dropped
        .iter()
        .map(|(&i, &count)| Diagnostic {
            severity: Severity::Warning,
            kind: illume_ri::ErrorKind::Limit,
            span: frame.primitives[i].span.clone(),
            request: None,
            message: format!(
                "{count} piece(s) still crossed the eye plane after {} eye splits (or split too deep) and were dropped",
                frame.options.eye_splits
            ),
        })
        .collect()
}
