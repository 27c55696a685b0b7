//! Grid-level tests (like OSL's testshade): whole surfaces shaded on a grid over a unit sphere
//! under one distantlight, compared per point with the closed forms.
// Grids are parallel arrays: index loops read more clearly than zips of five iterators.
#![allow(clippy::needless_range_loop)]

use glam::{DMat4, Vec3};
use illume_rib::{Param, Value};
use illume_shade::{light, shade_surface, surface, Light, ShadingEnv, ShadingGrid, SpecularModel};

fn floats(name: &str, v: &[f32]) -> Param {
    Param {
        name: name.to_string(),
        value: Value::Floats(v.to_vec()),
    }
}

/// The camera-facing hemisphere of a unit sphere at (0,0,5), seen orthographically.
fn sphere_grid(nu: usize, nv: usize) -> ShadingGrid {
    let mut g = ShadingGrid::new(nu, nv);
    let centre = Vec3::new(0.0, 0.0, 5.0);
    for iv in 0..nv {
        for iu in 0..nu {
            let k = iv * nu + iu;
            let phi = (iu as f32 + 0.5) / nu as f32 * std::f32::consts::TAU;
            let theta = (iv as f32 + 0.5) / nv as f32 * std::f32::consts::FRAC_PI_2;
            let n = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                -theta.cos(),
            );
            g.p[k] = centre + n;
            g.n[k] = n;
            g.ng[k] = n;
            g.dpdu[k] = Vec3::new(-phi.sin(), phi.cos(), 0.0);
            g.dpdv[k] = Vec3::new(
                theta.cos() * phi.cos(),
                theta.cos() * phi.sin(),
                theta.sin(),
            );
            g.cs[k] = Vec3::new(1.0, 0.5, 0.25);
        }
    }
    g.set_incident_from_p(true);
    g
}

const LIGHT_TRAVEL: Vec3 = Vec3::new(0.3, -0.5, 1.0);

fn distant() -> Light {
    let params = [
        floats("intensity", &[1.5]),
        floats("from", &[0.0, 0.0, 0.0]),
        floats("to", &LIGHT_TRAVEL.to_array()),
    ];
    light("distantlight", &params, DMat4::IDENTITY).unwrap().0
}

fn toward_light() -> Vec3 {
    (-LIGHT_TRAVEL).normalize()
}

fn assert_close(got: Vec3, want: Vec3, what: &str) {
    assert!(
        (got - want).abs().max_element() <= 1e-5 * want.abs().max_element().max(1.0),
        "{what}: {got} vs {want}"
    );
}

fn shade(name: &str, params: &[Param], model: SpecularModel) -> ShadingGrid {
    let (s, warnings) = surface(name, params).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut g = sphere_grid(24, 16);
    let l = distant();
    let env = ShadingEnv {
        specular_model: model,
        ..ShadingEnv::new()
    };
    shade_surface(&s, &mut g, &[&l], &env);
    g
}

#[test]
fn matte_sphere_is_kd_cos_theta() {
    let g = shade("matte", &[floats("Kd", &[0.7])], SpecularModel::Blinn);
    let mut lit = 0;
    for k in 0..g.len() {
        let cos = g.n[k].dot(toward_light()).max(0.0);
        lit += (cos > 0.0) as usize;
        assert_close(g.ci[k], g.cs[k] * 0.7 * 1.5 * cos, "matte");
        assert_eq!(g.oi[k], Vec3::ONE);
    }
    assert!(
        lit > g.len() / 4 && lit < g.len(),
        "the terminator crosses the grid"
    );
}

fn plastic_closed_form(g: &ShadingGrid, k: usize, kd: f32, ks: f32, exponent: f32) -> Vec3 {
    let l = toward_light();
    let cos = g.n[k].dot(l);
    if cos < 0.0 {
        return Vec3::ZERO;
    }
    let v = Vec3::new(0.0, 0.0, -1.0);
    let h = (l + v).normalize();
    let spec = g.n[k].dot(h).max(0.0).powf(exponent);
    1.5 * (g.cs[k] * kd * cos + Vec3::splat(ks * spec))
}

#[test]
fn plastic_sphere_is_kd_cos_plus_blinn_in_both_specular_models() {
    let params = [
        floats("Kd", &[0.6]),
        floats("Ks", &[0.4]),
        floats("roughness", &[0.05]),
    ];
    let blinn = shade("plastic", &params, SpecularModel::Blinn);
    let prman = shade("plastic", &params, SpecularModel::PrMan);
    let mut highlight = 0.0f32;
    for k in 0..blinn.len() {
        assert_close(
            blinn.ci[k],
            plastic_closed_form(&blinn, k, 0.6, 0.4, 1.0 / 0.05),
            "blinn",
        );
        assert_close(
            prman.ci[k],
            plastic_closed_form(&prman, k, 0.6, 0.4, 8.0 / 0.05),
            "prman",
        );
        highlight = highlight.max(blinn.ci[k].z - prman.ci[k].z);
    }
    assert!(
        highlight > 0.05,
        "the two models differ visibly ({highlight})"
    );
}

#[test]
fn oren_nayar_with_zero_sigma_equals_matte_on_the_grid() {
    let on = shade(
        "orennayar",
        &[floats("Kd", &[0.7]), floats("roughness", &[0.0])],
        SpecularModel::Blinn,
    );
    let matte = shade("matte", &[floats("Kd", &[0.7])], SpecularModel::Blinn);
    for k in 0..on.len() {
        assert_close(on.ci[k], matte.ci[k], "orennayar σ=0");
    }
    let rough = shade(
        "orennayar",
        &[floats("Kd", &[0.7]), floats("roughness", &[0.5])],
        SpecularModel::Blinn,
    );
    assert!((0..on.len()).any(|k| (rough.ci[k] - on.ci[k]).length() > 1e-2));
}

#[test]
fn premultiplied_by_opacity_and_overridden_by_primitive_variables() {
    let (s, _) = surface("matte", &[floats("uniform float Kd", &[0.7])]).unwrap();
    let mut g = sphere_grid(8, 8);
    g.os.iter_mut().for_each(|o| *o = Vec3::splat(0.5));
    let kd: Vec<f32> = (0..g.len()).map(|k| k as f32 / g.len() as f32).collect();
    g.set_var("Kd", 1, kd.clone());
    let l = distant();
    shade_surface(&s, &mut g, &[&l], &ShadingEnv::new());
    for k in 0..g.len() {
        let cos = g.n[k].dot(toward_light()).max(0.0);
        assert_close(g.ci[k], 0.5 * g.cs[k] * kd[k] * 1.5 * cos, "varying Kd");
        assert_eq!(g.oi[k], Vec3::splat(0.5));
    }
}

#[test]
fn every_surface_shades_a_degenerate_grid_without_nan() {
    let mut g = sphere_grid(6, 4);
    g.n[0] = Vec3::ZERO;
    g.i[1] = Vec3::ZERO;
    g.ng[2] = Vec3::ZERO;
    g.dpdu[3] = Vec3::ZERO;
    g.p[4] = Vec3::ZERO; // at the pointlight
    let pl = light("pointlight", &[], DMat4::IDENTITY).unwrap().0;
    let sl = light("spotlight", &[], DMat4::IDENTITY).unwrap().0;
    let dl = distant();
    for &name in illume_shade::Surface::names() {
        let (s, _) = surface(name, &[floats("roughness", &[0.0])])
            .unwrap_or_else(|_| surface(name, &[]).unwrap());
        let mut g = g.clone();
        shade_surface(&s, &mut g, &[&pl, &sl, &dl], &ShadingEnv::new());
        for k in 0..g.len() {
            assert!(
                g.ci[k].is_finite() && g.ci[k].min_element() >= 0.0,
                "{name}: Ci {} at {k}",
                g.ci[k]
            );
        }
    }
}

#[test]
fn nonfinite_inputs_are_repaired_and_counted() {
    let (s, _) = surface("matte", &[]).unwrap();
    let mut g = sphere_grid(4, 4);
    g.os[0] = Vec3::splat(f32::NAN);
    g.cs[1] = Vec3::splat(f32::INFINITY);
    let l = distant();
    let stats = shade_surface(&s, &mut g, &[&l], &ShadingEnv::new());
    assert_eq!(stats.nonfinite, 2);
    assert_eq!((g.oi[0], g.ci[0]), (Vec3::ONE, Vec3::ZERO));
    assert!(g.ci.iter().all(|c| c.is_finite()));
}

#[test]
fn derivatives_and_area_by_grid_differences() {
    // P = (2u, 3v², 1): Du(P) = (2,0,0), Dv(P) ≈ (0, 6v, 0) by forward differences.
    let mut g = ShadingGrid::new(5, 5);
    for k in 0..g.len() {
        g.p[k] = Vec3::new(2.0 * g.u[k], 3.0 * g.v[k] * g.v[k], 1.0);
    }
    let (pu, pv) = (g.deriv_u(&g.p), g.deriv_v(&g.p));
    let area = g.area();
    for k in 0..g.len() {
        assert!((pu[k] - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5);
        let (v0, v1) = if g.v[k] < 1.0 {
            (g.v[k], g.v[k] + g.dv)
        } else {
            (g.v[k] - g.dv, g.v[k])
        };
        let want = 3.0 * (v1 * v1 - v0 * v0) / g.dv;
        assert!((pv[k].y - want).abs() < 1e-4, "{} vs {want}", pv[k].y);
        assert!((area[k] - 2.0 * want * g.du * g.dv).abs() < 1e-5);
    }
    let s = g.deriv_u(&g.s);
    assert!(s.iter().all(|&x| (x - 1.0).abs() < 1e-5));
}

#[test]
fn thinplastic_is_lit_from_behind_through_diffuse_of_minus_nf() {
    // The light travels toward the camera (-z) and reaches the back of the camera-facing sphere.
    let back = light(
        "distantlight",
        &[floats("to", &[0.0, 0.0, -1.0])],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let (s, _) = surface("thinplastic", &[floats("Kt", &[0.3])]).unwrap();
    let mut g = sphere_grid(12, 8);
    shade_surface(&s, &mut g, &[&back], &ShadingEnv::new());
    for k in 0..g.len() {
        // Nf faces the camera; -Nf faces the light: cos = -Nf·L = -n·(0,0,1)... = -n.z.
        let cos = (-g.n[k].z).max(0.0);
        assert_close(g.ci[k], g.cs[k] * 0.3 * cos, "thinplastic backlight");
    }
    let (p, _) = surface("plastic", &[]).unwrap();
    let mut g = sphere_grid(12, 8);
    shade_surface(&p, &mut g, &[&back], &ShadingEnv::new());
    assert!(
        g.ci.iter().all(|&c| c == Vec3::ZERO),
        "plastic ignores lights behind"
    );
}

#[test]
fn metals_scale_specular_by_the_base_colour() {
    let l = distant();
    for (name, kd) in [("metal", 0.0f32), ("roughmetal", 0.1)] {
        let (s, _) = surface(name, &[floats("roughness", &[0.3])]).unwrap();
        let mut g = sphere_grid(12, 8);
        shade_surface(&s, &mut g, &[&l], &ShadingEnv::new());
        for k in 0..g.len() {
            let lv = toward_light();
            let cos = g.n[k].dot(lv);
            let want = if cos < 0.0 {
                Vec3::ZERO
            } else {
                let h = (lv + Vec3::NEG_Z).normalize();
                // The default specular model: PRMan's exponent 8/roughness.
                1.5 * g.cs[k] * (kd * cos + g.n[k].dot(h).max(0.0).powf(8.0 / 0.3))
            };
            assert_close(g.ci[k], want, name);
        }
    }
}

#[test]
fn wardanisotropic_defaults_xdir_to_dpdu_and_rotating_it_changes_the_highlight() {
    let l = distant();
    let (s, _) = surface("wardanisotropic", &[]).unwrap();
    let mut a = sphere_grid(16, 8);
    shade_surface(&s, &mut a, &[&l], &ShadingEnv::new());
    // Per point, the grid equals Kd·diffuse + Ks·ward with xdir = normalize(dPdu).
    for k in 0..a.len() {
        let lv = toward_light();
        let n = a.n[k];
        let x = (a.dpdu[k] - n * n.dot(a.dpdu[k])).normalize();
        let cos = n.dot(lv).max(0.0);
        let w = illume_shade::ward_anisotropic_term(n, Vec3::NEG_Z, lv, x, 0.15, 0.5);
        assert_close(
            a.ci[k],
            1.5 * a.cs[k] * (0.1 * cos + if cos > 0.0 { w } else { 0.0 }),
            "ward",
        );
    }
    let (t, _) = surface(
        "wardanisotropic",
        &[floats("vector xdir", &[0.0, 0.0, 1.0])],
    )
    .unwrap();
    let mut b = sphere_grid(16, 8);
    shade_surface(&t, &mut b, &[&l], &ShadingEnv::new());
    assert!((0..a.len()).any(|k| (a.ci[k] - b.ci[k]).length() > 1e-2));
}

#[test]
fn specular_model_option_values() {
    assert_eq!(
        SpecularModel::from_option("prman"),
        Some(SpecularModel::PrMan)
    );
    assert_eq!(
        SpecularModel::from_option("BMRT"),
        Some(SpecularModel::PrMan)
    );
    assert_eq!(
        SpecularModel::from_option("blinn"),
        Some(SpecularModel::Blinn)
    );
    assert_eq!(SpecularModel::from_option("phong"), None);
    assert_eq!(SpecularModel::default(), SpecularModel::PrMan);
    assert_eq!(SpecularModel::PrMan.exponent(0.1), 80.0);
}
