//! Axis-aligned bounds in camera space.
use glam::{DMat4, DVec3, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound {
    pub min: Vec3,
    pub max: Vec3,
}

impl Bound {
    pub const EMPTY: Bound = Bound {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Bound {
        points.into_iter().fold(Bound::EMPTY, |b, p| b.including(p))
    }

    pub fn including(self, p: Vec3) -> Bound {
        Bound {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn union(self, o: Bound) -> Bound {
        Bound {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Grows the bound by `r` on every side (displacement bounds).
    pub fn padded(self, r: f32) -> Bound {
        Bound {
            min: self.min - Vec3::splat(r),
            max: self.max + Vec3::splat(r),
        }
    }

    /// The eight corners, for transforming or projecting the bound.
    pub fn corners(&self) -> [Vec3; 8] {
        let (a, b) = (self.min, self.max);
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(b.x, a.y, a.z),
            Vec3::new(a.x, b.y, a.z),
            Vec3::new(b.x, b.y, a.z),
            Vec3::new(a.x, a.y, b.z),
            Vec3::new(b.x, a.y, b.z),
            Vec3::new(a.x, b.y, b.z),
            Vec3::new(b.x, b.y, b.z),
        ]
    }

    /// The bound of f64 points, rounded outward so every f32 rounding of a point inside the
    /// f64 box (and of values computed a little differently, e.g. by another basis) stays inside.
    pub fn from_dpoints(points: impl IntoIterator<Item = DVec3>) -> Bound {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in points {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if lo.cmpgt(hi).any() {
            return Bound::EMPTY;
        }
        // Relative slack: 1e-6 of the largest coordinate magnitude (f32 has ~6e-8).
        let pad = lo.abs().max(hi.abs()).max_element() * 1e-6 + 1e-30;
        Bound {
            min: (lo - DVec3::splat(pad)).as_vec3(),
            max: (hi + DVec3::splat(pad)).as_vec3(),
        }
    }

    /// The camera-space bound of an object-space box `[lo, hi]`: its eight corners transformed.
    pub fn of_transformed_box(camera_from_object: &DMat4, lo: DVec3, hi: DVec3) -> Bound {
        Bound::from_dpoints((0..8).map(|k| {
            let c = DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            camera_from_object.transform_point3(c)
        }))
    }
}
