//! A bounding volume hierarchy over triangles: binned surface-area-heuristic build (Wald,
//! "On fast construction of SAH-based bounding volume hierarchies", 2007) into a flat array of
//! nodes in depth-first order (pbrt's `LinearBVHNode` layout: the left child follows its parent,
//! the parent stores the right child's index), collapsed into four-wide nodes (`wide.rs`) that
//! rays traverse: any-hit for shadow rays, nearest-first for the closest hit.
//!
//! The build is sequential and every choice is a pure function of the input order (bins,
//! ties broken towards the lower axis and bin), so the same triangles always give the same
//! tree, whatever the thread count of the renderer around it.
use crate::quadric::Quadric;
use crate::slab::{self, SlabRay};
use crate::triangle::{PreparedRay, Triangle};
use crate::wide::{self, Child, Node4, WideRay};
use glam::{DVec3, Vec3};

/// Centroid bins per axis.
const BINS: usize = 16;
/// A node with at most this many triangles becomes a leaf when splitting does not pay.
const MAX_LEAF: usize = 4;
/// SAH cost of one traversal step relative to one triangle test.
const TRAVERSAL_COST: f32 = 1.0;
/// SAH cost of one closed-form quadric test relative to one triangle test. Counted as a
/// triangle, quadrics shared leaves of three or four (the nine spheres of the `occlusion`
/// bench, issue 19): a ray entering such a leaf tested every sphere in it, about one sphere
/// test per ray; as four, each sphere gets its own box, which the four-wide node tests at
/// once. Trees of triangles alone are built as before.
const QUADRIC_COST: f32 = 4.0;
/// The binary tree's depth is bounded by this (a leaf is forced below it; only a heap of
/// more than 65535 triangles with one centroid chains deeper, by its log₂).
const MAX_DEPTH: usize = 60;
/// Traversal stack: a visit pushes at most three more entries than it pops, and the
/// four-wide tree is no deeper than the binary one (≤ 60 + 17 levels).
const STACK: usize = 256;
/// The stack of a shallow tree (binary depth ≤ [`SHALLOW_DEPTH`]: at most 3·20 + 1 entries),
/// which most ray scenes are; clearing 2 KB for every ray showed in the profile of an
/// `occlusion()` frame (issue 19), whose trees of quadrics are a few levels deep.
const SHALLOW_STACK: usize = 64;
const SHALLOW_DEPTH: usize = 20;
/// The group of a subtree whose triangles belong to more than one group (or to none).
pub const NO_GROUP: u32 = u32::MAX;

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

    fn of_item(item: &Item, quadrics: &[Quadric]) -> Aabb {
        match item {
            Item::Triangle(t) => Aabb::of(t),
            Item::Quadric(k) => {
                let (min, max) = quadrics[*k as usize].bound;
                Aabb { min, max }
            }
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
    /// Quadrics intersected in closed form (`quadric.rs`).
    pub quadrics: usize,
    pub nodes: usize,
    pub leaves: usize,
    pub max_depth: usize,
}

/// The nearest hit of a ray: where along it, which triangle (its index in the vector given to
/// [`Bvh::new`]) and the barycentric weights of that triangle's three vertices at the hit.
/// A quadric's hit ([`Bvh::with_quadrics`]) has the id `triangle count + quadric index`, its
/// surface `(u, v)` in `uv` and no barycentric weights (all zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub triangle: u32,
    pub barycentric: [f64; 3],
    pub uv: Option<[f64; 2]>,
}

/// What a leaf holds: a triangle, or a quadric (an index into the tree's quadrics, which are
/// too large to sit among the triangles).
#[derive(Clone, Copy, Debug)]
enum Item {
    Triangle(Triangle),
    Quadric(u32),
}

/// A BVH over triangles that answers "is anything between here and there?" and "what does
/// this ray hit first?".
#[derive(Clone, Debug)]
pub struct Bvh {
    /// The four-wide tree (`wide.rs`); node 0 is the root.
    nodes: Vec<Node4>,
    /// The box around everything (padded), for [`Bvh::bound`].
    bound: Option<(Vec3, Vec3)>,
    items: Vec<Item>,
    quadrics: Vec<Quadric>,
    /// Per stored item: its index in the caller's vector (degenerate ones are dropped
    /// and the rest reordered, so the caller's data is found through this).
    ids: Vec<u32>,
    /// Per stored triangle: its group (empty when built without groups).
    groups: Vec<u32>,
    stats: BvhStats,
    /// The largest coordinate magnitude of the scene: the boxes are padded by
    /// `slab::pad(scale)` for the `f32` box test.
    scale: f32,
}

struct Build<'a> {
    /// Per triangle (build index): its group; empty: no groups.
    tri_group: &'a [u32],
    /// Per binary node: the group all its triangles share, or [`NO_GROUP`].
    node_group: Vec<u32>,
    bounds: Vec<Aabb>,
    centroids: Vec<Vec3>,
    /// Per item (build index): its SAH cost (1 for a triangle, [`QUADRIC_COST`]).
    costs: Vec<f32>,
    order: Vec<u32>,
    nodes: Vec<Node>,
    stats: BvhStats,
}

impl Bvh {
    /// Builds the tree. Degenerate (zero-area) and non-finite triangles are dropped: they can
    /// block no ray and would poison the bounds.
    pub fn new(triangles: Vec<Triangle>) -> Bvh {
        Bvh::with_groups(triangles, Vec::new())
    }

    /// [`Bvh::new`] with a group per triangle (the caller's primitive): subtrees of one group
    /// are known as such, so a ray can pass over a whole group it cannot hit
    /// ([`Bvh::occluded_except`]). `groups` is empty or one per triangle.
    pub fn with_groups(triangles: Vec<Triangle>, groups: Vec<u32>) -> Bvh {
        Bvh::with_quadrics(triangles, groups, Vec::new())
    }

    /// [`Bvh::with_groups`] plus quadrics intersected in closed form, each with its group
    /// (used when `groups` is not empty); quadric `k` has the id `triangles.len() + k`.
    /// Quadrics with a non-finite box are dropped.
    pub fn with_quadrics(
        triangles: Vec<Triangle>,
        groups: Vec<u32>,
        quadrics: Vec<(Quadric, u32)>,
    ) -> Bvh {
        let grouped =
            groups.len() == triangles.len() && (!groups.is_empty() || !quadrics.is_empty());
        let triangle_count = triangles.len() as u32;
        let group_of = |i: u32| {
            if grouped {
                groups[i as usize]
            } else {
                NO_GROUP
            }
        };
        let mut kept: Vec<(Item, u32, u32)> = triangles
            .into_iter()
            .zip(0u32..)
            .filter(|(t, _)| t.p.iter().all(|p| p.is_finite()) && t.double_area() > 0.0)
            .map(|(t, i)| (Item::Triangle(t), i, group_of(i)))
            .collect();
        let quadrics: Vec<(Quadric, u32)> = quadrics
            .into_iter()
            .zip(triangle_count..)
            .filter(|((q, _), _)| q.bound.0.is_finite() && q.bound.1.is_finite())
            .map(|((q, g), id)| {
                let g = if grouped { g } else { NO_GROUP };
                kept.push((Item::Quadric(0), id, g));
                (q, g)
            })
            .collect();
        // The quadric items index the kept quadrics in order.
        let mut next = 0u32;
        for k in kept.iter_mut() {
            if let Item::Quadric(index) = &mut k.0 {
                *index = next;
                next += 1;
            }
        }
        let quadrics: Vec<Quadric> = quadrics.into_iter().map(|(q, _)| q).collect();
        let items: Vec<Item> = kept.iter().map(|k| k.0).collect();
        let input_ids: Vec<u32> = kept.iter().map(|k| k.1).collect();
        let grouped = grouped && !kept.is_empty();
        let tri_group: Vec<u32> = if grouped {
            kept.iter().map(|k| k.2).collect()
        } else {
            Vec::new()
        };
        let bounds: Vec<Aabb> = items.iter().map(|i| Aabb::of_item(i, &quadrics)).collect();
        let centroids = bounds.iter().map(|b| (b.min + b.max) * 0.5).collect();
        let mut b = Build {
            tri_group: &tri_group,
            node_group: Vec::new(),
            bounds,
            centroids,
            costs: items
                .iter()
                .map(|i| match i {
                    Item::Triangle(_) => 1.0,
                    Item::Quadric(_) => QUADRIC_COST,
                })
                .collect(),
            order: (0..items.len() as u32).collect(),
            nodes: Vec::with_capacity(2 * items.len() / MAX_LEAF + 1),
            stats: BvhStats {
                triangles: items.len() - quadrics.len(),
                quadrics: quadrics.len(),
                ..BvhStats::default()
            },
        };
        if !items.is_empty() {
            b.node(0, items.len(), 0);
        }
        let ordered = b.order.iter().map(|&i| items[i as usize]).collect();
        let ids = b.order.iter().map(|&i| input_ids[i as usize]).collect();
        let groups = b
            .order
            .iter()
            .map(|&i| b.tri_group.get(i as usize).copied().unwrap_or(NO_GROUP))
            .collect();
        let node_group = std::mem::take(&mut b.node_group);
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
        let child = |i: u32| {
            let n = &nodes[i as usize];
            Child {
                min: n.bound.min,
                max: n.bound.max,
                first: if n.count > 0 { n.offset } else { i },
                count: u32::from(n.count),
                group: node_group[i as usize],
            }
        };
        let wide = match nodes.first() {
            Some(_) => wide::collapse(child(0), &|i| {
                [child(i + 1), child(nodes[i as usize].offset)]
            }),
            None => Vec::new(),
        };
        Bvh {
            bound: nodes.first().map(|n| (n.bound.min, n.bound.max)),
            nodes: wide,
            items: ordered,
            quadrics,
            ids,
            groups: if grouped { groups } else { Vec::new() },
            stats,
            scale,
        }
    }

    pub fn stats(&self) -> BvhStats {
        self.stats
    }

    /// The box around every triangle (slightly padded), `None` for an empty tree.
    pub fn bound(&self) -> Option<(Vec3, Vec3)> {
        self.bound
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
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
        self.traverse_any_depth(origin, dir, t_min, t_max, true, NO_GROUP, keep)
            .is_some()
    }

    /// [`Bvh::occluded_by`] passing over group `skip` (a primitive the caller has shown the
    /// ray cannot hit): its subtrees are not entered and its triangles not tested.
    pub fn occluded_except(
        &self,
        origin: DVec3,
        dir: DVec3,
        (t_min, t_max): (f64, f64),
        skip: u32,
        keep: &dyn Fn(u32) -> bool,
    ) -> bool {
        self.traverse_any_depth(origin, dir, t_min, t_max, true, skip, keep)
            .is_some()
    }

    /// A traversal stack sized for this tree, for [`Bvh::occluded_with`]: filled once and
    /// reused by many rays (clearing a fresh one per ray was 3.5% of an `occlusion()` frame,
    /// issue 19).
    pub fn stack(&self) -> TraversalStack {
        if self.stats.max_depth <= SHALLOW_DEPTH {
            TraversalStack::Shallow([(0, 0.0); SHALLOW_STACK])
        } else {
            TraversalStack::Deep(vec![(0, 0.0); STACK])
        }
    }

    /// [`Bvh::occluded_except`] on the caller's `stack` (from [`Bvh::stack`] of this tree).
    pub fn occluded_with(
        &self,
        stack: &mut TraversalStack,
        origin: DVec3,
        dir: DVec3,
        (t_min, t_max): (f64, f64),
        skip: u32,
        keep: &dyn Fn(u32) -> bool,
    ) -> bool {
        let q = Query {
            origin,
            dir,
            t_min,
            any: true,
            skip,
        };
        let stack = match stack {
            TraversalStack::Shallow(s) => &mut s[..],
            TraversalStack::Deep(s) => &mut s[..],
        };
        self.traverse(stack, q, t_max, keep).is_some()
    }

    /// [`Bvh::nearest_hit`] passing over group `skip` (as [`Bvh::occluded_except`]).
    pub fn nearest_hit_except(
        &self,
        origin: DVec3,
        dir: DVec3,
        (t_min, t_max): (f64, f64),
        skip: u32,
        keep: &dyn Fn(u32) -> bool,
    ) -> Option<Hit> {
        self.traverse_any_depth(origin, dir, t_min, t_max, false, skip, keep)
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
        self.traverse_any_depth(origin, dir, t_min, t_max, false, NO_GROUP, keep)
    }

    /// [`Bvh::traverse`] with the smaller stack when the tree is shallow enough for it.
    #[allow(clippy::too_many_arguments)]
    fn traverse_any_depth(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        any: bool,
        skip: u32,
        keep: &dyn Fn(u32) -> bool,
    ) -> Option<Hit> {
        let q = Query {
            origin,
            dir,
            t_min,
            any,
            skip,
        };
        if self.stats.max_depth <= SHALLOW_DEPTH {
            self.traverse(&mut [(0, 0.0); SHALLOW_STACK], q, t_max, keep)
        } else {
            self.traverse(&mut [(0, 0.0); STACK], q, t_max, keep)
        }
    }

    /// The traversal on `stack` (long enough for this tree: [`Bvh::stack`]).
    fn traverse(
        &self,
        stack: &mut [(u32, f32)],
        q: Query,
        mut t_max: f64,
        keep: &dyn Fn(u32) -> bool,
    ) -> Option<Hit> {
        let Query {
            origin,
            dir,
            t_min,
            any,
            skip,
        } = q;
        // Without groups nothing is skipped (every triangle's group is NO_GROUP).
        let skip = if self.groups.is_empty() {
            NO_GROUP
        } else {
            skip
        };
        if self.nodes.is_empty() || t_max.is_nan() || t_max <= t_min {
            return None;
        }
        if !origin.is_finite() || !dir.is_finite() || dir == DVec3::ZERO {
            return None;
        }
        // The triangle test's shear, made when the first triangle is met (rays that meet
        // only quadrics never need it).
        let mut prepared: Option<PreparedRay> = None;
        let wide = SlabRay::new(origin, dir, self.scale).map(|r| WideRay::new(&r));
        // Pending nodes with where the ray enters them, so the nearest is visited first and
        // nodes beyond a hit found meanwhile are skipped.
        let mut top = 0usize;
        let mut current = 0u32;
        let mut found = None;
        loop {
            let node = &self.nodes[current as usize];
            let (mut mask, entry) = match &wide {
                Some(w) => node.enters(w, t_max as f32),
                None => {
                    let ray = prepare(&mut prepared, origin, dir)?;
                    node.enters_exact(ray, t_max)
                }
            };
            let entry = entry.to_array();
            let mut inner = [(0u32, 0.0f32); 4];
            let mut inner_len = 0;
            while mask != 0 {
                let k = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if skip != NO_GROUP && node.group[k] == skip {
                    continue;
                }
                if node.count[k] == 0 {
                    inner[inner_len] = (node.first[k], entry[k]);
                    inner_len += 1;
                    continue;
                }
                let start = node.first[k] as usize;
                let end = start + node.count[k] as usize;
                for (i, (item, &id)) in self.items[start..end]
                    .iter()
                    .zip(&self.ids[start..end])
                    .enumerate()
                {
                    if skip != NO_GROUP && self.groups[start + i] == skip {
                        continue;
                    }
                    let (hit, barycentric, uv) = match item {
                        Item::Triangle(t) => {
                            let ray = prepare(&mut prepared, origin, dir)?;
                            match t.intersect_barycentric(ray, t_min, t_max) {
                                Some((hit, b)) => (hit, b, None),
                                None => continue,
                            }
                        }
                        Item::Quadric(k) => {
                            let q = &self.quadrics[*k as usize];
                            match q.intersect_with(origin, dir, (t_min, t_max), !any) {
                                Some((hit, uv)) => (hit, [0.0; 3], (!any).then_some(uv)),
                                None => continue,
                            }
                        }
                    };
                    if !keep(id) {
                        continue;
                    }
                    let h = Hit {
                        t: hit,
                        triangle: id,
                        barycentric,
                        uv,
                    };
                    if any {
                        return Some(h);
                    }
                    t_max = hit;
                    found = Some(h);
                }
            }
            // Farthest first onto the stack: the nearest comes off it next (an insertion
            // sort of at most four, stable, so the order is a pure function of the ray).
            for k in 1..inner_len {
                let mut j = k;
                while j > 0 && inner[j - 1].1 < inner[j].1 {
                    inner.swap(j - 1, j);
                    j -= 1;
                }
            }
            for &entry in &inner[..inner_len] {
                stack[top] = entry;
                top += 1;
            }
            let reach = t_max as f32 * slab::FAR_GROWTH;
            loop {
                if top == 0 {
                    return found;
                }
                top -= 1;
                let (next, enter) = stack[top];
                if enter <= reach {
                    current = next;
                    break;
                }
            }
        }
    }
}

/// A ray's part of a traversal: where it starts, which way, from where along it hits count,
/// whether any hit will do, and the group it passes over.
#[derive(Clone, Copy)]
struct Query {
    origin: DVec3,
    dir: DVec3,
    t_min: f64,
    any: bool,
    skip: u32,
}

/// A traversal stack that many rays reuse ([`Bvh::stack`]): in place for a shallow tree (no
/// allocation per shaded point), on the heap for a deep one.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)] // in place on purpose: one per shaded point, on its stack
pub enum TraversalStack {
    Shallow([(u32, f32); SHALLOW_STACK]),
    Deep(Vec<(u32, f32)>),
}

/// The ray prepared for triangle tests, made on first use.
fn prepare(slot: &mut Option<PreparedRay>, origin: DVec3, dir: DVec3) -> Option<&PreparedRay> {
    if slot.is_none() {
        *slot = PreparedRay::new(origin, dir);
    }
    slot.as_ref()
}

/// The group two subtrees share, or [`NO_GROUP`].
fn common(a: u32, b: u32) -> u32 {
    if a == b {
        a
    } else {
        NO_GROUP
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
        self.node_group.push(NO_GROUP);
        if n <= 1 || depth >= MAX_DEPTH {
            return self.leaf(index, start, end);
        }
        let Some((axis, mid)) = self.split(start, end, bound) else {
            return self.leaf(index, start, end);
        };
        let left = self.node(start, mid, depth + 1);
        let right = self.node(mid, end, depth + 1);
        self.node_group[index] = common(self.node_group[left], self.node_group[right]);
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
            let left = self.node(start, mid, MAX_DEPTH);
            let right = self.node(mid, end, MAX_DEPTH);
            self.node_group[index] = common(self.node_group[left], self.node_group[right]);
            let node = &mut self.nodes[index];
            node.offset = right as u32;
            node.count = 0;
            return index;
        }
        self.stats.leaves += 1;
        let group = |i: &u32| self.tri_group.get(*i as usize).copied().unwrap_or(NO_GROUP);
        let mut ids = self.order[start..end].iter();
        let first = ids.next().map_or(NO_GROUP, group);
        self.node_group[index] = ids.fold(first, |g, i| common(g, group(i)));
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
            let mut costs = [0.0f32; BINS];
            let mut boxes = [Aabb::EMPTY; BINS];
            for &i in ids {
                let b = bin_of(self.centroids[i as usize]);
                counts[b] += 1;
                costs[b] += self.costs[i as usize];
                boxes[b] = boxes[b].union(self.bounds[i as usize]);
            }
            // Sweep from the right to get each suffix's box and count, then from the left.
            let mut right_area = [0.0f32; BINS];
            let mut right_count = [0usize; BINS];
            let mut right_cost = [0.0f32; BINS];
            let (mut acc, mut cnt, mut sum) = (Aabb::EMPTY, 0, 0.0f32);
            for b in (1..BINS).rev() {
                acc = acc.union(boxes[b]);
                cnt += counts[b];
                sum += costs[b];
                right_area[b] = acc.half_area();
                right_count[b] = cnt;
                right_cost[b] = sum;
            }
            let (mut acc, mut cnt, mut sum) = (Aabb::EMPTY, 0, 0.0f32);
            for b in 0..BINS - 1 {
                acc = acc.union(boxes[b]);
                cnt += counts[b];
                sum += costs[b];
                if cnt == 0 || right_count[b + 1] == 0 {
                    continue;
                }
                let cost = acc.half_area() * sum + right_area[b + 1] * right_cost[b + 1];
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, b + 1));
                }
            }
        }
        let (cost, axis, split_bin) = best?;
        let n = end - start;
        let leaf_cost: f32 = ids.iter().map(|&i| self.costs[i as usize]).sum();
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
#[path = "bvh_tests.rs"]
mod tests;
