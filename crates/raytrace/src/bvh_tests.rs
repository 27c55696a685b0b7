//! Tests of the BVH (`bvh.rs`): kept apart so that file stays within its size.
use super::*;

#[test]
fn a_ray_along_a_face_of_a_single_triangle_box_finds_it() {
    // The triangle lies in the plane y = 0; a ray in that plane's slab still visits it.
    let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Z);
    let bvh = Bvh::new(vec![t]);
    assert!(bvh.bound().is_some());
    let o = DVec3::new(0.25, 1.0, 0.25);
    assert_eq!(bvh.nearest(o, DVec3::NEG_Y, 0.0, 10.0), Some(1.0));
    assert!(!bvh.occluded(o, DVec3::Y, 0.0, 10.0));
}

#[test]
fn spheres_a_little_apart_get_a_leaf_each() {
    use crate::quadric::QuadricShape;
    use glam::DMat4;
    // The `occlusion` bench's nine unit spheres, 2.4 apart: counted as triangles they
    // shared leaves of up to four, and a ray entering one tested them all.
    let spheres = (0..9)
        .map(|k| {
            let at = DVec3::new(f64::from(k % 3) * 2.4, 0.0, f64::from(k / 3) * 2.4);
            let q = Quadric::new(
                QuadricShape::Sphere {
                    radius: 1.0,
                    phimin: -std::f64::consts::FRAC_PI_2,
                    phimax: std::f64::consts::FRAC_PI_2,
                    thetamax: std::f64::consts::TAU,
                },
                DMat4::from_translation(-at),
                ((at - 1.0).as_vec3(), (at + 1.0).as_vec3()),
            );
            (q, k)
        })
        .collect();
    let bvh = Bvh::with_quadrics(Vec::new(), Vec::new(), spheres);
    assert_eq!(bvh.stats().leaves, 9);
    // Every sphere is still found.
    for k in 0..9 {
        let (x, z) = (f64::from(k % 3) * 2.4, f64::from(k / 3) * 2.4);
        let h = bvh.nearest_hit(DVec3::new(x, 5.0, z), DVec3::NEG_Y, 0.0, 10.0, &|_| true);
        assert_eq!(h.map(|h| (h.triangle, h.t)), Some((k, 4.0)));
    }
}

#[test]
fn quadrics_and_triangles_share_the_tree_with_ids_after_the_triangles() {
    use crate::quadric::QuadricShape;
    use glam::DMat4;
    // A unit sphere at z = 5 and a triangle in the plane z = 2 covering (0..1, 0..1).
    let sphere = Quadric::new(
        QuadricShape::Sphere {
            radius: 1.0,
            phimin: -std::f64::consts::FRAC_PI_2,
            phimax: std::f64::consts::FRAC_PI_2,
            thetamax: std::f64::consts::TAU,
        },
        DMat4::from_translation(-DVec3::new(0.0, 0.0, 5.0)),
        (Vec3::new(-1.0, -1.0, 4.0), Vec3::new(1.0, 1.0, 6.0)),
    );
    let tri = Triangle::new(
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::new(1.0, 0.0, 2.0),
        Vec3::new(0.0, 1.0, 2.0),
    );
    let bvh = Bvh::with_quadrics(vec![tri], vec![7], vec![(sphere, 9)]);
    assert_eq!(bvh.stats().quadrics, 1);
    let all = |_: u32| true;
    // Through the triangle first, then (past it) the sphere's near pole.
    let o = DVec3::new(0.1, 0.1, 0.0);
    let h = bvh.nearest_hit(o, DVec3::Z, 0.0, 100.0, &all).unwrap();
    assert_eq!((h.triangle, h.t, h.uv), (0, 2.0, None));
    let h = bvh.nearest_hit(o, DVec3::Z, 2.5, 100.0, &all).unwrap();
    assert_eq!(h.triangle, 1);
    let want = 5.0 - (1.0f64 - 0.02).sqrt();
    assert!((h.t - want).abs() < 1e-12 && h.uv.is_some());
    // Its group is passed over, and `keep` sees its id.
    let skip = bvh.nearest_hit_except(o, DVec3::Z, (2.5, 100.0), 9, &all);
    assert!(skip.is_none());
    assert!(!bvh.occluded_by(o, DVec3::Z, 2.5, 100.0, &|id| id != 1));
    assert!(bvh.occluded(DVec3::new(-0.5, 0.0, 0.0), DVec3::Z, 0.0, 100.0));
}
