//! The bound of a moving micropolygon over one time stratum of the shutter: the raster box of
//! its whole path there, and for a stratum without a motion key inside, the box it stays in
//! once moved back by its mean velocity plus its corners' straight raster chords, so that a
//! sample is rejected with two multiply-adds (see [`strata_paths`] for why the boxes hold).

use crate::motion::GridMotion;
use glam::DVec3;
use illume_ri::motion::segment;

/// What bounds a moving micropolygon over one time stratum `[t0, t1]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StratumBound {
    /// Raster box `[x0, x1, y0, y1]` of its whole path over the stratum.
    pub(crate) path: [f64; 4],
    /// Stratum start and the mean raster velocity (pixels per unit time) of its corners.
    pub(crate) t0: f64,
    pub(crate) v: [f64; 2],
    /// Raster box holding the micropolygon at every time `t` of the stratum once moved back
    /// by `v·(t − t0)`: a sample `(x, y, t)` it covers lies inside after the same move.
    pub(crate) still: [f64; 4],
    /// The corners' raster chords over the stratum, when no key lies inside it.
    pub(crate) chord: Option<Chord>,
}

impl StratumBound {
    /// Raster position `(x, y)` of a sample at time `t`, moved back by the mean velocity to
    /// the stratum start: what the `still` box and the still hull are compared with.
    #[inline(always)]
    pub(crate) fn moved_back(&self, x: f32, y: f32, t: f32) -> (f64, f64) {
        let dt = f64::from(t) - self.t0;
        (f64::from(x) - self.v[0] * dt, f64::from(y) - self.v[1] * dt)
    }
}

/// The straight raster paths of a micropolygon's corners over one stratum `[t0, t0 + Δt]`
/// without a key inside: corner `k` runs from `a[k]` by `d[k]` (raster x, y and camera z).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Chord {
    pub(crate) a: [DVec3; 4],
    pub(crate) d: [DVec3; 4],
    pub(crate) inv_dt: f64,
    pub(crate) persp: bool,
}

impl Chord {
    /// The corners at time `t` (`None` when one is behind the eye). Raster x, y are `X/W`
    /// with `X`, `W` linear in `t` (`W` the camera depth, or 1 orthographic), so corner `k`
    /// has done the fraction `s = τ·W₁/W(τ)` of its chord at `τ = (t − t0)/Δt`; its depth is
    /// linear in `τ`. The same positions as projecting the interpolated camera-space corners,
    /// without a projection per sample.
    #[inline]
    pub(crate) fn corners(&self, t: f64, t0: f64) -> Option<[DVec3; 4]> {
        let tau = (t - t0) * self.inv_dt;
        let mut v = [DVec3::ZERO; 4];
        for ((q, a), d) in v.iter_mut().zip(&self.a).zip(&self.d) {
            let z = a.z + d.z * tau;
            let s = if self.persp {
                if z <= 0.0 {
                    return None;
                }
                tau * (a.z + d.z) / z
            } else {
                tau
            };
            *q = DVec3::new(a.x + d.x * s, a.y + d.y * s, z);
        }
        Some(v)
    }
}

impl Chord {
    /// The outer edges of the micropolygon at the stratum start, pushed out by how far a
    /// corner strays once moved back by the mean velocity, plus `margin`: a sample the moving
    /// micropolygon covers lies inside once moved back (`None` when the start quad is not
    /// convex or has no area, where two triangles' union is not the quad's hull).
    ///
    /// Moved back, corner `k` is at `a_k + r_k·τ + d_k·(s_k − τ)` (see [`strata_paths`]),
    /// within `δ_k = |r_k| + |d_k|·q_k` per axis of `a_k`; a point of either triangle is the
    /// same convex combination of its corners, so it lies within `max δ_k` (Euclidean) of the
    /// start quad. The still box rejects a sample outside the quad's box; this rejects those in
    /// the box's corners, about half of the box for a micropolygon turned 45°, before the
    /// full test at the sample's time (2–5% of `rib/bench/camera_blur.rib`'s time).
    ///
    /// Only for a micropolygon whose edges do not reach out (`RasterTriangle`'s grid border
    /// reach): a triangle with one edge pushed out by `r` also covers a spike past the corners
    /// of that edge, `r / sin θ` long at an angle θ, outside the quad's edges pushed out by `r`.
    pub(crate) fn still_hull(&self, margin: f64) -> Option<StillHull> {
        let (a, d) = (&self.a, &self.d);
        let mean = d.iter().sum::<DVec3>() * 0.25;
        let mut stray: f64 = 0.0;
        for (a, d) in a.iter().zip(d) {
            let q = if self.persp {
                0.25 * d.z.abs() / a.z.min(a.z + d.z)
            } else {
                0.0
            };
            let r = *d - mean;
            let (sx, sy) = (r.x.abs() + d.x.abs() * q, r.y.abs() + d.y.abs() * q);
            stray = stray.max((sx * sx + sy * sy).sqrt());
        }
        let edge = |k: usize| a[(k + 1) % 4] - a[k];
        let cross = |u: DVec3, v: DVec3| u.x * v.y - u.y * v.x;
        let area: f64 = (0..4).map(|k| cross(a[k], a[(k + 1) % 4])).sum();
        if area == 0.0 || !area.is_finite() || !stray.is_finite() {
            return None;
        }
        let sign = area.signum();
        if (0..4).any(|k| sign * cross(edge(k), edge((k + 1) % 4)) < 0.0) {
            return None;
        }
        let mut e = [[0.0, 0.0, 1.0]; 4];
        for (k, e) in e.iter_mut().enumerate() {
            let u = edge(k);
            let len = (u.x * u.x + u.y * u.y).sqrt();
            if len > 0.0 {
                // Inward unit normal: left of each edge for a counter-clockwise quad.
                let (nx, ny) = (-u.y * sign / len, u.x * sign / len);
                *e = [nx, ny, stray + margin - (a[k].x * nx + a[k].y * ny)];
            }
        }
        e.iter()
            .flatten()
            .all(|x| x.is_finite())
            .then_some(StillHull { e })
    }
}

/// Half-planes `A·x + B·y + C ≥ 0`, one per outer edge of a micropolygon (a zero-length edge
/// passes everything), holding every sample it covers over a stratum once moved back
/// ([`Chord::still_hull`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct StillHull {
    e: [[f64; 3]; 4],
}

impl StillHull {
    /// Whether moved-back sample `(x, y)` may be covered, without a branch.
    #[inline(always)]
    pub(crate) fn holds(&self, x: f64, y: f64) -> bool {
        let pass = |[a, b, c]: [f64; 3]| a * x + b * y + c >= 0.0;
        pass(self.e[0]) & pass(self.e[1]) & pass(self.e[2]) & pass(self.e[3])
    }
}

/// A stratum's [`StillHull`], set up when a batch of candidates is first checked against it
/// and only for a batch of [`HULL_MIN`] or more: its eight square roots and divisions cost
/// about what testing a few candidates does (`rib/bench/transform_blur.rib` has one sample
/// per pixel in each of its 16 strata; set up for every stratum, the hull took 4% of its time).
pub(crate) struct LazyHull<'a> {
    chord: Option<&'a Chord>,
    margin: f64,
    hull: Option<Option<StillHull>>,
}

/// See [`LazyHull`].
const HULL_MIN: usize = 8;

impl<'a> LazyHull<'a> {
    /// The hull of `chord` (none without one) grown by `margin`.
    pub(crate) fn new(chord: Option<&'a Chord>, margin: f64) -> LazyHull<'a> {
        LazyHull {
            chord,
            margin,
            hull: None,
        }
    }

    /// The hull to check a batch of `n` candidates against, if any.
    pub(crate) fn for_candidates(&mut self, n: usize) -> Option<StillHull> {
        if n < HULL_MIN {
            return None;
        }
        let (chord, margin) = (self.chord, self.margin);
        *self
            .hull
            .get_or_insert_with(|| chord.and_then(|c| c.still_hull(margin)))
    }
}

/// The per-stratum bounds of micropolygon `quad` between consecutive `cuts` (times), in two
/// steps: [`strata_paths`] (each cut's corners and each stratum's `path`, set up once per
/// grid) and [`stratum_bound`] (the rest, only for the strata a bucket reaches).
///
/// A vertex moves linearly in camera space between keys, hence along a straight raster line
/// (a projective map keeps lines), so the box of its positions at a stratum's two cuts and at
/// every key between holds its whole path there (`path`). Without a key inside the stratum,
/// vertex `k` is at `a_k + d_k·s_k(t)` with `d_k` its raster step over the stratum and `s_k`
/// the fraction of it done at `t`: raster coordinates are `X/W` with `X`, `W` (camera depth,
/// or 1 for an orthographic camera) linear in `t`, so `s − τ = τ(1 − τ)(W₁ − W₀)/W(τ)` for
/// `τ = (t − t0)/(t1 − t0)`, at most `q_k = |W₁ − W₀| / (4·min W)` away from `τ`. Moved back
/// by the mean velocity `v`, the vertex is at `a_k + (d_k − v·Δt)·τ + d_k·(s_k − τ)`: inside
/// the box spanned by `a_k` and `a_k + d_k − v·Δt`, grown by `q_k·|d_k|` (`still`). For a
/// micropolygon that moves rigidly (camera blur, a translation) that box is its own size, so
/// a sample costs two multiply-adds and compares to reject instead of a full test. Each
/// position is projected once and shared by the two strata it ends. `None` when a position
/// does not project.
pub(crate) fn strata_paths(
    m: &GridMotion,
    quad: &[usize; 4],
    cuts: &[f64],
    project: &impl Fn(DVec3) -> Option<DVec3>,
    paths: &mut Vec<StratumPath>,
) -> Option<()> {
    let at = |p: DVec3| project(p).filter(|q| q.is_finite());
    let mut start = cut_corners(m, quad, *cuts.first()?, project)?;
    paths.clear();
    for w in cuts.windows(2) {
        let end = cut_corners(m, quad, w[1], project)?;
        let mut b = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
        start
            .iter()
            .chain(&end)
            .for_each(|&q| add_box(&mut b, q, q));
        let mut inner_key = false;
        for (key, &t) in m.keys.iter().zip(&m.times) {
            if t > w[0] && t < w[1] {
                inner_key = true;
                for &k in quad {
                    let q = at(key[k].as_dvec3())?;
                    add_box(&mut b, q, q);
                }
            }
        }
        paths.push(StratumPath { path: b, inner_key });
        start = end;
    }
    Some(())
}

/// The raster corners of micropolygon `quad` at time `t` (`None` when one does not project).
#[inline]
pub(crate) fn cut_corners(
    m: &GridMotion,
    quad: &[usize; 4],
    t: f64,
    project: &impl Fn(DVec3) -> Option<DVec3>,
) -> Option<[DVec3; 4]> {
    let seg = segment(&m.times, t);
    let mut v = [DVec3::ZERO; 4];
    for (q, &k) in v.iter_mut().zip(quad) {
        *q = project(m.at(k, seg)).filter(|q| q.is_finite())?;
    }
    Some(v)
}

/// Grows raster box `b` by the box spanned by `lo` and `hi`.
#[inline]
pub(crate) fn add_box(b: &mut [f64; 4], lo: DVec3, hi: DVec3) {
    *b = [
        b[0].min(lo.x),
        b[1].max(hi.x),
        b[2].min(lo.y),
        b[3].max(hi.y),
    ];
}

/// A stratum's path box (`StratumBound::path`) and whether a key lies strictly inside it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StratumPath {
    pub(crate) path: [f64; 4],
    pub(crate) inner_key: bool,
}

/// The bound of stratum `[t0, t1]` with path `p`, its corners at `t0` (`start`) and `t1`
/// (`end`): the `still` box and chord when no key lies inside it (see [`strata_paths`]).
pub(crate) fn stratum_bound(
    p: StratumPath,
    start: &[DVec3; 4],
    end: &[DVec3; 4],
    [t0, t1]: [f64; 2],
    persp: bool,
) -> StratumBound {
    let b = p.path;
    let dt = t1 - t0;
    let mut bound = StratumBound {
        path: b,
        t0,
        v: [0.0; 2],
        still: b,
        chord: None,
    };
    if !p.inner_key && dt > 0.0 {
        let mean = start.iter().zip(end).map(|(a, e)| *e - *a).sum::<DVec3>() * 0.25;
        let mut s = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
        for (a, e) in start.iter().zip(end) {
            let d = *e - *a;
            let q = if persp {
                0.25 * (e.z - a.z).abs() / a.z.min(e.z)
            } else {
                0.0
            };
            let r = d - mean;
            let grow = DVec3::new(d.x.abs(), d.y.abs(), 0.0) * q;
            add_box(
                &mut s,
                *a + r.min(DVec3::ZERO) - grow,
                *a + r.max(DVec3::ZERO) + grow,
            );
        }
        if s.iter().all(|x| x.is_finite()) {
            bound.v = [mean.x / dt, mean.y / dt];
            bound.still = s;
            bound.chord = Some(Chord {
                a: *start,
                d: [0, 1, 2, 3].map(|k| end[k] - start[k]),
                inv_dt: 1.0 / dt,
                persp,
            });
        }
    }
    bound
}

/// Whether micropolygon `quad` moves over the shutter `[open, close]` as one piece in raster
/// space (a camera move or a translation, or anything else that stays inside its own box once
/// moved back, such as shrinking): no key inside the shutter, and moved back by its mean
/// velocity its box over the shutter is at most a pixel wider and taller than its own box at
/// `open`. `false` when a corner does not project.
pub(crate) fn moves_rigidly(
    m: &GridMotion,
    quad: &[usize; 4],
    [open, close]: [f64; 2],
    project: &impl Fn(DVec3) -> Option<DVec3>,
    persp: bool,
) -> bool {
    if m.times.iter().any(|&t| t > open && t < close) {
        return false;
    }
    let (Some(a), Some(e)) = (
        cut_corners(m, quad, open, project),
        cut_corners(m, quad, close, project),
    ) else {
        return false;
    };
    let empty = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
    let (mut path, mut own) = (empty, empty);
    a.iter().chain(&e).for_each(|&q| add_box(&mut path, q, q));
    a.iter().for_each(|&q| add_box(&mut own, q, q));
    let p = StratumPath {
        path,
        inner_key: false,
    };
    let b = stratum_bound(p, &a, &e, [open, close], persp);
    let s = b.still;
    b.chord.is_some()
        && s[1] - s[0] <= own[1] - own[0] + 1.0
        && s[3] - s[2] <= own[3] - own[2] + 1.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A unit square (vertices 0..4, counter-clockwise) at depth 5 whose second key is the first
    /// mapped by `f`; orthographic raster = camera x, y.
    fn moved(f: impl Fn(Vec3) -> Vec3, times: Vec<f64>) -> GridMotion {
        let square: Vec<Vec3> = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
            .iter()
            .map(|&(x, y)| Vec3::new(x, y, 5.0))
            .collect();
        let mut keys = vec![square.clone()];
        for _ in 1..times.len() {
            keys.push(square.iter().map(|&p| f(p)).collect());
        }
        GridMotion::new(times, keys)
    }

    #[test]
    fn a_translation_moves_rigidly_and_a_rotation_or_an_inner_key_does_not() {
        let project = |p: DVec3| Some(p);
        let quad = [0, 1, 2, 3];
        let shutter = [0.0, 1.0];
        let slide = moved(|p| p + Vec3::new(40.0, 3.0, 0.0), vec![0.0, 1.0]);
        assert!(moves_rigidly(&slide, &quad, shutter, &project, false));
        // An eighth of a turn about the square's centre: moved back by the mean velocity
        // (zero) its corners' chords reach 0.83 beyond its box on each side. (A quarter turn
        // would not: each corner's chord runs along a side.)
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let turn = moved(
            |p| {
                let (x, y) = (p.x - 2.0, p.y - 2.0);
                Vec3::new(2.0 + h * (x - y), 2.0 + h * (x + y), p.z)
            },
            vec![0.0, 1.0],
        );
        assert!(!moves_rigidly(&turn, &quad, shutter, &project, false));
        // The same slide through a third key at mid-shutter.
        let keyed = moved(|p| p + Vec3::new(40.0, 3.0, 0.0), vec![0.0, 0.5, 1.0]);
        assert!(!moves_rigidly(&keyed, &quad, shutter, &project, false));
        // Growing to twice its size, it sweeps past its own box once moved back; shrinking,
        // it stays inside it, which is what counts (longer strata cost no more candidates).
        let grow = moved(|p| p * Vec3::new(2.0, 2.0, 1.0), vec![0.0, 1.0]);
        assert!(!moves_rigidly(&grow, &quad, shutter, &project, false));
        let shrink = moved(|p| p * Vec3::new(0.5, 0.5, 1.0), vec![0.0, 1.0]);
        assert!(moves_rigidly(&shrink, &quad, shutter, &project, false));
    }
    #[test]
    fn the_still_hull_holds_every_sample_the_moving_micropolygon_covers() {
        // Random convex and bent quads with random chords (perspective ones changing depth),
        // sampled at random times near the quad: a sample the exact test (corners at its time,
        // both triangles) covers must lie in the hull once moved back by the mean velocity.
        use crate::raster_triangle::{split_quad, RasterTriangle};
        let mut unit = crate::test_rng::unit_stream(0x9e37_79b9);
        let (mut covered, mut rejected, mut hulls) = (0, 0, 0);
        for case in 0..400 {
            let persp = case % 2 == 0;
            let size = 0.5 + 3.0 * unit();
            let turn = unit() * std::f64::consts::TAU;
            let (c, s) = (turn.cos(), turn.sin());
            let mut a = [DVec3::ZERO; 4];
            for (k, q) in a.iter_mut().enumerate() {
                let (x, y) = ([0.0, 1.0, 1.0, 0.0][k], [0.0, 0.0, 1.0, 1.0][k]);
                let (x, y) = (x + 0.3 * (unit() - 0.5), y + 0.3 * (unit() - 0.5));
                *q = DVec3::new(
                    50.0 + size * (c * x - s * y),
                    40.0 + size * (s * x + c * y),
                    2.0 + 8.0 * unit(),
                );
            }
            let motion = DVec3::new(30.0 * (unit() - 0.5), 30.0 * (unit() - 0.5), 0.0);
            let d = [0, 1, 2, 3].map(|_| {
                let z = if persp { 2.0 * (unit() - 0.5) } else { 0.0 };
                motion + DVec3::new(unit() - 0.5, unit() - 0.5, z) * (case % 3) as f64
            });
            let (t0, dt) = (0.25, 0.5);
            let chord = Chord {
                a,
                d,
                inv_dt: 1.0 / dt,
                persp,
            };
            let Some(hull) = chord.still_hull(1e-6) else {
                continue;
            };
            hulls += 1;
            let mean = d.iter().sum::<DVec3>() * 0.25;
            for _ in 0..400 {
                let tau = unit();
                let Some(v) = chord.corners(t0 + tau * dt, t0) else {
                    continue;
                };
                let centre = v.iter().sum::<DVec3>() * 0.25;
                let p = centre + DVec3::new(unit() - 0.5, unit() - 0.5, 0.0) * 2.5 * size;
                let hit = split_quad([0, 1, 2, 3], [0.0; 4]).iter().any(|&(tri, r)| {
                    RasterTriangle::new(tri.map(|k| v[k]), tri, r)
                        .is_some_and(|t| t.covers(p.x, p.y).is_some())
                });
                let back = p - mean * tau;
                let held = hull.holds(back.x, back.y);
                if hit {
                    covered += 1;
                    assert!(
                        held,
                        "case {case}: covered sample {p} at tau {tau} outside the hull"
                    );
                }
                rejected += usize::from(!held);
            }
        }
        assert!(
            hulls > 200 && covered > 20_000 && rejected > 20_000,
            "{hulls} {covered} {rejected}"
        );
    }
}
