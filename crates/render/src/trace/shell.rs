//! Where a primitive's ray-tracing triangles all lie: a ball and a slab around them. A ray
//! that starts outside one of them and moves away from it cannot meet the primitive, so the
//! traversal passes over the primitive's subtrees (`Bvh::occluded_except`).
//!
//! Why: a ray leaving a shaded point starts among its own primitive's triangles, and the
//! boxes and triangle tests near its origin were most of the work of an `occlusion()` ray
//! (issue 19). A flat primitive (polygon, disk, flat patch) lies in a thin slab that every ray
//! leaving it moves away from; a sphere lies in its ball, which a ray leaving on the outside
//! (`dot(origin − centre, dir) ≥ 0`) never re-enters. The test is exact, never a guess: the
//! ball and the slab hold every vertex (with a margin far above `f64` rounding), so they hold
//! every triangle, and a curved surface simply gets a shell its own points lie inside (and no
//! skipping).
use glam::DVec3;
use illume_raytrace::Triangle;

/// Relative margin on the shells' sizes (the triangle test's `f64` rounding is ~1e-16).
const MARGIN: f64 = 1e-9;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Shell {
    /// Centre and radius of a ball around every vertex (the centre of their box).
    ball: Option<(DVec3, f64)>,
    /// Unit normal, mid-plane offset and half thickness of a slab around every vertex.
    slab: Option<(DVec3, f64, f64)>,
}

impl Shell {
    pub fn of(tris: &[Triangle]) -> Shell {
        let verts = || tris.iter().flat_map(|t| t.p.iter().map(|p| p.as_dvec3()));
        let Some(first) = verts().next() else {
            return Shell::default();
        };
        let (lo, hi) = verts().fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        let centre = (lo + hi) * 0.5;
        let radius = verts().map(|p| (p - centre).length()).fold(0.0, f64::max);
        let scale = lo.abs().max(hi.abs()).max_element();
        let pad = MARGIN * (scale + radius);
        let ball = Some((centre, radius + pad));
        // The slab's normal: the area-weighted normal (zero for a closed surface).
        let n = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.p.map(|p| p.as_dvec3());
                (b - a).cross(c - a)
            })
            .fold(DVec3::ZERO, |s, x| s + x)
            .normalize_or_zero();
        let slab = (n != DVec3::ZERO).then(|| {
            let (dmin, dmax) = verts()
                .map(|p| n.dot(p))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), d| {
                    (a.min(d), b.max(d))
                });
            (n, 0.5 * (dmin + dmax), 0.5 * (dmax - dmin) + pad)
        });
        Shell { ball, slab }
    }

    /// A ball of `radius` about `centre` (a closed-form sphere's own: exact, no chords),
    /// padded by the same relative margin as [`Shell::of`].
    pub fn ball(centre: DVec3, radius: f64) -> Shell {
        let pad = MARGIN * (centre.abs().max_element() + radius);
        Shell {
            ball: Some((centre, radius + pad)),
            slab: None,
        }
    }

    /// The origin's part of [`Shell::excludes`], for many rays leaving one point.
    pub fn seen_from(&self, origin: DVec3) -> SeenFrom {
        let outside_ball = self.ball.and_then(|(c, r)| {
            let oc = origin - c;
            (oc.length_squared() > r * r).then_some(oc)
        });
        let slab = self.slab.and_then(|(n, mid, half)| {
            let s = n.dot(origin) - mid;
            (s > half || s < -half).then_some((n, s > half))
        });
        SeenFrom { outside_ball, slab }
    }

    /// The shell grown by `by` (a surface that lies up to `by` off the triangles it was
    /// measured on).
    pub fn grown(self, by: f64) -> Shell {
        Shell {
            ball: self.ball.map(|(c, r)| (c, r + by)),
            slab: self.slab.map(|(n, mid, half)| (n, mid, half + by)),
        }
    }

    /// Whether a ray from `origin` along `dir` can meet nothing inside the shell: it starts
    /// outside the ball and moves away from its centre, or outside the slab and away from it.
    pub fn excludes(&self, origin: DVec3, dir: DVec3) -> bool {
        if let Some((c, r)) = self.ball {
            let oc = origin - c;
            if oc.length_squared() > r * r && oc.dot(dir) >= 0.0 {
                return true;
            }
        }
        if let Some((n, mid, half)) = self.slab {
            let s = n.dot(origin) - mid;
            let d = n.dot(dir);
            if (s > half && d >= 0.0) || (s < -half && d <= 0.0) {
                return true;
            }
        }
        false
    }
}

/// A shell as seen from one ray origin ([`Shell::seen_from`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SeenFrom {
    /// The origin's offset from the ball's centre, when it lies outside the ball.
    outside_ball: Option<DVec3>,
    /// The slab's normal and whether the origin lies beyond its positive face, when it
    /// lies outside the slab.
    slab: Option<(DVec3, bool)>,
}

impl SeenFrom {
    /// [`Shell::excludes`] for a ray from this origin along `dir` (the same answer).
    pub fn excludes(&self, dir: DVec3) -> bool {
        if let Some(oc) = self.outside_ball {
            if oc.dot(dir) >= 0.0 {
                return true;
            }
        }
        if let Some((n, above)) = self.slab {
            let d = n.dot(dir);
            if (above && d >= 0.0) || (!above && d <= 0.0) {
                return true;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn quad(z: f32) -> Vec<Triangle> {
        let (a, b, c, d) = (
            Vec3::new(0.0, 0.0, z),
            Vec3::new(1.0, 0.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(0.0, 1.0, z),
        );
        vec![Triangle::new(a, b, c), Triangle::new(a, c, d)]
    }

    #[test]
    fn a_flat_primitive_excludes_rays_leaving_it_on_either_side() {
        let s = Shell::of(&quad(2.0));
        let above = DVec3::new(0.5, 0.5, 2.001);
        assert!(s.excludes(above, DVec3::new(0.3, 0.0, 1.0).normalize()));
        assert!(s.excludes(DVec3::new(0.5, 0.5, 1.999), -DVec3::Z));
        // Towards it, or starting inside its slab: it may be hit.
        assert!(!s.excludes(above, -DVec3::Z));
        assert!(!s.excludes(DVec3::new(0.5, 0.5, 2.0), DVec3::Z));
    }

    #[test]
    fn a_sphere_excludes_outward_rays_from_outside_only() {
        // An octahedron: every vertex at distance 1 from the origin.
        let v = [Vec3::X, Vec3::Y, Vec3::NEG_X, Vec3::NEG_Y];
        let mut tris = Vec::new();
        for k in 0..4 {
            let (a, b) = (v[k], v[(k + 1) % 4]);
            tris.push(Triangle::new(a, b, Vec3::Z));
            tris.push(Triangle::new(b, a, Vec3::NEG_Z));
        }
        let s = Shell::of(&tris);
        let o = DVec3::new(0.0, 0.0, 1.001);
        assert!(s.excludes(o, DVec3::new(1.0, 0.0, 0.01).normalize()));
        assert!(!s.excludes(o, DVec3::new(1.0, 0.0, -0.01).normalize()));
        assert!(!s.excludes(DVec3::new(0.0, 0.0, 0.999), DVec3::Z));
    }

    #[test]
    fn seen_from_an_origin_the_shell_excludes_the_same_rays() {
        let shells = [
            Shell::of(&quad(2.0)),
            Shell::ball(DVec3::new(0.5, 0.5, 2.0), 0.5),
        ];
        for shell in shells {
            for o in [
                (0.5, 0.5, 2.001),
                (0.5, 0.5, 1.999),
                (2.0, 0.5, 2.0),
                (0.5, 0.6, 2.0),
            ] {
                let o = DVec3::from(o);
                let seen = shell.seen_from(o);
                for k in 0..64 {
                    let a = f64::from(k) * 0.7;
                    let d = DVec3::new(a.cos() * a.sin(), (2.0 * a).sin(), a.cos());
                    assert_eq!(seen.excludes(d), shell.excludes(o, d), "{o} {d}");
                }
            }
        }
    }
}
