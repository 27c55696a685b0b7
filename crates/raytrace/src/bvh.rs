//! A bounding volume hierarchy over triangles: binned surface-area-heuristic build (Wald,
//! "On fast construction of SAH-based bounding volume hierarchies", 2007) into a flat array of
//! nodes in depth-first order (pbrt's `LinearBVHNode` layout: the left child follows its parent,
//! the parent stores the right child's index), and any-hit traversal for shadow rays.
//!
//! The build is sequential and every choice is a pure function of the input order (bins,
//! ties broken towards the lower axis and bin), so the same triangles always give the same
//! tree, whatever the thread count of the renderer around it.
use crate::slab::{self, SlabRay};
use crate::triangle::{PreparedRay, Triangle};
use glam::{DVec3, Vec3};

/// Centroid bins per axis.
const BINS: usize = 16;
/// A node with at most this many triangles becomes a leaf when splitting does not pay.
const MAX_LEAF: usize = 4;
/// SAH cost of one traversal step relative to one triangle test.
const TRAVERSAL_COST: f32 = 1.0;
/// Traversal stack: the tree depth is bounded by this (a leaf is forced below it).
const MAX_DEPTH: usize = 60;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Aabb {
    min: Vec3,
    max: Vec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    fn of(t: &Triangle) -> Aabb {
        Aabb {
            min: t.p[0].min(t.p[1]).min(t.p[2]),
            max: t.p[0].max(t.p[1]).max(t.p[2]),
        }
    }

    fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    fn including(self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    fn half_area(&self) -> f32 {
        let d = self.max - self.min;
        if d.min_element() < 0.0 {
            return 0.0;
        }
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// Slab test in `f64` against `(0, t_max)`. The `f32` box is exact in `f64`, and the
    /// `1 + 4ε` growth of the far distance (pbrt's `gamma(3)` argument) keeps a ray grazing a
    /// face from missing the box of a triangle it hits.
    fn hit(&self, ray: &PreparedRay, t_max: f64) -> bool {
        let (mut t0, mut t1) = (0.0f64, t_max);
        for k in 0..3 {
            let a = (f64::from(self.min[k]) - ray.origin[k]) * ray.inv_dir[k];
            let b = (f64::from(self.max[k]) - ray.origin[k]) * ray.inv_dir[k];
            // NaN is 0·∞: the origin lies on a slab plane the ray runs parallel to, so the
            // slab does not constrain the ray (the boundary counts as inside).
            if a.is_nan() || b.is_nan() {
                continue;
            }
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        let t1 = t1 * (1.0 + 4.0 * f64::EPSILON);
        t0 <= t1
    }
}

/// One node: a box, and either two children (`count == 0`: the left child is the next node,
/// the right one is at `offset`) or `count` triangles from `offset` in the triangle array.
#[derive(Clone, Copy, Debug)]
struct Node {
    bound: Aabb,
    offset: u32,
    count: u16,
    axis: u8,
}

/// Build statistics, for benchmarks and the `--stats` report.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BvhStats {
    pub triangles: usize,
    pub nodes: usize,
    pub leaves: usize,
    pub max_depth: usize,
}

/// The nearest hit of a ray: where along it, which triangle (its index in the vector given to
/// [`Bvh::new`]) and the barycentric weights of that triangle's three vertices at the hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub triangle: u32,
    pub barycentric: [f64; 3],
}

/// A BVH over triangles that answers "is anything between here and there?" and "what does
/// this ray hit first?".
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    triangles: Vec<Triangle>,
    /// Per stored triangle: its index in the caller's vector (degenerate ones are dropped
    /// and the rest reordered, so the caller's data is found through this).
    ids: Vec<u32>,
    stats: BvhStats,
    /// The largest coordinate magnitude of the scene: the boxes are padded by
    /// `slab::pad(scale)` for the `f32` box test.
    scale: f32,
}

struct Build<'a> {
    tris: &'a [Triangle],
    bounds: Vec<Aabb>,
    centroids: Vec<Vec3>,
    order: Vec<u32>,
    nodes: Vec<Node>,
    stats: BvhStats,
}

impl Bvh {
    /// Builds the tree. Degenerate (zero-area) and non-finite triangles are dropped: they can
    /// block no ray and would poison the bounds.
    pub fn new(triangles: Vec<Triangle>) -> Bvh {
        let (tris, input_ids): (Vec<Triangle>, Vec<u32>) = triangles
            .into_iter()
            .zip(0u32..)
            .filter(|(t, _)| t.p.iter().all(|p| p.is_finite()) && t.double_area() > 0.0)
            .unzip();
        let bounds: Vec<Aabb> = tris.iter().map(Aabb::of).collect();
        let centroids = bounds.iter().map(|b| (b.min + b.max) * 0.5).collect();
        let mut b = Build {
            tris: &tris,
            bounds,
            centroids,
            order: (0..tris.len() as u32).collect(),
            nodes: Vec::with_capacity(2 * tris.len() / MAX_LEAF + 1),
            stats: BvhStats {
                triangles: tris.len(),
                ..BvhStats::default()
            },
        };
        if !tris.is_empty() {
            b.node(0, tris.len(), 0);
        }
        let ordered = b.order.iter().map(|&i| b.tris[i as usize]).collect();
        let ids = b.order.iter().map(|&i| input_ids[i as usize]).collect();
        let mut stats = b.stats;
        stats.nodes = b.nodes.len();
        let mut nodes = b.nodes;
        let scale = nodes.first().map_or(0.0, |root| {
            root.bound.min.abs().max(root.bound.max.abs()).max_element()
        });
        let pad = Vec3::splat(slab::pad(scale));
        for n in &mut nodes {
            n.bound.min -= pad;
            n.bound.max += pad;
        }
        Bvh {
            nodes,
            triangles: ordered,
            ids,
            stats,
            scale,
        }
    }

    pub fn stats(&self) -> BvhStats {
        self.stats
    }

    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Whether any triangle is hit at `t ∈ (t_min, t_max)` along `origin + t·dir` (`dir` need
    /// not be unit length; `t` is in its units). Stops at the first hit found.
    pub fn occluded(&self, origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> bool {
        self.occluded_by(origin, dir, t_min, t_max, &|_| true)
    }

    /// [`Bvh::occluded`] counting only the triangles (caller's indices) that `keep` accepts:
    /// the visibility attributes decide which geometry each kind of ray sees.
    pub fn occluded_by(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        keep: &dyn Fn(u32) -> bool,
    ) -> bool {
        self.traverse(origin, dir, t_min, t_max, true, keep)
            .is_some()
    }

    /// The nearest hit's `t` in `(t_min, t_max)`, if any (for tests and probes).
    pub fn nearest(&self, origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        self.nearest_hit(origin, dir, t_min, t_max, &|_| true)
            .map(|h| h.t)
    }

    /// The nearest hit in `(t_min, t_max)` among the triangles `keep` accepts. Ties in `t`
    /// go to the triangle met first in the (deterministic) traversal.
    pub fn nearest_hit(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        keep: &dyn Fn(u32) -> bool,
    ) -> Option<Hit> {
        self.traverse(origin, dir, t_min, t_max, false, keep)
    }

    fn traverse(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        mut t_max: f64,
        any: bool,
        keep: &dyn Fn(u32) -> bool,
    ) -> Option<Hit> {
        if self.nodes.is_empty() || t_max.is_nan() || t_max <= t_min {
            return None;
        }
        let ray = PreparedRay::new(origin, dir)?;
        let slab = SlabRay::new(origin, dir, self.scale);
        let enters = |b: &Aabb, t_max: f64| match &slab {
            Some(r) => r.hits(b.min, b.max, t_max as f32),
            None => b.hit(&ray, t_max),
        };
        let negative = [dir.x < 0.0, dir.y < 0.0, dir.z < 0.0];
        let mut stack = [0u32; MAX_DEPTH + 2];
        let mut top = 0usize;
        let mut current = 0usize;
        let mut found = None;
        loop {
            let node = &self.nodes[current];
            if enters(&node.bound, t_max) {
                if node.count > 0 {
                    let start = node.offset as usize;
                    let end = start + node.count as usize;
                    for (t, &id) in self.triangles[start..end].iter().zip(&self.ids[start..end]) {
                        let Some((hit, barycentric)) = t.intersect_barycentric(&ray, t_min, t_max)
                        else {
                            continue;
                        };
                        if !keep(id) {
                            continue;
                        }
                        let h = Hit {
                            t: hit,
                            triangle: id,
                            barycentric,
                        };
                        if any {
                            return Some(h);
                        }
                        t_max = hit;
                        found = Some(h);
                    }
                } else {
                    // Visit the child nearer along the ray first (better early exit).
                    let (first, second) = if negative[node.axis as usize] {
                        (node.offset as usize, current + 1)
                    } else {
                        (current + 1, node.offset as usize)
                    };
                    stack[top] = second as u32;
                    top += 1;
                    current = first;
                    continue;
                }
            }
            if top == 0 {
                return found;
            }
            top -= 1;
            current = stack[top] as usize;
        }
    }
}

impl Build<'_> {
    /// Builds the node for `order[start..end]` and its subtree; returns its index.
    fn node(&mut self, start: usize, end: usize, depth: usize) -> usize {
        let index = self.nodes.len();
        self.stats.max_depth = self.stats.max_depth.max(depth);
        let ids = &self.order[start..end];
        let bound = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(self.bounds[i as usize]));
        self.nodes.push(Node {
            bound,
            offset: start as u32,
            count: (end - start) as u16,
            axis: 0,
        });
        let n = end - start;
        if n <= 1 || depth >= MAX_DEPTH {
            return self.leaf(index, start, end);
        }
        let Some((axis, mid)) = self.split(start, end, bound) else {
            return self.leaf(index, start, end);
        };
        self.node(start, mid, depth + 1);
        let right = self.node(mid, end, depth + 1);
        let node = &mut self.nodes[index];
        node.offset = right as u32;
        node.count = 0;
        node.axis = axis as u8;
        index
    }

    fn leaf(&mut self, index: usize, start: usize, end: usize) -> usize {
        // A leaf's count is a u16: an unsplittable heap of more triangles (all centroids equal)
        // is chained as a list of leaves under interior nodes.
        if end - start > u16::MAX as usize {
            let mid = start + (end - start) / 2;
            self.node(start, mid, MAX_DEPTH);
            let right = self.node(mid, end, MAX_DEPTH);
            let node = &mut self.nodes[index];
            node.offset = right as u32;
            node.count = 0;
            return index;
        }
        self.stats.leaves += 1;
        index
    }

    /// The best binned-SAH split of `order[start..end]` (reordered in place), as (axis, index
    /// of the first triangle on the right); `None` when a leaf is cheaper.
    fn split(&mut self, start: usize, end: usize, bound: Aabb) -> Option<(usize, usize)> {
        let ids = &self.order[start..end];
        let cb = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.including(self.centroids[i as usize]));
        let extent = cb.max - cb.min;
        let mut best: Option<(f32, usize, usize)> = None;
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let bin_of = |c: Vec3| -> usize {
                let f = (c[axis] - cb.min[axis]) / extent[axis];
                ((f * BINS as f32) as usize).min(BINS - 1)
            };
            let mut counts = [0usize; BINS];
            let mut boxes = [Aabb::EMPTY; BINS];
            for &i in ids {
                let b = bin_of(self.centroids[i as usize]);
                counts[b] += 1;
                boxes[b] = boxes[b].union(self.bounds[i as usize]);
            }
            // Sweep from the right to get each suffix's box and count, then from the left.
            let mut right_area = [0.0f32; BINS];
            let mut right_count = [0usize; BINS];
            let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
            for b in (1..BINS).rev() {
                acc = acc.union(boxes[b]);
                cnt += counts[b];
                right_area[b] = acc.half_area();
                right_count[b] = cnt;
            }
            let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
            for b in 0..BINS - 1 {
                acc = acc.union(boxes[b]);
                cnt += counts[b];
                if cnt == 0 || right_count[b + 1] == 0 {
                    continue;
                }
                let cost =
                    acc.half_area() * cnt as f32 + right_area[b + 1] * right_count[b + 1] as f32;
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, b + 1));
                }
            }
        }
        let (cost, axis, split_bin) = best?;
        let n = end - start;
        let leaf_cost = n as f32;
        let split_cost = TRAVERSAL_COST + cost / bound.half_area().max(f32::MIN_POSITIVE);
        if n <= MAX_LEAF && split_cost >= leaf_cost {
            return None;
        }
        let (lo, ext) = (cb.min[axis], extent[axis]);
        let centroids = &self.centroids;
        let goes_left = |i: u32| {
            let f = (centroids[i as usize][axis] - lo) / ext;
            ((f * BINS as f32) as usize).min(BINS - 1) < split_bin
        };
        // A stable partition keeps the build a pure function of the input order.
        let (left, right): (Vec<u32>, Vec<u32>) =
            self.order[start..end].iter().partition(|&&i| goes_left(i));
        let mid = start + left.len();
        self.order[start..mid].copy_from_slice(&left);
        self.order[mid..end].copy_from_slice(&right);
        Some((axis, mid))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_is_hit_by_a_ray_along_its_face() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        let ray = PreparedRay::new(DVec3::new(-1.0, 0.0, 0.5), DVec3::X).unwrap();
        assert!(b.hit(&ray, 10.0));
        let ray = PreparedRay::new(DVec3::new(-1.0, -0.01, 0.5), DVec3::X).unwrap();
        assert!(!b.hit(&ray, 10.0));
    }
}
