//! Bound → cull → eye-split → split until diceable at the ShadingRate: turns the frame's
//! primitives into dice-ready pieces with their dice rates. Decisions depend on the primitive
//! and the camera only (not on buckets or threads), so every run dices identically, whether a
//! primitive is refined in one go or lazily, a piece at a time as the buckets reach it
//! (`lazy_bands.rs`): a piece may stop early and wait ([`Item`]) for the band of buckets its
//! bound first touches, and refining it then continues exactly where it stopped.
use glam::{DVec3, Vec3};
use illume_geom::{Bound, Primitive};
use illume_ri::{Attributes, Camera};
use std::sync::Arc;

/// How much coarser (per side) a piece is diced when its vertices move `blur` raster pixels
/// over the keys: `max(1, blur/16)`, PRMan's `"dice" "motionfactor"` of 1. Detail finer than
/// the blur does not show, and a fine dice of a fast piece is what makes motion blur cost
/// more than the still frame: every micropolygon is tested along its whole path (about
/// `blur` pixels), so the sampling cost grows with micropolygons × blur, and a piece passing
/// close to the eye, diced finely where it is big, could take minutes (fuzz finding
/// `render_rib_slow_motion_eye`). Non-finite blur (a key that does not project) counts as none.
pub(crate) fn motion_factor(blur: f64) -> f64 {
    if blur.is_finite() {
        (blur / 16.0).max(1.0)
    } else {
        1.0
    }
}

/// Splitting deeper than this drops the piece (a degenerate primitive must not hang).
const MAX_SPLIT_DEPTH: u32 = 48;
/// A piece mostly outside the region is split rather than diced once its grid would have
/// more micropolygons than this, so the outside part is culled instead of diced.
const MIN_OFF_SCREEN_SPLIT: usize = 16;
/// Vertices per side of the coarse test dice used to measure raster size.
const TEST_DICE: usize = 5;
/// How many too-big splits whose children all still cover the whole frame
/// ([`Refiner::all_cover_frame`]) a piece may come from before it is diced at the grid size
/// instead (`fit_grid`), as at the deepest split. Such a split culls nothing and uncovers no
/// pixel; a piece whose bound is too loose for its size never stops making them (a cylinder
/// 10³⁶ long seen end-on by an orthographic camera: the bound's f32 slack of 10³⁰ puts every
/// piece over the whole frame, and the refiner split it into millions of pieces, minutes and
/// gigabytes for an 8×8 frame: fuzz finding `render_rib_slow_351f4312`). The children of a
/// split along a surface meet only along their seam, so both hold the frame only where a
/// strongly curved piece's boxes overlap over a tiny frame: rarely, and not eight times on one
/// path.
const MAX_STALLED_SPLITS: u32 = 8;

pub(crate) enum PrimRef<'a> {
    Borrowed(&'a dyn Primitive),
    Owned(Box<dyn Primitive>),
}

impl PrimRef<'_> {
    pub fn get(&self) -> &dyn Primitive {
        match self {
            PrimRef::Borrowed(p) => *p,
            PrimRef::Owned(p) => p.as_ref(),
        }
    }
}

pub(crate) struct Piece<'a> {
    pub prim: PrimRef<'a>,
    /// The later motion keys of the same piece (empty when it does not move); every key was
    /// split exactly like `prim` so they dice to matching grids.
    pub later: Vec<PrimRef<'a>>,
    pub attrs: Arc<Attributes>,
    /// Dice rates in vertices.
    pub nu: usize,
    pub nv: usize,
    /// Raster bound x0 x1 y0 y1 and nearest camera depth, over every motion key and grown by
    /// the circle of confusion.
    pub raster: [f32; 4],
    pub zmin: f32,
    /// Index of the frame primitive this piece came from.
    pub prim_index: usize,
    /// The child index taken at each split from the primitive down to this piece. Pieces in
    /// (`prim_index`, `path`) order are in the order a depth-first refine of the whole frame
    /// makes them, the order that breaks ties between samples at equal depth.
    pub path: Box<[u32]>,
}

impl Piece<'_> {
    /// The frame-wide refine order of two pieces (see [`Piece::path`]).
    pub fn refine_order(&self, other: &Piece) -> std::cmp::Ordering {
        (self.prim_index, &self.path).cmp(&(other.prim_index, &other.path))
    }
}

/// A primitive, or a piece of one, still to refine: where a lazy refine stopped.
pub(crate) struct Item<'a> {
    pub prim: PrimRef<'a>,
    /// The later motion keys, split like `prim`.
    pub later: Vec<PrimRef<'a>>,
    pub prim_index: usize,
    pub eye_splits: u32,
    pub depth: u32,
    /// Too-big splits on the way here whose children all covered the whole frame
    /// ([`MAX_STALLED_SPLITS`]).
    pub stalled: u32,
    /// See [`Piece::path`].
    pub path: Vec<u32>,
}

impl<'a> Item<'a> {
    /// A frame primitive, not refined at all yet.
    pub fn primitive(prim: PrimRef<'a>, later: Vec<PrimRef<'a>>, prim_index: usize) -> Item<'a> {
        Item {
            prim,
            later,
            prim_index,
            eye_splits: 0,
            depth: 0,
            stalled: 0,
            path: Vec::new(),
        }
    }

    /// The children of one split, each one level deeper; an eye split gives the
    /// `displacementbound` padding and the eye plane's depth ([`eye_split_choice`]).
    fn split(self, eye_split: Option<(f32, f64)>) -> impl Iterator<Item = Item<'a>> {
        let parts = split_keys(&self.prim, &self.later, eye_split);
        self.children(parts, eye_split.is_some(), false)
    }

    /// The items of an already made split of this one (`parts` from [`split_keys`]), each
    /// one level deeper; `eye_split` says whether it was an eye split, `stalled` whether all
    /// its children cover the whole frame.
    fn children(
        self,
        parts: Vec<(PrimRef<'a>, Vec<PrimRef<'a>>)>,
        eye_split: bool,
        stalled: bool,
    ) -> impl Iterator<Item = Item<'a>> {
        let Item {
            prim_index,
            eye_splits,
            depth,
            stalled: stalled_before,
            path,
            ..
        } = self;
        let eye_splits = eye_splits + u32::from(eye_split);
        let stalled = stalled_before + u32::from(stalled);
        parts
            .into_iter()
            .enumerate()
            .map(move |(i, (prim, later))| {
                let mut path = path.clone();
                path.push(i as u32);
                Item {
                    prim,
                    later,
                    prim_index,
                    eye_splits,
                    depth: depth + 1,
                    stalled,
                    path,
                }
            })
    }
}

/// What a refine produced: dice-ready pieces, pieces that wait for a later band of buckets
/// (with the band), and the counts of dropped pieces.
#[derive(Default)]
pub(crate) struct Refined<'a> {
    pub pieces: Vec<Piece<'a>>,
    pub deferred: Vec<(usize, Item<'a>)>,
    pub counts: RefineCounts,
}

#[derive(Clone)]
pub(crate) struct Refiner<'c> {
    pub camera: &'c Camera,
    /// Region (pixels, with filter margin) outside of which pieces are culled.
    pub region: [f32; 4],
    /// The whole frame's region (pixels, with the same margin), whatever the crop: where a
    /// piece counts as mostly outside. It must not follow the crop window, or a tile of a
    /// frame (`farm`'s `--crop` renders) would split and dice differently from the whole
    /// frame and the merged tiles would not be the frame's bits.
    pub frame_region: [f32; 4],
    pub eye_splits: u32,
    pub grid_size: usize,
    /// The thin lens when depth of field is on.
    pub lens: Option<crate::lens::Lens>,
}

/// Splits a piece and its motion keys alike (the first key chooses the cut, across its depth
/// for an eye split); keys that split into a different number of children are dropped (the
/// piece stops moving).
fn split_keys<'a>(
    prim: &PrimRef<'a>,
    later: &[PrimRef<'a>],
    eye_split: Option<(f32, f64)>,
) -> Vec<(PrimRef<'a>, Vec<PrimRef<'a>>)> {
    let choice = prim.get().split_choice();
    let choice = match eye_split {
        Some(pad) => eye_split_choice(prim.get(), choice, pad),
        None => choice,
    };
    let children = prim.get().split_as(choice);
    let mut keys: Vec<Vec<Box<dyn Primitive>>> =
        later.iter().map(|k| k.get().split_as(choice)).collect();
    if keys.iter().any(|k| k.len() != children.len()) {
        keys.clear();
    }
    let mut keys: Vec<_> = keys.into_iter().map(Vec::into_iter).collect();
    children
        .into_iter()
        .map(|c| {
            let ks = keys
                .iter_mut()
                .filter_map(|k| k.next().map(PrimRef::Owned))
                .collect();
            (PrimRef::Owned(c), ks)
        })
        .collect()
}

/// How to cut a piece whose bound (padded by `pad.0`) crosses the eye plane `z = pad.1`: the
/// primitive's usual cut (its longer side) or its cut across depth, whichever leaves fewer
/// children crossing (ties: the usual one). A ground plane, wider than deep, cut along its
/// width never separates what is in front of the eye from what is behind and runs out of eye
/// splits, losing visible pieces; a sphere padded across the eye plane by a large
/// `displacementbound` shrinks its padded bounds fastest along its longer side.
fn eye_split_choice(prim: &dyn Primitive, usual: u8, (pad, eye_z): (f32, f64)) -> u8 {
    let across = prim.eye_split_choice();
    if across == usual {
        return usual;
    }
    let crossing = |choice: u8| {
        prim.split_as(choice)
            .iter()
            .filter(|c| f64::from(c.bound().padded(pad).min.z) < eye_z)
            .count()
    };
    if crossing(across) < crossing(usual) {
        across
    } else {
        usual
    }
}

#[derive(Default)]
pub(crate) struct RefineCounts {
    pub culled: u64,
    pub eye_dropped: u64,
}

impl Refiner<'_> {
    fn eye_z(&self) -> f64 {
        self.camera.near.max(1e-4)
    }

    fn project(&self, p: Vec3) -> Option<DVec3> {
        self.camera.raster_from_camera(p.as_dvec3())
    }

    /// Whether the box lies entirely outside one side of the viewing volume of `region`.
    fn outside_frustum(&self, b: &Bound) -> bool {
        let c = self.camera;
        if f64::from(b.max.z) < c.near || f64::from(b.min.z) > c.far {
            return true;
        }
        if self.lens.is_some() {
            // Blur moves points sideways on screen; the padded raster test below culls.
            return false;
        }
        let [l, r, bot, t] = c.screen_window;
        let (w, h) = (f64::from(c.xres), f64::from(c.yres));
        // Screen-space edges of the region.
        let sx0 = l + f64::from(self.region[0]) / w * (r - l);
        let sx1 = l + f64::from(self.region[1]) / w * (r - l);
        let sy1 = t - f64::from(self.region[2]) / h * (t - bot);
        let sy0 = t - f64::from(self.region[3]) / h * (t - bot);
        let corners = b.corners().map(|p| p.as_dvec3());
        let d = c.perspective_scale;
        // Screen x of a point is x·d/z (perspective) or x: test the linear forms x·d − s·z.
        let all = |f: &dyn Fn(DVec3) -> bool| corners.iter().all(|&p| f(p));
        match d {
            Some(d) => {
                all(&|p| p.x * d - sx1 * p.z > 0.0)
                    || all(&|p| p.x * d - sx0 * p.z < 0.0)
                    || all(&|p| p.y * d - sy1 * p.z > 0.0)
                    || all(&|p| p.y * d - sy0 * p.z < 0.0)
            }
            None => {
                all(&|p| p.x > sx1)
                    || all(&|p| p.x < sx0)
                    || all(&|p| p.y > sy1)
                    || all(&|p| p.y < sy0)
            }
        }
    }

    /// Refines `item` depth first into `out`. Once the item no longer crosses the eye plane,
    /// `defer` sees its raster bound and may name a band of buckets to wait for instead.
    pub fn refine<'a>(
        &self,
        item: Item<'a>,
        attrs: &Arc<Attributes>,
        defer: &dyn Fn(&[f32; 4]) -> Option<usize>,
        out: &mut Refined<'a>,
    ) {
        let counts = &mut out.counts;
        // Vertices move linearly between keys, so the box around every key's bound holds the
        // piece over the whole shutter interval.
        let mut b = item.prim.get().bound();
        for k in &item.later {
            b = b.union(k.get().bound());
        }
        // The surface itself, before displacement padding and lens blur, for the dice
        // decision: a piece padded by a large `displacementbound` is not mostly off screen.
        let surface = b;
        let b = b.padded(attrs.displacement_bound);
        if b.is_empty() || self.outside_frustum(&b) {
            counts.culled += 1;
            return;
        }
        if item.depth >= MAX_SPLIT_DEPTH {
            counts.eye_dropped += 1;
            return;
        }
        let crosses_eye = self.camera.is_perspective() && f64::from(b.min.z) < self.eye_z();
        if crosses_eye {
            if item.eye_splits >= self.eye_splits {
                counts.eye_dropped += 1;
                return;
            }
            for child in item.split(Some((attrs.displacement_bound, self.eye_z()))) {
                self.refine(child, attrs, defer, out);
            }
            return;
        }
        let raster = self.raster_bound(&b);
        if let Some(band) = defer(&raster) {
            out.deferred.push((band, item));
            return;
        }
        if !item.prim.get().diceable() {
            for child in item.split(None) {
                self.refine(child, attrs, defer, out);
            }
            return;
        }
        if raster[1] < self.region[0]
            || raster[0] > self.region[1]
            || raster[3] < self.region[2]
            || raster[2] > self.region[3]
        {
            counts.culled += 1;
            return;
        }
        let (mut nu, mut nv) = self.dice_rates(item.prim.get(), &item.later, attrs);
        let surface = self.corner_raster(&surface);
        let micropolygons = (nu - 1) * (nv - 1);
        let over_size = micropolygons > self.grid_size;
        // A piece mostly off screen splits so its outside part is culled, if that split
        // shrinks it (made once here, and kept for the children).
        let off_screen_split =
            (!over_size && micropolygons > MIN_OFF_SCREEN_SPLIT && self.mostly_outside(&surface))
                .then(|| split_keys(&item.prim, &item.later, None))
                .filter(|parts| split_shrinks(item.prim.get(), parts));
        if (over_size || off_screen_split.is_some()) && item.depth + 1 < MAX_SPLIT_DEPTH {
            let (parts, stalled) = match off_screen_split {
                Some(parts) => (parts, false),
                None => {
                    let parts = split_keys(&item.prim, &item.later, None);
                    let stalled = self.all_cover_frame(&parts);
                    (parts, stalled)
                }
            };
            if !stalled || item.stalled < MAX_STALLED_SPLITS {
                for child in item.children(parts, false, stalled) {
                    self.refine(child, attrs, defer, out);
                }
                return;
            }
        }
        if over_size {
            // Still too big at the deepest split (a piece whose bound stops shrinking in f32,
            // such as a surface reaching 1e24), or after too many splits that shrank nothing
            // on screen: dice it coarser to fit the grid size rather than at up to 4096²
            // micropolygons (fuzz finding render_rib_oom_ef9010ac: gigabytes).
            (nu, nv) = fit_grid(nu, nv, self.grid_size);
        }
        out.pieces.push(Piece {
            prim: item.prim,
            later: item.later,
            attrs: attrs.clone(),
            nu,
            nv,
            raster,
            zmin: b.min.z,
            prim_index: item.prim_index,
            path: item.path.into_boxed_slice(),
        });
    }

    /// Whether less than half of a raster bound (grown by a pixel, so slivers count) lies
    /// in the frame's region. Why: a piece's dice rate comes from its whole projected size, so a
    /// ground plane's far strip, a few pixels tall but reaching far past both sides of the
    /// frame, would dice mostly off screen (8× the micropolygons of the pixels it covers in
    /// `tests/ground_plane.rs`); split, its outside halves are culled.
    fn mostly_outside(&self, raster: &[f32; 4]) -> bool {
        let r = &self.frame_region;
        let inside = |lo: f32, hi: f32, rlo: f32, rhi: f32| (hi.min(rhi) - lo.max(rlo)).max(0.0);
        let iw = inside(raster[0], raster[1], r[0], r[1]);
        let ih = inside(raster[2], raster[3], r[2], r[3]);
        let (w, h) = (raster[1] - raster[0], raster[3] - raster[2]);
        (iw + 1.0) * (ih + 1.0) < 0.5 * (w + 1.0) * (h + 1.0)
    }

    /// Whether every child of a split (`parts` from [`split_keys`]) still has a raster bound,
    /// over every motion key, that holds the whole frame's region: a split that can neither
    /// cull a part nor uncover any pixel ([`MAX_STALLED_SPLITS`]).
    fn all_cover_frame(&self, parts: &[(PrimRef, Vec<PrimRef>)]) -> bool {
        let f = &self.frame_region;
        parts.iter().all(|(child, later)| {
            let b = later
                .iter()
                .fold(child.get().bound(), |b, k| b.union(k.get().bound()));
            let r = self.corner_raster(&b);
            r[0] <= f[0] && r[1] >= f[1] && r[2] <= f[2] && r[3] >= f[3]
        })
    }

    /// Raster x0 x1 y0 y1 of the box's corners in front of the eye.
    fn corner_raster(&self, b: &Bound) -> [f32; 4] {
        let mut raster = [
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        for c in b.corners() {
            let Some(q) = self.project(c) else { continue };
            raster = [
                raster[0].min(q.x as f32),
                raster[1].max(q.x as f32),
                raster[2].min(q.y as f32),
                raster[3].max(q.y as f32),
            ];
        }
        raster
    }

    /// Raster x0 x1 y0 y1 of the box's corners (those in front of the eye), grown by the
    /// circle of confusion with depth of field.
    pub fn raster_bound(&self, b: &Bound) -> [f32; 4] {
        let mut raster = self.corner_raster(b);
        // Depth of field blurs every point by up to its circle of confusion.
        if let Some(lens) = &self.lens {
            let (gx, gy) = lens.blur_radius(
                f64::from(b.min.z).max(self.eye_z()),
                f64::from(b.max.z).max(self.eye_z()),
            );
            raster = [
                raster[0] - gx as f32,
                raster[1] + gx as f32,
                raster[2] - gy as f32,
                raster[3] + gy as f32,
            ];
        }
        raster
    }

    /// The smallest circle of confusion (raster pixels across) over the depths of `pts`: zero
    /// without a lens or when they straddle the focal plane.
    fn coc(&self, pts: &[Vec3]) -> f64 {
        let Some(lens) = &self.lens else { return 0.0 };
        let z = pts.iter().map(|p| f64::from(p.z));
        let (z0, z1) = z.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
            (a.min(z), b.max(z))
        });
        lens.min_blur_diameter(z0.max(self.eye_z()), z1)
    }

    /// Micropolygons per side so each is about `ShadingRate` pixels in area: the longest
    /// raster-space row/column of a coarse test dice, divided by √ShadingRate; for a moving
    /// piece also by its motion blur ([`motion_factor`]), for one out of focus by its circle of
    /// confusion (`lens::focus_factor`), whichever is larger.
    fn dice_rates(
        &self,
        prim: &dyn Primitive,
        later: &[PrimRef],
        attrs: &Attributes,
    ) -> (usize, usize) {
        let g = TestDice::of(prim);
        let pts: Vec<Option<DVec3>> = g.p.iter().map(|&p| self.project(p)).collect();
        let mut blur = 0.0f64;
        for k in later {
            let gk = TestDice::of(k.get());
            for (a, &p) in pts.iter().zip(&gk.p) {
                if let (Some(a), Some(b)) = (a, self.project(p)) {
                    blur = blur.max((b.truncate() - a.truncate()).length());
                }
            }
        }
        let dist = |a: usize, b: usize| match (pts[a], pts[b]) {
            (Some(a), Some(b)) => (a.truncate() - b.truncate()).length(),
            _ => 0.0,
        };
        let (mut lu, mut lv) = (0.0f64, 0.0f64);
        for j in 0..g.nv {
            lu = lu.max(
                (1..g.nu)
                    .map(|i| dist(j * g.nu + i - 1, j * g.nu + i))
                    .sum(),
            );
        }
        for i in 0..g.nu {
            lv = lv.max(
                (1..g.nv)
                    .map(|j| dist((j - 1) * g.nu + i, j * g.nu + i))
                    .sum(),
            );
        }
        let step = f64::from(attrs.shading_rate).sqrt()
            * motion_factor(blur).max(crate::lens::focus_factor(self.coc(&g.p)));
        let (min_u, min_v) = min_segments(&g);
        let rate = |l: f64, min: usize| -> usize {
            let n = ((l / step).ceil().clamp(1.0, 4096.0) as usize).max(min);
            if attrs.dice_binary {
                n.next_power_of_two()
            } else {
                n
            }
        };
        (rate(lu, min_u) + 1, rate(lv, min_v) + 1)
    }
}

/// A coarse dice's positions (`TEST_DICE` vertices a side), for the dice rates.
struct TestDice {
    nu: usize,
    nv: usize,
    p: Vec<Vec3>,
}

impl TestDice {
    fn of(prim: &dyn Primitive) -> TestDice {
        let (nu, nv, p) = prim.dice_positions(TEST_DICE, TEST_DICE);
        TestDice { nu, nv, p }
    }
}

/// The fewest micropolygons per side that give a piece area at all, from its test dice
/// (camera-space points, so a projection that lines points up does not count): a direction
/// whose first and last iso-lines are both collapsed to points (a sphere's poles) needs two
/// segments, and a closed direction (first and last iso-lines the same curve, a full sweep)
/// needs three. Without this a sphere about a pixel across diced at one segment per side has
/// every vertex of a row at one pole, or both columns on one meridian: all its micropolygons
/// have zero area and no sample ever sees it (the 10⁶-sphere scene of issue 23 came out empty).
fn min_segments(g: &TestDice) -> (usize, usize) {
    let (nu, nv) = (g.nu, g.nv);
    let (lo, hi) = g.p.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let tol = 1e-4 * (hi - lo).length();
    let same = |a: usize, b: usize| (g.p[a] - g.p[b]).length() <= tol;
    let row_is_point = |j: usize| (1..nu).all(|i| same(j * nu, j * nu + i));
    let col_is_point = |i: usize| (1..nv).all(|j| same(i, j * nu + i));
    let u_closed = (0..nv).all(|j| same(j * nu, j * nu + nu - 1));
    let v_closed = (0..nu).all(|i| same(i, (nv - 1) * nu + i));
    let need = |closed: bool, ends_are_points: bool| {
        if closed {
            3
        } else if ends_are_points {
            2
        } else {
            1
        }
    };
    (
        need(u_closed, col_is_point(0) && col_is_point(nu - 1)),
        need(v_closed, row_is_point(0) && row_is_point(nv - 1)),
    )
}

/// Vertex counts per side scaled down alike so the grid has at most `grid_size` micropolygons
/// (at least one per side).
fn fit_grid(nu: usize, nv: usize, grid_size: usize) -> (usize, usize) {
    let f = (grid_size as f64 / ((nu - 1) * (nv - 1)) as f64).sqrt();
    let side = |n: usize| (((n - 1) as f64 * f).floor() as usize).max(1);
    let (mut su, mut sv) = (side(nu), side(nv));
    while su * sv > grid_size.max(1) {
        if su >= sv {
            su -= 1;
        } else {
            sv -= 1;
        }
    }
    (su.max(1) + 1, sv.max(1) + 1)
}

/// Whether a split of `own` into `parts` (from [`split_keys`]) gives a child whose bound is
/// narrower than its own along some axis by at least 1% of its largest extent. A piece mostly
/// off screen is split so its outside part can be culled; a degenerate piece (flattened by a
/// singular transformation) can have children with its own bound at every depth, and splitting
/// it for that reason doubled its pieces down to the deepest split (fuzz finding
/// `render_rib_slow_c8a56e60`: minutes for an 8×6 frame).
fn split_shrinks(own: &dyn Primitive, parts: &[(PrimRef, Vec<PrimRef>)]) -> bool {
    let own = own.bound();
    let own_size = own.max - own.min;
    parts.iter().any(|(child, _)| {
        let b = child.get().bound();
        (own_size - (b.max - b.min)).max_element() > 0.01 * own_size.max_element()
    })
}
