//! Motion blur in the RI state (RI Spec 3.2 §4.1.3, §5.1): transformations that move over the
//! shutter interval, and the motion keys of moving primitives.
//!
//! A `MotionBegin [t0 t1 …]` block holds one transformation or one primitive per time. Between
//! the times everything is piecewise linear, as PRMan does it: matrices are interpolated entry
//! by entry (so a rotation between two keys sweeps the chord, not the arc: more keys follow the
//! arc closer), and a deforming primitive's diced vertices are interpolated one to one.
use glam::DMat4;
use illume_geom::Primitive;

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
