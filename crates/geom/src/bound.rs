//! Axis-aligned bounds in camera space.
use glam::Vec3;

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
}
