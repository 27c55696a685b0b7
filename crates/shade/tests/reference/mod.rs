//! Independent `f64` reference implementations, written straight from the chapter's formulas
//! (not from the crate's code), shared by the test files.
#![allow(dead_code)]
use glam::{DVec3, Vec3};

pub fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// SL `normalize`, with the zero vector for a zero input (the undefined case).
pub fn normalize(v: DVec3) -> DVec3 {
    let l = v.length();
    if l > 0.0 {
        v / l
    } else {
        DVec3::ZERO
    }
}

/// Listing 9.10 `diffuse()` for one light.
pub fn lambert(n: DVec3, l: DVec3) -> f64 {
    n.dot(normalize(l)).max(0.0)
}

/// Listing 9.10 `specular()` for one light, exponent `e`.
pub fn blinn(n: DVec3, v: DVec3, l: DVec3, e: f64) -> f64 {
    // `N` and `V` are unit by contract; rounding in a unit f32 vector is ~6e-8, which the
    // exponent (up to 10⁶) would amplify, so both sides normalise them.
    let (n, v) = (normalize(n), normalize(v));
    let h = normalize(normalize(l) + v);
    let x = n.dot(h).max(0.0);
    if x == 0.0 {
        0.0
    } else {
        x.powf(e)
    }
}

/// Listing 9.11, one light, with the listing's `acos`/`tan` (defined for `θi, θr < 90°`).
pub fn oren_nayar(n: DVec3, v: DVec3, l: DVec3, sigma: f64) -> f64 {
    let (n, v) = (normalize(n), normalize(v));
    let sigma2 = sigma * sigma;
    let a = 1.0 - 0.5 * sigma2 / (sigma2 + 0.33);
    let b = 0.45 * sigma2 / (sigma2 + 0.09);
    let theta_r = v.dot(n).clamp(-1.0, 1.0).acos();
    let v_perp_n = normalize(v - n * v.dot(n));
    let ln = normalize(l);
    let cos_theta_i = ln.dot(n);
    if cos_theta_i <= 0.0 {
        return 0.0;
    }
    let cos_phi_diff = v_perp_n.dot(normalize(ln - n * cos_theta_i));
    let theta_i = cos_theta_i.min(1.0).acos();
    let alpha = theta_i.max(theta_r);
    let beta = theta_i.min(theta_r);
    cos_theta_i * (a + b * cos_phi_diff.max(0.0) * alpha.sin() * beta.tan())
}

/// Listing 9.12 including `1/(4 αx αy)`, one light.
pub fn ward(n: DVec3, v: DVec3, l: DVec3, xdir: DVec3, ax: f64, ay: f64) -> f64 {
    let (n, v) = (normalize(n), normalize(v));
    let cos_theta_r = n.dot(v).clamp(0.0001, 1.0);
    let x = xdir / ax;
    let y = n.cross(xdir) / ay;
    let ln = normalize(l);
    let cos_theta_i = ln.dot(n);
    if cos_theta_i <= 0.0 {
        return 0.0;
    }
    let h = normalize(v + ln);
    let rho = (-2.0 * (x.dot(h).powi(2) + y.dot(h).powi(2)) / (1.0 + h.dot(n))).exp()
        / (cos_theta_i * cos_theta_r).sqrt();
    cos_theta_i * rho / (4.0 * ax * ay)
}

pub fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    if x < e0 {
        0.0
    } else if x >= e1 {
        1.0
    } else {
        let t = (x - e0) / (e1 - e0);
        t * t * (3.0 - 2.0 * t)
    }
}

/// Listing 9.13, one light.
pub fn glossy(n: DVec3, v: DVec3, l: DVec3, roughness: f64, sharpness: f64) -> f64 {
    let w = 0.18 * (1.0 - sharpness);
    smoothstep(0.72 - w, 0.72 + w, blinn(n, v, l, 1.0 / roughness))
}

/// Unpolarised Fresnel reflectance in the Cook-Torrance form
/// `F = ½ (g-c)²/(g+c)² (1 + ((c(g+c)-1)/(c(g-c)+1))²)`, `g² = n² + c² - 1`, `n = 1/eta`.
pub fn fresnel_kr(i: DVec3, nrm: DVec3, eta: f64) -> f64 {
    let c = normalize(i).dot(normalize(nrm)).abs();
    let n = 1.0 / eta;
    let g2 = n * n + c * c - 1.0;
    if g2 < 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// `|a - b| ≤ 1e-4 |b|` or `≤ 1e-6` absolute, the suite's agreement criterion.
pub fn agrees(a: f32, b: f64) -> bool {
    let diff = (a as f64 - b).abs();
    diff <= 1e-6 || diff <= 1e-4 * b.abs()
}

/// A small deterministic generator (SplitMix64), so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f64()
    }
    /// A uniformly distributed unit vector.
    pub fn unit(&mut self) -> Vec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z).as_vec3()
    }
    /// A unit vector in the hemisphere around `n`.
    pub fn hemisphere(&mut self, n: Vec3) -> Vec3 {
        let v = self.unit();
        if v.dot(n) < 0.0 {
            -v
        } else {
            v
        }
    }
}
