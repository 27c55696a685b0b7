//! The ray-tracing built-ins: BMRT's `trace`, `visibility`, `rayhittest`, `fulltrace`, PRMan's
//! `transmission` and `occlusion`, and the `"raytrace"` forms of `shadow()` and
//! `environment()`, through the renderer's [`RayTracer`] (none: rays see nothing, so `trace`
//! is black and everything is visible).
//!
//! Rays leave from the given point pushed off the shaded surface along the grid's `Ng` (the
//! tracer's offset); directions are normalized, so distances are camera-space lengths. A
//! `trace` at `Option "trace" "maxdepth"` returns black, as BMRT does.
//!
//! Sampled calls (`occlusion`, blurred ray-traced shadows) draw their numbers from a hash of
//! the point, the sample index and the frame seed only, so the same bits for any thread count.
use super::{fl, st, tr, Args};
use crate::exec::Exec;
use crate::value::{Mask, Slot, Value};
use glam::{DVec3, Vec3};
use illume_shade::{segment, CosinePattern, RayDifferential, RayStart, RayTracer};
use illume_sl::ast::{BuiltinId as B, Expr};
use illume_sl::types::BaseType;

/// What `rayhittest`/`fulltrace` report for a ray that hits nothing (BMRT's "infinity").
pub(crate) const NO_HIT: f32 = 1.0e30;

/// Stream tags keeping the sampled calls' random numbers apart.
const OCCLUSION_STREAM: u32 = 0x6f63_636c;
const SHADOW_STREAM: u32 = 0x7368_6477;
const ENVIRONMENT_STREAM: u32 = 0x656e_7672;

impl Exec<'_> {
    /// The ray-tracing family members; `None` for an overload the executor does not implement.
    pub(super) fn raytrace(&mut self, c: &Args) -> Option<Value> {
        let (a, n, mask) = (c.a, self.n, c.mask);
        Some(match (c.id, a.len()) {
            (B::Trace, 2) => {
                let (p, r) = (tr(&a[0]), tr(&a[1]));
                self.per_point(mask, Vec3::ZERO, |x, i, t| {
                    x.trace_colour(t, i, *p.at(i), *r.at(i), x.beam(i, &p, &r))
                })
            }
            (B::Visibility | B::Transmission, 2) => {
                let (p1, p2) = (tr(&a[0]), tr(&a[1]));
                let v = self.per_point(mask, Vec3::ONE, |x, i, t| {
                    x.transmission_between(t, i, *p1.at(i), *p2.at(i))
                });
                if c.ret == BaseType::Float {
                    let Value::Triple(s) = v else { return None };
                    Value::Float(s.map(|c| (c.x + c.y + c.z) / 3.0))
                } else {
                    v
                }
            }
            (B::RayHitTest, 4) => {
                let (p, r) = (tr(&a[0]), tr(&a[1]));
                let hits = self.hits(mask, &p, &r, false);
                self.write_back(&c.exprs[2], &triples(&hits, n, |h| h.1), mask);
                self.write_back(&c.exprs[3], &triples(&hits, n, |h| h.2), mask);
                Value::Float(Slot::varying(
                    hits.iter().map(|h| h.map_or(NO_HIT, |h| h.0)).collect(),
                ))
            }
            (B::FullTrace, 7) => {
                let (p, r) = (tr(&a[0]), tr(&a[1]));
                let hits = self.hits(mask, &p, &r, true);
                let e = c.exprs;
                let dist = hits.iter().map(|h| h.map_or(NO_HIT, |h| h.0)).collect();
                self.write_back(&e[2], &Value::Float(Slot::varying(dist)), mask);
                self.write_back(&e[3], &triples(&hits, n, |h| h.1), mask);
                self.write_back(&e[4], &triples(&hits, n, |h| h.2), mask);
                // The ray that missed everything: this one, when it missed (one bounce).
                // (A miss can still bring back the colour of the volume it crossed: `t` ∞.)
                let missed = |i: usize| hits[i].is_none_or(|h| h.0 >= NO_HIT);
                let miss = |i: usize, v: Vec3| if missed(i) { v } else { Vec3::ZERO };
                let pm = (0..n).map(|i| miss(i, *p.at(i))).collect();
                let rm = (0..n)
                    .map(|i| miss(i, r.at(i).normalize_or_zero()))
                    .collect();
                self.write_back(&e[5], &Value::Triple(Slot::varying(pm)), mask);
                self.write_back(&e[6], &Value::Triple(Slot::varying(rm)), mask);
                triples(&hits, n, |h| h.3)
            }
            (B::Occlusion, 3) => {
                let (p, nn, samples) = (tr(&a[0]), tr(&a[1]), fl(&a[2]));
                let maxdist = self.optional_float(c.pairs, mask, "maxdist", f32::INFINITY);
                let seed = self.env.seed;
                // One pattern per sample count (the count is almost always uniform).
                let pattern = std::cell::RefCell::new(CosinePattern::new(1));
                // The directions of one point, reused by the next (no allocation per point).
                let dirs = std::cell::RefCell::new(Vec::new());
                let v = self.per_point(mask, Vec3::ZERO, |x, i, t| {
                    let s = *samples.at(i);
                    let k = if s.is_finite() {
                        s.clamp(1.0, 4096.0) as u32
                    } else {
                        1
                    };
                    if pattern.borrow().len() != k as usize {
                        *pattern.borrow_mut() = CosinePattern::new(k);
                    }
                    let pattern = pattern.borrow();
                    let dirs = &mut dirs.borrow_mut();
                    let at = (*p.at(i), *nn.at(i));
                    let o = x.occlusion_at(t, i, at, (&pattern, dirs), maxdist, seed);
                    Vec3::splat(o)
                });
                let Value::Triple(s) = v else { return None };
                Value::Float(s.map(|c| c.x))
            }
            _ => return None,
        })
    }

    /// `f(self, point, tracer)` at every running point, `outside` elsewhere; `outside`
    /// everywhere when there is no tracer.
    fn per_point(
        &self,
        mask: &Mask,
        outside: Vec3,
        f: impl Fn(&Self, usize, &dyn RayTracer) -> Vec3,
    ) -> Value {
        let Some(t) = self.env.tracer else {
            return Value::triple(outside);
        };
        Value::Triple(Slot::varying(
            (0..self.n)
                .map(|i| if mask.get(i) { f(self, i, t) } else { outside })
                .collect(),
        ))
    }

    /// Where rays from grid point `i` leave: `p` (the call's point) on the grid's surface.
    pub(crate) fn ray_start(&self, i: usize, p: Vec3) -> RayStart {
        RayStart {
            p,
            ng: self.grid.ng.get(i).copied().unwrap_or(Vec3::ZERO),
            primitive: self.env.primitive,
            beam: RayDifferential::default(),
        }
    }

    /// The differentials of the ray from `p` along `r` at grid point `i`: the change of the
    /// origin and of the unit direction to its neighbours along u and v (grid differences,
    /// as `Du`/`Dv` take them).
    fn beam(&self, i: usize, p: &Slot<Vec3>, r: &Slot<Vec3>) -> RayDifferential {
        let [a, b, c, _] = self.grid.footprint(i);
        let unit = |k: usize| r.at(k).normalize_or_zero();
        RayDifferential {
            dp: [*p.at(b) - *p.at(a), *p.at(c) - *p.at(a)],
            dd: [unit(b) - unit(a), unit(c) - unit(a)],
        }
    }

    /// The colour seen along `r` from `p` (with the ray's differentials `beam`); black at the
    /// maximum depth.
    fn trace_colour(
        &self,
        t: &dyn RayTracer,
        i: usize,
        p: Vec3,
        r: Vec3,
        beam: RayDifferential,
    ) -> Vec3 {
        let dir = r.as_dvec3().normalize_or_zero();
        if dir == DVec3::ZERO || self.env.ray_depth >= t.max_depth() {
            return Vec3::ZERO;
        }
        let start = RayStart {
            beam,
            ..self.ray_start(i, p)
        };
        t.trace(&start, dir, self.env.ray_depth, true)
            .map_or(Vec3::ZERO, |h| h.ci)
    }

    /// The light transmitted from `p1` to `p2` (1: nothing in between).
    fn transmission_between(&self, t: &dyn RayTracer, i: usize, p1: Vec3, p2: Vec3) -> Vec3 {
        match segment(p1, p2) {
            Some((dir, len)) => t.transmission(&self.ray_start(i, p1), dir, len),
            None => Vec3::ONE,
        }
    }

    /// PRMan's `occlusion()`: the cosine-weighted fraction of the hemisphere about `n` that
    /// geometry within `maxdist` blocks, from the directions of `pattern` shifted by a hash of
    /// the point (partial opacity counts in part); `dirs` holds them (kept from point to
    /// point so its storage is reused).
    fn occlusion_at(
        &self,
        t: &dyn RayTracer,
        i: usize,
        (p, n): (Vec3, Vec3),
        (pattern, dirs): (&CosinePattern, &mut Vec<DVec3>),
        maxdist: f32,
        seed: u32,
    ) -> f32 {
        let nd = n.as_dvec3().normalize_or_zero();
        if nd == DVec3::ZERO || pattern.is_empty() {
            return 0.0;
        }
        let start = self.ray_start(i, p);
        let maxdist = if maxdist > 0.0 {
            f64::from(maxdist)
        } else {
            0.0
        };
        let stream = OCCLUSION_STREAM ^ seed;
        let shift = illume_shade::stratified_sample(p, 0, 1, stream);
        let jitter = illume_shade::lowbias32((shift.0 * 16_777_216.0) as u32 ^ stream);
        dirs.clear();
        pattern.directions(nd, shift, jitter, |dir| dirs.push(dir));
        let blocked = t.blocked(&start, dirs, maxdist);
        (blocked / pattern.len() as f64) as f32
    }

    /// `shadow("raytrace", Ps)` in a light shader: the shadowed fraction between `Ps` and the
    /// light position `Ps − L`, over `samples` rays aimed within a disk of radius `blur·|L|`
    /// about that position.
    pub(crate) fn raytraced_shadow(
        &self,
        mask: &Mask,
        ps: &Slot<Vec3>,
        samples: f32,
        blur: f32,
    ) -> Vec<f32> {
        let Some(t) = self.env.tracer else {
            return vec![0.0; self.n];
        };
        let l = match self.global(illume_sl::ast::Global::L) {
            Value::Triple(s) => s.clone(),
            _ => Slot::Uniform(Vec3::ZERO),
        };
        let blur = f64::from(blur.max(0.0));
        let count = if blur > 0.0 {
            samples.clamp(1.0, 4096.0) as u32
        } else {
            1
        };
        (0..self.n)
            .map(|i| {
                if !mask.get(i) {
                    return 0.0;
                }
                let (p, l) = (*ps.at(i), *l.at(i));
                let target = p.as_dvec3() - l.as_dvec3();
                let radius = blur * l.as_dvec3().length();
                let start = self.ray_start(i, p);
                let mut lit = 0.0f64;
                for k in 0..count {
                    let aim = if radius > 0.0 {
                        let stream = SHADOW_STREAM ^ self.env.seed;
                        let u = illume_shade::stratified_sample(p, k, count, stream);
                        target + disk_offset(l.as_dvec3(), u) * radius
                    } else {
                        target
                    };
                    let Some((dir, len)) = segment(p, aim.as_vec3()) else {
                        lit += 1.0;
                        continue;
                    };
                    let through = t.transmission(&start, dir, len);
                    lit += f64::from(through.x + through.y + through.z) / 3.0;
                }
                (1.0 - lit / f64::from(count)) as f32
            })
            .collect()
    }

    /// `environment("raytrace", R)`: the colour traced along `R` from `P`; with `blur` > 0
    /// the mean of `samples` rays spread uniformly over the cone of half-angle `blur`
    /// (radians, at most π/2) about `R`, stratified and hashed from the point like
    /// `occlusion()`. Blur 0 traces the single ray along `R` whatever `samples` says.
    pub(crate) fn raytraced_environment(
        &self,
        mask: &Mask,
        r: &Slot<Vec3>,
        samples: f32,
        blur: f32,
    ) -> Vec<Vec3> {
        let pslot = match self.global(illume_sl::ast::Global::P) {
            Value::Triple(s) => s.clone(),
            _ => Slot::Uniform(Vec3::ZERO),
        };
        let Some(t) = self.env.tracer else {
            return vec![Vec3::ZERO; self.n];
        };
        let blur = if blur.is_finite() {
            f64::from(blur).clamp(0.0, std::f64::consts::FRAC_PI_2)
        } else {
            0.0
        };
        let count = if blur > 0.0 && samples.is_finite() {
            samples.clamp(1.0, 4096.0) as u32
        } else {
            1
        };
        let stream = ENVIRONMENT_STREAM ^ self.env.seed;
        (0..self.n)
            .map(|i| {
                if !mask.get(i) {
                    return Vec3::ZERO;
                }
                let beam = || self.beam(i, &pslot, r);
                let (p, r) = (*pslot.at(i), *r.at(i));
                if blur == 0.0 {
                    return self.trace_colour(t, i, p, r, beam());
                }
                let axis = r.as_dvec3().normalize_or_zero();
                let mut sum = DVec3::ZERO;
                for k in 0..count {
                    let u = illume_shade::stratified_sample(p, k, count, stream);
                    let d = cone_direction(axis, blur, u);
                    let none = RayDifferential::default();
                    sum += self.trace_colour(t, i, p, d.as_vec3(), none).as_dvec3();
                }
                (sum / f64::from(count)).as_vec3()
            })
            .collect()
    }

    /// Per running point: (distance, hit point, normal, colour) of the nearest hit.
    #[allow(clippy::type_complexity)]
    fn hits(
        &self,
        mask: &Mask,
        p: &Slot<Vec3>,
        r: &Slot<Vec3>,
        shade: bool,
    ) -> Vec<Option<(f32, Vec3, Vec3, Vec3)>> {
        let Some(t) = self.env.tracer else {
            return vec![None; self.n];
        };
        (0..self.n)
            .map(|i| {
                let dir = r.at(i).as_dvec3().normalize_or_zero();
                if !mask.get(i) || dir == DVec3::ZERO {
                    return None;
                }
                let shade = shade && self.env.ray_depth < t.max_depth();
                let h = t.trace(&self.ray_start(i, *p.at(i)), dir, self.env.ray_depth, shade)?;
                let dist = if h.t.is_finite() { h.t as f32 } else { NO_HIT };
                Some((dist, h.p, h.n, h.ci))
            })
            .collect()
    }

    /// A uniform float optional parameter `name` of the call's `"name", value` pairs.
    fn optional_float(&mut self, pairs: &[Expr], mask: &Mask, name: &str, default: f32) -> f32 {
        let mut out = default;
        for pair in pairs.chunks(2) {
            let [k, v] = pair else { continue };
            let key = st(&self.eval(k, mask));
            let value = self.eval(v, mask);
            match (key == name, &value) {
                (true, Value::Float(s)) => out = *s.at(0),
                (true, _) => self.problem(format!("optional parameter \"{name}\" must be a float")),
                (false, _) => {
                    self.problem(format!("unknown optional parameter \"{key}\"; ignored"))
                }
            }
        }
        out
    }
}

/// A point of the unit disk perpendicular to `axis` from two uniform numbers (concentric by
/// polar mapping: `r = √a`).
fn disk_offset(axis: DVec3, (a, b): (f64, f64)) -> DVec3 {
    let w = axis.normalize_or_zero();
    let helper = if w.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let u = w.cross(helper).normalize_or_zero();
    let v = w.cross(u);
    let (r, phi) = (a.sqrt(), std::f64::consts::TAU * b);
    u * (r * phi.cos()) + v * (r * phi.sin())
}

/// A direction uniform over the solid angle of the cone of half-angle `angle` about the unit
/// `axis`, from two uniform numbers (`cos θ` uniform on `[cos angle, 1]`).
fn cone_direction(axis: DVec3, angle: f64, (a, b): (f64, f64)) -> DVec3 {
    if axis == DVec3::ZERO {
        return axis;
    }
    let cos_t = 1.0 - a * (1.0 - angle.cos());
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let ring = disk_offset(axis, (1.0, b));
    axis * cos_t + ring * sin_t
}

/// A varying triple from the hits (zero where nothing was hit).
fn triples(
    hits: &[Option<(f32, Vec3, Vec3, Vec3)>],
    n: usize,
    f: impl Fn(&(f32, Vec3, Vec3, Vec3)) -> Vec3,
) -> Value {
    Value::Triple(Slot::varying(
        (0..n)
            .map(|i| hits.get(i).copied().flatten().map_or(Vec3::ZERO, |h| f(&h)))
            .collect(),
    ))
}
