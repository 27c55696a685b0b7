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
    /// Every sample's points, each with the point that came before it in the same sample's
    /// list (`END`: none). One arena of both, not two: appending is one push, one capacity
    /// check (see [`VisibleLists::push`]).
    nodes: Vec<Node>,
    /// Whether an opaque point drops the points behind it (see [`VisibleLists::reset`]).
    drop_hidden: bool,
}

#[derive(Clone, Copy)]
struct Node {
    vp: VisiblePoint,
    next: u32,
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
        self.nodes.clear();
        self.drop_hidden = drop_hidden;
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.head.len()
    }

    /// The bytes the arena holds allocated.
    pub fn capacity_bytes(&self) -> usize {
        self.head.capacity() * 4 + self.nodes.capacity() * std::mem::size_of::<Node>()
    }

    /// Appends a point to sample `s`'s list. Inlined: it runs once per sample hit, and as
    /// a call with two arenas it was 44 instructions (`rib/sphere.rib`, 1.5 M hits).
    #[inline]
    pub fn push(&mut self, s: usize, vp: VisiblePoint) {
        let head = &mut self.head[s];
        let next = std::mem::replace(head, self.nodes.len() as u32);
        self.nodes.push(Node { vp, next });
    }

    /// Appends an opaque point to sample `s`'s list, first unlinking (when dropping hidden
    /// points) those that would sort after it: deeper, or as deep and later in `order` (at
    /// equal depth and order the earlier point sorts first, so it stays).
    ///
    /// A list of one point that sorts after it (an opaque scene's sample hit again, nearer)
    /// becomes the new point in place: the arena does not grow and nothing is unlinked.
    #[inline]
    pub fn push_opaque(&mut self, s: usize, vp: VisiblePoint) {
        if self.drop_hidden {
            let k = self.head[s];
            if k != END {
                let node = &mut self.nodes[k as usize];
                if node.next == END && sorts_after(&node.vp, &vp) {
                    node.vp = vp;
                    return;
                }
                self.drop_behind(s, &vp);
            }
        }
        self.push(s, vp);
    }

    /// Unlinks the points of sample `s`'s list that sort after `vp`.
    fn drop_behind(&mut self, s: usize, vp: &VisiblePoint) {
        let mut prev = END;
        let mut k = self.head[s];
        while k != END {
            let Node { vp: p, next } = self.nodes[k as usize];
            if sorts_after(&p, vp) {
                match prev {
                    END => self.head[s] = next,
                    _ => self.nodes[prev as usize].next = next,
                }
            } else {
                prev = k;
            }
            k = next;
        }
    }

    /// Whether sample `s` has no point.
    pub fn is_empty_at(&self, s: usize) -> bool {
        self.head[s] == END
    }

    /// Sample `s`'s point when it holds exactly one.
    #[inline]
    pub fn single(&self, s: usize) -> Option<&VisiblePoint> {
        let node = self.nodes.get(self.head[s] as usize)?;
        (node.next == END).then_some(&node.vp)
    }

    /// Sample `s`'s points in the order they came, into `out` (cleared first).
    pub fn collect(&self, s: usize, out: &mut Vec<VisiblePoint>) {
        out.clear();
        let mut k = self.head[s];
        while k != END {
            let node = &self.nodes[k as usize];
            out.push(node.vp);
            k = node.next;
        }
        out.reverse();
    }
}

/// Whether `p` sorts after `vp` in a sample's list: deeper, or as deep and later in `order`.
#[inline]
fn sorts_after(p: &VisiblePoint, vp: &VisiblePoint) -> bool {
    p.z.total_cmp(&vp.z).then(p.order.cmp(&vp.order)).is_gt()
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

    /// Random pushes, opaque or not, into a few samples give the lists of a plain model (an
    /// opaque point first drops every point that sorts after it), whichever path each push
    /// takes: an empty list, one point replaced in place, one point kept, a longer list.
    #[test]
    fn opaque_pushes_match_a_plain_model() {
        let mut seed = 0x9e37_79b9u32;
        let mut next = move |n: u32| {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed % n
        };
        for drop_hidden in [false, true] {
            let mut l = lists(4, drop_hidden);
            let mut model: Vec<Vec<(f32, u64)>> = vec![Vec::new(); 4];
            for _ in 0..2000 {
                let s = next(4) as usize;
                let p = point(next(6) as f32 * 0.5, u64::from(next(3)));
                if next(3) == 0 {
                    l.push(s, p);
                } else {
                    l.push_opaque(s, p);
                    if drop_hidden {
                        model[s].retain(|&(z, o)| !sorts_after(&point(z, o), &p));
                    }
                }
                model[s].push((p.z, p.order));
                assert_eq!(depths(&l, s), model[s]);
                assert_eq!(
                    l.single(s).map(|p| (p.z, p.order)),
                    match model[s][..] {
                        [one] => Some(one),
                        _ => None,
                    }
                );
            }
        }
    }
}
