//! The BVH against brute force, and the triangle test against closed forms and its watertight
//! guarantee.
use glam::{DVec3, Vec3};
use illume_raytrace::{Bvh, Triangle};
use proptest::prelude::*;

fn brute_nearest(tris: &[Triangle], o: DVec3, d: DVec3, t_max: f64) -> Option<f64> {
    tris.iter()
        .filter_map(|t| t.intersect(o, d, 0.0, t_max))
        .min_by(f64::total_cmp)
}

fn random_tris(seed: &[(f32, f32, f32)]) -> Vec<Triangle> {
    seed.chunks_exact(3)
        .map(|c| {
            let v = |k: usize| Vec3::new(c[k].0, c[k].1, c[k].2);
            Triangle::new(v(0), v(1), v(2))
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Any-hit and nearest-hit answers equal an exhaustive loop over every triangle.
    #[test]
    fn bvh_agrees_with_brute_force(
        pts in prop::collection::vec((-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0), 3..600),
        rays in prop::collection::vec(((-6.0f64..6.0, -6.0f64..6.0, -6.0f64..6.0),
                                        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0),
                                        0.1f64..20.0), 20),
    ) {
        let tris = random_tris(&pts);
        let bvh = Bvh::new(tris.clone());
        for ((ox, oy, oz), (dx, dy, dz), t_max) in rays {
            let (o, d) = (DVec3::new(ox, oy, oz), DVec3::new(dx, dy, dz));
            let brute = brute_nearest(&tris, o, d, t_max);
            prop_assert_eq!(bvh.nearest(o, d, 0.0, t_max), brute);
            prop_assert_eq!(bvh.occluded(o, d, 0.0, t_max), brute.is_some());
        }
    }
}

#[test]
fn hit_distance_matches_the_plane_equation() {
    let t = Triangle::new(
        Vec3::new(-1.0, -1.0, 3.0),
        Vec3::new(2.0, -1.0, 3.0),
        Vec3::new(-1.0, 2.0, 3.0),
    );
    let d = DVec3::new(0.1, 0.05, 1.0);
    let hit = t.intersect(DVec3::ZERO, d, 0.0, f64::INFINITY).unwrap();
    assert!((hit - 3.0).abs() < 1e-12, "{hit}");
    // Pointing away, or stopping short of the plane, misses.
    assert!(t.intersect(DVec3::ZERO, -d, 0.0, f64::INFINITY).is_none());
    assert!(t.intersect(DVec3::ZERO, d, 0.0, 2.9).is_none());
}

/// Rays aimed exactly at the shared edges and vertices of a closed tessellated cube never
/// pass between its triangles: every ray from inside hits.
#[test]
fn closed_mesh_is_watertight_at_shared_edges_and_vertices() {
    let n = 8;
    let mut tris = Vec::new();
    // Six faces of [-1,1]³, each an n×n grid of quads split along one diagonal.
    for axis in 0..3 {
        for side in [-1.0f32, 1.0] {
            let at = |i: usize, j: usize| {
                let (a, b) = (
                    -1.0 + 2.0 * i as f32 / n as f32,
                    -1.0 + 2.0 * j as f32 / n as f32,
                );
                let mut p = [0.0; 3];
                p[axis] = side;
                p[(axis + 1) % 3] = a;
                p[(axis + 2) % 3] = b;
                Vec3::from(p)
            };
            for j in 0..n {
                for i in 0..n {
                    tris.push(Triangle::new(at(i, j), at(i + 1, j), at(i + 1, j + 1)));
                    tris.push(Triangle::new(at(i, j), at(i + 1, j + 1), at(i, j + 1)));
                }
            }
        }
    }
    let bvh = Bvh::new(tris);
    let origin = DVec3::new(0.013, -0.021, 0.007);
    let mut misses = 0;
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            for j in 0..=n {
                for i in 0..=2 * n {
                    // Vertices, edge midpoints and diagonal points of every face grid.
                    let (a, b) = (-1.0 + i as f64 / n as f64, -1.0 + 2.0 * j as f64 / n as f64);
                    let mut p = [0.0; 3];
                    p[axis] = side;
                    p[(axis + 1) % 3] = a;
                    p[(axis + 2) % 3] = b;
                    let target = DVec3::from(p);
                    if !bvh.occluded(origin, target - origin, 0.0, 2.0) {
                        misses += 1;
                    }
                }
            }
        }
    }
    assert_eq!(misses, 0);
}

#[test]
fn degenerate_and_nonfinite_triangles_are_dropped() {
    let z = Vec3::ZERO;
    let bvh = Bvh::new(vec![
        Triangle::new(z, Vec3::X, Vec3::X * 2.0),
        Triangle::new(z, Vec3::X, Vec3::new(f32::NAN, 0.0, 0.0)),
    ]);
    assert!(bvh.is_empty());
    assert!(!bvh.occluded(DVec3::ZERO, DVec3::X, 0.0, 1.0));
    // Zero or NaN directions hit nothing rather than panic.
    let one = Bvh::new(vec![Triangle::new(z, Vec3::X, Vec3::Y)]);
    assert!(!one.occluded(DVec3::new(0.2, 0.2, -1.0), DVec3::ZERO, 0.0, 2.0));
    assert!(!one.occluded(DVec3::new(0.2, 0.2, -1.0), DVec3::splat(f64::NAN), 0.0, 2.0));
}

/// Many triangles with one centroid (an unsplittable heap) still build and answer.
#[test]
fn coincident_centroids_build_a_valid_tree() {
    let tris: Vec<Triangle> = (0..1000)
        .map(|k| {
            let s = 1.0 + k as f32 * 1e-3;
            Triangle::new(
                Vec3::new(-s, -s, 1.0),
                Vec3::new(s, -s, 1.0),
                Vec3::new(0.0, 2.0 * s, 1.0),
            )
        })
        .collect();
    let bvh = Bvh::new(tris);
    assert_eq!(bvh.stats().triangles, 1000);
    assert!(bvh.occluded(DVec3::ZERO, DVec3::Z, 0.0, 2.0));
    assert!(!bvh.occluded(DVec3::new(0.0, 5.0, 0.0), DVec3::Z, 0.0, 2.0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    /// `nearest_hit` with a filter equals brute force over the accepted triangles (ids are the
    /// input indices), and its barycentric weights rebuild the hit point `o + t·d` from the
    /// triangle's vertices.
    #[test]
    fn filtered_nearest_hit_agrees_with_brute_force_and_its_weights_rebuild_the_point(
        pts in prop::collection::vec((-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0), 3..300),
        rays in prop::collection::vec(((-6.0f64..6.0, -6.0f64..6.0, -6.0f64..6.0),
                                        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)), 20),
    ) {
        let tris = random_tris(&pts);
        let bvh = Bvh::new(tris.clone());
        let keep = |id: u32| id % 3 != 1;
        let kept: Vec<Triangle> = tris
            .iter()
            .enumerate()
            .filter(|(i, _)| keep(*i as u32))
            .map(|(_, t)| *t)
            .collect();
        for ((ox, oy, oz), (dx, dy, dz)) in rays {
            let (o, d) = (DVec3::new(ox, oy, oz), DVec3::new(dx, dy, dz));
            let brute = brute_nearest(&kept, o, d, 50.0);
            let hit = bvh.nearest_hit(o, d, 0.0, 50.0, &keep);
            prop_assert_eq!(hit.map(|h| h.t), brute);
            prop_assert_eq!(bvh.occluded_by(o, d, 0.0, 50.0, &keep), brute.is_some());
            if let Some(h) = hit {
                prop_assert!(keep(h.triangle));
                let t = tris[h.triangle as usize];
                let w = h.barycentric;
                prop_assert!((w[0] + w[1] + w[2] - 1.0).abs() < 1e-9);
                let p = t.p[0].as_dvec3() * w[0] + t.p[1].as_dvec3() * w[1] + t.p[2].as_dvec3() * w[2];
                let q = o + d * h.t;
                let scale = 1.0 + q.abs().max_element();
                prop_assert!((p - q).length() < 1e-9 * scale, "{p} vs {q}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    /// Passing over a group equals brute force over the other groups' triangles, for both
    /// queries; groups come in runs (as a scene's primitives do) so whole subtrees share one.
    #[test]
    fn skipping_a_group_agrees_with_brute_force_over_the_rest(
        pts in prop::collection::vec((-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0), 3..300),
        rays in prop::collection::vec(((-6.0f64..6.0, -6.0f64..6.0, -6.0f64..6.0),
                                        (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)), 20),
        run in 1usize..40,
        skip in 0u32..4,
    ) {
        let tris = random_tris(&pts);
        let groups: Vec<u32> = (0..tris.len()).map(|i| (i / run) as u32 % 4).collect();
        let bvh = Bvh::with_groups(tris.clone(), groups.clone());
        let rest: Vec<Triangle> = tris
            .iter()
            .zip(&groups)
            .filter(|(_, &g)| g != skip)
            .map(|(t, _)| *t)
            .collect();
        let all = |_: u32| true;
        for ((ox, oy, oz), (dx, dy, dz)) in rays {
            let (o, d) = (DVec3::new(ox, oy, oz), DVec3::new(dx, dy, dz));
            let brute = brute_nearest(&rest, o, d, 50.0);
            let hit = bvh.nearest_hit_except(o, d, (0.0, 50.0), skip, &all);
            prop_assert_eq!(hit.map(|h| h.t), brute);
            if let Some(h) = hit {
                prop_assert!(groups[h.triangle as usize] != skip);
            }
            prop_assert_eq!(bvh.occluded_except(o, d, (0.0, 50.0), skip, &all), brute.is_some());
            // Skipping nothing is the plain query.
            let plain = bvh.nearest(o, d, 0.0, 50.0);
            let none = bvh.nearest_hit_except(o, d, (0.0, 50.0), illume_raytrace::NO_GROUP, &all);
            prop_assert_eq!(none.map(|h| h.t), plain);
        }
    }
}
