//! Marching tetrahedra over a regular lattice: the triangle mesh of an isosurface
//! `field(p) = level`, in f64.
//!
//! Each cube is cut into the six Kuhn tetrahedra around its main diagonal. That triangulation
//! is consistent across neighbouring cubes (their shared faces are cut along the same
//! diagonal), so the mesh has no cracks and, unlike marching cubes, no ambiguous cases or
//! tables. Vertices are found by bracketed root finding on each crossing edge (Illinois
//! regula falsi), so they lie on the exact isosurface to f64 precision, not at a linear
//! interpolation of the lattice values; each edge is solved once and shared by its triangles.
//! Triangles wind so `(b − a) × (c − a)` points from the inside (`field > level`) out.
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// A lattice of `n[0] × n[1] × n[2]` points `origin + h·(i, j, k)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice {
    pub origin: DVec3,
    pub h: f64,
    pub n: [usize; 3],
}

impl Lattice {
    fn point(&self, i: usize, j: usize, k: usize) -> DVec3 {
        self.origin + DVec3::new(i as f64, j as f64, k as f64) * self.h
    }

    fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (k * self.n[1] + j) * self.n[0] + i
    }
}

/// The six tetrahedra of a unit cube as corner bit masks (bit 0 = +x, 1 = +y, 2 = +z), each a
/// monotone path from corner 0 to corner 7 (one per ordering of the axes).
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 1, 5, 7],
    [0, 2, 3, 7],
    [0, 2, 6, 7],
    [0, 4, 5, 7],
    [0, 4, 6, 7],
];

/// Where `g(t) = 0` on `[0, 1]` given `g(0) > 0 ≥ g(1)`: Illinois regula falsi, falling back
/// to bisection when it stalls; ≤ 100 steps, to `|Δt| < 1e-15`.
pub fn bracketed_root(g: &dyn Fn(f64) -> f64, g0: f64, g1: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (0.0f64, 1.0f64, g0, g1);
    let mut side = 0i8;
    for step in 0..100 {
        let t = if step % 8 == 7 || fa == fb {
            0.5 * (a + b)
        } else {
            (a * fb - b * fa) / (fb - fa)
        };
        let t = if t > a && t < b { t } else { 0.5 * (a + b) };
        let ft = g(t);
        if ft > 0.0 {
            a = t;
            fa = ft;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        } else {
            b = t;
            fb = ft;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        }
        if b - a < 1e-15 || ft == 0.0 {
            return t;
        }
    }
    0.5 * (a + b)
}

/// Polygonizes `field(p) = level` over the lattice. Points outside the lattice are treated
/// as outside the surface only in that the mesh is cut at the lattice boundary, so callers
/// pad the lattice beyond the surface's bound.
pub fn marching_tetrahedra(
    lattice: &Lattice,
    field: &(dyn Fn(DVec3) -> f64 + Sync),
    level: f64,
) -> TriangleMesh {
    let [nx, ny, nz] = lattice.n;
    // The lattice's field values, a plane per task: they are most of the work (up to 131³
    // evaluations, serial while the RIB is read), and each is a pure function of its point.
    let mut values = vec![0.0f64; nx * ny * nz];
    let plane = (nx * ny).max(1);
    values
        .par_chunks_mut(plane)
        .enumerate()
        .for_each(|(k, values)| {
            for j in 0..ny {
                for i in 0..nx {
                    values[j * nx + i] = field(lattice.point(i, j, k)) - level;
                }
            }
        });
    let mut mesh = TriangleMesh::default();
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    for k in 0..nz.saturating_sub(1) {
        for j in 0..ny.saturating_sub(1) {
            for i in 0..nx.saturating_sub(1) {
                let corner = |c: usize| (i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
                let ids: [usize; 8] = std::array::from_fn(|c| {
                    let (a, b, d) = corner(c);
                    lattice.index(a, b, d)
                });
                let inside = ids.iter().filter(|&&id| values[id] > 0.0).count();
                if inside == 0 || inside == 8 {
                    continue;
                }
                let pos: [DVec3; 8] = std::array::from_fn(|c| {
                    let (a, b, d) = corner(c);
                    lattice.point(a, b, d)
                });
                for tet in KUHN {
                    let v = tet.map(|c| (ids[c], pos[c], values[ids[c]]));
                    emit_tetrahedron(&v, field, level, &mut edges, &mut mesh);
                }
            }
        }
    }
    mesh
}

type Corner = (usize, DVec3, f64);

fn emit_tetrahedron(
    v: &[Corner; 4],
    field: &(dyn Fn(DVec3) -> f64 + Sync),
    level: f64,
    edges: &mut HashMap<(usize, usize), u32>,
    mesh: &mut TriangleMesh,
) {
    let (ins, outs): (Vec<&Corner>, Vec<&Corner>) = v.iter().partition(|c| c.2 > 0.0);
    if ins.is_empty() || outs.is_empty() {
        return;
    }
    let mut vertex = |a: &Corner, b: &Corner| -> u32 {
        *edges.entry((a.0, b.0)).or_insert_with(|| {
            let (pa, pb) = (a.1, b.1);
            let t = bracketed_root(&|t| field(pa + (pb - pa) * t) - level, a.2, b.2);
            mesh.positions.push(pa + (pb - pa) * t);
            (mesh.positions.len() - 1) as u32
        })
    };
    let ring: Vec<u32> = match (ins.len(), outs.len()) {
        (1, 3) => outs.iter().map(|o| vertex(ins[0], o)).collect(),
        (3, 1) => ins.iter().map(|i| vertex(i, outs[0])).collect(),
        // Two in, two out: the four crossing edges form a quad, in cyclic order.
        _ => vec![
            vertex(ins[0], outs[0]),
            vertex(ins[0], outs[1]),
            vertex(ins[1], outs[1]),
            vertex(ins[1], outs[0]),
        ],
    };
    let centroid = |cs: &[&Corner]| cs.iter().map(|c| c.1).sum::<DVec3>() / cs.len() as f64;
    let outward = centroid(&outs) - centroid(&ins);
    let tris: &[[usize; 3]] = if ring.len() == 3 {
        &[[0, 1, 2]]
    } else {
        &[[0, 1, 2], [0, 2, 3]]
    };
    for t in tris {
        let [a, b, c] = t.map(|k| ring[k]);
        let (pa, pb, pc) = (
            mesh.positions[a as usize],
            mesh.positions[b as usize],
            mesh.positions[c as usize],
        );
        let n = (pb - pa).cross(pc - pa);
        if n.length_squared() == 0.0 || a == b || b == c || a == c {
            continue;
        }
        mesh.triangles.push(if n.dot(outward) >= 0.0 {
            [a, b, c]
        } else {
            [a, c, b]
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(r: f64) -> impl Fn(DVec3) -> f64 + Sync {
        move |p: DVec3| r * r - p.length_squared()
    }

    fn lattice(half: f64, n: usize) -> Lattice {
        Lattice {
            origin: DVec3::splat(-half),
            h: 2.0 * half / (n - 1) as f64,
            n: [n; 3],
        }
    }

    #[test]
    fn sphere_vertices_lie_on_the_surface_and_triangles_face_out() {
        let mesh = marching_tetrahedra(&lattice(1.3, 17), &ball(1.0), 0.0);
        assert!(mesh.triangles.len() > 200);
        for p in &mesh.positions {
            assert!((p.length() - 1.0).abs() < 1e-12, "{p}");
        }
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            assert!((b - a).cross(c - a).dot(a + b + c) > 0.0);
        }
    }

    #[test]
    fn sphere_mesh_is_closed() {
        // Every edge of a closed, consistently wound mesh is used once in each direction.
        let mesh = marching_tetrahedra(&lattice(1.3, 12), &ball(1.0), 0.0);
        let mut count: HashMap<(u32, u32), i32> = HashMap::new();
        for t in &mesh.triangles {
            for e in 0..3 {
                *count.entry((t[e], t[(e + 1) % 3])).or_default() += 1;
            }
        }
        for (&(a, b), &n) in &count {
            assert_eq!(n, 1, "edge {a}-{b} used {n} times");
            assert_eq!(count.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
        }
    }

    #[test]
    fn enclosed_volume_approaches_the_ball() {
        // Divergence theorem: V = Σ (a · (b × c)) / 6 over outward triangles.
        let mesh = marching_tetrahedra(&lattice(1.3, 40), &ball(1.0), 0.0);
        let v: f64 = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        let exact = 4.0 / 3.0 * std::f64::consts::PI;
        // Chords of length ~h = 0.067 under-cut the ball by about h²/8 of the radius → ~0.2%·3.
        assert!((v - exact).abs() / exact < 0.01, "{v} vs {exact}");
    }

    #[test]
    fn bracketed_root_finds_a_simple_root() {
        let t = bracketed_root(&|t| 0.3 - t * t, 0.3, -0.7);
        assert!((t - 0.3f64.sqrt()).abs() < 1e-14);
    }
}
