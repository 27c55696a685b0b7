//! Per-light reflection kernels: what one pass of an illuminance loop adds for one light, as a
//! scalar weight on `Cl`. The grid-level functions (`diffuse()`, `specular()`, the chapter's
//! `LocIllum*`) sum these over the cached lights (see `illuminance.rs`).
//!
//! Every kernel takes `f32` vectors as the grid stores them, with `L` unnormalised (as an
//! illuminance loop provides it), and evaluates in `f64`: the Blinn exponent `1/roughness` reaches
//! 10⁶, which multiplies the relative rounding of `N·H` by 10⁶ in `f32`, and the chapter's `acos`/
//! `tan` forms lose everything near 90°. Each result is finite and non-negative for any input.
use crate::shadingenv::SpecularModel;
use glam::{DVec3, Vec3};

fn unit(v: Vec3) -> DVec3 {
    let d = v.as_dvec3();
    let len = d.length();
    if len > 1e-30 && len.is_finite() {
        d / len
    } else {
        DVec3::ZERO
    }
}

fn unit64(d: DVec3) -> DVec3 {
    let len = d.length();
    if len > 1e-300 && len.is_finite() {
        d / len
    } else {
        DVec3::ZERO
    }
}

/// `x^e` for `x ∈ [0,1]`, `e ≥ 0` possibly infinite (roughness 0): the limit, never NaN.
fn pow01(x: f64, e: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        // 0^0 is the limit of x^e as e→0: the highlight covers the hemisphere.
        return if e == 0.0 { 1.0 } else { 0.0 };
    }
    x.min(1.0).powf(e)
}

/// The Blinn-Phong exponent for `roughness` under `model`; roughness ≤ 0 is a perfect mirror
/// (infinite exponent), NaN is treated the same way.
fn blinn_exponent(model: SpecularModel, roughness: f32) -> f64 {
    let r = roughness as f64;
    if r.is_nan() || r <= 0.0 {
        return f64::INFINITY;
    }
    match model {
        SpecularModel::Blinn => 1.0 / r,
        SpecularModel::PrMan => 8.0 / r,
    }
}

/// Lambert, Listing 9.10 `diffuse()`: `max(0, N · normalize(L))` (`N` unit).
pub fn diffuse_term(n: Vec3, l: Vec3) -> f32 {
    unit(n).dot(unit(l)).max(0.0) as f32
}

/// Blinn-Phong, Listing 9.10 `specular()`: `max(0, N·H)^e`, `H = normalize(normalize(L) + V)`,
/// `e = 1/roughness` (or `8/roughness` under [`SpecularModel::PrMan`]). `N`, `V` unit.
pub fn blinn_phong(n: Vec3, v: Vec3, l: Vec3, roughness: f32, model: SpecularModel) -> f32 {
    let h = unit64(unit(l) + unit(v));
    pow01(unit(n).dot(h), blinn_exponent(model, roughness)) as f32
}

/// RI `specularbrdf(L, N, V, roughness)`: one light's share of `specular()`.
pub fn specularbrdf(l: Vec3, n: Vec3, v: Vec3, roughness: f32, model: SpecularModel) -> f32 {
    blinn_phong(n, v, l, roughness, model)
}

/// RI `phong(N, V, size)` for one light: `max(0, R·normalize(L))^size`, `R = reflect(-V, N)`.
pub fn phong_term(n: Vec3, v: Vec3, l: Vec3, size: f32) -> f32 {
    let (n, v) = (unit(n), unit(v));
    let r = -v + 2.0 * v.dot(n) * n;
    pow01(r.dot(unit(l)), (size as f64).max(0.0)) as f32
}

/// Oren-Nayar, Listing 9.11, one light: `cosθi (A + B max(0, cos(φr-φi)) sin α tan β)` with
/// `σ = roughness`; 0 for a light below the horizon (the `illuminance(P, N, PI/2)` cone).
///
/// `sin α tan β` is evaluated from cosines (`α = max(θi, θr)` has the smaller cosine), so normal
/// incidence (`V = N`, where `V_perp_N` is undefined: φ term dropped) and 90° views stay finite;
/// the listing's `acos`/`tan` give `tan(π/2)` there. A view below the horizon counts as 90°.
pub fn oren_nayar_term(n: Vec3, v: Vec3, l: Vec3, roughness: f32) -> f32 {
    let (n, v, ln) = (unit(n), unit(v), unit(l));
    let cos_i = ln.dot(n).min(1.0);
    if cos_i.is_nan() || cos_i <= 0.0 {
        return 0.0;
    }
    let sigma2 = (roughness as f64) * (roughness as f64);
    let a = 1.0 - 0.5 * sigma2 / (sigma2 + 0.33);
    let b = 0.45 * sigma2 / (sigma2 + 0.09);
    let cos_r = v.dot(n).clamp(0.0, 1.0);
    let v_perp = unit64(v - n * v.dot(n));
    let l_perp = unit64(ln - n * cos_i);
    let cos_phi = v_perp.dot(l_perp).max(0.0);
    let (cos_alpha, cos_beta) = (cos_i.min(cos_r), cos_i.max(cos_r));
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let tan_beta = (1.0 - cos_beta * cos_beta).max(0.0).sqrt() / cos_beta;
    let b_term = if b > 0.0 {
        b * cos_phi * sin_alpha * tan_beta
    } else {
        0.0
    };
    (cos_i * (a + b_term)).max(0.0) as f32
}

/// Ward anisotropic, Listing 9.12, one light, *including* the final `1/(4 αx αy)`:
/// `cosθi · exp(-2((X·H)² + (Y·H)²)/(1 + H·N)) / sqrt(cosθi cosθr) / (4 αx αy)`,
/// `X = xdir/αx`, `Y = (N × xdir)/αy`, `cosθr = clamp(N·V, 1e-4, 1)` as the listing guards.
///
/// Further guards: roughness is clamped to ≥ 1e-4 (the listing divides by it), and `1 + H·N`
/// to ≥ 1e-12 (zero only when `H = -N`, a view from below).
pub fn ward_anisotropic_term(
    n: Vec3,
    v: Vec3,
    l: Vec3,
    xdir: Vec3,
    xroughness: f32,
    yroughness: f32,
) -> f32 {
    let (n, v, ln) = (unit(n), unit(v), unit(l));
    let cos_i = ln.dot(n);
    if cos_i.is_nan() || cos_i <= 0.0 {
        return 0.0;
    }
    let cos_i = cos_i.min(1.0);
    let ax = (xroughness as f64).max(1e-4);
    let ay = (yroughness as f64).max(1e-4);
    let xdir = xdir.as_dvec3();
    let cos_r = n.dot(v).clamp(1e-4, 1.0);
    let x = xdir / ax;
    let y = n.cross(xdir) / ay;
    let h = unit64(v + ln);
    let denom = (1.0 + h.dot(n)).max(1e-12);
    let xh = x.dot(h);
    let yh = y.dot(h);
    let rho = (-2.0 * (xh * xh + yh * yh) / denom).exp() / (cos_i * cos_r).sqrt();
    let c = cos_i * rho / (4.0 * ax * ay);
    if c.is_finite() {
        c.max(0.0) as f32
    } else {
        0.0
    }
}

/// Glossy, Listing 9.13, one light: `smoothstep(.72 - w, .72 + w, max(0, N·H)^(1/roughness))`,
/// `w = .18 (1 - sharpness)`. The exponent is always `1/roughness` (the listing's own choice,
/// independent of the `specular()` model).
pub fn glossy_term(n: Vec3, v: Vec3, l: Vec3, roughness: f32, sharpness: f32) -> f32 {
    let h = unit64(unit(l) + unit(v));
    let spec = pow01(
        unit(n).dot(h),
        blinn_exponent(SpecularModel::Blinn, roughness),
    );
    let w = 0.18 * (1.0 - sharpness as f64);
    smoothstep64(0.72 - w, 0.72 + w, spec) as f32
}

fn smoothstep64(e0: f64, e1: f64, x: f64) -> f64 {
    if x < e0 {
        0.0
    } else if x >= e1 {
        1.0
    } else {
        let t = (x - e0) / (e1 - e0);
        t * t * (3.0 - 2.0 * t)
    }
}
