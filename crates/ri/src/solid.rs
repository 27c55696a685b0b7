//! The constructive-solid-geometry tree of one frame (RI Spec 3.2 §5.8, `SolidBegin`/`SolidEnd`).
//!
//! Each `SolidBegin` adds a node; its leaves are the *primitive* solids, whose surfaces
//! (however many requests make them) bound one closed volume. The hider never sees the tree's
//! shape in the RIB: every [`FramePrimitive`](crate::FramePrimitive) only names the leaf it
//! bounds, and the hider asks the tree whether a point is inside the composite solid.
//!
//! Separate top-level `SolidBegin` blocks are separate trees (roots): a surface event on one
//! solid never changes another's membership.
use crate::state::Ri;
use illume_rib::Span;

/// A solid's set operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SolidOp {
    /// A leaf: the volume bounded by the block's surfaces (inside = opposite the outward normal).
    Primitive,
    Union,
    Intersection,
    /// The first child minus all the others.
    Difference,
}

impl SolidOp {
    /// The RIB token's operation, `None` when the token is not one of the four.
    pub fn from_token(token: &str) -> Option<SolidOp> {
        Some(match token {
            "primitive" => SolidOp::Primitive,
            "union" => SolidOp::Union,
            "intersection" => SolidOp::Intersection,
            "difference" => SolidOp::Difference,
            _ => return None,
        })
    }
}

/// One `SolidBegin` block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SolidNode {
    pub op: SolidOp,
    /// Child node indices, in RIB order (the order matters for a difference).
    pub children: Vec<u32>,
    /// The enclosing solid, `None` for a root.
    pub parent: Option<u32>,
}

/// Every solid of a frame. Node indices are `u32` so the hider's visible points stay small.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SolidTree {
    pub nodes: Vec<SolidNode>,
}

impl SolidTree {
    /// Adds a node under `parent` and returns its index.
    pub fn add(&mut self, op: SolidOp, parent: Option<u32>) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(SolidNode {
            op,
            children: Vec::new(),
            parent,
        });
        if let Some(p) = parent.and_then(|p| self.nodes.get_mut(p as usize)) {
            p.children.push(id);
        }
        id
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The root of the tree `node` belongs to.
    pub fn root(&self, mut node: u32) -> u32 {
        while let Some(p) = self.nodes.get(node as usize).and_then(|n| n.parent) {
            node = p;
        }
        node
    }

    /// Whether a point is inside solid `node`, given whether it is inside each primitive leaf.
    /// Empty unions, intersections and differences contain nothing.
    pub fn contains(&self, node: u32, inside_leaf: &dyn Fn(u32) -> bool) -> bool {
        let Some(n) = self.nodes.get(node as usize) else {
            return false;
        };
        let mut kids = n.children.iter().map(|&c| self.contains(c, inside_leaf));
        match n.op {
            SolidOp::Primitive => inside_leaf(node),
            SolidOp::Union => kids.any(|k| k),
            SolidOp::Intersection => !n.children.is_empty() && kids.all(|k| k),
            SolidOp::Difference => kids.next().unwrap_or(false) && !kids.any(|k| k),
        }
    }
}

// ---- SolidBegin/SolidEnd in the RI state ----------------------------------------------

impl Ri {
    /// Opens a CSG node under the innermost open solid. The caller pushes the block, so
    /// `SolidEnd` and block recovery pop `open_solids` in step with the block stack.
    pub(crate) fn solid_begin(&mut self, op: &str, span: &Span) {
        let op = SolidOp::from_token(op).unwrap_or_else(|| {
            self.diagnostics.error(
                span,
                "SolidBegin",
                format!("unknown operation `{op}` (treated as \"union\")"),
            );
            SolidOp::Union
        });
        let parent = self.open_solids.last().copied();
        let node = match parent {
            Some(p) if self.is_primitive_solid(p) => {
                self.diagnostics.warn(
                    span,
                    "SolidBegin",
                    "a primitive solid can not contain solids: this block's surfaces join the enclosing primitive solid",
                );
                p
            }
            _ => self.solids.add(op, parent),
        };
        self.open_solids.push(node);
    }

    /// The primitive solid the next geometry bounds: the open primitive solid, or, for a
    /// surface directly inside a union/intersection/difference, a primitive solid of its own.
    pub(crate) fn solid_leaf(&mut self) -> Option<u32> {
        let top = *self.open_solids.last()?;
        Some(if self.is_primitive_solid(top) {
            top
        } else {
            self.solids.add(SolidOp::Primitive, Some(top))
        })
    }

    pub(crate) fn is_primitive_solid(&self, node: u32) -> bool {
        self.solids
            .nodes
            .get(node as usize)
            .is_some_and(|n| n.op == SolidOp::Primitive)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (A ∪ B) − C against the boolean formula, for all eight leaf states.
    #[test]
    fn nested_difference_matches_the_formula() {
        let mut t = SolidTree::default();
        let d = t.add(SolidOp::Difference, None);
        let u = t.add(SolidOp::Union, Some(d));
        let a = t.add(SolidOp::Primitive, Some(u));
        let b = t.add(SolidOp::Primitive, Some(u));
        let c = t.add(SolidOp::Primitive, Some(d));
        assert_eq!(t.root(a), d);
        assert_eq!(t.root(c), d);
        for bits in 0..8u32 {
            let inside = |l: u32| {
                let k = [a, b, c].iter().position(|&x| x == l).unwrap();
                bits & (1 << k) != 0
            };
            let (ia, ib, ic) = (inside(a), inside(b), inside(c));
            assert_eq!(t.contains(d, &inside), (ia || ib) && !ic, "bits {bits:03b}");
        }
    }

    #[test]
    fn intersection_and_empty_nodes() {
        let mut t = SolidTree::default();
        let i = t.add(SolidOp::Intersection, None);
        let a = t.add(SolidOp::Primitive, Some(i));
        let b = t.add(SolidOp::Primitive, Some(i));
        let e = t.add(SolidOp::Intersection, None);
        let f = t.add(SolidOp::Difference, None);
        for bits in 0..4u32 {
            let inside = |l: u32| bits & (1 << (l - a)) != 0;
            assert_eq!(t.contains(i, &inside), bits == 3);
            assert!(!t.contains(e, &inside));
            assert!(!t.contains(f, &inside));
        }
        assert_eq!(t.root(b), i);
        assert!(!t.contains(99, &|_| true));
    }
}
