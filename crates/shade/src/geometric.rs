//! Shading Language geometric functions (RI Spec 3.2 §15.3): `faceforward`, `reflect`,
//! `refract`, `fresnel`. Zero-length inputs give zero (never NaN), so a degenerate micropolygon
//! shades black instead of poisoning a pixel.
use glam::{DVec3, Vec3};

/// `normalize(v)`, or the zero vector when `v` has no direction (zero, denormal or non-finite
/// length). SL's `normalize` divides by zero there; a NaN would reach the pixel.
pub fn normalize_or_zero(v: Vec3) -> Vec3 {
    let d = v.as_dvec3();
    let len = d.length();
    if len > 1e-30 && len.is_finite() {
        (d / len).as_vec3()
    } else {
        Vec3::ZERO
    }
}

/// `faceforward(N, I, Nref)`: `N` flipped, if needed, to point against `I` as judged by `Nref`
/// (SL's two-argument form uses `Nref = Ng`). When `I ⟂ Nref` `N` is returned unchanged.
pub fn faceforward(n: Vec3, i: Vec3, nref: Vec3) -> Vec3 {
    if i.dot(nref) > 0.0 {
        -n
    } else {
        n
    }
}

/// `reflect(I, N) = I - 2 (I·N) N` (`N` unit).
pub fn reflect(i: Vec3, n: Vec3) -> Vec3 {
    i - 2.0 * i.dot(n) * n
}

/// `refract(I, N, eta)`: the RI Spec's formula, `eta` the ratio of the index on `I`'s side to the
/// other side, `I`, `N` unit and facing each other; zero on total internal reflection.
pub fn refract(i: Vec3, n: Vec3, eta: f32) -> Vec3 {
    let (i, n, eta) = (i.as_dvec3(), n.as_dvec3(), eta as f64);
    let idotn = i.dot(n);
    let k = 1.0 - eta * eta * (1.0 - idotn * idotn);
    if k < 0.0 {
        Vec3::ZERO
    } else {
        (eta * i - (eta * idotn + k.sqrt()) * n).as_vec3()
    }
}

/// The outputs of [`fresnel`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fresnel {
    /// Fraction of light reflected (unpolarised dielectric Fresnel equations).
    pub kr: f32,
    /// Fraction transmitted, `1 - kr` (the chapter's Listing 9.9 overrides it the same way).
    pub kt: f32,
    /// Mirror direction `reflect(I, N)`.
    pub r: Vec3,
    /// Refracted direction `refract(I, N, eta)`, zero on total internal reflection.
    pub t: Vec3,
}

/// `fresnel(I, N, eta, Kr, Kt, R, T)` (chapter 9 §9.2.5). `I` and `N` are normalised here;
/// `eta` is the ratio of the index of `I`'s medium to the far side's (`1/ior` entering plastic).
///
/// Singular points: `eta = 1` is no interface (`Kr = 0`, `T = I`); total internal reflection gives
/// `Kr = 1`; grazing incidence (`I ⟂ N`) gives `Kr = 1`; zero-length `I` or `N` gives `Kr = 1`,
/// `R = T = 0`. Evaluated in `f64`: the two amplitude ratios cancel near `eta = 1`.
pub fn fresnel(i: Vec3, n: Vec3, eta: f32) -> Fresnel {
    let (i64, n64) = (
        i.as_dvec3().normalize_or_zero(),
        n.as_dvec3().normalize_or_zero(),
    );
    let i = normalize_or_zero(i);
    let n = normalize_or_zero(n);
    let r = reflect(i, n);
    if eta == 1.0 {
        return Fresnel {
            kr: 0.0,
            kt: 1.0,
            r,
            t: i,
        };
    }
    // Normalised again in f64: near the critical angle `Kr` is infinitely sensitive to `cosθi`.
    let kr = fresnel_kr(i64, n64, eta as f64) as f32;
    let t = refract(i, n, eta);
    Fresnel {
        kr,
        kt: 1.0 - kr,
        r,
        t,
    }
}

/// Unpolarised reflectance `(rs² + rp²)/2` for unit `i`, `n`.
fn fresnel_kr(i: DVec3, n: DVec3, eta: f64) -> f64 {
    let cos_i = i.dot(n).abs().min(1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 || (eta.is_nan() || eta <= 0.0) {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let (ds, dp) = (eta * cos_i + cos_t, cos_i + eta * cos_t);
    if ds <= 0.0 || dp <= 0.0 {
        return 1.0;
    }
    let rs = (eta * cos_i - cos_t) / ds;
    let rp = (cos_i - eta * cos_t) / dp;
    (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0)
}
