//! Shading-ready geometry for ray hits: every vertex of the ray-tracing tessellation keeps what
//! a shader reads at a surface point (`P`, `N`, `dPdu`, `dPdv`, `u`, `v`, `s`, `t`, `Cs`,
//! `Os`), and a hit becomes a one-point grid by interpolating its triangle's three vertices
//! with the hit's barycentric weights (in `f64`).
//!
//! Not carried: other primitive variables (a shader parameter bound to a vertex variable reads
//! its default at a hit), and ray differentials (the one-point grid has no neighbours, so
//! texture lookups at hits are point-sampled).
use crate::rayscene::RayScene;
use glam::{DVec3, Vec3};
use illume_geom::Grid;
use illume_raytrace::Hit;
use illume_ri::Attributes;

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

/// The hit as a one-point grid for the hit primitive's shaders, and its frame primitive.
pub(crate) fn hit_grid(scene: &RayScene, hit: &Hit, origin: DVec3, dir: DVec3) -> (Grid, usize) {
    let v = scene.vertices(hit.triangle);
    let w = hit.barycentric;
    let mix3 = |f: &dyn Fn(&HitVertex) -> Vec3| {
        (f(v[0]).as_dvec3() * w[0] + f(v[1]).as_dvec3() * w[1] + f(v[2]).as_dvec3() * w[2])
            .as_vec3()
    };
    let mix1 = |f: &dyn Fn(&HitVertex) -> f32| {
        (f64::from(f(v[0])) * w[0] + f64::from(f(v[1])) * w[1] + f64::from(f(v[2])) * w[2]) as f32
    };
    let prim = scene.prim_of(hit.triangle);
    let ng = facet_normal(v);
    let n = if prim.displaced {
        ng
    } else {
        let n = mix3(&|x| x.n).normalize_or_zero();
        if n == Vec3::ZERO {
            ng
        } else {
            n
        }
    };
    // The point on the ray, not the interpolated one: the ray's own hit is exact.
    let p = (origin + dir * hit.t).as_vec3();
    let grid = Grid {
        nu: 1,
        nv: 1,
        p: vec![p],
        n: vec![n],
        ng: vec![ng],
        dpdu: vec![mix3(&|x| x.dpdu)],
        dpdv: vec![mix3(&|x| x.dpdv)],
        u: vec![mix1(&|x| x.uv[0])],
        v: vec![mix1(&|x| x.uv[1])],
        du: prim.du,
        dv: prim.dv,
        s: vec![mix1(&|x| x.st[0])],
        t: vec![mix1(&|x| x.st[1])],
        cs: Some(vec![mix3(&|x| x.cs)]),
        os: Some(vec![mix3(&|x| x.os)]),
        ..Grid::default()
    };
    (grid, scene.prim_index(hit.triangle))
}

/// `Os` at the hit (for partial transmission).
pub(crate) fn hit_opacity(scene: &RayScene, hit: &Hit) -> Vec3 {
    let v = scene.vertices(hit.triangle);
    let w = hit.barycentric;
    (v[0].os.as_dvec3() * w[0] + v[1].os.as_dvec3() * w[1] + v[2].os.as_dvec3() * w[2]).as_vec3()
}
