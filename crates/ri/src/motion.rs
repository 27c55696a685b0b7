//! Motion blur in the RI state (RI Spec 3.2 §4.1.3, §5.1): transformations that move over the
//! shutter interval, and the motion keys of moving primitives.
//!
//! A `MotionBegin [t0 t1 …]` block holds one transformation or one primitive per time. Between
//! the times everything is piecewise linear, as PRMan does it: matrices are interpolated entry
//! by entry (so a rotation between two keys sweeps the chord, not the arc: more keys follow the
//! arc closer), and a deforming primitive's diced vertices are interpolated one to one.
use crate::state::{BlockKind, Ri};
use glam::DMat4;
use illume_geom::Primitive;
use illume_rib::{Request, Span};

/// A transformation that is `mats[k]` at `times[k]`, piecewise linear between them and clamped
/// outside them (times outside the shutter just shape the interpolation).
#[derive(Clone, Debug, PartialEq)]
pub struct MovingTransform {
    pub times: Vec<f64>,
    pub mats: Vec<DMat4>,
}

/// Where `t` falls among the non-decreasing `times`: segment start `k` and weight of `k + 1`.
pub fn segment(times: &[f64], t: f64) -> (usize, f64) {
    let n = times.len();
    if n < 2 || t <= times[0] {
        return (0, 0.0);
    }
    if t >= times[n - 1] {
        return (n - 2, 1.0);
    }
    let k = times.windows(2).position(|w| t < w[1]).unwrap_or(n - 2);
    let span = times[k + 1] - times[k];
    let w = if span > 0.0 {
        (t - times[k]) / span
    } else {
        1.0
    };
    (k, w)
}

impl MovingTransform {
    /// The transformation at time `t`.
    pub fn at(&self, t: f64) -> DMat4 {
        if self.mats.len() == 1 {
            return self.mats[0];
        }
        let (k, w) = segment(&self.times, t);
        self.mats[k] * (1.0 - w) + self.mats[k + 1] * w
    }

    /// Every key post-multiplied by `m` (a `ConcatTransform` after the motion block).
    pub fn then(&self, m: DMat4) -> MovingTransform {
        MovingTransform {
            times: self.times.clone(),
            mats: self.mats.iter().map(|k| *k * m).collect(),
        }
    }

    /// The transformation `f(t)` keyed at every time of `times` (sorted, duplicates removed).
    pub fn sampled(mut times: Vec<f64>, f: impl Fn(f64) -> DMat4) -> MovingTransform {
        times.sort_by(f64::total_cmp);
        times.dedup();
        let mats = times.iter().map(|&t| f(t)).collect();
        MovingTransform { times, mats }
    }
}

/// The later positions of a moving primitive: [`crate::FramePrimitive::primitive`] is the key
/// at `times[0]`, `later[k − 1]` the key at `times[k]`, all of one topology (they dice to the
/// same `nu × nv` grid and split the same way through `Primitive::split_as`).
#[derive(Debug)]
pub struct MotionKeys {
    pub times: Vec<f32>,
    pub later: Vec<Box<dyn Primitive>>,
}

// ---- MotionBegin/MotionEnd in the RI state --------------------------------------------

/// An open `MotionBegin` block: its times, the transform it started from, and what each of
/// its requests produced (one transformation or one primitive list per time).
pub(crate) struct OpenMotion {
    pub(crate) times: Vec<f64>,
    pub(crate) base: (DMat4, Option<MovingTransform>),
    pub(crate) transforms: Vec<(DMat4, Option<MovingTransform>)>,
    pub(crate) geometry: Vec<Vec<Box<dyn illume_geom::Primitive>>>,
    /// Span and name of the first request, for the block's errors.
    pub(crate) first: Option<(Span, String)>,
}

impl Ri {
    pub(crate) fn motion_begin(&mut self, times: Vec<f32>, span: &Span) {
        self.push_block(BlockKind::Motion, span);
        if self.motion.is_some() {
            self.diagnostics.error_kind(
                crate::ErrorKind::Nesting,
                span,
                "MotionBegin",
                "motion blocks can not nest (its requests apply as if outside it)",
            );
            return;
        }
        let sorted = times.windows(2).all(|w| w[0] <= w[1]);
        if times.is_empty() || !sorted || times.iter().any(|t| !t.is_finite()) {
            self.diagnostics.error_kind(
                crate::ErrorKind::BadMotion,
                span,
                "MotionBegin",
                "expected one or more increasing times (its requests apply as if outside it)",
            );
            return;
        }
        self.motion = Some(OpenMotion {
            times: times.iter().map(|&t| f64::from(t)).collect(),
            base: (self.ctm, self.ctm_motion.clone()),
            transforms: Vec::new(),
            geometry: Vec::new(),
            first: None,
        });
    }

    /// The k-th transformation of a motion block: applied to the transform the block started
    /// from, kept for `MotionEnd`.
    pub(crate) fn motion_transform(&mut self, req: Request, span: &Span) {
        let Some(m) = self.motion.as_mut() else {
            return;
        };
        m.first
            .get_or_insert((span.clone(), req.name().to_string()));
        let (ctm, motion) = m.base.clone();
        self.ctm = ctm;
        self.ctm_motion = motion;
        self.transform_request(req, span);
        let result = (self.ctm, self.ctm_motion.take());
        let m = self.motion.as_mut().expect("checked above");
        m.transforms.push(result);
        (self.ctm, self.ctm_motion) = m.base.clone();
    }

    /// `MotionEnd`: the block's transformations become one moving transform, its primitives one
    /// moving primitive each.
    pub(crate) fn motion_end(&mut self, _span: &Span) {
        let Some(m) = self.motion.take() else { return };
        let n = m.times.len();
        let Some((span, name)) = m.first else { return };
        if !m.transforms.is_empty() && !m.geometry.is_empty() {
            self.diagnostics.error(
                &span,
                &name,
                "a motion block holds either transformations or primitives, not both (the first of each is used)",
            );
        }
        let count = m.transforms.len().max(m.geometry.len());
        if count != n && (m.geometry.is_empty() || m.transforms.is_empty()) {
            self.diagnostics.error(
                &span,
                &name,
                format!("MotionBegin gave {n} times but the block holds {count} requests (the first is used)"),
            );
        }
        let mut transforms = m.transforms;
        if transforms.len() == n && m.geometry.is_empty() {
            let at = |k: usize, t: f64| {
                let (c, mm): &(DMat4, Option<MovingTransform>) = &transforms[k];
                mm.as_ref().map_or(*c, |mm| mm.at(t))
            };
            let mut times = m.times.clone();
            for (_, mm) in &transforms {
                times.extend(mm.iter().flat_map(|mm| mm.times.iter().copied()));
            }
            let moving = MovingTransform::sampled(times, |t| {
                let (k, w) = segment(&m.times, t);
                if n == 1 {
                    at(0, t)
                } else {
                    at(k, t) * (1.0 - w) + at(k + 1, t) * w
                }
            });
            self.ctm = moving.mats[0];
            // Keys that all agree (motion blocks that cancel, as in Aqsis' transmb_test) are
            // no motion: the primitives stay on the hider's fast path.
            let moves = moving.mats.iter().any(|m| *m != moving.mats[0]);
            self.ctm_motion = moves.then_some(moving);
        } else if !transforms.is_empty() {
            (self.ctm, self.ctm_motion) = transforms.swap_remove(0);
        }
        let mut geometry = m.geometry;
        if geometry.len() == n && transforms.is_empty() {
            self.push_primitives(m.times, geometry, &span, &name);
        } else if !geometry.is_empty() {
            let first = geometry.swap_remove(0);
            self.push_primitives(vec![0.0], vec![first], &span, &name);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn piecewise_linear_and_clamped() {
        let m = MovingTransform {
            times: vec![0.0, 1.0, 3.0],
            mats: [0.0, 2.0, 6.0]
                .map(|x| DMat4::from_translation(DVec3::new(x, 0.0, 0.0)))
                .to_vec(),
        };
        let x = |t: f64| m.at(t).transform_point3(DVec3::ZERO).x;
        assert_eq!(x(-1.0), 0.0);
        assert!((x(0.25) - 0.5).abs() < 1e-12);
        assert!((x(2.0) - 4.0).abs() < 1e-12);
        assert_eq!(x(5.0), 6.0);
        assert_eq!(segment(&[0.0, 1.0], 0.5), (0, 0.5));
    }
}
