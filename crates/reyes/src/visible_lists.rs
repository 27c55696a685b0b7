//! The visible points of a bucket's samples in one arena: per sample a linked list through
//! one `Vec` of points, instead of one heap `Vec` per sample (issue 21 part 3: allocating and
//! freeing those was 7–11% of a still frame's CPU). The arena is cleared, not freed, between
//! the buckets a thread renders (see `SampleBuffer`'s spare buffers).
//!
//! Most samples of an opaque scene end with one point: when an opaque point arrives, the
//! points that would composite behind it are unlinked at once (when nothing else needs them:
//! see [`VisibleLists::reset`]), so lists stay short and compositing sorts almost nothing.
use crate::visible::VisiblePoint;

/// The end of a list.
const END: u32 = u32::MAX;

/// Per sample, the visible points it collected, in the order they came.
#[derive(Default)]
pub(crate) struct VisibleLists {
    /// Per sample, its newest point (`END`: none).
    head: Vec<u32>,
    /// Every sample's points; `next[k]` is the point that came before point `k` in the same
    /// sample's list.
    points: Vec<VisiblePoint>,
    next: Vec<u32>,
    /// Whether an opaque point drops the points behind it (see [`VisibleLists::reset`]).
    drop_hidden: bool,
}

impl VisibleLists {
    /// Empties every list for reuse with `samples` samples, keeping the allocations. With
    /// `drop_hidden`, [`VisibleLists::push_opaque`] unlinks the points that sort behind the
    /// opaque one. Compositing stops at an opaque point, so only two things ever look behind
    /// it: CSG resolution (a solid's hits behind it change which points are kept) and the
    /// `midpoint` depth filter (the second point's depth): the caller turns it off for frames
    /// with solids or that filter.
    pub fn reset(&mut self, samples: usize, drop_hidden: bool) {
        self.head.clear();
        self.head.resize(samples, END);
        self.points.clear();
        self.next.clear();
        self.drop_hidden = drop_hidden;
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.head.len()
    }

    /// The bytes the arena holds allocated.
    pub fn capacity_bytes(&self) -> usize {
        self.head.capacity() * 4
            + self.points.capacity() * std::mem::size_of::<VisiblePoint>()
            + self.next.capacity() * 4
    }

    /// Appends a point to sample `s`'s list.
    pub fn push(&mut self, s: usize, vp: VisiblePoint) {
        let k = self.points.len() as u32;
        self.points.push(vp);
        self.next.push(self.head[s]);
        self.head[s] = k;
    }

    /// Appends an opaque point to sample `s`'s list, first unlinking (when dropping hidden
    /// points) those that would sort after it: deeper, or as deep and later in `order` (at
    /// equal depth and order the earlier point sorts first, so it stays).
    pub fn push_opaque(&mut self, s: usize, vp: VisiblePoint) {
        if self.drop_hidden {
            let mut prev = END;
            let mut k = self.head[s];
            while k != END {
                let p = &self.points[k as usize];
                let after = p.z.total_cmp(&vp.z).then(p.order.cmp(&vp.order)).is_gt();
                let next = self.next[k as usize];
                if after {
                    match prev {
                        END => self.head[s] = next,
                        _ => self.next[prev as usize] = next,
                    }
                } else {
                    prev = k;
                }
                k = next;
            }
        }
        self.push(s, vp);
    }

    /// Whether sample `s` has no point.
    pub fn is_empty_at(&self, s: usize) -> bool {
        self.head[s] == END
    }

    /// Sample `s`'s point when it holds exactly one.
    #[inline]
    pub fn single(&self, s: usize) -> Option<&VisiblePoint> {
        let k = self.head[s];
        (k != END && self.next[k as usize] == END).then(|| &self.points[k as usize])
    }

    /// Sample `s`'s points in the order they came, into `out` (cleared first).
    pub fn collect(&self, s: usize, out: &mut Vec<VisiblePoint>) {
        out.clear();
        let mut k = self.head[s];
        while k != END {
            out.push(self.points[k as usize]);
            k = self.next[k as usize];
        }
        out.reverse();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn point(z: f32, order: u64) -> VisiblePoint {
        VisiblePoint {
            z,
            order,
            c: Vec3::splat(z),
            o: Vec3::ONE,
            tag: 0,
        }
    }

    fn depths(l: &VisibleLists, s: usize) -> Vec<(f32, u64)> {
        let mut out = Vec::new();
        l.collect(s, &mut out);
        out.iter().map(|p| (p.z, p.order)).collect()
    }

    fn lists(samples: usize, drop_hidden: bool) -> VisibleLists {
        let mut l = VisibleLists::default();
        l.reset(samples, drop_hidden);
        l
    }

    #[test]
    fn lists_keep_their_samples_and_arrival_order() {
        let mut l = lists(3, false);
        l.push(1, point(3.0, 0));
        l.push(0, point(1.0, 0));
        l.push(1, point(2.0, 5));
        l.push_opaque(1, point(1.5, 2));
        assert_eq!(depths(&l, 0), [(1.0, 0)]);
        assert_eq!(depths(&l, 1), [(3.0, 0), (2.0, 5), (1.5, 2)]);
        assert!(depths(&l, 2).is_empty());
        l.reset(2, true);
        assert_eq!(l.len(), 2);
        assert!(depths(&l, 1).is_empty());
    }

    #[test]
    fn an_opaque_point_drops_exactly_what_sorts_behind_it() {
        let mut l = lists(1, true);
        for (z, order) in [(3.0, 0), (1.0, 9), (2.0, 7), (2.0, 3), (2.0, 4), (0.5, 1)] {
            l.push(0, point(z, order));
        }
        // Depth 2 at order 4: the equal point stays (it came first), order 7 goes.
        l.push_opaque(0, point(2.0, 4));
        assert_eq!(
            depths(&l, 0),
            [(1.0, 9), (2.0, 3), (2.0, 4), (0.5, 1), (2.0, 4)]
        );
        l.push_opaque(0, point(0.7, 0));
        assert_eq!(depths(&l, 0), [(0.5, 1), (0.7, 0)]);
        l.push_opaque(0, point(0.1, 0));
        assert_eq!(depths(&l, 0), [(0.1, 0)]);
    }
}
