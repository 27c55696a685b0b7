//! The four-wide form of the tree that rays traverse (a "BVH4", as Embree's and pbrt's
//! successors use): the binary SAH tree is collapsed so each node holds up to four children's
//! boxes side by side, one `f32` SIMD lane per child, and one visit tests all four boxes at
//! once.
//!
//! Why: `occlusion()` shoots 16 incoherent rays per shaded point (issue 19), and the binary
//! traversal spent half the frame loading one box per node and testing it alone. Collapsing
//! halves the visits and the four box tests cost about one.
//!
//! Collapse: starting from a binary node's two children, the interior child with the largest
//! box surface is replaced by its own two children until there are four or only leaves are
//! left (a pure function of the binary tree, so the same triangles give the same tree).
//!
//! The box test is [`crate::slab`]'s, lane by lane: boxes are padded, a ray far outside the
//! scene takes the exact `f64` test per child instead.
use crate::slab::{self, SlabRay};
use crate::triangle::PreparedRay;
use glam::{Vec3, Vec4};

/// One node: up to four children (`len` of them). Child `k` is a leaf of `count[k]`
/// triangles from `first[k]` in the triangle array, or (`count[k] == 0`) the node at index
/// `first[k]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node4 {
    min: [Vec4; 3],
    max: [Vec4; 3],
    pub first: [u32; 4],
    pub count: [u32; 4],
    /// Per child: the group all its triangles belong to, or `NO_GROUP`.
    pub group: [u32; 4],
    len: u8,
}

/// A child of a binary node, as the collapse sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Child {
    pub min: Vec3,
    pub max: Vec3,
    /// Leaf: triangles `first..first + count`; interior (`count == 0`): the binary node index.
    pub first: u32,
    pub count: u32,
    pub group: u32,
}

impl Child {
    fn half_area(&self) -> f32 {
        let d = (self.max - self.min).max(Vec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// Collapses a binary tree given as `children(i)` (the two children of interior node `i`)
/// from `root` into four-wide nodes; the root is node 0.
pub(crate) fn collapse(root: Child, children: &dyn Fn(u32) -> [Child; 2]) -> Vec<Node4> {
    let mut out = Vec::new();
    if root.count > 0 {
        // A single leaf: one node with one child.
        out.push(node_of(&[root]));
        return out;
    }
    collapse_into(root.first, children, &mut out);
    out
}

fn collapse_into(binary: u32, children: &dyn Fn(u32) -> [Child; 2], out: &mut Vec<Node4>) -> u32 {
    let mut kids: Vec<Child> = children(binary).to_vec();
    while kids.len() < 4 {
        // The interior child with the largest box (ties: the first), opened up.
        let Some((k, _)) = kids.iter().enumerate().filter(|(_, c)| c.count == 0).fold(
            None,
            |best: Option<(usize, f32)>, (k, c)| {
                let a = c.half_area();
                match best {
                    Some((_, b)) if b >= a => best,
                    _ => Some((k, a)),
                }
            },
        ) else {
            break;
        };
        let [l, r] = children(kids[k].first);
        kids[k] = l;
        kids.insert(k + 1, r);
    }
    let index = out.len();
    out.push(node_of(&kids));
    for (k, c) in kids.iter().enumerate() {
        if c.count == 0 {
            let child = collapse_into(c.first, children, out);
            out[index].first[k] = child;
        }
    }
    index as u32
}

fn node_of(kids: &[Child]) -> Node4 {
    let lane = |f: &dyn Fn(&Child) -> f32| {
        let mut v = [0.0f32; 4];
        for (k, c) in kids.iter().enumerate() {
            v[k] = f(c);
        }
        Vec4::from_array(v)
    };
    let mut first = [0u32; 4];
    let mut count = [0u32; 4];
    let mut group = [crate::bvh::NO_GROUP; 4];
    for (k, c) in kids.iter().enumerate() {
        first[k] = c.first;
        count[k] = c.count;
        group[k] = c.group;
    }
    Node4 {
        min: [lane(&|c| c.min.x), lane(&|c| c.min.y), lane(&|c| c.min.z)],
        max: [lane(&|c| c.max.x), lane(&|c| c.max.y), lane(&|c| c.max.z)],
        first,
        count,
        group,
        len: kids.len() as u8,
    }
}

/// A ray prepared for the four-lane test: origin and inverse direction splatted per axis.
pub(crate) struct WideRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
}

impl WideRay {
    pub fn new(ray: &SlabRay) -> WideRay {
        let (o, d) = (ray.origin(), ray.inv_dir());
        WideRay {
            origin: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            inv_dir: [Vec4::splat(d.x), Vec4::splat(d.y), Vec4::splat(d.z)],
        }
    }
}

impl Node4 {
    /// Which children the ray enters within `(0, t_max)` (bit `k`: child `k`), and where it
    /// enters each (for visiting the nearest first).
    #[inline]
    pub fn enters(&self, ray: &WideRay, t_max: f32) -> (u32, Vec4) {
        let mut t0 = Vec4::ZERO;
        let mut t1 = Vec4::splat(t_max * slab::FAR_GROWTH);
        for k in 0..3 {
            let a = (self.min[k] - ray.origin[k]) * ray.inv_dir[k];
            let b = (self.max[k] - ray.origin[k]) * ray.inv_dir[k];
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        let live = (1u32 << self.len) - 1;
        (t0.cmple(t1).bitmask() & live, t0)
    }

    /// [`Node4::enters`] with the exact `f64` test (rays from far outside the scene).
    pub fn enters_exact(&self, ray: &PreparedRay, t_max: f64) -> (u32, Vec4) {
        let mut mask = 0;
        let mut t0 = [0.0f32; 4];
        for (k, entry) in t0.iter_mut().enumerate().take(self.len as usize) {
            let min = Vec3::new(self.min[0][k], self.min[1][k], self.min[2][k]);
            let max = Vec3::new(self.max[0][k], self.max[1][k], self.max[2][k]);
            if let Some(t) = slab::exact_entry(min, max, ray, t_max) {
                mask |= 1 << k;
                *entry = t as f32;
            }
        }
        (mask, Vec4::from_array(t0))
    }
}
