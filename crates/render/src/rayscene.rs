//! The frame's shadow-casting geometry for ray-traced shadows and area lights (BMRT's
//! `Attribute "light" "shadows"`, `shadow("raytrace", …)`, `AreaLightSource`): every primitive
//! that casts shadows, split until diceable and diced at a coarse, bounded rate into
//! triangles, in one BVH. Built once per frame, and only when some light needs it.
//!
//! The rate is view-dependent but bucket- and thread-independent: about one triangle edge per
//! [`EDGE_PIXELS`] raster pixels, and at least one segment per [`MAX_TURN`] of the surface's
//! turning (a caster small on screen can cast a large shadow: near a point light, or under
//! grazing light), between [`MIN_SEGMENTS`] and [`MAX_SEGMENTS`] per side of a diceable piece. Each piece is diced at twice that rate so the half-way vertices measure how
//! far the triangles lie from the true surface (the chord's sagitta); the largest such distance
//! of a primitive is the offset its own shadow rays start with, so a lit curved surface never
//! shadows itself on the chords of its own tessellation.
//!
//! Displaced primitives cast displaced shadows: each caster grid (the fine one, so the chord
//! error is measured on the displaced surface) runs the primitive's displacement shader.
//!
//! Not modelled: partial transmission ("Os"/"shader" cast as opaque), motion; area-light
//! geometry is sampled undisplaced.
use glam::{DVec3, Vec3};
use illume_geom::{Grid, Primitive};
use illume_raytrace::{Bvh, Triangle};
use illume_ri::{Camera, Frame};
use illume_shade::{AreaEmitter, Occlusion};
use rayon::prelude::*;

/// Target raster length of a triangle edge.
const EDGE_PIXELS: f64 = 4.0;
/// Segments per side of a diceable piece (a sphere gets at least this many around).
const MIN_SEGMENTS: usize = 8;
const MAX_SEGMENTS: usize = 128;
/// Largest turn of the tessellation's edge direction per segment, whatever the raster size:
/// chords of a circle then stay within `1 − cos(MAX_TURN/2)` ≈ 3e-4 of its radius, so the
/// shadow of a full disk covers 0.9996 of the circle (the 4 px rule alone gave a 5% smaller
/// shadow for a disk ten times smaller on screen than its shadow).
const MAX_TURN: f64 = std::f64::consts::TAU / 128.0;
/// Segments per side when the piece cannot be measured in raster space (behind the eye).
const UNMEASURED_SEGMENTS: usize = 32;
/// Area lights are sampled on a finer tessellation: its chords shrink the sampled shape.
const MIN_EMITTER_SEGMENTS: usize = 32;
/// Splitting deeper than this dices whatever is left as it is.
const MAX_SPLIT_DEPTH: u32 = 24;
/// Margin on the measured chord distance (the sagitta between the sampled half-way points).
const OFFSET_MARGIN: f32 = 1.5;

pub(crate) struct RayScene {
    bvh: Bvh,
    /// Per frame primitive: how far shadow rays from it start off its surface.
    offsets: Vec<f32>,
}

impl Occlusion for RayScene {
    fn occluded(&self, origin: DVec3, dir: DVec3, t_max: f64) -> bool {
        self.bvh.occluded(origin, dir, 0.0, t_max)
    }
}

impl RayScene {
    /// Tessellates every primitive that casts shadows (not area-light geometry: an emitter
    /// does not block its own light).
    /// `displaced(prim, grid)` gives the grid's displaced positions (`None`: not displaced).
    pub fn build(
        frame: &Frame,
        displaced: &(dyn Fn(usize, &Grid) -> Option<Vec<Vec3>> + Sync),
    ) -> RayScene {
        let per_prim: Vec<(Vec<Triangle>, f32)> = frame
            .primitives
            .par_iter()
            .enumerate()
            .map(|(index, fp)| {
                let a = &fp.attributes;
                let mut tris = Vec::new();
                let mut offset = 0.0f32;
                // Geometry that blocks no ray cannot shadow itself either: no offset needed.
                if !a.casts_shadows || a.area_light.is_some() {
                    return (tris, offset);
                }
                for mut g in diced(fp.primitive.as_ref(), &frame.camera, MIN_SEGMENTS) {
                    if let Some(p) = displaced(index, &g) {
                        g.p = p;
                    }
                    offset = offset.max(triangles(&g, &mut tris));
                }
                (tris, offset * OFFSET_MARGIN)
            })
            .collect();
        let offsets = per_prim.iter().map(|p| p.1).collect();
        let tris = per_prim.into_iter().flat_map(|p| p.0).collect();
        RayScene {
            bvh: Bvh::new(tris),
            offsets,
        }
    }

    /// The shadow-ray offset for grids of frame primitive `prim`.
    pub fn offset(&self, prim: usize) -> f32 {
        self.offsets.get(prim).copied().unwrap_or(0.0)
    }
}

/// The geometry of area light `light`: every primitive declared in its `AreaLightSource`
/// block, diced, with normals oriented as the hider orients them.
pub(crate) fn emitter(frame: &Frame, light: usize) -> AreaEmitter {
    let mut e = AreaEmitter::new();
    for fp in &frame.primitives {
        if fp.attributes.area_light != Some(light) {
            continue;
        }
        let flip = fp.normal_sign();
        for g in diced(fp.primitive.as_ref(), &frame.camera, MIN_EMITTER_SEGMENTS) {
            // Every other vertex: the coarse grid (the fine one only measures chord error).
            let (nu, nv) = (g.nu.div_ceil(2), g.nv.div_ceil(2));
            let p: Vec<Vec3> = (0..nv)
                .flat_map(|j| (0..nu).map(move |i| (i, j)))
                .map(|(i, j)| g.p[2 * j * g.nu + 2 * i])
                .collect();
            e.add_grid(nu, nv, &p, flip);
        }
    }
    e
}

/// The primitive split until diceable, each piece diced at twice its ray-tracing rate
/// (`2·segments + 1` vertices per side).
fn diced(prim: &dyn Primitive, camera: &Camera, min_segments: usize) -> Vec<Grid> {
    let mut out = Vec::new();
    dice_into(prim, camera, min_segments, 0, &mut out);
    out
}

fn dice_into(
    prim: &dyn Primitive,
    camera: &Camera,
    min_segments: usize,
    depth: u32,
    out: &mut Vec<Grid>,
) {
    if prim.bound().is_empty() {
        return;
    }
    if !prim.diceable() && depth < MAX_SPLIT_DEPTH {
        for child in prim.split() {
            dice_into(child.as_ref(), camera, min_segments, depth + 1, out);
        }
        return;
    }
    if !prim.diceable() {
        return;
    }
    let (su, sv) = segments(prim, camera, min_segments);
    let g = prim.dice(2 * su + 1, 2 * sv + 1);
    if g.nu >= 3 && g.nv >= 3 && g.p.len() == g.nu * g.nv && g.nu % 2 == 1 && g.nv % 2 == 1 {
        out.push(g);
    }
}

/// Side of the coarse test dice that measures a piece.
const TEST: usize = 5;

/// Triangle segments per side: the longer of the raster rule (the longest row/column of a
/// coarse test dice over [`EDGE_PIXELS`]) and the turning rule (its largest turning over
/// [`MAX_TURN`]), clamped.
fn segments(prim: &dyn Primitive, camera: &Camera, min_segments: usize) -> (usize, usize) {
    let g = prim.dice(TEST, TEST);
    if g.p.len() != TEST * TEST {
        return (UNMEASURED_SEGMENTS, UNMEASURED_SEGMENTS);
    }
    let p_camera: Vec<DVec3> = g.p.iter().map(|p| p.as_dvec3()).collect();
    let (tu, tv) = turning(&p_camera);
    let by_turn = |t: f64| (t / MAX_TURN).ceil();
    let raster: Option<Vec<DVec3>> = p_camera
        .iter()
        .map(|&p| camera.raster_from_camera(p))
        .collect();
    let Some(raster) = raster else {
        let n = |t: f64| (by_turn(t) as usize).clamp(UNMEASURED_SEGMENTS, MAX_SEGMENTS);
        return (n(tu), n(tv));
    };
    let at = |i: usize, j: usize| raster[j * TEST + i].truncate();
    let (mut lu, mut lv) = (0.0f64, 0.0f64);
    for a in 0..TEST {
        lu = lu.max((1..TEST).map(|i| (at(i, a) - at(i - 1, a)).length()).sum());
        lv = lv.max((1..TEST).map(|j| (at(a, j) - at(a, j - 1)).length()).sum());
    }
    let rate = |l: f64, t: f64| {
        let n = (l / EDGE_PIXELS).ceil().max(by_turn(t));
        if n.is_finite() {
            (n as usize).clamp(min_segments, MAX_SEGMENTS)
        } else {
            MAX_SEGMENTS
        }
    };
    (rate(lu, tu), rate(lv, tv))
}

/// The largest total turning (radians) of the edge direction along a row (u) and a column (v)
/// of the `TEST × TEST` points: the sum of the angles between consecutive chords, scaled by
/// `(TEST−1)/(TEST−2)` since the `TEST−1` chords of a row show only `TEST−2` of its turns
/// (a full circle seen as a square turns 3·90°, not 360°). Collapsed chords (a pole) turn
/// nothing.
fn turning(p: &[DVec3]) -> (f64, f64) {
    let row_turn = |at: &dyn Fn(usize) -> DVec3| {
        let chords: Vec<DVec3> = (1..TEST).map(|k| at(k) - at(k - 1)).collect();
        let turn: f64 = chords
            .windows(2)
            .filter(|c| c[0].length_squared() > 0.0 && c[1].length_squared() > 0.0)
            .map(|c| c[0].angle_between(c[1]))
            .filter(|a| a.is_finite())
            .sum();
        turn * (TEST - 1) as f64 / (TEST - 2) as f64
    };
    let (mut tu, mut tv) = (0.0f64, 0.0f64);
    for a in 0..TEST {
        tu = tu.max(row_turn(&|i| p[a * TEST + i]));
        tv = tv.max(row_turn(&|j| p[j * TEST + a]));
    }
    (tu, tv)
}

/// Appends the triangles of the coarse grid (the even vertices of `g`) and returns the
/// largest distance between the true surface (the odd, half-way vertices) and those triangles'
/// edges and diagonals: a bound on how far a point of the surface lies from its tessellation.
fn triangles(g: &Grid, out: &mut Vec<Triangle>) -> f32 {
    let at = |i: usize, j: usize| g.p[j * g.nu + i];
    let mid = |a: Vec3, b: Vec3| (a.as_dvec3() + b.as_dvec3()) * 0.5;
    let mut err = 0.0f64;
    for j in (0..g.nv - 2).step_by(2) {
        for i in (0..g.nu - 2).step_by(2) {
            let (a, b, c, d) = (at(i, j), at(i + 2, j), at(i + 2, j + 2), at(i, j + 2));
            out.push(Triangle::new(a, b, c));
            out.push(Triangle::new(a, c, d));
            let centre = at(i + 1, j + 1).as_dvec3();
            let checks = [
                (at(i + 1, j).as_dvec3(), mid(a, b)),
                (at(i, j + 1).as_dvec3(), mid(a, d)),
                (at(i + 2, j + 1).as_dvec3(), mid(b, c)),
                (at(i + 1, j + 2).as_dvec3(), mid(d, c)),
                (centre, mid(a, c)),
                (centre, mid(b, d)),
            ];
            for (surface, chord) in checks {
                let e = (surface - chord).length();
                if e.is_finite() {
                    err = err.max(e);
                }
            }
        }
    }
    err as f32
}
