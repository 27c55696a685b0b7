//! `TrimCurve` (RI Spec 3.2 §5.5): loops of rational B-spline curves in a NuPatch's (u, v)
//! parameter space. The curves are an attribute: they cut every NuPatch that follows in the
//! same attribute block.
//!
//! Each curve is evaluated in f64 into a polyline (a fixed number of chords per non-empty knot
//! span, enough for the chord error to stay far below a micropolygon), each loop is closed, and
//! a parameter point is **kept when it is inside an odd number of loop crossings** (even-odd
//! rule over all loops together, so a loop inside a loop cuts a hole). Points outside every
//! loop are trimmed away: a square patch trimmed by a circle keeps the disk.
use crate::knots::KnotVector;
use glam::DVec2;

/// Chords per non-empty knot span of a trim curve. A quadratic arc of a unit circle split into
/// 64 chords deviates from its chords by at most `1 − cos(π/256) ≈ 7.5e-5` of the radius.
const CHORDS_PER_SPAN: usize = 64;

/// The trim loops as closed polylines in (u, v) parameter space, with their bounding boxes.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimCurves {
    loops: Vec<Loop>,
}

#[derive(Clone, Debug, PartialEq)]
struct Loop {
    points: Vec<DVec2>,
    lo: DVec2,
    hi: DVec2,
}

/// The arrays of one `TrimCurve` request, as the RIB gives them.
#[derive(Clone, Copy, Debug)]
pub struct TrimCurveArgs<'a> {
    pub ncurves: &'a [i32],
    pub order: &'a [i32],
    pub knot: &'a [f32],
    pub min: &'a [f32],
    pub max: &'a [f32],
    pub n: &'a [i32],
    pub u: &'a [f32],
    pub v: &'a [f32],
    pub w: &'a [f32],
}

impl TrimCurves {
    /// Evaluates every curve of the request; a count mismatch, bad knots or a non-positive
    /// weight is an error naming the curve.
    pub fn new(a: TrimCurveArgs) -> Result<TrimCurves, String> {
        if a.ncurves.iter().any(|&c| c < 0) {
            return Err("ncurves must not be negative".to_string());
        }
        let total: usize = a.ncurves.iter().map(|&c| c as usize).sum();
        for (name, len) in [("order", a.order.len()), ("min", a.min.len())] {
            if len != total {
                return Err(format!(
                    "{name} has {len} values, expected {total} (one per curve)"
                ));
            }
        }
        if a.max.len() != total || a.n.len() != total {
            return Err(format!(
                "max and n need {total} values (one per curve), found {} and {}",
                a.max.len(),
                a.n.len()
            ));
        }
        let points: usize = a.n.iter().map(|&n| n.max(0) as usize).sum();
        if a.u.len() != points || a.v.len() != points || a.w.len() != points {
            return Err(format!(
                "u, v, w need {points} values (Σ n), found {}, {}, {}",
                a.u.len(),
                a.v.len(),
                a.w.len()
            ));
        }
        let (mut curve, mut knot0, mut cp0) = (0usize, 0usize, 0usize);
        let mut loops = Vec::with_capacity(a.ncurves.len());
        for &nc in a.ncurves {
            let mut pts = Vec::new();
            for _ in 0..nc {
                let (order, n) = (a.order[curve], a.n[curve]);
                let nk = (n.max(0) + order.max(0)) as usize;
                let knots = a
                    .knot
                    .get(knot0..knot0 + nk)
                    .ok_or_else(|| format!("curve {curve}: knot array too short"))?;
                let kv =
                    KnotVector::new(knots, order, n).map_err(|e| format!("curve {curve}: {e}"))?;
                let range = [f64::from(a.min[curve]), f64::from(a.max[curve])];
                let cps = cp0..cp0 + n as usize;
                let ctrl: Vec<[f64; 3]> = cps
                    .map(|k| [a.u[k], a.v[k], a.w[k]].map(f64::from))
                    .collect();
                if ctrl
                    .iter()
                    .any(|c| !c.iter().all(|x| x.is_finite()) || c[2] <= 0.0)
                {
                    return Err(format!(
                        "curve {curve}: control points need finite u, v and w > 0"
                    ));
                }
                polyline(&kv, &ctrl, range, &mut pts);
                curve += 1;
                knot0 += nk;
                cp0 += n as usize;
            }
            if pts.len() >= 3 {
                let lo = pts
                    .iter()
                    .fold(DVec2::splat(f64::INFINITY), |a, &p| a.min(p));
                let hi = pts
                    .iter()
                    .fold(DVec2::splat(f64::NEG_INFINITY), |a, &p| a.max(p));
                loops.push(Loop {
                    points: pts,
                    lo,
                    hi,
                });
            }
        }
        if knot0 != a.knot.len() {
            return Err(format!(
                "knot has {} values, expected {knot0} (Σ n + order)",
                a.knot.len()
            ));
        }
        Ok(TrimCurves { loops })
    }

    /// No loops: nothing is trimmed.
    pub fn is_empty(&self) -> bool {
        self.loops.is_empty()
    }

    /// Whether `(u, v)` is kept: inside an odd number of loops (even-odd crossings of a ray
    /// toward +u, half-open edges so a vertex on the ray counts once).
    pub fn keeps(&self, u: f64, v: f64) -> bool {
        let mut inside = false;
        for l in &self.loops {
            if v < l.lo.y || v >= l.hi.y || u > l.hi.x {
                continue;
            }
            let n = l.points.len();
            for k in 0..n {
                let (a, b) = (l.points[k], l.points[(k + 1) % n]);
                if (a.y > v) != (b.y > v) {
                    let x = a.x + (v - a.y) / (b.y - a.y) * (b.x - a.x);
                    if x > u {
                        inside = !inside;
                    }
                }
            }
        }
        inside
    }
}

/// Appends the curve over `range` (clamped to its domain) as points, `CHORDS_PER_SPAN` chords
/// per non-empty span, rational (u/w, v/w).
fn polyline(kv: &KnotVector, ctrl: &[[f64; 3]], range: [f64; 2], out: &mut Vec<DVec2>) {
    let [d0, d1] = kv.domain();
    let (t0, t1) = (range[0].max(d0), range[1].min(d1));
    if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
        return;
    }
    let order = kv.order();
    let (mut n, mut dn) = (vec![0.0; order], vec![0.0; order]);
    let mut eval = |t: f64| {
        let span = kv.span(t);
        kv.basis(span, t, &mut n, &mut dn);
        let mut h = [0.0; 3];
        for (k, &b) in n.iter().enumerate() {
            let c = ctrl[span + k + 1 - order];
            for (h, c) in h.iter_mut().zip(c) {
                *h += b * c;
            }
        }
        DVec2::new(h[0] / h[2], h[1] / h[2])
    };
    let mut breaks: Vec<f64> = vec![t0];
    breaks.extend(
        kv.segments()
            .map(|(_, [a, _])| a)
            .filter(|&a| a > t0 && a < t1),
    );
    breaks.push(t1);
    breaks.dedup();
    for w in breaks.windows(2) {
        for s in 0..CHORDS_PER_SPAN {
            out.push(eval(
                w[0] + (w[1] - w[0]) * s as f64 / CHORDS_PER_SPAN as f64,
            ));
        }
    }
    out.push(eval(t1));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit square's boundary as one linear (order 2) curve of 5 points.
    fn square(c: f32, r: f32) -> TrimCurves {
        let (u, v) = (
            [c - r, c + r, c + r, c - r, c - r],
            [c - r, c - r, c + r, c + r, c - r],
        );
        TrimCurves::new(TrimCurveArgs {
            ncurves: &[1],
            order: &[2],
            knot: &[0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0],
            min: &[0.0],
            max: &[4.0],
            n: &[5],
            u: &u,
            v: &v,
            w: &[1.0; 5],
        })
        .unwrap()
    }

    #[test]
    fn even_odd_keeps_inside_of_a_square_loop() {
        let t = square(0.5, 0.25);
        assert!(t.keeps(0.5, 0.5));
        assert!(!t.keeps(0.1, 0.5));
        assert!(!t.keeps(0.5, 0.9));
    }

    #[test]
    fn count_mismatches_are_errors() {
        let e = TrimCurves::new(TrimCurveArgs {
            ncurves: &[1],
            order: &[2],
            knot: &[0.0, 0.0, 1.0, 1.0],
            min: &[0.0],
            max: &[1.0],
            n: &[2],
            u: &[0.0],
            v: &[0.0, 1.0],
            w: &[1.0, 1.0],
        });
        assert!(e.is_err());
    }
}
