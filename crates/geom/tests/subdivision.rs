//! Catmull–Clark subdivision against closed forms: a cube's corners converge to their limit
//! position, infinitely sharp creases stay on the control polygon, holes are not rendered,
//! `interpolateboundary` makes the boundary the cubic B-spline of the boundary polygon.
mod support;

use glam::DVec3;
use illume_geom::subdivision::{control_mesh_of, Mesh, SubdivisionArgs};
use illume_rib::Request;
use support::*;

/// The cube [-1,1]³: vertex k has coordinates (±1, ±1, ±1) by its bits (x = bit 0, y = bit 1,
/// z = bit 2); faces wound outward.
fn cube_points() -> Vec<f32> {
    (0..8)
        .flat_map(|k| [0, 1, 2].map(|b| if k >> b & 1 == 1 { 1.0 } else { -1.0 }))
        .collect()
}

const CUBE_FACES: [i32; 24] = [
    0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5,
];

fn request(
    points: Vec<f32>,
    nvertices: Vec<i32>,
    vertices: Vec<i32>,
    tags: &[(&str, Vec<i32>, Vec<f32>)],
) -> Request {
    Request::SubdivisionMesh {
        scheme: "catmull-clark".to_string(),
        nvertices,
        vertices,
        tags: tags.iter().map(|t| t.0.to_string()).collect(),
        nargs: tags
            .iter()
            .flat_map(|t| [t.1.len() as i32, t.2.len() as i32])
            .collect(),
        intargs: tags.iter().flat_map(|t| t.1.clone()).collect(),
        floatargs: tags.iter().flat_map(|t| t.2.clone()).collect(),
        params: vec![floats("P", &points)],
    }
}

fn cube(tags: &[(&str, Vec<i32>, Vec<f32>)]) -> Request {
    request(cube_points(), vec![4; 6], CUBE_FACES.to_vec(), tags)
}

fn mesh(r: &Request) -> Mesh {
    let Request::SubdivisionMesh {
        scheme,
        nvertices,
        vertices,
        tags,
        nargs,
        intargs,
        floatargs,
        params,
    } = r
    else {
        unreachable!()
    };
    let args = SubdivisionArgs {
        scheme,
        nvertices,
        vertices,
        tags,
        nargs,
        intargs,
        floatargs,
    };
    control_mesh_of(args, params, &ctx()).unwrap().0
}

/// The limit of the cube corner v = (1,1,1), valence n = 3, all faces quads. Catmull–Clark's
/// limit mask (Halstead, Kass & DeRose 1993, from the dominant left eigenvector of the
/// subdivision matrix) weighs the vertex n², each edge neighbour 4 and each face-diagonal
/// vertex 1, over n(n+5) = 24. Per coordinate: the vertex 1 (×9), the edge neighbours
/// (−1,1,1), (1,−1,1), (1,1,−1) sum to 1 (×4), the diagonals (−1,−1,1), (−1,1,−1), (1,−1,−1)
/// sum to −1: (9 + 4 − 1)/24 = 1/2.
const CUBE_CORNER_LIMIT: f64 = (9.0 + 4.0 - 1.0) / 24.0;

#[test]
fn cube_corner_converges_to_the_catmull_clark_limit() {
    let m = mesh(&cube(&[]));
    let limit = DVec3::splat(CUBE_CORNER_LIMIT);
    // Plain subdivision (no limit stencil): the corner vertex keeps its index and its distance
    // to the limit shrinks every step (geometrically, by the subdominant eigenvalue).
    let mut last = f64::INFINITY;
    for level in 1..=7 {
        let d = m.subdivided(level).position(7).distance(limit);
        assert!(d < last, "level {level}: {d} after {last}");
        last = d;
    }
    assert!(
        last < 2e-3,
        "after 7 levels the corner is {last} from its limit"
    );
    // The limit stencil lands on it exactly.
    for level in 1..=3 {
        let d = m.limit_mesh(level).position(7).distance(limit);
        assert!(
            d < 1e-12,
            "pushed to the limit at level {level}: off by {d}"
        );
    }
    // Through build and dice (f32 grids): the farthest point along the diagonal is the corner.
    let grids = all_grids(&build_ok(&cube(&[])), 3);
    let corner =
        grids
            .iter()
            .flat_map(|g| g.p.iter().map(|&p| v3(p)))
            .fold(DVec3::splat(-9.0), |a, p| {
                if p.x + p.y + p.z > a.x + a.y + a.z {
                    p
                } else {
                    a
                }
            });
    assert!(corner.distance(limit) < 1e-6, "diced corner {corner}");
}

#[test]
fn infinitely_sharp_crease_and_corners_keep_the_top_edges_on_the_control_polygon() {
    // The top face's four edges creased (sharpness 10 > levels: never softens), and its four
    // vertices as corners: the limit boundary of the top face is the square itself.
    let top = vec![4, 5, 7, 6, 4];
    let tags = [
        ("crease", top.clone(), vec![10.0]),
        ("corner", vec![4, 5, 6, 7], vec![10.0]),
    ];
    let m = mesh(&cube(&tags)).limit_mesh(3);
    let on_top: Vec<DVec3> = (0..m.rows.len())
        .map(|v| m.position(v))
        .filter(|p| p.z > 1.0 - 1e-9)
        .collect();
    assert!(m.rows.iter().all(|r| r[2] <= 1.0 + 1e-12));
    // The crease loop isolates the top face: its whole 9×9 limit grid stays flat at z = 1,
    // inside the square, and the 32 points of its border (8 segments per edge after 3 levels)
    // lie on the square's edges.
    assert_eq!(on_top.len(), 81);
    assert!(on_top
        .iter()
        .all(|p| p.x.abs().max(p.y.abs()) <= 1.0 + 1e-12));
    let border = on_top
        .iter()
        .filter(|p| (p.x.abs().max(p.y.abs()) - 1.0).abs() < 1e-12)
        .count();
    assert_eq!(border, 32);
    // An edge midpoint is a limit point.
    assert!(on_top
        .iter()
        .any(|p| p.distance(DVec3::new(0.0, 1.0, 1.0)) < 1e-12));
    // Without the crease the top is rounded: nothing reaches z = 1.
    let smooth = mesh(&cube(&[])).limit_mesh(3);
    assert!(smooth.rows.iter().all(|r| r[2] < 0.9));
}

#[test]
fn hole_faces_are_not_rendered() {
    let full = build_ok(&cube(&[]));
    // Face 1 is the top (z = +1).
    let holed = build_ok(&cube(&[("hole", vec![1], vec![])]));
    assert_eq!(holed.len() * 6, full.len() * 5);
    let near_top_centre = |prims: &[Box<dyn illume_geom::Primitive>]| {
        all_grids(prims, 3)
            .iter()
            .flat_map(|g| g.p.clone())
            .filter(|p| p.x.abs() < 0.3 && p.y.abs() < 0.3 && p.z > 0.0)
            .count()
    };
    assert!(near_top_centre(&full) > 0);
    assert_eq!(near_top_centre(&holed), 0);
}

/// A 4×4-vertex (3×3-face) sheet, x = i, y = j, with uneven heights.
fn sheet(tags: &[(&str, Vec<i32>, Vec<f32>)]) -> (Request, Vec<f64>) {
    let z = |i: i32, j: i32| ((i * 7 + j * 3) % 5) as f32 * 0.25 - 0.4 * (i * j) as f32 / 9.0;
    let mut pts = Vec::new();
    let mut zs = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            pts.extend([i as f32, j as f32, z(i, j)]);
            zs.push(f64::from(z(i, j)));
        }
    }
    let mut verts = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            let k = j * 4 + i;
            verts.extend([k, k + 1, k + 5, k + 4]);
        }
    }
    (request(pts, vec![4; 9], verts, tags), zs)
}

#[test]
fn interpolateboundary_makes_the_boundary_the_cubic_b_spline_of_its_polygon() {
    let (r, z) = sheet(&[("interpolateboundary", vec![], vec![])]);
    let m = mesh(&r).limit_mesh(3);
    // Along the edge y = 0 the boundary polygon is P0..P3 = vertices 0..3 (corners at the
    // ends interpolate: the B-spline with phantom points 2P0 − P1). Uniform cubic B-spline:
    // at the knot of P1 the limit is (P0 + 4P1 + P2)/6; at the middle of span P1P2 it is
    // (P0 + 23P1 + 23P2 + P3)/48.
    let knot = (z[0] + 4.0 * z[1] + z[2]) / 6.0;
    assert!((m.position(1).z - knot).abs() < 1e-12);
    assert!(m.position(1).distance(DVec3::new(1.0, 0.0, knot)) < 1e-12);
    let mid = (z[0] + 23.0 * z[1] + 23.0 * z[2] + z[3]) / 48.0;
    let found = (0..m.rows.len())
        .map(|v| m.position(v))
        .find(|p| (p.x - 1.5).abs() < 1e-12 && p.y.abs() < 1e-12)
        .expect("a limit point at the span's middle");
    assert!((found.z - mid).abs() < 1e-12, "{} vs {mid}", found.z);
    // The corner is interpolated.
    assert!(m.position(0).distance(DVec3::new(0.0, 0.0, z[0])) < 1e-12);
    // Without the tag only the face away from the boundary renders: 64 of 9·64 quads.
    let with = build_ok(&r).len();
    let without = build_ok(&sheet(&[]).0).len();
    assert_eq!((with, without), (9 * 64, 64));
}

#[test]
fn facevarying_and_uniform_values_reach_the_grids() {
    // Face-varying s: each cube face carries 0 1 2 3 at its corners; uniform id per face.
    let fv: Vec<f32> = (0..6).flat_map(|_| [0.0, 1.0, 2.0, 3.0]).collect();
    let ids: Vec<f32> = (0..6).map(|f| f as f32).collect();
    let mut r = cube(&[]);
    if let Request::SubdivisionMesh { params, .. } = &mut r {
        params.push(floats("facevarying float q", &fv));
        params.push(floats("uniform float id", &ids));
    }
    let grids = all_grids(&build_ok(&r), 2);
    assert_eq!(grids.len(), 6 * 64);
    let var =
        |g: &illume_geom::Grid, n: &str| g.vars.iter().find(|v| v.name == n).unwrap().data.clone();
    // Face-varying values are interpolated linearly within their face: between 0 and 3, and
    // each face's quads hit all four corner values exactly.
    for g in &grids {
        assert!(var(g, "q").iter().all(|&q| (0.0..=3.0).contains(&q)));
    }
    for f in 0..6 {
        let mut corners: Vec<f32> = grids
            .iter()
            .filter(|g| var(g, "id")[0] == f as f32)
            .flat_map(|g| var(g, "q"))
            .filter(|q| q.fract() == 0.0)
            .collect();
        corners.sort_by(f32::total_cmp);
        corners.dedup();
        assert_eq!(corners, [0.0, 1.0, 2.0, 3.0], "face {f}");
    }
}

#[test]
fn bad_meshes_are_errors_not_panics() {
    for r in [
        request(cube_points(), vec![4; 6], CUBE_FACES[..20].to_vec(), &[]),
        request(
            cube_points(),
            vec![2, 4, 4, 4, 4, 6],
            CUBE_FACES.to_vec(),
            &[],
        ),
        request(
            cube_points()[..21].to_vec(),
            vec![4; 6],
            CUBE_FACES.to_vec(),
            &[],
        ),
        cube(&[("crease", vec![0, 99], vec![1.0])]),
        cube(&[("hole", vec![6], vec![])]),
    ] {
        assert!(illume_geom::build(&r, &ctx()).is_err(), "{r:?}");
    }
    let mut loop_scheme = cube(&[]);
    if let Request::SubdivisionMesh { scheme, .. } = &mut loop_scheme {
        *scheme = "loop".to_string();
    }
    assert!(matches!(
        illume_geom::build(&loop_scheme, &ctx()),
        Err(illume_geom::GeomError::Unsupported(_))
    ));
}
