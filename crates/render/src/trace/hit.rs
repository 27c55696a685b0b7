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
//! Not carried: other primitive variables (a shader parameter bound to a vertex variable reads
//! its default at a hit).
use crate::rayscene::RayScene;
use glam::{DVec3, Vec3};
use illume_geom::Grid;
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
}

/// Appends the vertices of the coarse grid of `g` (its even-indexed vertices, each once) to
/// `verts` and the triangles `rayscene::triangles` makes from them (two per quad, same order)
/// to `tris`, as indices into `verts`.
pub(crate) fn hit_vertices(
    g: &Grid,
    a: &Attributes,
    verts: &mut Vec<HitVertex>,
    tris: &mut Vec<[u32; 3]>,
) {
    let vertex = |i: usize, j: usize| {
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
        }
    };
    let base = verts.len() as u32;
    let cu = g.nu.div_ceil(2);
    for j in (0..g.nv).step_by(2) {
        for i in (0..g.nu).step_by(2) {
            verts.push(vertex(i, j));
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

/// The hit as a grid for the hit primitive's shaders, and its frame primitive: one point, or
/// with a ray beam (`beam`, see [`RayDifferential`]) the 2×2 grid of the hit and the hit
/// offset by the beam's two footprint vectors on the triangle's plane, so grid differences
/// (`Du`, `Dv`, `area`, the filter width of `texture()`) are those of the beam. Only the
/// first point's result is used; the other three are its neighbours.
pub(crate) fn hit_grid(
    scene: &RayScene,
    hit: &Hit,
    origin: DVec3,
    dir: DVec3,
    beam: &RayDifferential,
) -> (Grid, usize) {
    let v = scene.vertices(hit.triangle);
    let prim = scene.prim_of(hit.triangle);
    let ng = facet_normal(v);
    // The point on the ray, not the interpolated one: the ray's own hit is exact.
    let p = origin + dir * hit.t;
    let footprint = if beam.is_none() {
        None
    } else {
        beam.transfer(dir, hit.t, ng.as_dvec3())
    };
    let points: Vec<(DVec3, [f64; 3])> = match footprint {
        Some([dx, dy]) => [DVec3::ZERO, dx, dy, dx + dy]
            .iter()
            .map(|&o| (p + o, barycentric(v, p + o).unwrap_or(hit.barycentric)))
            .collect(),
        None => vec![(p, hit.barycentric)],
    };
    let mix3 = |w: &[f64; 3], f: &dyn Fn(&HitVertex) -> Vec3| {
        (f(v[0]).as_dvec3() * w[0] + f(v[1]).as_dvec3() * w[1] + f(v[2]).as_dvec3() * w[2])
            .as_vec3()
    };
    let mix1 = |w: &[f64; 3], f: &dyn Fn(&HitVertex) -> f32| {
        (f64::from(f(v[0])) * w[0] + f64::from(f(v[1])) * w[1] + f64::from(f(v[2])) * w[2]) as f32
    };
    let each3 = |f: &dyn Fn(&HitVertex) -> Vec3| -> Vec<Vec3> {
        points.iter().map(|(_, w)| mix3(w, f)).collect()
    };
    let each1 = |f: &dyn Fn(&HitVertex) -> f32| -> Vec<f32> {
        points.iter().map(|(_, w)| mix1(w, f)).collect()
    };
    let normal = |w: &[f64; 3]| {
        let n = mix3(w, &|x| x.n).normalize_or_zero();
        if prim.displaced || n == Vec3::ZERO {
            ng
        } else {
            n
        }
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
        p: points.iter().map(|(q, _)| q.as_vec3()).collect(),
        n: points.iter().map(|(_, w)| normal(w)).collect(),
        ng: vec![ng; points.len()],
        dpdu: each3(&|x| x.dpdu),
        dpdv: each3(&|x| x.dpdv),
        u,
        v: vv,
        du,
        dv,
        s: each1(&|x| x.st[0]),
        t: each1(&|x| x.st[1]),
        cs: Some(each3(&|x| x.cs)),
        os: Some(each3(&|x| x.os)),
        ..Grid::default()
    };
    (grid, scene.prim_index(hit.triangle))
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
    let v = scene.vertices(hit.triangle);
    let w = hit.barycentric;
    (v[0].os.as_dvec3() * w[0] + v[1].os.as_dvec3() * w[1] + v[2].os.as_dvec3() * w[2]).as_vec3()
}
