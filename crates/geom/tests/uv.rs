//! The u, v that shaders see, against closed forms (RI Spec 3.2 §5.1–5.2, as PRMan and Aqsis
//! give them; Aqsis's `uv_test` shows `Ci = (u, v, 0)`): a polygon's u, v are its object-space
//! x, y; a patch mesh's run over the whole mesh, 0 to 1 across all its subpatches, with `du`
//! and `dPdu` in those units.
mod support;
use glam::{DMat4, DVec3};
use illume_geom::Grid;
use illume_rib::Request;
use support::*;

const N: usize = 5;

/// Every diced vertex of `prims` with its (u, v), in camera space.
fn vertices(prims: &[Box<dyn illume_geom::Primitive>]) -> Vec<(Grid, usize)> {
    prims
        .iter()
        .flat_map(|p| {
            let g = p.dice(N, N);
            (0..g.len()).map(move |k| (g.clone(), k))
        })
        .collect()
}

#[test]
fn polygon_u_v_are_object_x_y() {
    // A concave (so ear-clipped) polygon off the origin, seen through a rotation and shift.
    let m = DMat4::from_translation(DVec3::new(0.3, -0.2, 6.0)) * DMat4::from_rotation_y(0.4);
    let p: [f32; 15] = [
        0.5, -1., 0., 2., -1., 0., 2., 3., 0., 1.2, 1., 0., 0.5, 3., 0.,
    ];
    let r = Request::Polygon {
        params: vec![floats("P", &p)],
    };
    let prims = illume_geom::build(&r, &ctx_with(m)).unwrap();
    assert!(prims.len() >= 2, "ear clipping gives triangles");
    let object_from_camera = m.inverse();
    for (g, k) in vertices(&prims) {
        let o = object_from_camera.transform_point3(g.p[k].as_dvec3());
        assert!(
            (f64::from(g.u[k]) - o.x).abs() < 1e-5,
            "u {} at x {}",
            g.u[k],
            o.x
        );
        assert!(
            (f64::from(g.v[k]) - o.y).abs() < 1e-5,
            "v {} at y {}",
            g.v[k],
            o.y
        );
    }
}

fn patch_mesh(kind: &str, nu: i32, nv: i32, p: Vec<f32>) -> Request {
    Request::PatchMesh {
        kind: kind.to_string(),
        nu,
        uwrap: "nonperiodic".to_string(),
        nv,
        vwrap: "nonperiodic".to_string(),
        params: vec![floats("P", &p)],
    }
}

/// Checks that every vertex has u = x / width, v = y / height and that `du`, `dPdu` are
/// in those units: dP/du = (width, 0, 0), dP/dv = (0, height, 0).
fn assert_mesh_spans(prims: &[Box<dyn illume_geom::Primitive>], width: f64, height: f64) {
    let mut seen_u = (f64::MAX, f64::MIN);
    for (g, k) in vertices(prims) {
        let p = g.p[k].as_dvec3();
        let (u, v) = (f64::from(g.u[k]), f64::from(g.v[k]));
        assert!((u - p.x / width).abs() < 1e-6, "u {u} at x {}", p.x);
        assert!((v - p.y / height).abs() < 1e-6, "v {v} at y {}", p.y);
        let dpdu = g.dpdu[k].as_dvec3();
        let dpdv = g.dpdv[k].as_dvec3();
        assert!(
            (dpdu - DVec3::new(width, 0.0, 0.0)).length() < 1e-4,
            "dPdu {dpdu}"
        );
        assert!(
            (dpdv - DVec3::new(0.0, height, 0.0)).length() < 1e-4,
            "dPdv {dpdv}"
        );
        // du is one step of this grid's u.
        if k + 1 < g.nu {
            let step = f64::from(g.u[k + 1] - g.u[k]);
            assert!(
                (f64::from(g.du) - step).abs() < 1e-6,
                "du {} step {step}",
                g.du
            );
        }
        seen_u = (seen_u.0.min(u), seen_u.1.max(u));
    }
    assert!(
        seen_u.0.abs() < 1e-9 && (seen_u.1 - 1.0).abs() < 1e-9,
        "{seen_u:?}"
    );
}

#[test]
fn bilinear_patch_mesh_u_v_span_the_mesh() {
    // 4 × 2 points, 3 × 1 subpatches over [0, 3] × [0, 2].
    let mut p = Vec::new();
    for j in 0..2 {
        for i in 0..4 {
            p.extend([i as f32, 2.0 * j as f32, 0.0]);
        }
    }
    let prims = build_ok(&patch_mesh("bilinear", 4, 2, p));
    assert_eq!(prims.len(), 3);
    assert_mesh_spans(&prims, 3.0, 2.0);
}

#[test]
fn bicubic_patch_mesh_u_v_span_the_mesh() {
    // Bezier, 7 × 4 evenly spaced points: 2 × 1 subpatches, linear in x over [0, 6].
    let mut p = Vec::new();
    for j in 0..4 {
        for i in 0..7 {
            p.extend([i as f32, j as f32, 0.0]);
        }
    }
    let prims = build_ok(&patch_mesh("bicubic", 7, 4, p));
    assert_eq!(prims.len(), 2);
    assert_mesh_spans(&prims, 6.0, 3.0);
}

#[test]
fn a_single_patch_keeps_u_v_over_unit_square() {
    let r = Request::Patch {
        kind: "bilinear".to_string(),
        params: vec![floats(
            "P",
            &[0., 0., 0., 4., 0., 0., 0., 5., 0., 4., 5., 0.],
        )],
    };
    assert_mesh_spans(&build_ok(&r), 4.0, 5.0);
}
