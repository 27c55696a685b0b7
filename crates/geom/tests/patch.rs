//! Patches and patch meshes against closed forms and direct f64 evaluation.
mod support;
use glam::{DMat4, DVec3, Vec3};
use illume_geom::patch::BicubicSurface;
use illume_geom::{basis_matrix, build, GeomError, Parametric, Primitive};
use illume_rib::{Request, Value};
use proptest::prelude::*;
use std::sync::Arc;
use support::*;

fn patch(kind: &str, p: &[f32]) -> Request {
    Request::Patch {
        kind: kind.to_string(),
        params: vec![floats("P", p)],
    }
}

fn mesh(
    kind: &str,
    nu: i32,
    uwrap: &str,
    nv: i32,
    vwrap: &str,
    params: Vec<illume_rib::Param>,
) -> Request {
    Request::PatchMesh {
        kind: kind.to_string(),
        nu,
        uwrap: uwrap.to_string(),
        nv,
        vwrap: vwrap.to_string(),
        params,
    }
}

fn ctx_basis(name: &str) -> illume_geom::BuildContext<'static> {
    let (m, step) = basis_matrix(name).unwrap();
    let mut c = ctx();
    c.basis = (m, step, m, step);
    c
}

#[test]
fn planar_bilinear_patch_area_is_the_trapezoid() {
    // Corners (0,0) (2,0) (0,1) (3,1): a trapezoid of parallel sides 2 and 3, height 1.
    let r = patch(
        "bilinear",
        &[0., 0., 0., 2., 0., 0., 0., 1., 0., 3., 1., 0.],
    );
    let a = area(&build_ok(&r), 50);
    assert!(close(a, 2.5, 1e-9), "{a}");
}

#[test]
fn flat_bicubic_patch_area_is_its_rectangle() {
    // Control points on a warped but monotone grid of [0,2]×[0,1]: the image is the rectangle.
    let xs = [0.0, 0.2, 1.5, 2.0];
    let ys = [0.0, 0.6, 0.7, 1.0];
    let p: Vec<f32> = (0..16).flat_map(|k| [xs[k % 4], ys[k / 4], 0.0]).collect();
    let a = area(&build_ok(&patch("bicubic", &p)), 200);
    assert!(close(a, 2.0, 1e-5), "{a}");
}

/// `[u³ u² u 1]·M·G·Mᵀ·[v³ v² v 1]ᵀ` written out directly in f64.
fn direct(m: &[f32; 16], g: &[DVec3], u: f64, v: f64) -> DVec3 {
    let uu = [u * u * u, u * u, u, 1.0];
    let vv = [v * v * v, v * v, v, 1.0];
    let mut wu = [0.0; 4];
    let mut wv = [0.0; 4];
    for c in 0..4 {
        for r in 0..4 {
            wu[c] += uu[r] * m[4 * r + c] as f64;
            wv[c] += vv[r] * m[4 * r + c] as f64;
        }
    }
    let mut p = DVec3::ZERO;
    for j in 0..4 {
        for i in 0..4 {
            p += g[j * 4 + i] * wu[i] * wv[j];
        }
    }
    p
}

fn grid_points(seed: u64) -> Vec<DVec3> {
    (0..16)
        .map(|k| {
            let h = |s: u64| {
                (((k as u64 + 1) * 2654435761 + s * 97 + seed * 7919) % 1000) as f64 / 250.0 - 2.0
            };
            DVec3::new(h(1) + (k % 4) as f64, h(2) + (k / 4) as f64, h(3))
        })
        .collect()
}

#[test]
fn every_basis_matches_direct_f64_evaluation() {
    let explicit: [f32; 16] = [
        0.5, -1.0, 0.25, 2.0, 1.0, 0.0, -2.0, 0.5, -0.5, 3.0, 1.0, 0.0, 0.0, 0.5, 1.0, 1.0,
    ];
    let bases: Vec<(&str, [f32; 16])> = ["bezier", "b-spline", "catmull-rom", "hermite", "power"]
        .iter()
        .map(|n| (*n, basis_matrix(n).unwrap().0))
        .chain(std::iter::once(("explicit", explicit)))
        .collect();
    for (seed, (name, m)) in bases.iter().enumerate() {
        let g = grid_points(seed as u64);
        let p: Vec<f32> = g.iter().flat_map(|q| q.as_vec3().to_array()).collect();
        let g32: Vec<DVec3> = p
            .chunks(3)
            .map(|c| Vec3::from_slice(c).as_dvec3())
            .collect();
        let mut c = ctx();
        c.basis = (*m, 4, *m, 4);
        let prims = build(&patch("bicubic", &p), &c).unwrap();
        let grid = prims[0].dice(6, 5);
        for j in 0..5 {
            for i in 0..6 {
                let want = direct(m, &g32, i as f64 / 5.0, j as f64 / 4.0);
                let got = grid.p[j * 6 + i].as_dvec3();
                assert!(
                    (got - want).length() < 1e-5 * want.length().max(1.0),
                    "{name} ({i},{j}) {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn patch_mesh_equals_its_patches_one_by_one() {
    for (basis, nu, nv) in [
        ("b-spline", 6, 5),
        ("bezier", 7, 4),
        ("catmull-rom", 5, 5),
        ("hermite", 6, 4),
    ] {
        let c = ctx_basis(basis);
        let step = basis_matrix(basis).unwrap().1 as usize;
        let pts: Vec<DVec3> = (0..nu * nv)
            .map(|k| {
                DVec3::new(
                    (k % nu) as f64,
                    (k / nu) as f64,
                    ((k * 37) % 11) as f64 * 0.1,
                )
            })
            .collect();
        let flat: Vec<f32> = pts.iter().flat_map(|q| q.as_vec3().to_array()).collect();
        let r = mesh(
            "bicubic",
            nu as i32,
            "nonperiodic",
            nv as i32,
            "nonperiodic",
            vec![floats("P", &flat)],
        );
        let prims = build(&r, &c).unwrap();
        let (npu, npv) = ((nu - 4) / step + 1, (nv - 4) / step + 1);
        assert_eq!(prims.len(), npu * npv, "{basis}");
        for j in 0..npv {
            for i in 0..npu {
                let sub: Vec<f32> = (0..16)
                    .flat_map(|n| {
                        flat[3 * ((j * step + n / 4) * nu + i * step + n % 4)..][..3].to_vec()
                    })
                    .collect();
                let one = build(&patch("bicubic", &sub), &c).unwrap();
                assert_eq!(
                    prims[j * npu + i].dice(5, 5).p,
                    one[0].dice(5, 5).p,
                    "{basis} ({i},{j})"
                );
            }
        }
    }
}

#[test]
fn periodic_mesh_closes_and_neighbours_share_edges() {
    // A periodic b-spline ring of 8 control points around z, 4 rows up.
    let (nu, nv) = (8usize, 4usize);
    let pts: Vec<f32> = (0..nu * nv)
        .flat_map(|k| {
            let a = (k % nu) as f32 / nu as f32 * std::f32::consts::TAU;
            [a.cos(), a.sin(), (k / nu) as f32]
        })
        .collect();
    let r = mesh(
        "bicubic",
        8,
        "periodic",
        4,
        "nonperiodic",
        vec![floats("P", &pts)],
    );
    let prims = build(&r, &ctx_basis("b-spline")).unwrap();
    assert_eq!(prims.len(), 8);
    let grids: Vec<_> = prims.iter().map(|p| p.dice(5, 5)).collect();
    for k in 0..8 {
        let (a, b) = (&grids[k], &grids[(k + 1) % 8]);
        for j in 0..5 {
            let d = (a.p[j * 5 + 4] - b.p[j * 5]).length();
            assert!(d < 1e-6, "patch {k} row {j}: gap {d}");
        }
    }
}

#[test]
fn varying_uniform_and_vertex_variables_follow_the_subpatches() {
    // Bilinear 3×2 mesh: 2 patches in u; varying = 3×2 values, uniform = 2.
    let p: Vec<f32> = (0..6)
        .flat_map(|k| [(k % 3) as f32, (k / 3) as f32, 0.0])
        .collect();
    let cs: Vec<f32> = (0..6).flat_map(|k| [k as f32, 0.0, 1.0]).collect();
    let r = mesh(
        "bilinear",
        3,
        "nonperiodic",
        2,
        "nonperiodic",
        vec![
            floats("P", &p),
            floats("Cs", &cs),
            floats("uniform float id", &[7.0, 9.0]),
            floats("vertex float h", &[0., 1., 2., 3., 4., 5.]),
        ],
    );
    let prims = build_ok(&r);
    assert_eq!(prims.len(), 2);
    let g = prims[1].dice(3, 3);
    let cs = g.cs.as_ref().unwrap();
    assert_eq!(cs[0].x, 1.0);
    assert_eq!(cs[2].x, 2.0);
    assert_eq!(cs[6].x, 4.0);
    assert_eq!(cs[8].x, 5.0);
    assert_eq!(cs[4].x, 3.0); // centre: mean of 1, 2, 4, 5
    let id = g.vars.iter().find(|v| v.name == "id").unwrap();
    assert!(id.data.iter().all(|&x| x == 9.0));
    let h = g.vars.iter().find(|v| v.name == "h").unwrap();
    assert_eq!(h.data[8], 5.0);
    // Default s,t span the whole mesh: the second patch covers s ∈ [0.5, 1].
    assert_eq!((g.s[0], g.s[2], g.t[8]), (0.5, 1.0, 1.0));
}

#[test]
fn bicubic_vertex_variable_interpolates_like_the_position() {
    // A vertex float equal to each control point's x is the patch's x everywhere.
    let g = grid_points(3);
    let p: Vec<f32> = g.iter().flat_map(|q| q.as_vec3().to_array()).collect();
    let xs: Vec<f32> = p.chunks(3).map(|c| c[0]).collect();
    let r = Request::Patch {
        kind: "bicubic".into(),
        params: vec![floats("P", &p), floats("vertex float px", &xs)],
    };
    let grid = build(&r, &ctx_basis("catmull-rom")).unwrap()[0].dice(4, 4);
    let px = &grid.vars.iter().find(|v| v.name == "px").unwrap().data;
    for (k, q) in grid.p.iter().enumerate() {
        assert!((px[k] - q.x).abs() < 1e-5);
    }
}

#[test]
fn pz_and_pw_positions() {
    let r = Request::Patch {
        kind: "bilinear".into(),
        params: vec![floats("Pz", &[0.0, 1.0, 2.0, 3.0])],
    };
    let g = build_ok(&r)[0].dice(2, 2);
    assert_eq!(
        g.p,
        vec![
            Vec3::new(0., 0., 0.),
            Vec3::new(1., 0., 1.),
            Vec3::new(0., 1., 2.),
            Vec3::new(1., 1., 3.)
        ]
    );
    let r = Request::Patch {
        kind: "bilinear".into(),
        params: vec![floats(
            "Pw",
            &[
                0., 0., 0., 1., 2., 0., 0., 2., 0., 4., 0., 4., 3., 3., 0., 3.,
            ],
        )],
    };
    let g = build_ok(&r)[0].dice(2, 2);
    assert_eq!(g.p[1], Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(g.p[2], Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(g.p[3], Vec3::new(1.0, 1.0, 0.0));
}

#[test]
fn bad_meshes_are_errors_not_panics() {
    let p = vec![0.0f32; 15 * 3];
    let bad = mesh(
        "bicubic",
        5,
        "nonperiodic",
        3,
        "nonperiodic",
        vec![floats("P", &p)],
    );
    assert!(matches!(
        build(&bad, &ctx()),
        Err(GeomError::Invalid { .. })
    ));
    let wrap = mesh(
        "bilinear",
        2,
        "sideways",
        2,
        "nonperiodic",
        vec![floats("P", &[0.0; 12])],
    );
    assert!(build(&wrap, &ctx()).is_err());
    let nan = patch(
        "bilinear",
        &[f32::NAN, 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.],
    );
    assert!(build(&nan, &ctx()).is_err());
    let hostile = mesh(
        "bilinear",
        i32::MAX,
        "nonperiodic",
        i32::MAX,
        "periodic",
        vec![floats("P", &[0.0; 12])],
    );
    assert!(build(&hostile, &ctx()).is_err());
    let missing = Request::Patch {
        kind: "bilinear".into(),
        params: vec![],
    };
    assert!(build(&missing, &ctx()).is_err());
    let ints = Request::Patch {
        kind: "bilinear".into(),
        params: vec![illume_rib::Param {
            name: "P".into(),
            value: Value::Ints(vec![0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]),
        }],
    };
    assert_eq!(area(&build_ok(&ints), 4), 1.0);
    let huge = patch(
        "bilinear",
        &[
            -1e30, -1e30, 0., 1e30, -1e30, 0., -1e30, 1e30, 0., 1e30, 1e30, 0.,
        ],
    );
    let g = build_ok(&huge)[0].dice(3, 3);
    assert!(g.p.iter().all(|p| p.is_finite()));
}

proptest! {
    #[test]
    fn bicubic_bounds_contain_diced_points(
        seed in 0u64..1000, basis in 0usize..5,
        u0 in 0.0f64..1.0, du in 0.0f64..1.0, v0 in 0.0f64..1.0, dv in 0.0f64..1.0,
        angle in -3.0f64..3.0,
    ) {
        let name = ["bezier", "b-spline", "catmull-rom", "hermite", "power"][basis];
        let mut c = ctx_basis(name);
        c.camera_from_object = DMat4::from_translation(DVec3::new(0.3, -2.0, 5.0)) * DMat4::from_rotation_y(angle);
        let p: Vec<f32> = grid_points(seed).iter().flat_map(|q| q.as_vec3().to_array()).collect();
        let prims = build(&patch("bicubic", &p), &c).unwrap();
        let whole = &prims[0];
        let mut todo: Vec<Box<dyn Primitive>> = whole.split();
        todo.extend(todo[0].split());
        let g: [DVec3; 16] = std::array::from_fn(|k| Vec3::from_slice(&p[3 * k..]).as_dvec3());
        let m = basis_matrix(name).unwrap().0;
        let surface = BicubicSurface::new(&g, &m, &m, &c.camera_from_object);
        let (u1, v1) = ((u0 + du).min(1.0), (v0 + dv).min(1.0));
        todo.push(Box::new(Parametric::new(Arc::new(surface), Arc::new(vec![])).sub_range([u0, u1], [v0, v1])));
        todo.push(prims.into_iter().next().unwrap());
        for piece in &todo {
            let b = piece.bound();
            for q in &piece.dice(9, 7).p {
                prop_assert!(q.cmpge(b.min).all() && q.cmple(b.max).all(), "{} {q} outside {b:?}", name);
            }
        }
    }
}

#[test]
fn teapot_is_32_patches_inside_its_hull_with_shared_edges() {
    let r = Request::Geometry {
        kind: "teapot".into(),
        params: vec![],
    };
    let prims = build_ok(&r);
    assert_eq!(prims.len(), 32);
    let b = prims
        .iter()
        .fold(illume_geom::Bound::EMPTY, |b, p| b.union(p.bound()));
    // The hull of the Newell control points: x ∈ [−3, 3.525], y ∈ [−2, 2], z ∈ [0, 3.15].
    assert!(
        b.min.cmpge(Vec3::new(-3.0, -2.0, 0.0) - 1e-4).all()
            && b.max.cmple(Vec3::new(3.525, 2.0, 3.15) + 1e-4).all(),
        "{b:?}"
    );
    assert!(b.min.x < -2.9 && b.max.x > 3.3 && b.max.z > 3.1, "{b:?}");
    // Body patches 0 and 1 share control points 3, 7, 11, 15: patch 0's u = 1 edge.
    let (g0, g1) = (prims[0].dice(9, 9), prims[1].dice(9, 9));
    for j in 0..9 {
        let d = (g0.p[j * 9 + 8] - g1.p[j * 9]).length();
        assert!(d < 1e-5, "row {j}: gap {d}");
    }
    // The lid's collapsed rows still get unit normals.
    let lid = prims[20].dice(5, 5);
    assert!(lid.ng.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
}

#[test]
fn split_patch_pieces_share_edges_bit_exactly() {
    let p: Vec<f32> = grid_points(11)
        .iter()
        .flat_map(|q| q.as_vec3().to_array())
        .collect();
    for basis in ["bezier", "b-spline", "hermite"] {
        let prims = build(&patch("bicubic", &p), &ctx_basis(basis)).unwrap();
        let halves = prims[0].split();
        let (ga, gb) = (halves[0].dice(6, 6), halves[1].dice(6, 6));
        let col = (0..6).all(|j| ga.p[j * 6 + 5] == gb.p[j * 6]);
        let row = (0..6).all(|i| ga.p[30 + i] == gb.p[i]);
        assert!(col || row, "{basis}");
    }
}
