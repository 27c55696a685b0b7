//! Reflection maps (Listings 9.5–9.9), painted textures and the standard surfaces' closed forms,
//! through a mock `TextureLookup` that reports what it was asked.
// Grids are parallel arrays: index loops read more clearly than zips of five iterators.
#![allow(clippy::needless_range_loop)]

use glam::{DMat4, DVec3, Vec3};
use illume_rib::{Param, Value};
use illume_shade::{
    displace, displacement, fresnel, raysphere, shade_surface, surface, ShadingEnv, ShadingGrid,
    ShadowOptions, TextureLookup, TextureOptions, WarnOnce,
};
use std::sync::Mutex;

fn floats(name: &str, v: &[f32]) -> Param {
    Param {
        name: name.to_string(),
        value: Value::Floats(v.to_vec()),
    }
}

fn string(name: &str, v: &str) -> Param {
    Param {
        name: name.to_string(),
        value: Value::Strings(vec![v.to_string()]),
    }
}

/// Environment: colour = first direction / 100, alpha (channel 3) = 0.5.
/// Texture: colour = (s, t, 0.5) of the first corner, alpha 0.25. Records (name, first, fill).
#[derive(Default)]
struct Probe {
    calls: Mutex<Vec<(String, usize, f32)>>,
}

impl TextureLookup for Probe {
    fn texture(
        &self,
        name: &str,
        first: usize,
        n: usize,
        st: [[f32; 2]; 4],
        o: &TextureOptions,
    ) -> Option<[f32; 4]> {
        if name == "missing.tx" {
            return None;
        }
        self.calls
            .lock()
            .unwrap()
            .push((name.to_string(), first, o.fill));
        // The footprint's centre, as the texture cache filters about it (the corners are
        // centred on the shaded point).
        let centre = |c: usize| 0.25 * (st[0][c] + st[1][c] + st[2][c] + st[3][c]);
        let all = [centre(0), centre(1), 0.5, 0.25];
        let mut out = [0.0; 4];
        out[..n].copy_from_slice(&all[first..first + n]);
        Some(out)
    }
    fn environment(
        &self,
        name: &str,
        first: usize,
        n: usize,
        d: [Vec3; 4],
        o: &TextureOptions,
    ) -> Option<[f32; 4]> {
        if name == "missing.env" {
            return None;
        }
        self.calls
            .lock()
            .unwrap()
            .push((name.to_string(), first, o.fill));
        let all = [d[0].x / 100.0, d[0].y / 100.0, d[0].z / 100.0, 0.5];
        let mut out = [0.0; 4];
        out[..n].copy_from_slice(&all[first..first + n]);
        Some(out)
    }
    fn shadow(&self, _: &str, _: [Vec3; 4], _: &ShadowOptions) -> Option<f32> {
        None
    }
}

fn one_point(p: Vec3, n: Vec3, i: Vec3) -> ShadingGrid {
    let mut g = ShadingGrid::new(1, 1);
    g.p[0] = p;
    g.n[0] = n;
    g.ng[0] = n;
    g.i[0] = i;
    g
}

#[test]
fn raysphere_matches_the_quadratic() {
    // From inside: one hit ahead.
    let h = raysphere(Vec3::new(0.0, 0.0, 50.0), Vec3::X, 100.0, 1e-4);
    assert_eq!(h.count, 1);
    assert!((h.t0 as f64 - (100.0f64 * 100.0 - 50.0 * 50.0).sqrt()).abs() < 1e-3);
    // From outside toward the centre: two hits.
    let h = raysphere(Vec3::new(-300.0, 0.0, 0.0), Vec3::X, 100.0, 1e-4);
    assert_eq!((h.count, h.t0, h.t1), (2, 200.0, 400.0));
    // Missing and tangent rays.
    assert_eq!(
        raysphere(Vec3::new(0.0, 200.0, -300.0), Vec3::Z, 100.0, 1e-4).count,
        0
    );
    let h = raysphere(Vec3::new(0.0, 100.0, -300.0), Vec3::Z, 100.0, 1e-4);
    assert_eq!((h.count, h.t0), (1, 300.0));
    // Behind the ray: nothing.
    assert_eq!(
        raysphere(Vec3::new(-300.0, 0.0, 0.0), Vec3::NEG_X, 100.0, 1e-4).count,
        0
    );
}

#[test]
fn shinymetal_traces_the_finite_environment_sphere_in_its_space() {
    let probe = Probe::default();
    // World is camera translated: world origin at camera (0,0,10).
    let env = ShadingEnv {
        camera_from_world: DMat4::from_translation(DVec3::new(0.0, 0.0, 10.0)),
        textures: Some(&probe),
        ..ShadingEnv::new()
    };
    // A mirror at world (0,0,-50) facing the camera, 45° so I reflects to -x.
    let n = Vec3::new(-1.0, 0.0, -1.0).normalize();
    let g0 = one_point(Vec3::new(0.0, 0.0, -40.0), n, Vec3::Z);
    let params = [
        floats("Ka", &[0.0]),
        floats("Kd", &[0.0]),
        floats("Ks", &[0.0]),
        floats("Kr", &[1.0]),
        string("envname", "room.env"),
    ];
    let (s, w) = surface("shinymetal", &params).unwrap();
    assert!(w.is_empty(), "{w:?}");
    let mut g = g0.clone();
    shade_surface(&s, &mut g, &[], &env);
    // Ray from world (0,0,-50) along -x meets the radius-100 sphere at (-86.60, 0, -50).
    let want = Vec3::new(-(100.0f32 * 100.0 - 50.0 * 50.0).sqrt(), 0.0, -50.0) / 100.0;
    assert!((g.ci[0] - want).length() < 1e-4, "{} vs {want}", g.ci[0]);
    let calls = probe.calls.lock().unwrap().clone();
    assert!(
        calls.contains(&("room.env".to_string(), 3, 1.0)),
        "alpha via envname[3], fill 1: {calls:?}"
    );
    // RI 3.2 texturename: infinitely distant, direction only.
    let (s, _) = surface(
        "shinymetal",
        &[
            floats("Ka", &[0.0]),
            floats("Kd", &[0.0]),
            floats("Ks", &[0.0]),
            floats("Kr", &[1.0]),
            string("texturename", "room.env"),
        ],
    )
    .unwrap();
    let mut g = g0.clone();
    shade_surface(&s, &mut g, &[], &env);
    assert!(
        (g.ci[0] - Vec3::new(-0.01, 0.0, 0.0)).length() < 1e-5,
        "{}",
        g.ci[0]
    );
}

#[test]
fn ndc_envspace_uses_reflmap_at_the_points_ndc_position() {
    let probe = Probe::default();
    // NDC = (x/z, y/z) shifted: a projective map.
    let ndc = DMat4::from_cols_array(&[
        0.5, 0.0, 0.0, 0.0, //
        0.0, 0.5, 0.0, 0.0, //
        0.5, 0.5, 0.0, 1.0, //
        0.0, 0.0, 0.0, 0.0,
    ]);
    let env = ShadingEnv {
        ndc_from_camera: ndc,
        textures: Some(&probe),
        ..ShadingEnv::new()
    };
    let p = Vec3::new(1.0, -2.0, 4.0);
    let mut g = one_point(p, Vec3::NEG_Z, p);
    let params = [
        floats("Ka", &[0.0]),
        floats("Kd", &[0.0]),
        floats("Ks", &[0.0]),
        floats("Kr", &[0.5]),
        string("envname", "mirror.tx"),
        string("envspace", "NDC"),
    ];
    let (s, _) = surface("shinymetal", &params).unwrap();
    shade_surface(&s, &mut g, &[], &env);
    let (x, y) = (0.5 * 1.0 / 4.0 + 0.5, 0.5 * -2.0 / 4.0 + 0.5);
    assert!(
        (g.ci[0] - 0.5 * Vec3::new(x, y, 0.5)).length() < 1e-6,
        "{}",
        g.ci[0]
    );
    assert!(probe
        .calls
        .lock()
        .unwrap()
        .contains(&("mirror.tx".to_string(), 3, 1.0)));
}

#[test]
fn shinyplastic_weights_reflection_by_fresnel_and_diffuse_by_one_minus() {
    let probe = Probe::default();
    let env = ShadingEnv {
        textures: Some(&probe),
        ..ShadingEnv::new()
    };
    let n = Vec3::new(0.0, -0.6, -0.8);
    let i = Vec3::Z;
    let amb = illume_shade::light("ambientlight", &[], DMat4::IDENTITY)
        .unwrap()
        .0;
    let params = [
        floats("Ka", &[1.0]),
        floats("Kd", &[0.0]),
        floats("Ks", &[0.0]),
        floats("Kr", &[1.0]),
        string("envname", "room.env"),
        floats("envrad", &[1e6]),
    ];
    let (s, _) = surface("shinyplastic", &params).unwrap();
    let mut g = one_point(Vec3::ZERO, n, i);
    g.cs[0] = Vec3::new(0.2, 0.4, 0.6);
    shade_surface(&s, &mut g, &[&amb], &env);
    let f = fresnel(i, n, 1.0 / 1.5);
    let dir = f.r * 1e6; // far sphere: the hit is ≈ envrad · R
    let want = (1.0 - f.kr) * g.cs[0] + f.kr * dir / 100.0;
    assert!(
        (g.ci[0] - want).length() < 1e-3 * want.length(),
        "{} vs {want}",
        g.ci[0]
    );
    assert!(f.kr > 0.04 && f.kr < 0.2);
}

#[test]
fn missing_maps_warn_once_and_contribute_black() {
    let probe = Probe::default();
    let warnings = WarnOnce::new();
    let env = ShadingEnv {
        textures: Some(&probe),
        warnings: Some(&warnings),
        ..ShadingEnv::new()
    };
    let (s, _) = surface(
        "shinymetal",
        &[
            floats("Ka", &[0.0]),
            floats("Kd", &[0.0]),
            floats("Ks", &[0.0]),
            string("envname", "missing.env"),
        ],
    )
    .unwrap();
    let mut g = ShadingGrid::new(4, 4);
    shade_surface(&s, &mut g, &[], &env);
    shade_surface(&s, &mut g, &[], &env);
    assert!(g.ci.iter().all(|&c| c == Vec3::ZERO));
    assert_eq!(
        warnings.messages(),
        vec!["map `missing.env` not found; black".to_string()]
    );
    let (p, _) = surface("paintedplastic", &[string("texturename", "missing.tx")]).unwrap();
    let amb = illume_shade::light("ambientlight", &[], DMat4::IDENTITY)
        .unwrap()
        .0;
    shade_surface(&p, &mut g, &[&amb], &env);
    assert!(g.ci.iter().all(|&c| c == Vec3::ZERO));
    assert_eq!(warnings.messages().len(), 2);
}

#[test]
fn paintedplastic_multiplies_the_texture_into_the_diffuse_colour() {
    let probe = Probe::default();
    let env = ShadingEnv {
        textures: Some(&probe),
        ..ShadingEnv::new()
    };
    let amb = illume_shade::light("ambientlight", &[], DMat4::IDENTITY)
        .unwrap()
        .0;
    let (p, w) = surface(
        "paintedplastic",
        &[string("texturename", "grid.tx"), floats("Ka", &[0.5])],
    )
    .unwrap();
    assert!(w.is_empty());
    let mut g = ShadingGrid::new(3, 3);
    shade_surface(&p, &mut g, &[&amb], &env);
    for k in 0..g.len() {
        let want = 0.5 * Vec3::new(g.s[k], g.t[k], 0.5);
        assert!((g.ci[k] - want).length() < 1e-6, "{} vs {want}", g.ci[k]);
    }
}

#[test]
fn defaultsurface_and_constant_closed_forms() {
    let (d, _) = surface("defaultsurface", &[]).unwrap();
    let (c, _) = surface("constant", &[]).unwrap();
    let n = Vec3::new(0.0, 0.6, -0.8);
    let mut g = one_point(Vec3::ZERO, n * 3.0, Vec3::Z * 2.0);
    g.cs[0] = Vec3::new(1.0, 0.5, 0.25);
    g.os[0] = Vec3::splat(0.5);
    shade_surface(&d, &mut g, &[], &ShadingEnv::new());
    let want = 0.5 * g.cs[0] * (0.2 + 0.8 * 0.64);
    assert!((g.ci[0] - want).length() < 1e-6);
    shade_surface(&c, &mut g, &[], &ShadingEnv::new());
    assert_eq!(g.ci[0], 0.5 * g.cs[0]);
}

#[test]
fn surface_binding_reports_bad_parameters_and_unknown_names() {
    let params = [
        floats("Kd", &[0.1, 0.2]),
        floats("color Ks", &[1.0, 1.0, 1.0]),
        string("roughness", "rough"),
        floats("Kx", &[1.0]),
        floats("uniform color specularcolor", &[1.0, 0.0, 0.0]),
    ];
    let (s, w) = surface("plastic", &params).unwrap();
    assert_eq!(w.len(), 4, "{w:?}");
    for (warning, name) in w.iter().zip(["Kd", "Ks", "roughness", "Kx"]) {
        assert!(warning.contains(name), "{warning}");
    }
    assert_eq!(s.name(), "plastic");
    let err = surface("wood", &[]).unwrap_err();
    assert!(
        err.to_string().contains("wood") && err.to_string().contains("plastic"),
        "{err}"
    );
    assert!(displacement("dents", &[]).is_err());
}

#[test]
fn bumpy_moves_p_along_n_by_km_times_texture() {
    let probe = Probe::default();
    let env = ShadingEnv {
        textures: Some(&probe),
        ..ShadingEnv::new()
    };
    let (d, _) = displacement(
        "bumpy",
        &[floats("Km", &[2.0]), string("texturename", "bump.tx")],
    )
    .unwrap();
    let mut g = ShadingGrid::new(4, 4);
    for k in 0..g.len() {
        g.p[k] = Vec3::new(g.u[k], g.v[k], 1.0);
    }
    let before = g.p.clone();
    displace(&d, &mut g, &env);
    for k in 0..g.len() {
        // texture channel 0 of the probe is s: P moves by 2·s along N = -z.
        let want = before[k] + Vec3::new(0.0, 0.0, -2.0 * g.s[k]);
        assert!((g.p[k] - want).length() < 1e-6, "{} vs {want}", g.p[k]);
        assert!(g.n[k].is_finite() && g.n[k].dot(Vec3::NEG_Z) > 0.0);
    }
    // The plane tilts: z = 1 - 2u, so the normal is ∝ (-2, 0, -1) (facing the camera).
    let nn = g.n[5].normalize();
    assert!(
        (nn - Vec3::new(-2.0, 0.0, -1.0).normalize()).length() < 1e-5,
        "{nn}"
    );
}
