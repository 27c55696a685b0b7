//! The frame's shadow-casting geometry for ray-traced shadows and area lights (BMRT's
//! `Attribute "light" "shadows"`, `shadow("raytrace", …)`, `AreaLightSource`): every primitive
//! that casts shadows, split until diceable and diced at a coarse, bounded rate into
//! triangles, in one BVH. Built once per frame, and only when some light needs it.
//!
//! The rate is bucket- and thread-independent: at least one segment per [`MAX_TURN`] of the
//! surface's turning (a caster small on screen can cast a large shadow: near a point light, or
//! under grazing light), between [`MIN_SEGMENTS`] and [`MAX_SEGMENTS`] per side of a diceable
//! piece; displaced primitives (and area-light geometry) also get about one triangle edge per
//! [`EDGE_PIXELS`] raster pixels, as the displacement's detail is on the scale of the camera's
//! dicing. Undisplaced ones do not: a flat or gently curved surface needs no more triangles
//! for rays than its turning asks (PRMan's coarser "trace" dicing; a ground plane was 32k
//! triangles and is now 128). Each piece is diced at twice that rate so the half-way vertices measure how
//! far the triangles lie from the true surface (the chord's sagitta); the largest such distance
//! of a primitive is the offset its own shadow rays start with, so a lit curved surface never
//! shadows itself on the chords of its own tessellation.
//!
//! Displaced primitives cast displaced shadows: each caster grid (the fine one, so the chord
//! error is measured on the displaced surface) runs the primitive's displacement shader.
//!
//! The same tessellation serves `trace()` from the Shading Language: each triangle keeps its
//! primitive and its vertices' shading data (`trace::hit`), so a hit point can be shaded by
//! its own surface shader; per-primitive flags say which rays see it (visibility attributes).
//!
//! Whole undisplaced spheres, disks, cylinders and cones are not put in as triangles but as
//! closed-form quadrics (`trace::analytic`); their tessellation only carries shading data.
//!
//! Not modelled: motion; area-light geometry is sampled undisplaced; the built-in lights'
//! shadow rays see `"Os"`/`"shader"` casters as opaque (SL `transmission()` sees `1 − Os`).
use crate::trace::analytic::{ray_quadric, Analytic};
use crate::trace::hit::{hit_vertices, HitVertex};
use crate::trace::shell::{SeenFrom, Shell};
use glam::{DVec3, Vec3};
use illume_geom::{Grid, Primitive};
use illume_raytrace::{Bvh, Quadric, Triangle, NO_GROUP};
use illume_ri::{Attributes, Camera, Frame};
use illume_shade::{AreaEmitter, Occlusion};
use rayon::prelude::*;
use std::sync::Arc;

/// Target raster length of a triangle edge.
const EDGE_PIXELS: f64 = 4.0;
/// Segments per side of a diceable piece (a sphere gets at least this many around).
const MIN_SEGMENTS: usize = 8;
const MAX_SEGMENTS: usize = 128;
/// Largest turn of the tessellation's edge direction per segment, whatever the raster size:
/// chords of a circle then stay within `1 − cos(MAX_TURN/2)` ≈ 1.2e-3 of its radius, so the
/// shadow of a full disk covers 0.998 of the circle (the 4 px rule alone gave a 5% smaller
/// shadow for a disk ten times smaller on screen than its shadow). 2π/64 rather than 2π/128:
/// a sphere is 8k triangles instead of 33k, which halved the build of an `occlusion()` frame's
/// ray scene (issue 19) for a shadow 0.1% smaller.
const MAX_TURN: f64 = std::f64::consts::TAU / 64.0;
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
    /// Per frame primitive: what rays see of it.
    prims: Vec<PrimRays>,
    /// Per triangle (the BVH's ids): its primitive and its three vertices in `verts`.
    tri_prim: Vec<u32>,
    tri_verts: Vec<[u32; 3]>,
    verts: Vec<HitVertex>,
    /// The vertices' primitive variable values (`HitVertex::vars` indexes it).
    var_data: Vec<f32>,
    /// Some shadow caster is seen as `1 − Os` (else transmission is all or nothing).
    partial_casters: bool,
}

/// What rays see of one frame primitive.
pub(crate) struct PrimRays {
    pub attributes: Option<Arc<Attributes>>,
    /// How far rays from it start off its surface.
    pub offset: f32,
    /// Shadow rays (built-in lights, `transmission`, `occlusion`) see it.
    pub shadow: bool,
    /// Shadow rays see it as `1 − Os` rather than opaque.
    pub shadow_os: bool,
    /// `trace()` rays see it.
    pub traced: bool,
    /// Its triangles carry displaced positions: normals come from the facets.
    pub displaced: bool,
    /// The parametric step between tessellation vertices.
    pub du: f32,
    pub dv: f32,
    /// Where its triangles lie: rays leaving it away from this cannot hit it.
    pub shell: Shell,
    /// A quadric in the BVH in closed form (its triangles are not in it).
    pub analytic: Option<Analytic>,
    /// Its `N` is the user's (not flipped by the orientation).
    pub user_normals: bool,
    /// Its primitive variables that hits carry, and their scalars per vertex in total.
    pub vars: Vec<VarLayout>,
    pub var_floats: usize,
}

/// One primitive variable as the ray scene stores it per vertex.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct VarLayout {
    pub name: String,
    pub ty: illume_rib::Type,
    pub components: usize,
}

impl Occlusion for RayScene {
    fn occluded(&self, origin: DVec3, dir: DVec3, t_max: f64) -> bool {
        self.bvh
            .occluded_by(origin, dir, 0.0, t_max, &|id| self.prim_of(id).shadow)
    }
}

/// The per-primitive output of the build: triangles, their vertices' shading data, and what
/// rays see of it.
struct PrimBuild {
    tris: Vec<Triangle>,
    verts: Vec<HitVertex>,
    corners: Vec<[u32; 3]>,
    var_data: Vec<f32>,
    /// A quadric that replaces `tris` in the BVH.
    quadric: Option<Quadric>,
    rays: PrimRays,
}

impl RayScene {
    /// Tessellates every primitive that rays can see: shadow casters (not area-light
    /// geometry: an emitter does not block its own light) and geometry visible to `trace()`.
    /// `displaced(prim, grid)` gives the grid's displaced positions (`None`: not displaced).
    /// `parallel`: over rayon's pool (only when not built from inside a shading task).
    pub fn build(
        frame: &Frame,
        displaced: &(dyn Fn(usize, &Grid) -> Option<Vec<Vec3>> + Sync),
        parallel: bool,
    ) -> RayScene {
        let one = |(index, fp): (usize, &illume_ri::FramePrimitive)| -> PrimBuild {
            let a = &fp.attributes;
            let shadow = a.casts_shadows && a.area_light.is_none();
            let mut b = PrimBuild {
                tris: Vec::new(),
                verts: Vec::new(),
                corners: Vec::new(),
                var_data: Vec::new(),
                quadric: None,
                rays: PrimRays {
                    attributes: Some(a.clone()),
                    offset: 0.0,
                    shadow,
                    shadow_os: a.transmission_os,
                    traced: a.visible_to_rays,
                    displaced: false,
                    du: 0.0,
                    dv: 0.0,
                    shell: Shell::default(),
                    analytic: None,
                    user_normals: false,
                    vars: Vec::new(),
                    var_floats: 0,
                },
            };
            // Geometry that blocks no ray cannot shadow itself either: no offset needed.
            if !shadow && !b.rays.traced {
                return b;
            }
            let mut offset = 0.0f32;
            let rate = Rate {
                min_segments: MIN_SEGMENTS,
                raster: a.displacement.is_some(),
            };
            let grids = diced(fp.primitive.as_ref(), &frame.camera, rate);
            if let Some(g) = grids.first() {
                b.rays.user_normals = g.user_normals;
                b.rays.vars = g
                    .vars
                    .iter()
                    .map(|v| VarLayout {
                        name: v.name.clone(),
                        ty: v.ty,
                        components: v.components,
                    })
                    .collect();
                b.rays.var_floats = b.rays.vars.iter().map(|v| v.components).sum();
            }
            let single = grids.len() == 1;
            for mut g in grids {
                if let Some(p) = displaced(index, &g) {
                    g.p = p;
                    b.rays.displaced = true;
                }
                (b.rays.du, b.rays.dv) = (2.0 * g.du, 2.0 * g.dv);
                offset = offset.max(triangles(&g, &mut b.tris));
                let base = b.verts.len() as u32;
                hit_vertices(
                    &g,
                    a,
                    &b.rays.vars,
                    &mut b.verts,
                    &mut b.corners,
                    &mut b.var_data,
                );
                if single && !b.rays.displaced {
                    b.rays.analytic = fp
                        .primitive
                        .quadric()
                        .and_then(|(shape, m)| Analytic::new(shape, m, &g, base));
                    b.quadric = b.rays.analytic.as_ref().and_then(|_| {
                        let (shape, m) = fp.primitive.quadric()?;
                        let bound = fp.primitive.bound();
                        ray_quadric(&shape, m, (bound.min, bound.max))
                    });
                    if b.quadric.is_none() {
                        b.rays.analytic = None;
                    }
                }
            }
            b.rays.offset = offset * OFFSET_MARGIN;
            // A quadric's surface bulges past its chords by at most the chord distance.
            let bulge = if b.quadric.is_some() { offset } else { 0.0 };
            b.rays.shell = Shell::of(&b.tris).grown(f64::from(bulge) * 2.0);
            // A closed-form sphere's shell is its own ball: the rays that leave it outwards
            // (most of those from its points) then pass over it, where the grown ball of its
            // chords held their origins and they tested the sphere for nothing.
            if let Some((c, r)) = b.quadric.as_ref().and_then(Quadric::sphere_ball) {
                b.rays.shell = Shell::ball(c, r);
            }
            b
        };
        let per_prim: Vec<PrimBuild> = if parallel {
            frame.primitives.par_iter().enumerate().map(one).collect()
        } else {
            frame.primitives.iter().enumerate().map(one).collect()
        };
        let mut scene = RayScene {
            bvh: Bvh::new(Vec::new()),
            prims: Vec::with_capacity(per_prim.len()),
            tri_prim: Vec::new(),
            tri_verts: Vec::new(),
            verts: Vec::new(),
            var_data: Vec::new(),
            partial_casters: false,
        };
        let mut all = Vec::new();
        let mut groups = Vec::new();
        let mut quadrics = Vec::new();
        for (index, mut b) in per_prim.into_iter().enumerate() {
            let base = scene.verts.len() as u32;
            let var_base = scene.var_data.len() as u32;
            scene.verts.extend(b.verts.into_iter().map(|v| HitVertex {
                vars: v.vars + var_base,
                ..v
            }));
            scene.var_data.extend(b.var_data);
            if let Some(a) = b.rays.analytic.as_mut() {
                a.base += base;
            }
            match b.quadric {
                Some(q) => quadrics.push((q, index as u32)),
                None => {
                    for (t, c) in b.tris.into_iter().zip(b.corners) {
                        scene.tri_verts.push(c.map(|k| base + k));
                        scene.tri_prim.push(index as u32);
                        all.push(t);
                        groups.push(index as u32);
                    }
                }
            }
            scene.prims.push(b.rays);
        }
        // Quadric ids follow the triangles' (`Bvh::with_quadrics`).
        for &(_, index) in &quadrics {
            scene.tri_verts.push([0; 3]);
            scene.tri_prim.push(index);
        }
        scene.bvh = Bvh::with_quadrics(all, groups, quadrics);
        scene.partial_casters = scene.prims.iter().any(|p| p.shadow && p.shadow_os);
        scene
    }

    /// The shadow-ray offset for grids of frame primitive `prim`.
    pub fn offset(&self, prim: usize) -> f32 {
        self.prims.get(prim).map_or(0.0, |p| p.offset)
    }

    /// The BVH group a ray from `origin` along `dir`, leaving primitive `prim`, can pass over:
    /// `prim` itself when its shell shows the ray cannot meet it again, else none.
    pub fn skip(&self, prim: usize, origin: DVec3, dir: DVec3) -> u32 {
        match self.prims.get(prim) {
            Some(p) if p.shell.excludes(origin, dir) => prim as u32,
            _ => NO_GROUP,
        }
    }

    /// The shell of primitive `prim` as seen from `origin`: [`RayScene::skip`] for many
    /// rays leaving one point (`None`: nothing to pass over).
    pub fn seen_from(&self, prim: usize, origin: DVec3) -> Option<SeenFrom> {
        self.prims.get(prim).map(|p| p.shell.seen_from(origin))
    }

    /// Whether any shadow caster is partly transparent to shadow rays (`"Os"`/`"shader"`).
    pub fn has_partial_casters(&self) -> bool {
        self.partial_casters
    }

    pub fn prim(&self, prim: usize) -> Option<&PrimRays> {
        self.prims.get(prim)
    }

    /// The primitive that triangle `id` belongs to.
    pub fn prim_of(&self, id: u32) -> &PrimRays {
        &self.prims[self.tri_prim[id as usize] as usize]
    }

    pub fn prim_index(&self, id: u32) -> usize {
        self.tri_prim[id as usize] as usize
    }

    /// The three vertices of triangle `id`.
    pub fn vertices(&self, id: u32) -> [&HitVertex; 3] {
        self.corner_ids(id).map(|k| &self.verts[k as usize])
    }

    /// The vertex indices of triangle `id`'s corners.
    pub fn corner_ids(&self, id: u32) -> [u32; 3] {
        self.tri_verts[id as usize]
    }

    pub fn vertex(&self, k: u32) -> &HitVertex {
        &self.verts[k as usize]
    }

    /// The `count` primitive variable values of vertex `k` (empty where there are none).
    pub fn vertex_vars(&self, k: u32, count: usize) -> &[f32] {
        let start = self.verts[k as usize].vars as usize;
        self.var_data.get(start..start + count).unwrap_or(&[])
    }

    pub fn bvh(&self) -> &Bvh {
        &self.bvh
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
        let rate = Rate {
            min_segments: MIN_EMITTER_SEGMENTS,
            raster: true,
        };
        for g in diced(fp.primitive.as_ref(), &frame.camera, rate) {
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

/// How finely a primitive is diced for rays.
#[derive(Clone, Copy, Debug)]
struct Rate {
    /// Fewest segments per side of a diceable piece.
    min_segments: usize,
    /// Also about one edge per [`EDGE_PIXELS`] raster pixels.
    raster: bool,
}

/// The primitive split until diceable, each piece diced at twice its ray-tracing rate
/// (`2·segments + 1` vertices per side).
fn diced(prim: &dyn Primitive, camera: &Camera, rate: Rate) -> Vec<Grid> {
    let mut out = Vec::new();
    dice_into(prim, camera, rate, 0, &mut out);
    out
}

fn dice_into(prim: &dyn Primitive, camera: &Camera, rate: Rate, depth: u32, out: &mut Vec<Grid>) {
    if prim.bound().is_empty() {
        return;
    }
    if !prim.diceable() && depth < MAX_SPLIT_DEPTH {
        for child in prim.split() {
            dice_into(child.as_ref(), camera, rate, depth + 1, out);
        }
        return;
    }
    if !prim.diceable() {
        return;
    }
    let (su, sv) = segments(prim, camera, rate);
    let g = prim.dice(2 * su + 1, 2 * sv + 1);
    if g.nu >= 3 && g.nv >= 3 && g.p.len() == g.nu * g.nv && g.nu % 2 == 1 && g.nv % 2 == 1 {
        out.push(g);
    }
}

/// Side of the coarse test dice that measures a piece.
const TEST: usize = 5;

/// Triangle segments per side: the longer of the raster rule (the longest row/column of a
/// coarse test dice over [`EDGE_PIXELS`]; only when `rate.raster`) and the turning rule (its
/// largest turning over [`MAX_TURN`]), clamped.
fn segments(prim: &dyn Primitive, camera: &Camera, rate: Rate) -> (usize, usize) {
    let min_segments = rate.min_segments;
    let g = prim.dice(TEST, TEST);
    if g.p.len() != TEST * TEST {
        return (UNMEASURED_SEGMENTS, UNMEASURED_SEGMENTS);
    }
    let p_camera: Vec<DVec3> = g.p.iter().map(|p| p.as_dvec3()).collect();
    let (tu, tv) = turning(&p_camera);
    let by_turn = |t: f64| (t / MAX_TURN).ceil();
    if !rate.raster {
        let n = |t: f64| (by_turn(t) as usize).clamp(min_segments, MAX_SEGMENTS);
        return (n(tu), n(tv));
    }
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
