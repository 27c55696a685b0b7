//! Constructive solid geometry resolved in a sample's visible-point list (RI Spec 3.2 §5.8).
//!
//! The classic REYES way: every visible point on a solid's surface knows its primitive solid
//! and whether it is an *entering* hit (front-facing with respect to the solid's outward
//! normal) or an *exiting* one. Walking the depth-sorted list front to back, each hit sets its
//! primitive solid's inside/outside state; the point is kept only where that changes whether
//! the sample ray is inside the composite solid (the tree's root), because that is where the
//! composite's surface is. Points of primitives outside any solid pass through untouched.
//!
//! Every sample starts in the state of the eye: inside the primitive solids that contain it
//! (see [`crate::csg_eye`]), outside the others.
//!
//! Hits *set* the state rather than count it: a grid border reaches a little outward so that
//! neighbouring grids overlap (see the hider's `seam_reach`), and a sample in that overlap sees
//! the same surface twice; a second entering hit must not count as being "twice inside".
use illume_ri::{SolidOp, SolidTree};

/// The solid id of a visible point on a primitive that bounds no solid.
pub(crate) const NO_SOLID: u32 = u32::MAX;

/// A composite solid whose primitive solids are at most this many is looked up in a table of
/// its membership (2^n entries) instead of walking its tree per surface event.
const TABLE_LEAVES: usize = 10;

/// A frame's solids, ready to resolve visible-point lists.
pub(crate) struct SolidResolver<'a> {
    tree: &'a SolidTree,
    /// The root of each node, so an event only re-evaluates its own tree.
    roots: Vec<u32>,
    /// The primitive solids the eye is inside: every sample ray starts inside them.
    eye_inside: Vec<u32>,
    /// Per node: its bit in its root's [`SolidResolver::tables`] entry (primitive solids of a
    /// tabled root only).
    bits: Vec<Option<u32>>,
    /// Per node that is a root with at most [`TABLE_LEAVES`] primitive solids: whether a point
    /// is inside the composite, indexed by the set of its primitive solids the point is inside
    /// (bit [`SolidResolver::bits`]). The tree walk per event was 14% of `rib/csg.rib` at 2×.
    tables: Vec<Option<Vec<bool>>>,
}

impl<'a> SolidResolver<'a> {
    /// `None` when the frame has no solids: the hider then skips resolution entirely.
    /// `eye_inside`: the primitive solids that contain the eye.
    pub fn new(tree: &'a SolidTree, eye_inside: &[u32]) -> Option<SolidResolver<'a>> {
        if tree.is_empty() {
            return None;
        }
        let roots: Vec<u32> = (0..tree.nodes.len() as u32).map(|n| tree.root(n)).collect();
        let mut bits = vec![None; tree.nodes.len()];
        let mut tables = vec![None; tree.nodes.len()];
        for root in (0..tree.nodes.len() as u32).filter(|&n| roots[n as usize] == n) {
            let leaves: Vec<u32> = (0..tree.nodes.len() as u32)
                .filter(|&n| roots[n as usize] == root)
                .filter(|&n| tree.nodes[n as usize].op == SolidOp::Primitive)
                .collect();
            if leaves.len() > TABLE_LEAVES {
                continue;
            }
            for (bit, &leaf) in leaves.iter().enumerate() {
                bits[leaf as usize] = Some(bit as u32);
            }
            let table = (0..1u32 << leaves.len())
                .map(|set| {
                    let inside = |l: u32| leaves.iter().position(|&x| x == l);
                    tree.contains(root, &|l| inside(l).is_some_and(|b| set >> b & 1 == 1))
                })
                .collect();
            tables[root as usize] = Some(table);
        }
        Some(SolidResolver {
            tree,
            roots,
            eye_inside: eye_inside.to_vec(),
            bits,
            tables,
        })
    }

    /// Whether a point inside the primitive solids `inside` (and outside the others) is inside
    /// the composite solid `root`: [`SolidTree::contains`], from the root's table when it has
    /// one.
    fn inside_root(&self, root: u32, inside: &[u32]) -> bool {
        let Some(table) = self.tables.get(root as usize).and_then(Option::as_ref) else {
            return self.tree.contains(root, &|l| inside.contains(&l));
        };
        let set = (inside.iter())
            .filter(|&&l| self.roots.get(l as usize) == Some(&root))
            .filter_map(|&l| self.bits.get(l as usize).copied().flatten())
            .fold(0usize, |set, bit| set | 1 << bit);
        table[set]
    }

    /// Removes from a depth-sorted list the solid hits that are not on the composite surface.
    /// `event` gives a point's primitive solid ([`NO_SOLID`] for none) and whether it enters.
    /// `complete`: no opaque surface cut the list short (see [`Self::unmatched_entries`]).
    pub fn resolve<T>(&self, list: &mut Vec<T>, complete: bool, event: impl Fn(&T) -> (u32, bool)) {
        if list.iter().all(|p| event(p).0 == NO_SOLID) {
            return;
        }
        let spurious = if complete {
            unmatched_entries(list.iter().map(&event))
        } else {
            Vec::new()
        };
        // The primitive solids this sample is inside (a list: a sample meets few solids).
        let mut inside: Vec<u32> = self.eye_inside.clone();
        let mut index = 0;
        list.retain(|p| {
            let (leaf, entering) = event(p);
            index += 1;
            if leaf == NO_SOLID {
                return true;
            }
            if spurious.contains(&(index - 1)) {
                return false;
            }
            let pos = inside.iter().position(|&l| l == leaf);
            if pos.is_some() == entering {
                // Already in that state: a repeated hit, or leaving a solid never entered.
                return false;
            }
            let Some(&root) = self.roots.get(leaf as usize) else {
                return true;
            };
            let before = self.inside_root(root, &inside);
            match pos {
                Some(k) => {
                    inside.swap_remove(k);
                }
                None => inside.push(leaf),
            }
            let after = self.inside_root(root, &inside);
            before != after
        });
    }
}

/// Indices of entering hits that a closed surface never matched with an exit behind them.
///
/// Why: at a solid's silhouette the front and back micropolygons are diced separately, so
/// their polygonal outlines differ by a sliver, and a sample in the sliver hits only the
/// front. Taken at face value the ray would stay inside that solid to infinity and, say,
/// carve a thin dark ring out of whatever it is subtracted from. A ray that leaves every
/// closed surface it enters (when nothing opaque cut the list short) shows such an entry
/// was a graze: it is ignored. (A graze that hits only the back is already ignored: an exit
/// from a solid never entered.)
fn unmatched_entries(events: impl Iterator<Item = (u32, bool)>) -> Vec<usize> {
    // (primitive solid, index of the entry that made the ray inside it, if it still is).
    let mut state: Vec<(u32, Option<usize>)> = Vec::new();
    for (i, (leaf, entering)) in events.enumerate() {
        if leaf == NO_SOLID {
            continue;
        }
        match state.iter_mut().find(|s| s.0 == leaf) {
            Some(s) => match (s.1, entering) {
                (None, true) => s.1 = Some(i),
                (Some(_), false) => s.1 = None,
                _ => {}
            },
            None => state.push((leaf, entering.then_some(i))),
        }
    }
    state.into_iter().filter_map(|s| s.1).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1-D ray through A = [0, 4] minus B = [1, 2] and a plain surface at 3: A − B is
    /// [0, 1) ∪ (2, 4], so its surfaces are A's entry at 0, B's near wall at 1 (leaving the
    /// composite into the hole), B's far wall at 2 (re-entering it) and A's exit at 4.
    #[test]
    fn difference_keeps_the_composite_boundary() {
        let mut t = SolidTree::default();
        let d = t.add(SolidOp::Difference, None);
        let a = t.add(SolidOp::Primitive, Some(d));
        let b = t.add(SolidOp::Primitive, Some(d));
        let r = SolidResolver::new(&t, &[]).unwrap();
        // (depth, solid, entering)
        let mut l = vec![
            (0.0, a, true),
            (0.0, a, true), // seam duplicate
            (1.0, b, true),
            (2.0, b, false),
            (3.0, NO_SOLID, true),
            (4.0, a, false),
            (5.0, b, false), // leaves a solid it never entered
        ];
        r.resolve(&mut l, false, |p| (p.1, p.2));
        let z: Vec<f64> = l.iter().map(|p| p.0).collect();
        assert_eq!(z, [0.0, 1.0, 2.0, 3.0, 4.0]);
    }

    /// A ray that enters B before A: A's entry inside B is not on A − B, nor is B's front.
    #[test]
    fn subtracted_solid_in_front_hides_the_first_solid() {
        let mut t = SolidTree::default();
        let d = t.add(SolidOp::Difference, None);
        let a = t.add(SolidOp::Primitive, Some(d));
        let b = t.add(SolidOp::Primitive, Some(d));
        let u = t.add(SolidOp::Union, None);
        let c = t.add(SolidOp::Primitive, Some(u));
        let r = SolidResolver::new(&t, &[]).unwrap();
        let mut l = vec![
            (0.0, b, true),
            (0.5, c, true),
            (1.0, a, true),
            (2.0, b, false),
            (3.0, a, false),
            (4.0, c, false),
        ];
        r.resolve(&mut l, false, |p| (p.1, p.2));
        let z: Vec<f64> = l.iter().map(|p| p.0).collect();
        assert_eq!(z, [0.5, 2.0, 3.0, 4.0]);
        assert!(SolidResolver::new(&SolidTree::default(), &[]).is_none());
    }

    /// A − B where the ray grazes B's front at its silhouette and never hits B's back: with
    /// a complete list the graze is ignored and A's entry stays; a list cut short by an
    /// opaque surface can not tell a graze from an exit hidden behind it.
    #[test]
    fn a_graze_on_a_silhouette_enters_nothing() {
        let mut t = SolidTree::default();
        let d = t.add(SolidOp::Difference, None);
        let a = t.add(SolidOp::Primitive, Some(d));
        let b = t.add(SolidOp::Primitive, Some(d));
        let r = SolidResolver::new(&t, &[]).unwrap();
        let graze = vec![(0.0, b, true), (1.0, a, true), (2.0, a, false)];
        let mut l = graze.clone();
        r.resolve(&mut l, true, |p| (p.1, p.2));
        let z: Vec<f64> = l.iter().map(|p| p.0).collect();
        assert_eq!(z, [1.0, 2.0]);
        let mut l = graze;
        r.resolve(&mut l, false, |p| (p.1, p.2));
        assert!(l.is_empty());
        // B entered twice (a seam duplicate) and left once is matched.
        let mut l = vec![
            (0.0, b, true),
            (0.0, b, true),
            (0.5, a, true),
            (1.0, b, false),
            (2.0, a, false),
        ];
        r.resolve(&mut l, true, |p| (p.1, p.2));
        let z: Vec<f64> = l.iter().map(|p| p.0).collect();
        assert_eq!(z, [1.0, 2.0]);
    }

    /// The eye inside A ∩ B (a camera in a room): the first hits are exits, and the nearer
    /// one is where the ray leaves the intersection; from outside both, nothing is kept
    /// before the entries.
    #[test]
    fn an_eye_inside_the_solid_sees_its_first_exit() {
        let mut t = SolidTree::default();
        let i = t.add(SolidOp::Intersection, None);
        let a = t.add(SolidOp::Primitive, Some(i));
        let b = t.add(SolidOp::Primitive, Some(i));
        let hits = vec![(1.0, b, false), (2.0, a, false)];
        let mut l = hits.clone();
        SolidResolver::new(&t, &[a, b])
            .unwrap()
            .resolve(&mut l, true, |p| (p.1, p.2));
        let z: Vec<f64> = l.iter().map(|p| p.0).collect();
        assert_eq!(z, [1.0]);
        // Assumed outside (the old behaviour): exits of solids never entered are dropped.
        let mut l = hits;
        SolidResolver::new(&t, &[])
            .unwrap()
            .resolve(&mut l, true, |p| (p.1, p.2));
        assert!(l.is_empty());
    }

    /// Random trees (some with more primitive solids than a table takes) and random sets of
    /// primitive solids: the table answers what the tree walk answers.
    #[test]
    fn tables_answer_as_the_tree_walk() {
        let mut h = 0x9e37_79b9u32;
        let mut next = |n: u32| {
            h ^= h << 13;
            h ^= h >> 17;
            h ^= h << 5;
            h % n
        };
        let ops = [SolidOp::Union, SolidOp::Intersection, SolidOp::Difference];
        let (mut tabled, mut walked) = (0, 0);
        for _ in 0..200 {
            let mut t = SolidTree::default();
            let mut groups: Vec<u32> = Vec::new();
            for _ in 0..1 + next(4) {
                let root = t.add(ops[next(3) as usize], None);
                groups.push(root);
                for _ in 0..next(5) {
                    let parent = groups[next(groups.len() as u32) as usize];
                    if t.nodes[parent as usize].op != SolidOp::Primitive {
                        let g = t.add(ops[next(3) as usize], Some(parent));
                        groups.push(g);
                    }
                }
                for _ in 0..1 + next(14) {
                    let parent = groups[next(groups.len() as u32) as usize];
                    t.add(SolidOp::Primitive, Some(parent));
                }
            }
            let r = SolidResolver::new(&t, &[]).unwrap();
            let n = t.nodes.len() as u32;
            for root in (0..n).filter(|&x| t.root(x) == x) {
                tabled += usize::from(r.tables[root as usize].is_some());
                walked += usize::from(r.tables[root as usize].is_none());
                for _ in 0..50 {
                    // Any nodes, of any tree, in any order.
                    let inside: Vec<u32> = (0..n).filter(|_| next(3) == 0).collect();
                    let walk = t.contains(root, &|l| inside.contains(&l));
                    assert_eq!(r.inside_root(root, &inside), walk, "{t:?} {inside:?}");
                }
            }
        }
        assert!(
            tabled > 100 && walked > 10,
            "{tabled} tabled, {walked} walked"
        );
    }
}
