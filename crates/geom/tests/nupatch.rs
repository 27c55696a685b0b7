//! NuPatch against closed forms: the rational quadratic circle is exact, vertex variables follow
//! the rational basis, primitive-variable counts follow RI Spec 3.2 §5.5.
mod support;

use illume_geom::{build, BuildContext, GeomError};
use illume_rib::{Param, Request, Value};
use support::*;

const H: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// The rational quadratic unit circle: 9 homogeneous points (corners of the square with weight
/// √2/2), knots 0 0 0 1 1 2 2 3 3 4 4 4 (each quarter a conic arc, Piegl & Tiller §7.5).
fn circle() -> Vec<[f32; 3]> {
    let xy = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    xy.iter()
        .enumerate()
        .map(|(k, &(x, y))| [x, y, if k % 2 == 1 { H } else { 1.0 }])
        .collect()
}

const CIRCLE_KNOTS: [f32; 12] = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];

/// A cylinder of radius `r`, z ∈ [0, 1]: the circle swept linearly (v order 2).
fn cylinder(r: f32, extra: Vec<Param>) -> Request {
    let mut pw = Vec::new();
    for z in [0.0, 1.0] {
        for [x, y, w] in circle() {
            pw.extend([r * x * w, r * y * w, z * w, w]);
        }
    }
    let mut params = vec![floats("Pw", &pw)];
    params.extend(extra);
    Request::NuPatch {
        nu: 9,
        uorder: 3,
        uknot: CIRCLE_KNOTS.to_vec(),
        umin: 0.0,
        umax: 4.0,
        nv: 2,
        vorder: 2,
        vknot: vec![0.0, 0.0, 1.0, 1.0],
        vmin: 0.0,
        vmax: 1.0,
        params,
    }
}

#[test]
fn rational_circle_cylinder_lies_on_the_circle_within_1e_6() {
    let r = 1.5;
    let prims = build_ok(&cylinder(r, vec![]));
    assert_eq!(prims.len(), 4, "one piece per non-empty knot span");
    let mut worst: f64 = 0.0;
    let mut points = 0;
    for g in all_grids(&prims, 17) {
        for k in 0..g.len() {
            let p = v3(g.p[k]);
            worst = worst.max(((p.x * p.x + p.y * p.y).sqrt() - f64::from(r)).abs());
            // The tangent along the circle is perpendicular to the radius.
            let t = v3(g.dpdu[k]).normalize();
            assert!(
                t.x * p.x + t.y * p.y < 1e-5 * f64::from(r),
                "tangent at {p}"
            );
            points += 1;
        }
    }
    assert!(points > 4 * 17 * 17 - 1);
    assert!(worst < 1e-6, "largest distance from the circle {worst}");
}

#[test]
fn vertex_variable_follows_the_rational_basis() {
    // Give each control point its own Cartesian x: the rational interpolation of those values
    // is then exactly the surface's x (Σ Nw·x / Σ Nw).
    let x: Vec<f32> = [0.0, 1.0]
        .iter()
        .flat_map(|_| circle().into_iter().map(|[x, _, _]| 2.0 * x))
        .collect();
    let prims = build_ok(&cylinder(2.0, vec![floats("vertex float px", &x)]));
    for g in all_grids(&prims, 9) {
        let var = g
            .vars
            .iter()
            .find(|v| v.name == "px")
            .expect("px on the grid");
        for k in 0..g.len() {
            assert!(
                (var.data[k] - g.p[k].x).abs() < 1e-5,
                "{} vs {}",
                var.data[k],
                g.p[k].x
            );
        }
    }
}

#[test]
fn varying_and_uniform_counts_follow_the_segments() {
    // 9 control points of order 3 make 7 u segments (the spec counts the empty ones between
    // doubled knots too) × 1 v segment: uniform 7, varying 8 × 2 = 16.
    let ok = build(
        &cylinder(
            1.0,
            vec![
                floats("uniform float id", &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
                floats("varying float vv", &[0.0; 16]),
            ],
        ),
        &ctx(),
    );
    assert!(ok.is_ok(), "{:?}", ok.err());
    // 18 varying values are 2 too many: cut to the 16 counted, with a warning that says so.
    let warnings = std::cell::RefCell::new(Vec::new());
    let c = BuildContext {
        warnings: Some(&warnings),
        ..ctx()
    };
    let cut = build(
        &cylinder(1.0, vec![floats("varying float vv", &[0.0; 18])]),
        &c,
    );
    assert!(cut.is_ok(), "{:?}", cut.err());
    let w = warnings.into_inner();
    assert!(w[0].contains("has 18 values, expected 16"), "{w:?}");
    // Each non-empty segment's piece carries its own uniform value.
    let prims = build_ok(&cylinder(
        1.0,
        vec![floats(
            "uniform float id",
            &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        )],
    ));
    let ids: Vec<f32> = all_grids(&prims, 3)
        .iter()
        .map(|g| g.vars.iter().find(|v| v.name == "id").unwrap().data[0])
        .collect();
    assert_eq!(ids, [0.0, 2.0, 4.0, 6.0]);
}

#[test]
fn bad_nupatches_are_errors_not_panics() {
    let with = |f: &dyn Fn(&mut Request)| {
        let mut r = cylinder(1.0, vec![]);
        f(&mut r);
        build(&r, &ctx())
    };
    let knots = |r: &mut Request| {
        if let Request::NuPatch { uknot, .. } = r {
            uknot.pop();
        }
    };
    assert!(matches!(with(&knots), Err(GeomError::Invalid { .. })));
    let weight = |r: &mut Request| {
        if let Request::NuPatch { params, .. } = r {
            params[0].value = Value::Floats(vec![0.0; 72]);
        }
    };
    assert!(matches!(with(&weight), Err(GeomError::Invalid { .. })));
    let order = |r: &mut Request| {
        if let Request::NuPatch { uorder, .. } = r {
            *uorder = 40;
        }
    };
    assert!(matches!(with(&order), Err(GeomError::Invalid { .. })));
    // umin ≥ umax leaves nothing to render.
    let empty = |r: &mut Request| {
        if let Request::NuPatch { umin, umax, .. } = r {
            (*umin, *umax) = (2.0, 2.0);
        }
    };
    assert!(with(&empty).unwrap().is_empty());
}

#[test]
fn split_halves_share_their_edge_bit_for_bit() {
    let prims = build_ok(&cylinder(1.0, vec![]));
    let halves = prims[1].split();
    let (a, b) = (halves[0].dice(5, 5), halves[1].dice(5, 5));
    let bound = prims[1].bound();
    for g in [&a, &b] {
        for p in &g.p {
            assert!(p.cmpge(bound.min).all() && p.cmple(bound.max).all());
        }
    }
    let shared = |g: &illume_geom::Grid, first: bool| -> Vec<glam::Vec3> {
        if a.p[0] == b.p[0] {
            // Split along v: rows.
            let j = if first { g.nv - 1 } else { 0 };
            g.p[j * g.nu..(j + 1) * g.nu].to_vec()
        } else {
            let i = if first { g.nu - 1 } else { 0 };
            (0..g.nv).map(|j| g.p[j * g.nu + i]).collect()
        }
    };
    assert_eq!(shared(&a, true), shared(&b, false));
}

#[test]
fn varying_values_are_bilinear_in_each_knot_segment() {
    // Varying values at the segment corners are their knot values (0 1 1 2 2 3 3 4, twice):
    // interpolated linearly in each segment they give back the knot parameter, 4·u.
    let knots_at_corners: Vec<f32> = (0..2).flat_map(|_| CIRCLE_KNOTS[2..10].to_vec()).collect();
    let prims = build_ok(&cylinder(
        1.0,
        vec![floats("varying float kt", &knots_at_corners)],
    ));
    for g in all_grids(&prims, 7) {
        let var = g.vars.iter().find(|v| v.name == "kt").unwrap();
        for k in 0..g.len() {
            assert!(
                (var.data[k] - 4.0 * g.u[k]).abs() < 1e-5,
                "{} at u {}",
                var.data[k],
                g.u[k]
            );
        }
    }
}
