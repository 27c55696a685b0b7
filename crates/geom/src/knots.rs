//! Knot vectors and B-spline basis functions (Cox–de Boor), in f64, shared by `NuPatch` and
//! `TrimCurve` (RI Spec 3.2 §5.5). An order-`k` (degree `k−1`) spline with `n` control points
//! has `n + k` non-decreasing knots and is defined over `[knot[k−1], knot[n]]`.
//!
//! The basis is the triangular recurrence of Piegl & Tiller, *The NURBS Book* (algorithm A2.2):
//! it only touches the `k` functions that are non-zero on one span, and its divisions are by
//! sums of knot differences that are positive on a non-empty span, so it never divides by zero.
//! Derivatives come from the degree-`k−2` functions (`N'ⱼ,ₚ = p/(uⱼ₊ₚ−uⱼ)·Nⱼ,ₚ₋₁ − …`).

/// A validated knot vector with its order and control-point count.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    order: usize,
    n: usize,
}

impl KnotVector {
    /// Checks `order ≥ 1`, `n ≥ order`, `n + order` finite non-decreasing knots and a
    /// non-empty parameter range; the message says what is wrong.
    pub fn new(knots: &[f32], order: i32, n: i32) -> Result<KnotVector, String> {
        if order < 1 {
            return Err(format!("order must be at least 1, found {order}"));
        }
        if n < order {
            return Err(format!(
                "needs at least order = {order} control points, found {n}"
            ));
        }
        let (order, n) = (order as usize, n as usize);
        if knots.len() != n + order {
            return Err(format!(
                "needs n + order = {} knots, found {}",
                n + order,
                knots.len()
            ));
        }
        if knots.iter().any(|k| !k.is_finite()) {
            return Err("knots must be finite".to_string());
        }
        if knots.windows(2).any(|w| w[1] < w[0]) {
            return Err("knots must be non-decreasing".to_string());
        }
        let knots: Vec<f64> = knots.iter().map(|&k| f64::from(k)).collect();
        if knots[n] <= knots[order - 1] {
            return Err("knots leave an empty parameter range".to_string());
        }
        Ok(KnotVector { knots, order, n })
    }

    pub fn order(&self) -> usize {
        self.order
    }

    /// Control points.
    pub fn len(&self) -> usize {
        self.n
    }

    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    pub fn knot(&self, i: usize) -> f64 {
        self.knots[i]
    }

    /// The parameter range `[knot[order−1], knot[n]]` the spline is defined over.
    pub fn domain(&self) -> [f64; 2] {
        [self.knots[self.order - 1], self.knots[self.n]]
    }

    /// Spans `i` (`order−1 ≤ i < n`) with their knot intervals `[knot[i], knot[i+1]]`; empty
    /// intervals (repeated knots) included, as the spec's uniform/varying counts include them.
    pub fn segments(&self) -> impl Iterator<Item = (usize, [f64; 2])> + '_ {
        (self.order - 1..self.n).map(|i| (i, [self.knots[i], self.knots[i + 1]]))
    }

    /// The span `i` with `knot[i] ≤ t < knot[i+1]` (the last non-empty span at the domain's
    /// end, the first one below it), so every `t` evaluates with a non-empty interval.
    pub fn span(&self, t: f64) -> usize {
        let [lo, hi] = self.domain();
        let (first, last) = (self.order - 1, self.n - 1);
        if t >= hi {
            return (first..=last)
                .rev()
                .find(|&i| self.knots[i] < self.knots[i + 1])
                .unwrap_or(last);
        }
        if t <= lo {
            return (first..=last)
                .find(|&i| self.knots[i] < self.knots[i + 1])
                .unwrap_or(first);
        }
        // Largest i in [first, last] with knot[i] ≤ t.
        let upto = self.knots[first..=last].partition_point(|&k| k <= t);
        first + upto.saturating_sub(1)
    }

    /// The `order` basis functions non-zero on `span` at `t` (`Nⱼ` for `j = span−order+1 …
    /// span`) and their derivatives `dN/dt`.
    pub fn basis(&self, span: usize, t: f64, n: &mut [f64], dn: &mut [f64]) {
        let p = self.order - 1;
        if p == 0 {
            n[0] = 1.0;
            dn[0] = 0.0;
            return;
        }
        // Degree p−1 functions N_{span−p+1 … span, p−1}.
        with_scratch(p, |lower| self.basis_with_lower(span, t, lower, n, dn));
    }

    /// [`KnotVector::basis`] for degree `p = lower.len() ≥ 1`, `lower` a scratch buffer.
    fn basis_with_lower(
        &self,
        span: usize,
        t: f64,
        lower: &mut [f64],
        n: &mut [f64],
        dn: &mut [f64],
    ) {
        let p = lower.len();
        self.basis_of_degree(span, t, p - 1, lower);
        let u = &self.knots;
        for k in 0..=p {
            let j = span + k - p;
            let a = if k >= 1 { lower[k - 1] } else { 0.0 };
            let b = if k < p { lower[k] } else { 0.0 };
            let da = u[j + p] - u[j];
            let db = u[j + p + 1] - u[j + 1];
            let (fa, ga) = if da > 0.0 {
                ((t - u[j]) / da, p as f64 / da)
            } else {
                (0.0, 0.0)
            };
            let (fb, gb) = if db > 0.0 {
                ((u[j + p + 1] - t) / db, p as f64 / db)
            } else {
                (0.0, 0.0)
            };
            n[k] = fa * a + fb * b;
            dn[k] = ga * a - gb * b;
        }
    }

    /// The spans `(span, [a, b])` that the parameter range `[t0, t1]` crosses, each with the
    /// part of the range inside it (one span when the range lies in one knot interval).
    pub fn spans_of_range(&self, t0: f64, t1: f64) -> Vec<(usize, [f64; 2])> {
        let first = self.span(t0);
        (first..self.n)
            .take_while(|&i| i == first || self.knots[i] < t1)
            .filter(|&i| self.knots[i] < self.knots[i + 1])
            .map(|i| (i, [t0.max(self.knots[i]), t1.min(self.knots[i + 1])]))
            .filter(|(_, [a, b])| a <= b)
            .collect()
    }

    /// The Bézier form of the spline over `[a, b]` inside the non-empty `span`: row `i` holds
    /// the weights of control points `span−p … span` that make the `i`-th Bézier control
    /// point, the blossom `f(a,…,a, b,…,b)` with `i` copies of `b` (de Boor's recurrence with
    /// a different argument per level). Why: the hull of these `p + 1` points bounds the curve
    /// over `[a, b]` only, where the hull of the B-spline control points bounds the whole span
    /// (a bilinear patch split a thousand times would keep the whole patch as its bound).
    pub fn bezier_of_range(&self, span: usize, [a, b]: [f64; 2]) -> Vec<Vec<f64>> {
        let p = self.order - 1;
        let u = &self.knots;
        (0..=p)
            .map(|i| {
                // Coefficient vectors of d_k, k = 0..=p, over the span's control points.
                let mut d: Vec<Vec<f64>> = (0..=p)
                    .map(|k| (0..=p).map(|m| f64::from(u8::from(m == k))).collect())
                    .collect();
                for r in 1..=p {
                    let x = if r <= p - i { a } else { b };
                    for k in (r..=p).rev() {
                        let j = span + k - p;
                        let den = u[j + p + 1 - r] - u[j];
                        let alpha = if den > 0.0 { (x - u[j]) / den } else { 0.0 };
                        let (lo, hi) = d.split_at_mut(k);
                        for (h, l) in hi[0].iter_mut().zip(&lo[k - 1]) {
                            *h = (1.0 - alpha) * l + alpha * *h;
                        }
                    }
                }
                d.swap_remove(p)
            })
            .collect()
    }

    /// Algorithm A2.2: the `q + 1` degree-`q` functions non-zero on `span`.
    fn basis_of_degree(&self, span: usize, t: f64, q: usize, out: &mut [f64]) {
        with_scratch(q + 1, |left| {
            with_scratch(q + 1, |right| {
                self.basis_of_degree_in(span, t, out, left, right)
            })
        });
    }

    /// [`KnotVector::basis_of_degree`] with `left` and `right` scratch buffers of `q + 1`.
    fn basis_of_degree_in(
        &self,
        span: usize,
        t: f64,
        out: &mut [f64],
        left: &mut [f64],
        right: &mut [f64],
    ) {
        let u = &self.knots;
        let q = left.len() - 1;
        out[0] = 1.0;
        for j in 1..=q {
            left[j] = t - u[span + 1 - j];
            right[j] = u[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                let denom = right[r + 1] + left[j - r];
                let temp = if denom != 0.0 { out[r] / denom } else { 0.0 };
                out[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            out[j] = saved;
        }
    }
}

/// Runs `f` on `n` zeroed floats, on the stack for the orders curves and patches use: the
/// basis is evaluated at every diced vertex, and allocating its buffers there was 7% of
/// `rib/geometry.rib`'s CPU (issue 21 part 3).
fn with_scratch<R>(n: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    const INLINE: usize = 16;
    if n <= INLINE {
        f(&mut [0.0; INLINE][..n])
    } else {
        f(&mut vec![0.0; n])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Independent reference: the recursive Cox–de Boor definition with 0/0 = 0.
    fn cox_de_boor(u: &[f64], j: usize, p: usize, t: f64) -> f64 {
        if p == 0 {
            return if u[j] <= t && t < u[j + 1] { 1.0 } else { 0.0 };
        }
        let a = if u[j + p] > u[j] {
            (t - u[j]) / (u[j + p] - u[j]) * cox_de_boor(u, j, p - 1, t)
        } else {
            0.0
        };
        let b = if u[j + p + 1] > u[j + 1] {
            (u[j + p + 1] - t) / (u[j + p + 1] - u[j + 1]) * cox_de_boor(u, j + 1, p - 1, t)
        } else {
            0.0
        };
        a + b
    }

    #[test]
    fn basis_matches_recursive_definition_and_its_difference_quotient() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
        let kv = KnotVector::new(&knots, 4, 8).unwrap();
        let u: Vec<f64> = knots.iter().map(|&k| f64::from(k)).collect();
        let (mut n, mut dn) = ([0.0; 4], [0.0; 4]);
        for s in 0..=97 {
            let t = 0.013 + s as f64 * 0.0305;
            let span = kv.span(t);
            kv.basis(span, t, &mut n, &mut dn);
            let sum: f64 = n.iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-12,
                "partition of unity at {t}: {sum}"
            );
            for k in 0..4 {
                let j = span + k - 3;
                let r = cox_de_boor(&u, j, 3, t);
                assert!((n[k] - r).abs() < 1e-12, "N{j} at {t}: {} vs {r}", n[k]);
                let h = 1e-6;
                let fd = (cox_de_boor(&u, j, 3, t + h) - cox_de_boor(&u, j, 3, t - h)) / (2.0 * h);
                assert!((dn[k] - fd).abs() < 1e-4, "N{j}' at {t}: {} vs {fd}", dn[k]);
            }
        }
    }

    #[test]
    fn span_skips_empty_intervals_at_the_ends() {
        let kv = KnotVector::new(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3, 3).unwrap();
        assert_eq!(kv.span(1.0), 2);
        assert_eq!(kv.span(0.0), 2);
        assert_eq!(kv.span(0.5), 2);
    }

    #[test]
    fn bad_knot_vectors_are_reported() {
        assert!(KnotVector::new(&[0.0, 1.0, 0.5, 1.0], 2, 2).is_err());
        assert!(KnotVector::new(&[0.0, 1.0, 1.0], 2, 2).is_err());
        assert!(KnotVector::new(&[0.0; 4], 2, 2).is_err());
        assert!(KnotVector::new(&[0.0, 1.0], 0, 2).is_err());
        assert!(KnotVector::new(&[0.0, f32::NAN, 1.0, 1.0], 2, 2).is_err());
    }

    /// The Bézier form of a sub-range must trace the same curve: evaluate it with Bernstein
    /// polynomials and compare with the recursive Cox–de Boor sum over the original control
    /// values, for ranges inside one span and ranges crossing knots.
    #[test]
    fn bezier_of_range_traces_the_spline_over_the_range() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
        let kv = KnotVector::new(&knots, 4, 8).unwrap();
        let u: Vec<f64> = knots.iter().map(|&k| f64::from(k)).collect();
        let ctrl = [0.3, -1.2, 2.5, 0.7, -0.4, 1.9, 3.3, -2.0];
        let spline = |t: f64| -> f64 {
            // The closed end of the domain: evaluate just inside it.
            let t = t.min(3.0 - 1e-12);
            (0..8).map(|j| ctrl[j] * cox_de_boor(&u, j, 3, t)).sum()
        };
        let bernstein = |i: usize, s: f64| -> f64 {
            let binom = [1.0, 3.0, 3.0, 1.0][i];
            binom * s.powi(i as i32) * (1.0 - s).powi(3 - i as i32)
        };
        for (t0, t1) in [(0.1, 0.3), (0.55, 0.9), (1.2, 1.21), (0.2, 2.7), (0.0, 3.0)] {
            let spans = kv.spans_of_range(t0, t1);
            assert!(!spans.is_empty());
            assert_eq!(spans.first().unwrap().1[0], t0);
            assert_eq!(spans.last().unwrap().1[1], t1);
            for (span, [a, b]) in spans {
                let m = kv.bezier_of_range(span, [a, b]);
                let bez: Vec<f64> = m
                    .iter()
                    .map(|w| (0..4).map(|k| w[k] * ctrl[span - 3 + k]).sum())
                    .collect();
                for q in 0..=10 {
                    let s = q as f64 / 10.0;
                    let got: f64 = (0..4).map(|i| bez[i] * bernstein(i, s)).sum();
                    let want = spline(a + s * (b - a));
                    assert!(
                        (got - want).abs() < 1e-9,
                        "[{a},{b}] at {s}: {got} vs {want}"
                    );
                }
            }
        }
    }
}
