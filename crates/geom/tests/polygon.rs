//! Polygons against exact areas, winding, variables and bad input.
mod support;
use glam::{DMat4, DVec3, Vec3};
use illume_geom::{build, BuildContext, GeomError};
use illume_rib::{Param, Request, Value};
use support::*;

fn pts(p: &[[f32; 3]]) -> Vec<f32> {
    p.iter().flatten().copied().collect()
}

fn ints(v: &[i32]) -> Vec<i32> {
    v.to_vec()
}

#[test]
fn square_polygon_area_and_normal_follow_the_winding() {
    let ccw = [[0., 0., 0.], [2., 0., 0.], [2., 3., 0.], [0., 3., 0.]];
    let r = Request::Polygon {
        params: vec![floats("P", &pts(&ccw))],
    };
    let prims = build_ok(&r);
    assert!(close(area(&prims, 8), 6.0, 1e-12));
    let g = prims[0].dice(3, 3);
    assert!(g.ng.iter().all(|n| (*n - Vec3::Z).length() < 1e-6));
    let mut cw = ccw;
    cw.reverse();
    let g = build_ok(&Request::Polygon {
        params: vec![floats("P", &pts(&cw))],
    })[0]
        .dice(3, 3);
    assert!(g.ng.iter().all(|n| (*n + Vec3::Z).length() < 1e-6));
}

/// An L shape of area 3 with a square hole of area 0.25, in the tilted plane z = x.
fn l_with_hole() -> (Vec<[f32; 3]>, Vec<i32>) {
    let outer = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];
    let hole = [[0.25, 0.25], [0.25, 0.75], [0.75, 0.75], [0.75, 0.25]];
    let p = outer
        .iter()
        .chain(&hole)
        .map(|[x, y]| [*x, *y, *x])
        .collect();
    (p, vec![6, 4])
}

#[test]
fn concave_general_polygon_with_hole_area() {
    let (p, nverts) = l_with_hole();
    let r = Request::GeneralPolygon {
        nverts: ints(&nverts),
        params: vec![floats("P", &pts(&p))],
    };
    let prims = build_ok(&r);
    // The plane z = x stretches areas by √2.
    let want = 2.75 * 2f64.sqrt();
    let a = area(&prims, 4);
    assert!(close(a, want, 1e-9), "{a} vs {want}");
    // Every triangle keeps the outer loop's counter-clockwise winding: normal ∝ (−1, 0, 1).
    let n = Vec3::new(-1.0, 0.0, 1.0).normalize();
    for p in &prims {
        let g = p.dice(3, 3);
        assert!((g.ng[0] - n).length() < 1e-5, "{}", g.ng[0]);
    }
}

#[test]
fn points_polygons_mesh_area_and_variables() {
    // A 2×2 grid of unit quads over 9 shared vertices, one face given as a concave pentagon
    // would be overkill: the last face is split into two triangles instead.
    let p: Vec<[f32; 3]> = (0..9)
        .map(|k| [(k % 3) as f32, (k / 3) as f32, 0.0])
        .collect();
    let r = Request::PointsPolygons {
        nverts: ints(&[4, 4, 4, 3, 3]),
        verts: ints(&[0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 4, 8, 7]),
        params: vec![
            floats("P", &pts(&p)),
            floats(
                "Cs",
                &(0..9)
                    .flat_map(|k| [k as f32, 0.0, 0.0])
                    .collect::<Vec<_>>(),
            ),
            floats("uniform float id", &[10., 11., 12., 13., 14.]),
            floats(
                "facevarying float fv",
                &(0..18).map(|k| k as f32).collect::<Vec<_>>(),
            ),
        ],
    };
    let prims = build_ok(&r);
    assert_eq!(prims.len(), 5);
    assert!(close(area(&prims, 5), 4.0, 1e-12));
    // Face 0 is the quad 0 1 4 3: bilinear corners 0, 1, 3, 4.
    let g = prims[0].dice(3, 3);
    let cs: Vec<f32> = g.cs.as_ref().unwrap().iter().map(|c| c.x).collect();
    assert_eq!(
        (cs[0], cs[2], cs[6], cs[8], cs[4]),
        (0.0, 1.0, 3.0, 4.0, 2.0)
    );
    let fv = &g.vars.iter().find(|v| v.name == "fv").unwrap().data;
    assert_eq!((fv[0], fv[2], fv[6], fv[8]), (0.0, 1.0, 3.0, 2.0));
    let g = prims[4].dice(3, 3);
    let id = &g.vars.iter().find(|v| v.name == "id").unwrap().data;
    assert!(id.iter().all(|&x| x == 14.0));
    // Default texture coordinates are the object-space (x, y).
    for (k, p) in g.p.iter().enumerate() {
        assert!((g.s[k] - p.x).abs() < 1e-6 && (g.t[k] - p.y).abs() < 1e-6);
    }
    // Over a triangle the variables are linear in position: Cs.x = 3y + x on this grid.
    for (p, c) in g.p.iter().zip(g.cs.as_ref().unwrap()) {
        assert!((c.x - (3.0 * p.y + p.x)).abs() < 1e-5, "{p} {c}");
    }
}

#[test]
fn points_general_polygons_with_hole_and_second_face() {
    let (mut p, _) = l_with_hole();
    p.push([5.0, 0.0, 0.0]);
    p.push([6.0, 0.0, 0.0]);
    p.push([5.0, 1.0, 0.0]);
    let r = Request::PointsGeneralPolygons {
        nloops: ints(&[2, 1]),
        nverts: ints(&[6, 4, 3]),
        verts: (0..13).collect(),
        params: vec![floats("P", &pts(&p))],
    };
    let a = area(&build_ok(&r), 3);
    assert!(close(a, 2.75 * 2f64.sqrt() + 0.5, 1e-9), "{a}");
}

#[test]
fn user_normals_use_the_inverse_transpose() {
    // A user N equal to the true normal stays perpendicular to the surface under a shear and
    // an anisotropic scale only if transformed by the inverse transpose.
    let m = DMat4::from_cols_array(&[
        1.0, 0.0, 0.0, 0.0, 0.7, 2.0, 0.0, 0.0, 0.3, 0.0, 0.5, 0.0, 1.0, 2.0, 9.0, 1.0,
    ]);
    let square = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
    let r = Request::Polygon {
        params: vec![
            floats("P", &pts(&square)),
            floats("N", &[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.]),
        ],
    };
    let g = build(&r, &ctx_with(m)).unwrap()[0].dice(3, 3);
    for (n, ng) in g.n.iter().zip(&g.ng) {
        assert!(n.dot(*ng).abs() > 0.99999, "{n} vs {ng}");
        assert!((n.length() - 1.0).abs() < 1e-5);
    }
    let p = g.p[0].as_dvec3();
    assert!((p - DVec3::new(1.0, 2.0, 9.0)).length() < 1e-6);
}

#[test]
fn bad_polygons_are_errors_with_counts() {
    let square = pts(&[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]);
    let r = Request::PointsPolygons {
        nverts: ints(&[4]),
        verts: ints(&[0, 1, 2]),
        params: vec![floats("P", &square)],
    };
    assert!(matches!(build(&r, &ctx()), Err(GeomError::Invalid { .. })));
    let r = Request::PointsPolygons {
        nverts: ints(&[3]),
        verts: ints(&[0, 1, -2]),
        params: vec![floats("P", &square)],
    };
    assert!(build(&r, &ctx()).is_err());
    // A primitive variable with too few values is dropped with a warning; the polygon stays.
    let r = Request::Polygon {
        params: vec![floats("P", &square), floats("Cs", &[1.0; 5])],
    };
    let warnings = std::cell::RefCell::new(Vec::new());
    let c = BuildContext {
        warnings: Some(&warnings),
        ..ctx()
    };
    let built = build(&r, &c).unwrap();
    assert_eq!(built.len(), 1);
    assert!(built[0].dice(2, 2).cs.is_none(), "Cs was dropped");
    let w = warnings.into_inner();
    assert!(w[0].contains("\"Cs\" has 5 values, expected 12"), "{w:?}");
    let mut nan = square.clone();
    nan[4] = f32::NAN;
    assert!(build(
        &Request::Polygon {
            params: vec![floats("P", &nan)]
        },
        &ctx()
    )
    .is_err());
    assert!(build(&Request::Polygon { params: vec![] }, &ctx()).is_err());
    // Hostile counts fail the checks without allocating for them.
    let r = Request::GeneralPolygon {
        nverts: ints(&[i32::MAX, i32::MAX]),
        params: vec![floats("P", &square)],
    };
    assert!(build(&r, &ctx()).is_err());
    let r = Request::PointsPolygons {
        nverts: ints(&[3]),
        verts: ints(&[0, 1, i32::MAX]),
        params: vec![floats("P", &square)],
    };
    assert!(build(&r, &ctx()).is_err());
    let r = Request::Polygon {
        params: vec![
            floats("P", &square),
            floats("varying float[4611686018427387904] big", &[1.0]),
        ],
    };
    // A hostile array length is only too few values: that variable is dropped, with a warning.
    let warnings = std::cell::RefCell::new(Vec::new());
    let c = BuildContext {
        warnings: Some(&warnings),
        ..ctx()
    };
    assert_eq!(build(&r, &c).unwrap().len(), 1);
    assert!(warnings.into_inner()[0].contains("\"big\" has 1 values"));
    // Degenerate faces (collinear, two vertices) build nothing rather than failing.
    let line = pts(&[[0., 0., 0.], [1., 0., 0.], [2., 0., 0.]]);
    assert!(build_ok(&Request::Polygon {
        params: vec![floats("P", &line)]
    })
    .is_empty());
    let r = Request::PointsPolygons {
        nverts: ints(&[2]),
        verts: ints(&[0, 1]),
        params: vec![Param {
            name: "P".into(),
            value: Value::Ints(vec![0, 0, 0, 1, 1, 1]),
        }],
    };
    assert!(build_ok(&r).is_empty());
    let huge = pts(&[
        [-1e30, -1e30, 0.],
        [1e30, -1e30, 0.],
        [0., 1e30, 0.],
        [-1e30, 5e29, 0.],
        [-5e29, 0., 0.],
    ]);
    for p in build_ok(&Request::Polygon {
        params: vec![floats("P", &huge)],
    }) {
        assert!(p.dice(3, 3).p.iter().all(|q| q.is_finite()));
    }
}
