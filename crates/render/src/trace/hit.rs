//! Shading-ready geometry for ray hits: every vertex of the ray-tracing tessellation keeps what
//! a shader reads at a surface point (`P`, `N`, `dPdu`, `dPdv`, `u`, `v`, `s`, `t`, `Cs`,
//! `Os`), and a hit becomes a one-point grid by interpolating its triangle's three vertices
//! with the hit's barycentric weights (in `f64`).
//!
//! A ray that carries differentials (`trace()` from a shaded grid) is shaded over the 2×2
//! grid its beam covers at the hit, so texture lookups there are filtered over the beam's
//! footprint rather than point-sampled; rays without one (sampled directions) give a
//! one-point grid.
//!
//! The primitive's other variables (user `varying`/`vertex`/`facevarying` ones a shader
//! parameter binds to, and a user `N`) are stored per vertex the same way and interpolated at
//! the hit like `Cs`, so a reflected surface shows the values of its own primitive variables.
//! A facevarying variable is carried as the grid shows it (one value per vertex of a diced
//! piece), so it stays discontinuous across the faces the tessellation keeps apart.
//!
//! Quadrics (`analytic.rs`) are hit in closed form: their points blend the four vertices of
//! the (u, v) cell the hit lies in, and take `P`, `dPdu`, `dPdv`, `N` from the surface.
use crate::rayscene::{PrimRays, RayScene, VarLayout};
use glam::{DVec3, Vec3};
use illume_geom::{Grid, GridVar};
use illume_raytrace::Hit;
use illume_ri::Attributes;
use illume_shade::RayDifferential;

/// The shading data of one tessellation vertex (camera space, normals unflipped as in
/// [`Grid`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct HitVertex {
    pub p: Vec3,
    pub n: Vec3,
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    pub uv: [f32; 2],
    pub st: [f32; 2],
    pub cs: Vec3,
    pub os: Vec3,
    /// Where its primitive variables' values start in the scene's `var_data`.
    pub vars: u32,
}

/// Appends the vertices of the coarse grid of `g` (its even-indexed vertices, each once) to
/// `verts` and the triangles `rayscene::triangles` makes from them (two per quad, same order)
/// to `tris`, as indices into `verts`; each vertex's values of the variables `layout` names
/// go to `var_data` (zeros for one the grid lacks), its `vars` the index of the first.
pub(crate) fn hit_vertices(
    g: &Grid,
    a: &Attributes,
    layout: &[VarLayout],
    verts: &mut Vec<HitVertex>,
    tris: &mut Vec<[u32; 3]>,
    var_data: &mut Vec<f32>,
) {
    let sources: Vec<Option<&GridVar>> = layout
        .iter()
        .map(|l| {
            g.vars.iter().find(|v| {
                v.name == l.name
                    && v.components == l.components
                    && v.data.len() >= g.len() * l.components
            })
        })
        .collect();
    let vertex = |i: usize, j: usize, vars: u32| {
        let k = j * g.nu + i;
        HitVertex {
            p: g.p[k],
            n: g.n.get(k).copied().unwrap_or(Vec3::ZERO),
            dpdu: g.dpdu.get(k).copied().unwrap_or(Vec3::ZERO),
            dpdv: g.dpdv.get(k).copied().unwrap_or(Vec3::ZERO),
            uv: [
                g.u.get(k).copied().unwrap_or(0.0),
                g.v.get(k).copied().unwrap_or(0.0),
            ],
            st: [
                g.s.get(k).copied().unwrap_or(0.0),
                g.t.get(k).copied().unwrap_or(0.0),
            ],
            cs: g
                .cs
                .as_ref()
                .and_then(|c| c.get(k).copied())
                .unwrap_or(Vec3::from(a.color)),
            os: g
                .os
                .as_ref()
                .and_then(|c| c.get(k).copied())
                .unwrap_or(Vec3::from(a.opacity)),
            vars,
        }
    };
    let base = verts.len() as u32;
    let cu = g.nu.div_ceil(2);
    for j in (0..g.nv).step_by(2) {
        for i in (0..g.nu).step_by(2) {
            let v = vertex(i, j, var_data.len() as u32);
            verts.push(v);
            let k = j * g.nu + i;
            for (l, src) in layout.iter().zip(&sources) {
                match src {
                    Some(src) => var_data
                        .extend_from_slice(&src.data[k * l.components..(k + 1) * l.components]),
                    None => var_data.extend(std::iter::repeat_n(0.0, l.components)),
                }
            }
        }
    }
    let at = |i: usize, j: usize| base + (j / 2 * cu + i / 2) as u32;
    for j in (0..g.nv - 2).step_by(2) {
        for i in (0..g.nu - 2).step_by(2) {
            let (a, b, c, d) = (at(i, j), at(i + 2, j), at(i + 2, j + 2), at(i, j + 2));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
}

/// The facet normal of a triangle (the orientation of `dPdu × dPdv`, as the grid's `Ng`).
fn facet_normal(v: [&HitVertex; 3]) -> Vec3 {
    let [a, b, c] = v.map(|v| v.p.as_dvec3());
    (b - a).cross(c - a).normalize_or_zero().as_vec3()
}

/// One point of a hit grid: where it is and the tessellation vertices it blends (scene
/// vertex indices and weights), with the closed-form frame on a quadric.
struct Point {
    p: DVec3,
    corners: Vec<(u32, f64)>,
    /// On a quadric: `dPdu`, `dPdv` and the unit normal there.
    frame: Option<(DVec3, DVec3, DVec3)>,
}

/// The points of a hit grid: the hit, and with a beam footprint `[dx, dy]` the hit offset by
/// each and by both (a 2×2 grid).
fn points(scene: &RayScene, hit: &Hit, p: DVec3, footprint: Option<[DVec3; 2]>) -> Vec<Point> {
    let offsets: &[DVec3] = match &footprint {
        Some([dx, dy]) => &[DVec3::ZERO, *dx, *dy, *dx + *dy],
        None => &[DVec3::ZERO],
    };
    let prim = scene.prim_of(hit.triangle);
    if let (Some(a), Some([u, v])) = (prim.analytic.as_ref(), hit.uv) {
        return offsets
            .iter()
            .map(|&o| {
                let [du, dv] = a.param_offset(u, v, o);
                let (u, v) = (u + du, v + dv);
                Point {
                    p: p + o,
                    corners: a.corners(u, v).to_vec(),
                    frame: Some(a.frame(u, v)),
                }
            })
            .collect();
    }
    let ids = scene.corner_ids(hit.triangle);
    let tri = ids.map(|k| scene.vertex(k));
    offsets
        .iter()
        .map(|&o| {
            let w = if o == DVec3::ZERO {
                hit.barycentric
            } else {
                barycentric(tri, p + o).unwrap_or(hit.barycentric)
            };
            Point {
                p: p + o,
                corners: ids.iter().copied().zip(w).collect(),
                frame: None,
            }
        })
        .collect()
}

/// The hit as a grid for the hit primitive's shaders, and its frame primitive: one point, or
/// with a ray beam (`beam`, see [`RayDifferential`]) the 2×2 grid of the hit and the hit
/// offset by the beam's two footprint vectors on the surface's tangent plane, so grid
/// differences (`Du`, `Dv`, `area`, the filter width of `texture()`) are those of the beam.
/// Only the first point's result is used; the other three are its neighbours. The primitive's
/// own variables (`Cs`, `Os`, `s`, `t`, user primitive variables, a user `N`) are interpolated
/// at each point.
pub(crate) fn hit_grid(
    scene: &RayScene,
    hit: &Hit,
    origin: DVec3,
    dir: DVec3,
    beam: &RayDifferential,
) -> (Grid, usize) {
    let prim = scene.prim_of(hit.triangle);
    let analytic_n = match (prim.analytic.as_ref(), hit.uv) {
        (Some(a), Some([u, v])) => Some(a.frame(u, v).2).filter(|n| *n != DVec3::ZERO),
        _ => None,
    };
    let ng = match analytic_n {
        Some(n) => n.as_vec3(),
        None if hit.uv.is_some() => (-dir).as_vec3(),
        None => facet_normal(scene.vertices(hit.triangle)),
    };
    // The point on the ray, not the interpolated one: the ray's own hit is exact.
    let p = origin + dir * hit.t;
    let footprint = if beam.is_none() {
        None
    } else {
        beam.transfer(dir, hit.t, ng.as_dvec3())
    };
    let points = points(scene, hit, p, footprint);
    let mix3 = |pt: &Point, f: &dyn Fn(&HitVertex) -> Vec3| {
        let sum = pt.corners.iter().fold(DVec3::ZERO, |s, &(k, w)| {
            s + f(scene.vertex(k)).as_dvec3() * w
        });
        sum.as_vec3()
    };
    let mix1 = |pt: &Point, f: &dyn Fn(&HitVertex) -> f32| {
        let sum = pt
            .corners
            .iter()
            .fold(0.0f64, |s, &(k, w)| s + f64::from(f(scene.vertex(k))) * w);
        sum as f32
    };
    let each3 = |f: &dyn Fn(&HitVertex) -> Vec3| -> Vec<Vec3> {
        points.iter().map(|pt| mix3(pt, f)).collect()
    };
    let each1 = |f: &dyn Fn(&HitVertex) -> f32| -> Vec<f32> {
        points.iter().map(|pt| mix1(pt, f)).collect()
    };
    let normal = |pt: &Point| {
        let n = mix3(pt, &|x| x.n).normalize_or_zero();
        let analytic = pt.frame.map(|f| f.2.as_vec3()).filter(|n| *n != Vec3::ZERO);
        match analytic {
            Some(a) if !prim.user_normals => a,
            _ if prim.displaced || n == Vec3::ZERO => ng,
            _ => n,
        }
    };
    let frame_or = |pt: &Point, k: usize, f: &dyn Fn(&HitVertex) -> Vec3| match pt.frame {
        Some(fr) => [fr.0, fr.1][k].as_vec3(),
        None => mix3(pt, f),
    };
    let (u, vv) = (each1(&|x| x.uv[0]), each1(&|x| x.uv[1]));
    let side = if points.len() == 4 { 2 } else { 1 };
    // The parametric spacing the grid's differences are divided by: the beam's change of
    // u across it (Du(u) = 1), else the tessellation's step.
    let step = |d: f32, fallback: f32| if d.abs() > 0.0 { d.abs() } else { fallback };
    let (du, dv) = if side == 2 {
        (step(u[1] - u[0], prim.du), step(vv[2] - vv[0], prim.dv))
    } else {
        (prim.du, prim.dv)
    };
    let grid = Grid {
        nu: side,
        nv: side,
        p: points.iter().map(|pt| pt.p.as_vec3()).collect(),
        n: points.iter().map(normal).collect(),
        user_normals: prim.user_normals,
        ng: vec![ng; points.len()],
        dpdu: points
            .iter()
            .map(|pt| frame_or(pt, 0, &|x| x.dpdu))
            .collect(),
        dpdv: points
            .iter()
            .map(|pt| frame_or(pt, 1, &|x| x.dpdv))
            .collect(),
        u,
        v: vv,
        du,
        dv,
        s: each1(&|x| x.st[0]),
        t: each1(&|x| x.st[1]),
        cs: Some(each3(&|x| x.cs)),
        os: Some(each3(&|x| x.os)),
        vars: hit_vars(scene, prim, &points),
        ..Grid::default()
    };
    (grid, scene.prim_index(hit.triangle))
}

/// The primitive's own variables at the grid's points, blended from their vertices' values.
fn hit_vars(scene: &RayScene, prim: &PrimRays, points: &[Point]) -> Vec<GridVar> {
    let mut offset = 0usize;
    prim.vars
        .iter()
        .map(|layout| {
            let mut data = Vec::with_capacity(points.len() * layout.components);
            for pt in points {
                for c in 0..layout.components {
                    let sum = pt.corners.iter().fold(0.0f64, |s, &(k, w)| {
                        let values = scene.vertex_vars(k, prim.var_floats);
                        s + f64::from(values.get(offset + c).copied().unwrap_or(0.0)) * w
                    });
                    data.push(sum as f32);
                }
            }
            offset += layout.components;
            GridVar {
                name: layout.name.clone(),
                ty: layout.ty,
                components: layout.components,
                data,
            }
        })
        .collect()
}

/// The barycentric weights of `q` (on the triangle's plane, possibly outside the triangle)
/// relative to the triangle's vertices; `None` for a degenerate triangle.
fn barycentric(v: [&HitVertex; 3], q: DVec3) -> Option<[f64; 3]> {
    let [a, b, c] = v.map(|x| x.p.as_dvec3());
    let (e1, e2, d) = (b - a, c - a, q - a);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d1, d2) = (d.dot(e1), d.dot(e2));
    let det = d11 * d22 - d12 * d12;
    if det.abs() <= f64::MIN_POSITIVE || !det.is_finite() {
        return None;
    }
    let wb = (d22 * d1 - d12 * d2) / det;
    let wc = (d11 * d2 - d12 * d1) / det;
    Some([1.0 - wb - wc, wb, wc])
}

/// `Os` at the hit (for partial transmission).
pub(crate) fn hit_opacity(scene: &RayScene, hit: &Hit) -> Vec3 {
    let prim = scene.prim_of(hit.triangle);
    let corners: Vec<(u32, f64)> = match (prim.analytic.as_ref(), hit.uv) {
        (Some(a), Some([u, v])) => a.corners(u, v).to_vec(),
        _ => scene
            .corner_ids(hit.triangle)
            .into_iter()
            .zip(hit.barycentric)
            .collect(),
    };
    let sum = corners.iter().fold(DVec3::ZERO, |s, &(k, w)| {
        s + scene.vertex(k).os.as_dvec3() * w
    });
    sum.as_vec3()
}
