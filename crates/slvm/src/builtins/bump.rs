//! `bump(name[chan], N, dPds, dPdt [, s, t | 8 corners])` (RI 3.0–3.1; RI 3.2 dropped it for
//! `calculatenormal(P + amount·N)`, which real shaders now use): the change of the normal that a
//! height map `F(s, t)` read from channel `chan` would give if `P` were displaced by
//! `F·normalize(N)`. Blinn's first-order form (1978), scaled to `N`'s own length so that
//! `N + bump(…)` is the bumped normal whatever length `N` has:
//!
//! `D = |N| / |dPds × dPdt| · (F_s · (n̂ × dPdt) − F_t · (n̂ × dPds))`, `n̂ = normalize(N)`.
//!
//! `F_s`, `F_t` are central differences of filtered lookups shifted by half the point's own
//! footprint in `s` and `t` (at least 1e-4), so the slope is the map's at the scale it is seen.
use crate::exec::Exec;
use crate::value::{Mask, Slot, Value};
use glam::{DVec3, Vec3};
use illume_sl::ast::Global;
use illume_texture::{TextureLookup, TextureOptions};

/// The smallest half-step of the differences in `s`/`t`.
const MIN_STEP: f32 = 1e-4;

impl Exec<'_> {
    pub(super) fn bump_call(
        &mut self,
        tex: &dyn TextureLookup,
        (name, channel): (&str, usize),
        opts: &TextureOptions,
        coords: &[Value],
        mask: &Mask,
    ) -> Value {
        let n = self.n;
        let zero = Value::Triple(Slot::Uniform(Vec3::ZERO));
        if coords.len() < 3 {
            return zero;
        }
        let vec = |v: &Value| match v {
            Value::Triple(s) => s.clone(),
            _ => Slot::Uniform(Vec3::ZERO),
        };
        let flt = |v: &Value| match v {
            Value::Float(s) => s.clone(),
            _ => Slot::Uniform(0.0),
        };
        let (nn, dpds, dpdt) = (vec(&coords[0]), vec(&coords[1]), vec(&coords[2]));
        let st: Vec<Slot<f32>> = if coords.len() > 3 {
            coords[3..].iter().map(flt).collect()
        } else {
            vec![flt(self.global(Global::s)), flt(self.global(Global::t))]
        };
        let (s, t): (Vec<Slot<f32>>, Vec<Slot<f32>>) = (
            st.iter().step_by(2).cloned().collect(),
            st.iter().skip(1).step_by(2).cloned().collect(),
        );
        let mut missing = false;
        let mut out = vec![Vec3::ZERO; n];
        for (i, o) in out.iter_mut().enumerate() {
            if !mask.get(i) {
                continue;
            }
            let (cs, ct) = (self.corners(&s, i), self.corners(&t, i));
            let span = |c: [f32; 4]| {
                let (lo, hi) = c
                    .iter()
                    .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &x| {
                        (a.min(x), b.max(x))
                    });
                (0.5 * (hi - lo)).max(MIN_STEP)
            };
            let (hs, ht) = (span(cs), span(ct));
            let mut height = |ds: f32, dt: f32| {
                let q = [0, 1, 2, 3].map(|k| [cs[k] + ds, ct[k] + dt]);
                match tex.texture(name, channel, 1, q, opts) {
                    Some(v) if v[0].is_finite() => f64::from(v[0]),
                    Some(_) => 0.0,
                    None => {
                        missing = true;
                        0.0
                    }
                }
            };
            let fs = (height(hs, 0.0) - height(-hs, 0.0)) / (2.0 * f64::from(hs));
            let ft = (height(0.0, ht) - height(0.0, -ht)) / (2.0 * f64::from(ht));
            *o = blinn(
                nn.at(i).as_dvec3(),
                dpds.at(i).as_dvec3(),
                dpdt.at(i).as_dvec3(),
                fs,
                ft,
            );
        }
        if missing {
            self.env.warn(&format!("bump `{name}` not found; no bump"));
        }
        Value::Triple(Slot::varying(out))
    }
}

/// Blinn's normal perturbation for slopes `fs`, `ft`, in `N`'s scale; zero where a vector is
/// degenerate or the result is not finite.
fn blinn(n: DVec3, dpds: DVec3, dpdt: DVec3, fs: f64, ft: f64) -> Vec3 {
    let (len, area) = (n.length(), dpds.cross(dpdt).length());
    if len <= 0.0 || area <= 0.0 || !len.is_finite() || !area.is_finite() {
        return Vec3::ZERO;
    }
    let nh = n / len;
    let d = (nh.cross(dpdt) * fs - nh.cross(dpds) * ft) * (len / area);
    if d.is_finite() {
        d.as_vec3()
    } else {
        Vec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::blinn;
    use glam::DVec3;

    /// A plane displaced by `F = a·s + b·t` along its normal has the exact normal
    /// `dPds × dPdt + …`; Blinn's form is exact for a linear height on a plane.
    #[test]
    fn a_linear_height_tilts_the_normal_exactly() {
        let (a, b) = (0.3, -0.7);
        let (dpds, dpdt) = (DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 0.5, 0.0));
        let n = dpds.cross(dpdt); // (0, 0, 1)
        for scale in [1.0, 0.25, 7.0] {
            let d = blinn(n * scale, dpds, dpdt, a, b).as_dvec3();
            // The displaced surface P + F·ẑ: its tangents (2, 0, a) and (0, .5, b).
            let exact = DVec3::new(2.0, 0.0, a).cross(DVec3::new(0.0, 0.5, b));
            let bumped = (n * scale + d).normalize();
            // The result is stored as f32.
            assert!((bumped - exact.normalize()).length() < 1e-6, "{bumped}");
        }
        assert_eq!(blinn(DVec3::ZERO, dpds, dpdt, a, b), glam::Vec3::ZERO);
    }
}
