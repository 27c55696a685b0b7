//! Blobby built through `geom::build` / `build_blobby`, checked against independent f64 fields
//! written here from the formulas (not from `BlobbyField`).
mod support;

use glam::{DMat4, DVec3, Vec3};
use illume_geom::blobby::{build_blobby, isosurface_mesh, BlobbyArgs};
use illume_geom::blobby_field::BlobbyField;
use illume_geom::{build, Primitive};
use illume_rib::{Param, Request, Value};
use proptest::prelude::*;
use std::sync::Arc;
use support::{ctx, ctx_with, floats};

/// The bump of the RenderMan Blobby, in f64: `(1 − s)³` inside the unit ball.
fn bump(s: f64) -> f64 {
    if s < 1.0 {
        (1.0 - s).powi(3)
    } else {
        0.0
    }
}

/// Radius of a lone unit blob's isosurface: `bump(r²) = 1/2`.
fn r_star() -> f64 {
    (1.0 - 0.5f64.cbrt()).sqrt()
}

/// A blob of radius `r` at `c` as 16 RIB floats (row-vector order: translation last).
fn blob(c: [f64; 3], r: f64) -> Vec<f32> {
    let mut m = vec![0.0f32; 16];
    m[0] = r as f32;
    m[5] = r as f32;
    m[10] = r as f32;
    m[12] = c[0] as f32;
    m[13] = c[1] as f32;
    m[14] = c[2] as f32;
    m[15] = 1.0;
    m
}

fn sphere_field(p: DVec3, c: [f64; 3], r: f64) -> f64 {
    bump((p - DVec3::from_array(c)).length_squared() / (r * r))
}

fn blobby(nleaf: i32, code: &[i32], fl: &[f32], params: Vec<Param>) -> Request {
    Request::Blobby {
        nleaf,
        code: code.to_vec(),
        floats: fl.to_vec(),
        strings: vec![],
        params,
    }
}

/// Every vertex of a 6×6 dice of every piece, with its shading normal and grid.
fn diced(prims: &[Box<dyn Primitive>]) -> Vec<illume_geom::Grid> {
    prims.iter().map(|p| p.dice(6, 6)).collect()
}

#[test]
fn one_blob_dices_onto_the_sphere_of_radius_r_star() {
    // Camera = object translated by (0, 0, 5): check positions in camera space.
    let m = DMat4::from_translation(DVec3::new(0.0, 0.0, 5.0));
    let prims = build(
        &blobby(1, &[1001, 0], &blob([0.5, -0.25, 0.0], 2.0), vec![]),
        &ctx_with(m),
    )
    .unwrap();
    assert!(prims.len() > 100, "{} pieces", prims.len());
    let c = DVec3::new(0.5, -0.25, 5.0);
    let r = 2.0 * r_star();
    let mut worst = 0.0f64;
    for g in diced(&prims) {
        for (k, p) in g.p.iter().enumerate() {
            let d = p.as_dvec3() - c;
            // f32 storage of |p| ≈ 5 rounds to ~3e-7.
            worst = worst.max((d.length() - r).abs());
            // Shading normal: the analytic outward normal of the sphere.
            let n = g.n[k].as_dvec3();
            assert!((n - d.normalize()).length() < 1e-5, "{n} at {d}");
        }
    }
    assert!(worst < 1e-6, "worst distance from the sphere {worst}");
}

#[test]
fn every_piece_bound_contains_its_diced_points() {
    let prims = build(&blobby(1, &[1001, 0], &blob([0.0; 3], 1.0), vec![]), &ctx()).unwrap();
    for p in &prims {
        let b = p.bound();
        for q in p.dice(5, 5).p {
            assert!(
                q.cmpge(b.min).all() && q.cmple(b.max).all(),
                "{q} outside {b:?}"
            );
        }
    }
}

#[test]
fn mesh_vertices_of_an_ellipsoid_lie_on_its_isosurface() {
    // A rotated, stretched ellipsoid: |M⁻¹ p|² = r*² exactly on the surface.
    let m = DMat4::from_translation(DVec3::new(0.3, 0.1, -0.2))
        * DMat4::from_rotation_z(0.7)
        * DMat4::from_scale(DVec3::new(2.0, 0.7, 1.2));
    let mut fl = vec![0.0f32; 16];
    for (d, s) in fl.iter_mut().zip(m.to_cols_array()) {
        *d = s as f32;
    }
    let mf = DMat4::from_cols_array(
        &fl.iter()
            .map(|&x| f64::from(x))
            .collect::<Vec<_>>()
            .try_into()
            .unwrap(),
    );
    let field = Arc::new(BlobbyField::decode(1, &[1001, 0], &fl, &[]).unwrap());
    let (mesh, _) = isosurface_mesh(&field, 24).unwrap();
    assert!(mesh.triangles.len() > 500);
    for p in &mesh.positions {
        let q = mf.inverse().transform_point3(*p);
        // In unit space the surface is the sphere r*; 1e-6 in unit space is < 2e-6 here.
        assert!((q.length() - r_star()).abs() < 1e-9, "{p}");
    }
}

#[test]
fn projected_volume_of_one_blob_matches_the_ball() {
    // Divergence theorem over the flat mesh: within the chord error of 24 cells.
    let field = Arc::new(BlobbyField::decode(1, &[1001, 0], &blob([0.0; 3], 1.0), &[]).unwrap());
    let (mesh, _) = isosurface_mesh(&field, 24).unwrap();
    let v: f64 = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum();
    let exact = 4.0 / 3.0 * std::f64::consts::PI * r_star().powi(3);
    assert!((v - exact).abs() / exact < 0.02, "{v} vs {exact}");
}

/// Whether `p` is inside the closed mesh: parity of crossings of a ray in a generic direction.
fn inside_mesh(mesh: &illume_geom::polygonize::TriangleMesh, p: DVec3) -> bool {
    let d = DVec3::new(1.0, 0.1234567, 0.0765432).normalize();
    let mut n = 0;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let (e1, e2) = (b - a, c - a);
        let h = d.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-14 {
            continue;
        }
        let s = p - a;
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = d.dot(q) / det;
        let t = e2.dot(q) / det;
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 {
            n += 1;
        }
    }
    n % 2 == 1
}

/// Checks the mesh of `code` against the reference field on a grid of sample points away from
/// the surface (|f − ½| > 0.02, where a 40-cell mesh cannot be on the wrong side), and that
/// every mesh vertex is on the reference isosurface.
fn check_against_reference(
    code: &[i32],
    fl: &[f32],
    nleaf: i32,
    crease: bool,
    reference: &dyn Fn(DVec3) -> f64,
) {
    let field = Arc::new(BlobbyField::decode(nleaf, code, fl, &[]).unwrap());
    let (mesh, _) = isosurface_mesh(&field, 40).unwrap();
    assert!(!mesh.triangles.is_empty());
    for p in &mesh.positions {
        assert!(
            (reference(*p) - 0.5).abs() < 1e-9,
            "vertex {p}: {}",
            reference(*p)
        );
    }
    // Every diced vertex of every piece (camera = object space here) is on the surface too.
    // 1e-5: f32 rounding of positions (~6e-8) times gradients of a few units. At a max/min
    // crease a few points find no crossing along any of their projection directions and keep
    // their flat-triangle position: there at most 2% of the vertices may be off (1.1% for the
    // max pair here), by < 0.05
    // in field (< 0.2 of a lattice cell).
    let args = BlobbyArgs {
        nleaf,
        code,
        floats: fl,
        strings: &[],
    };
    let (prims, _) = build_blobby(&args, &vec![], &ctx(), &|_| 16).unwrap();
    let (mut off, mut total) = (0usize, 0usize);
    for g in diced(&prims) {
        for p in &g.p {
            let f = reference(p.as_dvec3());
            total += 1;
            if (f - 0.5).abs() >= 1e-5 {
                off += 1;
                assert!(
                    crease && (f - 0.5).abs() < 0.05,
                    "diced vertex {p}: field {f}"
                );
            }
        }
    }
    assert!(
        off * 50 <= total,
        "{off} of {total} diced vertices off the surface"
    );
    let (mut inside, mut outside) = (0, 0);
    for i in 0..15 {
        for j in 0..15 {
            for k in 0..5 {
                let p = DVec3::new(
                    -1.6 + 3.2 * i as f64 / 14.0,
                    -1.0 + 2.0 * j as f64 / 14.0,
                    -0.4 + 0.8 * k as f64 / 4.0,
                );
                let f = reference(p);
                if (f - 0.5).abs() < 0.02 {
                    continue;
                }
                assert_eq!(inside_mesh(&mesh, p), f > 0.5, "at {p}: field {f}");
                if f > 0.5 {
                    inside += 1;
                } else {
                    outside += 1;
                }
            }
        }
    }
    assert!(inside > 20 && outside > 20, "{inside} in, {outside} out");
}

/// Two unit blobs at x = ±0.4375 (exact in f32) (they overlap) and their floats.
fn pair() -> (Vec<f32>, [f64; 3], [f64; 3]) {
    let (a, b) = ([-0.4375, 0.0, 0.0], [0.4375, 0.0, 0.0]);
    let mut fl = blob(a, 1.0);
    fl.extend(blob(b, 1.0));
    (fl, a, b)
}

#[test]
fn add_matches_the_sum_of_fields() {
    let (fl, a, b) = pair();
    check_against_reference(&[1001, 0, 1001, 16, 0, 2, 0, 1], &fl, 2, false, &|p| {
        sphere_field(p, a, 1.0) + sphere_field(p, b, 1.0)
    });
}

#[test]
fn max_and_min_match_their_fields() {
    let (fl, a, b) = pair();
    check_against_reference(&[1001, 0, 1001, 16, 2, 2, 0, 1], &fl, 2, true, &|p| {
        sphere_field(p, a, 1.0).max(sphere_field(p, b, 1.0))
    });
    // min of two blobs 0.375 apart (overlapping enough to leave a lens).
    let (a2, b2) = ([-0.1875, 0.0, 0.0], [0.1875, 0.0, 0.0]);
    let mut fl2 = blob(a2, 1.0);
    fl2.extend(blob(b2, 1.0));
    check_against_reference(&[1001, 0, 1001, 16, 3, 2, 0, 1], &fl2, 2, true, &|p| {
        sphere_field(p, a2, 1.0).min(sphere_field(p, b2, 1.0))
    });
}

#[test]
fn subtract_and_multiply_match_their_fields() {
    // A big blob with a small one carved out of its side.
    let (a, b) = ([0.0, 0.0, 0.0], [0.625, 0.0, 0.0]);
    let mut fl = blob(a, 2.5);
    fl.extend(blob(b, 1.0));
    check_against_reference(&[1001, 0, 1001, 16, 4, 0, 1], &fl, 2, false, &|p| {
        sphere_field(p, a, 2.5) - sphere_field(p, b, 1.0)
    });
    // Product with a constant 1.625: a blob scaled in strength (bigger isosurface).
    let mut fl = blob([0.0; 3], 2.0);
    fl.push(1.625);
    check_against_reference(&[1001, 0, 1000, 16, 1, 2, 0, 1], &fl, 2, false, &|p| {
        1.625 * sphere_field(p, [0.0; 3], 2.0)
    });
}

#[test]
fn segment_blob_is_a_capsule() {
    // Segment from (−1,0,0) to (1,0,0), radius 1, identity matrix: the isosurface is the
    // capsule of radius r* around the segment.
    let mut fl = vec![-1.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
    fl.extend(blob([0.0; 3], 1.0));
    let field = Arc::new(BlobbyField::decode(1, &[1002, 0], &fl, &[]).unwrap());
    let (mesh, _) = isosurface_mesh(&field, 40).unwrap();
    let rs = r_star();
    let (mut xmin, mut xmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in &mesh.positions {
        let c = DVec3::new(p.x.clamp(-1.0, 1.0), 0.0, 0.0);
        assert!(((*p - c).length() - rs).abs() < 1e-9, "{p}");
        xmin = xmin.min(p.x);
        xmax = xmax.max(p.x);
    }
    // End caps reach 1 + r* (within the lattice's sampling of the cap: a cell is 0.075).
    assert!(
        (xmax - (1.0 + rs)).abs() < 0.01 && (xmin + 1.0 + rs).abs() < 0.01,
        "{xmin} {xmax}"
    );
}

#[test]
fn varying_cs_blends_by_leaf_fields() {
    let (fl, a, b) = pair();
    let cs = Param {
        name: "varying color Cs".to_string(),
        value: Value::Floats(vec![1.0, 0.0, 0.0, 0.0, 0.0, 1.0]),
    };
    let prims = build(
        &blobby(2, &[1001, 0, 1001, 16, 0, 2, 0, 1], &fl, vec![cs]),
        &ctx(),
    )
    .unwrap();
    let mut checked = 0;
    for g in diced(&prims) {
        let cs = g.cs.as_ref().expect("Cs");
        for (p, c) in g.p.iter().zip(cs) {
            let p = p.as_dvec3();
            let (fa, fb) = (sphere_field(p, a, 1.0), sphere_field(p, b, 1.0));
            let expect = Vec3::new((fa / (fa + fb)) as f32, 0.0, (fb / (fa + fb)) as f32);
            assert!((*c - expect).length() < 1e-5, "{c} vs {expect} at {p}");
            checked += 1;
        }
    }
    assert!(checked > 1000);
}

#[test]
fn constant_cs_is_carried() {
    let prims = build(
        &blobby(
            1,
            &[1001, 0],
            &blob([0.0; 3], 1.0),
            vec![floats("Cs", &[0.2, 0.4, 0.6])],
        ),
        &ctx(),
    )
    .unwrap();
    let g = prims[0].dice(3, 3);
    assert!(g.cs.unwrap().iter().all(|&c| c == Vec3::new(0.2, 0.4, 0.6)));
}

#[test]
fn cells_follow_the_callback() {
    let fl = blob([0.0; 3], 1.0);
    let args = BlobbyArgs {
        nleaf: 1,
        code: &[1001, 0],
        floats: &fl,
        strings: &[],
    };
    let count = |cells: usize| {
        build_blobby(&args, &vec![], &ctx(), &|b| {
            assert_eq!(b, [-1.0, 1.0, -1.0, 1.0, -1.0, 1.0]);
            cells
        })
        .unwrap()
        .0
        .len()
    };
    // Triangles grow with the square of the resolution.
    let (c8, c16) = (count(8), count(16));
    assert!(c16 > 3 * c8 && c16 < 5 * c8, "{c8} → {c16}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Any code array either decodes or is an error; building never panics.
    #[test]
    fn random_code_never_panics(
        nleaf in 0i32..4,
        code in prop::collection::vec(prop_oneof![0i32..8, 1000i32..1004, -3i32..40], 0..14),
        fl in prop::collection::vec(-2.0f32..2.0, 0..40),
    ) {
        let args = BlobbyArgs { nleaf, code: &code, floats: &fl, strings: &[] };
        let _ = build_blobby(&args, &vec![], &ctx(), &|_| 6);
    }
}
