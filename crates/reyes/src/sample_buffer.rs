//! A bucket's samples and the visible points they collect: one buffer for still and moving
//! (motion-blurred, lens-blurred) micropolygons, so both deposit hits the same way and the
//! compositing and film stages see one layout.
//!
//! The samples cover every pixel whose samples reach the bucket's pixel centres through the
//! pixel filter, pixel by pixel (rows first), `n_per` samples per pixel; a sample's position
//! (and time and lens position, when something blurs) is a hash of its pixel, index and frame
//! only, so neighbouring buckets agree on the samples they share.
use crate::csg::NO_SOLID;
use crate::dice::{ShadedGrid, TriangleShade};
use crate::film::SampleRegion;
pub(crate) use crate::raster_triangle::{split_quad, RasterTriangle};
use crate::sampling::{pixel_sample_positions, sample_time_lens};
use crate::time_strata::{push_time_ordered, TimedSample};
use crate::visible::{VisiblePoint, NO_AOV};
use crate::visible_lists::VisibleLists;
use std::cell::RefCell;

/// How a bucket's samples are placed.
pub(crate) struct SampleSetup {
    /// `PixelSamples` per pixel (x, y).
    pub spp: [u32; 2],
    pub frame: i32,
    pub jitter: bool,
    /// Whether times and lens positions are needed (something moves or a lens blurs).
    pub blur: bool,
    /// Whether a lens blurs (lens positions are needed).
    pub lens: bool,
    pub shutter: [f32; 2],
    /// Camera clipping planes.
    pub near_far: [f32; 2],
    pub perspective: bool,
    /// Floats per visible point's AOV record (0: no AOVs).
    pub aov_stride: usize,
    /// The primitive solids that contain the eye (see `csg_eye`): where each sample's CSG
    /// state starts.
    pub eye_in_solids: Vec<u32>,
    /// Whether an opaque visible point may drop the points behind it: not when the frame has
    /// solids or uses the `midpoint` depth filter (see [`VisibleLists::reset`]).
    pub drop_hidden: bool,
}

pub(crate) struct SampleBuffer {
    /// First pixel (x, y) and size in pixels of the sample region; samples per pixel.
    pub origin: [i32; 2],
    pub size: [usize; 2],
    pub n_per: usize,
    /// Raster position per sample.
    pub pos: Vec<(f32, f32)>,
    /// Every sample with its time and lens position, pixel by pixel as in `pos` but each
    /// pixel's samples in time order, so a time stratum is a run per pixel (`time_strata.rs`);
    /// empty when nothing blurs.
    pub timed: Vec<TimedSample>,
    /// Visible points per sample, unsorted.
    pub lists: VisibleLists,
    /// Per sample, the depth of the nearest opaque visible point (nothing behind it shows).
    pub opaque_z: Vec<f32>,
    /// The samples whose `opaque_z` is still infinite, and the largest `opaque_z` when none
    /// is (`None`: to be found again), for [`SampleBuffer::max_opaque_z`].
    open: usize,
    max_opaque: Option<f32>,
    pub near_far: [f32; 2],
    pub shutter: [f32; 2],
    pub(crate) perspective: bool,
    /// AOV records of the visible points (`aov_stride` floats each), indexed by their tag.
    pub aov_store: Vec<f32>,
    pub aov_stride: usize,
}

/// One sample hit of a micropolygon, ready to become a [`VisiblePoint`].
pub(crate) struct Hit {
    /// Grid vertices of the hit triangle and the barycentric weights of the sample in it.
    pub idx: [usize; 3],
    pub w: [f64; 3],
    /// The micropolygon's first vertex (names its constant colour when shading is flat).
    pub first: usize,
    pub z: f32,
    /// Piece index (high 32 bits) and micropolygon index: the tie-break order at equal depth.
    pub order: u64,
    /// Whether the triangle was wound counter-clockwise at the sample (CSG entering test).
    pub ccw: bool,
}

impl SampleBuffer {
    /// The samples reaching the pixels `[px0, px1, py0, py1]` through a filter of radius
    /// `(rx, ry)`, in the allocations of the last buffer this thread dropped.
    pub fn new([px0, px1, py0, py1]: [u32; 4], (rx, ry): (f32, f32), set: &SampleSetup) -> Self {
        let sx0 = (px0 as f32 + 0.5 - rx).floor() as i32;
        let sx1 = (px1 as f32 - 0.5 + rx).floor() as i32 + 1;
        let sy0 = (py0 as f32 + 0.5 - ry).floor() as i32;
        let sy1 = (py1 as f32 - 0.5 + ry).floor() as i32 + 1;
        let (sw, sh) = ((sx1 - sx0) as usize, (sy1 - sy0) as usize);
        let spp = set.spp;
        let n_per = (spp[0] * spp[1]) as usize;
        let n = sw * sh * n_per;
        let Spare {
            mut pos,
            mut timed,
            mut lists,
            mut opaque_z,
            mut aov_store,
        } = SPARE.with(|s| s.borrow_mut().take()).unwrap_or_default();
        pos.clear();
        pos.reserve(n);
        let rect = [sx0, sx1, sy0, sy1];
        pixel_sample_positions(rect, spp, set.frame, set.jitter, &mut pos);
        timed.clear();
        if set.blur {
            timed.reserve(pos.len());
            let mut time_lens = Vec::with_capacity(n_per);
            for py in sy0..sy1 {
                for px in sx0..sx1 {
                    let (frame, jitter) = (set.frame, set.jitter);
                    time_lens.clear();
                    let (shutter, lens) = (set.shutter, set.lens);
                    sample_time_lens(px, py, spp, frame, jitter, shutter, lens, &mut time_lens);
                    let first = timed.len();
                    push_time_ordered(&pos[first..first + n_per], &time_lens, first, &mut timed);
                }
            }
        }
        lists.reset(n, set.drop_hidden);
        opaque_z.clear();
        opaque_z.resize(n, f32::INFINITY);
        aov_store.clear();
        SampleBuffer {
            origin: [sx0, sy0],
            size: [sw, sh],
            n_per,
            lists,
            opaque_z,
            open: n,
            max_opaque: None,
            pos,
            timed,
            near_far: set.near_far,
            shutter: set.shutter,
            perspective: set.perspective,
            aov_store,
            aov_stride: set.aov_stride,
        }
    }

    /// The samples as the film sees them.
    pub fn region(&self) -> SampleRegion<'_> {
        SampleRegion {
            origin: self.origin,
            size: self.size,
            per_pixel: self.n_per,
            pos: &self.pos,
        }
    }

    /// The farthest depth at which some sample still sees through: a piece starting behind it
    /// is hidden in the whole bucket. Asked once per piece, so it is kept rather than
    /// searched for each time (issue 21 part 3: the search was 6% of `rib/geometry.rib`):
    /// infinite while some sample has no opaque point, otherwise searched again only after
    /// the sample holding the largest depth moved nearer.
    pub fn max_opaque_z(&mut self) -> f32 {
        if self.open > 0 {
            return f32::INFINITY;
        }
        *self
            .max_opaque
            .get_or_insert_with(|| self.opaque_z.iter().copied().fold(0.0f32, f32::max))
    }

    /// Sets sample `s`'s nearest opaque depth (`z` passed the depth test against it).
    fn set_opaque_z(&mut self, s: usize, z: f32) {
        let old = std::mem::replace(&mut self.opaque_z[s], z);
        if old == f32::INFINITY {
            self.open -= 1;
        } else if self.max_opaque == Some(old) {
            self.max_opaque = None;
        }
    }

    /// Records one sample hit of a micropolygon (still or moving) in sample `s`: colour and
    /// opacity of its triangle (`shade`, from [`ShadedGrid::triangle_shade`]) interpolated at
    /// the hit's barycentric weights (or the micropolygon's constant when shading is flat).
    ///
    /// Inlined into the samplers: as a call it spent ~21 instructions per hit passing the
    /// hit and saving registers (`rib/sphere.rib` at 640×480: 32 M of 3.23 G).
    #[inline(always)]
    pub fn deposit(&mut self, g: &ShadedGrid, s: usize, hit: Hit, shade: &TriangleShade) {
        let (c, o) = shade.at(hit.w);
        let stride = self.aov_stride;
        let mut aov = NO_AOV;
        if let Some(k) = self.aov_store.len().checked_div(stride) {
            let k = k.min(NO_AOV as usize) as u32;
            if k < NO_AOV && g.push_aov(&mut self.aov_store, stride, hit.idx, hit.w, hit.first) {
                aov = k;
            }
        }
        let vp = VisiblePoint {
            z: hit.z,
            order: hit.order,
            c,
            o,
            tag: VisiblePoint::tag(g.matte, hit.ccw == g.ccw_enters, aov),
        };
        // A solid's surface may yet be carved away, so it hides nothing behind it.
        if o.min_element() >= 1.0 && g.solid == NO_SOLID {
            self.lists.push_opaque(s, vp);
            self.set_opaque_z(s, hit.z);
        } else {
            self.lists.push(s, vp);
        }
    }
}

/// The allocations of a dropped [`SampleBuffer`], for the next bucket the same thread renders:
/// buckets are many and alike, so their buffers are reused instead of allocated and freed.
#[derive(Default)]
struct Spare {
    pos: Vec<(f32, f32)>,
    timed: Vec<TimedSample>,
    lists: VisibleLists,
    opaque_z: Vec<f32>,
    aov_store: Vec<f32>,
}

/// A spare set whose visible points or AOV records outgrow this many bytes is freed instead
/// of kept: one bucket full of transparent layers should not hold memory for the frame.
const SPARE_LIMIT: usize = 8 << 20;

thread_local! {
    static SPARE: RefCell<Option<Spare>> = const { RefCell::new(None) };
}

impl Drop for SampleBuffer {
    fn drop(&mut self) {
        let spare = Spare {
            pos: std::mem::take(&mut self.pos),
            timed: std::mem::take(&mut self.timed),
            lists: std::mem::take(&mut self.lists),
            opaque_z: std::mem::take(&mut self.opaque_z),
            aov_store: std::mem::take(&mut self.aov_store),
        };
        if spare.lists.capacity_bytes() + spare.aov_store.capacity() * 4 <= SPARE_LIMIT {
            // `try_with`: a thread being torn down has no spare to keep.
            let _ = SPARE.try_with(|s| *s.borrow_mut() = Some(spare));
        }
    }
}
