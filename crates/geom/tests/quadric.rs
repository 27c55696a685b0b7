//! Quadrics against their closed-form areas, bounds and transforms.
mod support;
use glam::{DMat4, DVec3};
use illume_geom::quadric::{Quadric, Shape};
use illume_geom::{build, GeomError, Parametric, Primitive};
use illume_rib::Request;
use proptest::prelude::*;
use std::f64::consts::PI;
use std::sync::Arc;
use support::*;

fn sphere(r: f32, zmin: f32, zmax: f32, thetamax: f32) -> Request {
    Request::Sphere {
        radius: r,
        zmin,
        zmax,
        thetamax,
        params: vec![],
    }
}

fn assert_area(r: &Request, expected: f64) {
    let a = area(&build_ok(r), 300);
    assert!(
        close(a, expected, 2e-4),
        "{}: area {a}, expected {expected}",
        r.name()
    );
}

#[test]
fn unit_sphere_area_is_4_pi() {
    assert_area(&sphere(1.0, -1.0, 1.0, 360.0), 4.0 * PI);
}

#[test]
fn sphere_zone_area_is_r_theta_dz() {
    // A zone of a sphere has area r·θ·(zmax − zmin) (Archimedes).
    assert_area(&sphere(2.0, -0.5, 1.5, 360.0), 2.0 * 2.0 * PI * 2.0);
    assert_area(&sphere(1.0, 0.2, 0.9, 90.0), 1.0 * PI / 2.0 * 0.7);
    assert_area(
        &sphere(1.0, -1.0, 1.0, -120.0),
        1.0 * (2.0 * PI / 3.0) * 2.0,
    );
    // zmin/zmax beyond the radius are clamped to the poles.
    assert_area(&sphere(1.0, -5.0, 5.0, 180.0), 2.0 * PI);
}

#[test]
fn disk_cylinder_cone_areas() {
    let disk = Request::Disk {
        height: 0.5,
        radius: 2.0,
        thetamax: 270.0,
        params: vec![],
    };
    assert_area(&disk, 0.75 * PI * 4.0);
    let cyl = Request::Cylinder {
        radius: 1.5,
        zmin: -1.0,
        zmax: 2.0,
        thetamax: 360.0,
        params: vec![],
    };
    assert_area(&cyl, 2.0 * PI * 1.5 * 3.0);
    let cone = Request::Cone {
        height: 2.0,
        radius: 1.0,
        thetamax: -180.0,
        params: vec![],
    };
    assert_area(&cone, 0.5 * PI * 1.0 * (1.0f64 + 4.0).sqrt());
}

#[test]
fn paraboloid_area_matches_closed_form() {
    // ρ² = k z with k = rmax²/zmax; area = θ ∫ sqrt(k z + k²/4) dz.
    let (rmax, zmin, zmax) = (1.0f64, 0.0f64, 2.0f64);
    let k = rmax * rmax / zmax;
    let prim = |z: f64| 2.0 / (3.0 * k) * (k * z + k * k / 4.0).powf(1.5);
    let expected = 2.0 * PI * (prim(zmax) - prim(zmin));
    assert_area(
        &Request::Paraboloid {
            rmax: rmax as f32,
            zmin: zmin as f32,
            zmax: zmax as f32,
            thetamax: 360.0,
            params: vec![],
        },
        expected,
    );
}

#[test]
fn torus_area_matches_closed_form() {
    // θ · r · [R Δφ + r (sin φmax − sin φmin)]
    let (big, r) = (3.0f64, 0.5f64);
    assert_area(
        &Request::Torus {
            major_radius: big as f32,
            minor_radius: r as f32,
            phimin: 0.0,
            phimax: 360.0,
            thetamax: 360.0,
            params: vec![],
        },
        4.0 * PI * PI * big * r,
    );
    let (p0, p1) = (-30.0f64.to_radians(), 100.0f64.to_radians());
    assert_area(
        &Request::Torus {
            major_radius: big as f32,
            minor_radius: r as f32,
            phimin: -30.0,
            phimax: 100.0,
            thetamax: 90.0,
            params: vec![],
        },
        PI / 2.0 * r * (big * (p1 - p0) + r * (p1.sin() - p0.sin())),
    );
}

#[test]
fn hyperboloid_area_matches_f64_integral() {
    // Surface of revolution: θ ∫ ρ(v) |(ρ'(v), z'(v))| dv, integrated by Simpson in f64.
    let (a, b) = (DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 1.0));
    let f = |v: f64| {
        let p = a + v * (b - a);
        let d = b - a;
        let rho = p.truncate().length();
        let drho = p.truncate().dot(d.truncate()) / rho;
        rho * (drho * drho + d.z * d.z).sqrt()
    };
    let n = 2000;
    let h = 1.0 / n as f64;
    let simpson: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    assert_area(
        &Request::Hyperboloid {
            point1: [1.0, 0.0, 0.0],
            point2: [0.0, 1.0, 1.0],
            thetamax: 360.0,
            params: vec![],
        },
        2.0 * PI * simpson,
    );
}

#[test]
fn rotate_90_about_z_puts_sphere_x_on_y() {
    // `Rotate 90 0 0 1`: object +x (θ = 0 on the equator) lands on camera +y.
    let m = DMat4::from_rotation_z(90f64.to_radians()) * DMat4::from_translation(DVec3::ZERO);
    let prims = build(&sphere(1.0, -1.0, 1.0, 360.0), &ctx_with(m)).unwrap();
    let g = prims[0].dice(5, 5);
    let p = g.p[2 * 5];
    assert!((p - glam::Vec3::Y).length() < 1e-6, "{p}");
    let b = prims[0].bound();
    assert!(b.min.x <= -1.0 && b.max.y >= 1.0 && b.max.z >= 1.0);
}

#[test]
fn split_halves_share_edge_vertices_bit_exactly() {
    let prims = build_ok(&sphere(1.0, -0.7, 0.9, 300.0));
    let halves = prims[0].split();
    assert_eq!(halves.len(), 2);
    let (a, b) = (halves[0].dice(7, 7), halves[1].dice(7, 7));
    // Either a u split (a's last column is b's first) or a v split (rows).
    let col_match = (0..7).all(|j| a.p[j * 7 + 6] == b.p[j * 7]);
    let row_match = (0..7).all(|i| a.p[6 * 7 + i] == b.p[i]);
    assert!(col_match || row_match);
    // Splitting further and again keeps the shared corners exact.
    let quarters: Vec<_> = halves.iter().flat_map(|h| h.split()).collect();
    assert_eq!(quarters.len(), 4);
}

#[test]
fn degenerate_quadrics_build_nothing_and_bad_numbers_are_errors() {
    for r in [
        sphere(0.0, -1.0, 1.0, 360.0),
        sphere(1.0, 0.5, 0.5, 360.0),
        sphere(1.0, -1.0, 1.0, 0.0),
        Request::Cylinder {
            radius: 1.0,
            zmin: 1.0,
            zmax: 1.0,
            thetamax: 360.0,
            params: vec![],
        },
        Request::Paraboloid {
            rmax: 1.0,
            zmin: 0.0,
            zmax: 0.0,
            thetamax: 360.0,
            params: vec![],
        },
    ] {
        assert!(build_ok(&r).is_empty(), "{r:?}");
    }
    assert!(matches!(
        build(&sphere(f32::NAN, -1.0, 1.0, 360.0), &ctx()),
        Err(GeomError::Invalid { .. })
    ));
    let huge = build_ok(&sphere(1e30, -1e30, 1e30, 360.0));
    let g = huge[0].dice(4, 4);
    assert!(g.p.iter().all(|p| p.is_finite()));
    assert!(huge[0].bound().max.x >= 1e30 * 0.999);
    // A piece that cannot shrink still splits into something (itself) without panicking.
    let mut p: Vec<Box<dyn Primitive>> = build_ok(&sphere(1.0, -1.0, 1.0, 360.0));
    for _ in 0..200 {
        p = p.remove(0).split();
    }
    assert!(!p.is_empty());
}

#[test]
fn sphere_normals_point_along_position_up_to_sign_even_at_poles() {
    let prims = build_ok(&sphere(2.0, -2.0, 2.0, 360.0));
    let g = prims[0].dice(9, 9);
    for (p, n) in g.p.iter().zip(&g.ng) {
        let c = p.normalize().dot(*n).abs();
        assert!(c > 0.999, "p {p} n {n}");
    }
}

#[test]
fn default_st_follows_texture_coordinates() {
    let mut c = ctx();
    c.texture_coordinates = [0.0, 1.0, 2.0, 1.0, 0.0, 3.0, 2.0, 3.0];
    let prims = build(&sphere(1.0, -1.0, 1.0, 360.0), &c).unwrap();
    let g = prims[0].dice(3, 3);
    assert_eq!((g.s[0], g.t[0]), (0.0, 1.0));
    assert_eq!((g.s[8], g.t[8]), (2.0, 3.0));
    assert_eq!((g.s[4], g.t[4]), (1.0, 2.0));
}

fn arb_quadric() -> impl Strategy<Value = Request> {
    let a = -3.0f32..3.0;
    let t = -360.0f32..360.0;
    prop_oneof![
        (0.1f32..3.0, a.clone(), a.clone(), t.clone())
            .prop_map(|(r, z0, z1, tm)| sphere(r, z0, z1, tm)),
        (a.clone(), 0.1f32..3.0, t.clone()).prop_map(|(h, r, tm)| Request::Cone {
            height: h,
            radius: r,
            thetamax: tm,
            params: vec![]
        }),
        (0.1f32..3.0, a.clone(), a.clone(), t.clone()).prop_map(|(r, z0, z1, tm)| {
            Request::Cylinder {
                radius: r,
                zmin: z0,
                zmax: z1,
                thetamax: tm,
                params: vec![],
            }
        }),
        (
            prop::array::uniform3(a.clone()),
            prop::array::uniform3(a.clone()),
            t.clone()
        )
            .prop_map(|(p1, p2, tm)| Request::Hyperboloid {
                point1: p1,
                point2: p2,
                thetamax: tm,
                params: vec![]
            }),
        (0.1f32..3.0, 0.0f32..1.0, 1.0f32..3.0, t.clone()).prop_map(|(r, z0, z1, tm)| {
            Request::Paraboloid {
                rmax: r,
                zmin: z0,
                zmax: z1,
                thetamax: tm,
                params: vec![],
            }
        }),
        (a.clone(), 0.1f32..3.0, t.clone()).prop_map(|(h, r, tm)| Request::Disk {
            height: h,
            radius: r,
            thetamax: tm,
            params: vec![]
        }),
        (
            0.5f32..3.0,
            0.1f32..1.0,
            -400.0f32..400.0,
            -400.0f32..400.0,
            t
        )
            .prop_map(|(big, r, p0, p1, tm)| Request::Torus {
                major_radius: big,
                minor_radius: r,
                phimin: p0,
                phimax: p1,
                thetamax: tm,
                params: vec![]
            }),
    ]
}

proptest! {
    #[test]
    fn bound_contains_every_diced_point(
        r in arb_quadric(),
        u0 in 0.0f64..1.0, du in 0.0f64..1.0, v0 in 0.0f64..1.0, dv in 0.0f64..1.0,
        angle in -3.0f64..3.0, shift in prop::array::uniform3(-5.0f64..5.0),
    ) {
        let m = DMat4::from_translation(DVec3::from_array(shift)) * DMat4::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), angle);
        let prims = build(&r, &ctx_with(m)).unwrap();
        for p in &prims {
            let whole = p.bound();
            let (u1, v1) = ((u0 + du).min(1.0), (v0 + dv).min(1.0));
            let mut pieces: Vec<Box<dyn Primitive>> = vec![p.split().remove(0)];
            pieces.extend(sub(&r, m, [u0, u1], [v0, v1]).map(|s| Box::new(s) as Box<dyn Primitive>));
            for piece in pieces.iter().chain(std::iter::once(p)) {
                let b = piece.bound();
                let g = piece.dice(9, 9);
                for q in &g.p {
                    prop_assert!(q.cmpge(b.min).all() && q.cmple(b.max).all(), "{q} outside {b:?}");
                    prop_assert!(q.cmpge(whole.min).all() && q.cmple(whole.max).all());
                }
            }
        }
    }
}

proptest! {
    /// A grid of a quadric shares each column's angle and each row's profile; every vertex
    /// must still be what `eval` gives at its `(u, v)`, bit for bit.
    #[test]
    fn a_quadric_grid_is_its_points_evaluated_one_by_one(
        r in arb_quadric(),
        us in prop::collection::vec(-0.2f64..1.2, 1..7),
        vs in prop::collection::vec(-0.2f64..1.2, 1..7),
        angle in -3.0f64..3.0,
    ) {
        use illume_geom::parametric::Surface;
        let m = DMat4::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), angle);
        let Ok(Some(shape)) = Shape::from_request(&r) else { return Ok(()) };
        let q = Quadric { shape, camera_from_object: m };
        let mut grid = Vec::new();
        q.eval_grid(&us, &vs, &mut grid);
        prop_assert_eq!(grid.len(), us.len() * vs.len());
        for (k, got) in grid.iter().enumerate() {
            let want = q.eval(us[k % us.len()], vs[k / us.len()]);
            for (a, b) in got.iter().zip(&want) {
                prop_assert!(
                    a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits),
                    "{a} != {b}"
                );
            }
        }
    }
}

/// The sub-range `u × v` of the quadric `r`, built from the public surface types.
fn sub(r: &Request, m: DMat4, u: [f64; 2], v: [f64; 2]) -> Option<Parametric> {
    let shape = Shape::from_request(r).unwrap()?;
    let q = Quadric {
        shape,
        camera_from_object: m,
    };
    Some(Parametric::new(Arc::new(q), Arc::new(vec![])).sub_range(u, v))
}

#[test]
fn quadric_variables_interpolate_over_u_and_v() {
    let r = Request::Cylinder {
        radius: 1.0,
        zmin: 0.0,
        zmax: 1.0,
        thetamax: 90.0,
        params: vec![
            floats("Cs", &[0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.]),
            floats("constant float Kd", &[0.25]),
            floats(
                "varying vector dir",
                &[1., 0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0.],
            ),
            floats("st", &[0., 0., 2., 0., 0., 2., 2., 2.]),
        ],
    };
    let m = DMat4::from_rotation_z(90f64.to_radians())
        * DMat4::from_translation(DVec3::new(0.0, 0.0, 5.0));
    let g = build(&r, &ctx_with(m)).unwrap()[0].dice(5, 3);
    let cs = g.cs.clone().unwrap();
    for (k, c) in cs.iter().enumerate() {
        assert!((c.x - g.u[k]).abs() < 1e-6 && (c.y - g.v[k]).abs() < 1e-6);
        assert!((g.s[k] - 2.0 * g.u[k]).abs() < 1e-6 && (g.t[k] - 2.0 * g.v[k]).abs() < 1e-6);
    }
    let kd = g.vars.iter().find(|v| v.name == "Kd").unwrap();
    assert!(kd.data.iter().all(|&x| x == 0.25));
    // A vector is rotated but not translated.
    let dir = g.vars.iter().find(|v| v.name == "dir").unwrap();
    assert_eq!(dir.components, 3);
    assert!(
        (dir.data[0]).abs() < 1e-6 && (dir.data[1] - 1.0).abs() < 1e-6 && dir.data[2].abs() < 1e-6
    );
    // The translation applies to points: z of the cylinder's base is at 5.
    assert!((g.p[0].z - 5.0).abs() < 1e-6);
}
