//! Light shaders (Listings 9.14–9.19) against their formulas, light categories and message
//! passing (§9.4, Listing 9.10), and the once-per-grid light cache.
// Grids are parallel arrays: index loops read more clearly than zips of five iterators.
#![allow(clippy::needless_range_loop)]

use glam::{DMat4, DVec3, Vec3};
use illume_rib::{Param, Value};
use illume_shade::{
    category_matches, light, shade_surface, surface, Illuminance, LightCache, ShadingEnv,
    ShadingGrid, ShadowOptions, SpecularModel, TextureLookup, TextureOptions, WarnOnce,
};
use std::sync::atomic::{AtomicUsize, Ordering};

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

/// A grid of the given points, normals facing -z, orthographic view.
fn grid_of(points: &[Vec3]) -> ShadingGrid {
    let mut g = ShadingGrid::new(points.len(), 1);
    g.p.copy_from_slice(points);
    g
}

fn run_one(
    name: &str,
    params: &[Param],
    camera_from_shader: DMat4,
    points: &[Vec3],
) -> (Vec<Vec3>, Vec<Vec3>, Vec<bool>) {
    let (l, w) = light(name, params, camera_from_shader).unwrap();
    assert!(w.is_empty(), "{w:?}");
    let g = grid_of(points);
    let cache = LightCache::run(&[&l], &g, &ShadingEnv::new());
    let s = &cache.lights[0].1;
    (s.l.clone(), s.cl.clone(), s.lit.clone())
}

#[test]
fn pointlight_falls_off_as_inverse_square_from_its_shader_space_origin() {
    let shader = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0));
    let pts = [
        Vec3::new(1.0, 2.0, 5.0),
        Vec3::new(4.0, 6.0, 3.0),
        Vec3::new(1.0, 2.0, 3.0),
    ];
    let params = [
        floats("intensity", &[8.0]),
        floats("lightcolor", &[1.0, 0.5, 0.25]),
    ];
    let (l, cl, _) = run_one("pointlight", &params, shader, &pts);
    assert_eq!(l[0], Vec3::new(0.0, 0.0, -2.0));
    assert!((cl[0] - Vec3::new(2.0, 1.0, 0.5)).length() < 1e-6);
    assert!((cl[1] - Vec3::new(8.0, 4.0, 2.0) / 25.0).length() < 1e-6);
    // The light at the shaded point: no direction, no light, no NaN.
    assert_eq!((l[2], cl[2]), (Vec3::ZERO, Vec3::ZERO));
}

#[test]
fn pointlight_very_close_saturates_instead_of_overflowing() {
    let (_, cl, _) = run_one(
        "pointlight",
        &[],
        DMat4::IDENTITY,
        &[Vec3::new(0.0, 0.0, 1e-30)],
    );
    assert!(cl[0].is_finite() && cl[0].x > 1e30);
}

#[test]
fn distantlight_is_parallel_and_unattenuated() {
    let params = [
        floats("from", &[0.0, 0.0, 0.0]),
        floats("to", &[0.0, 0.0, 2.0]),
        floats("intensity", &[0.5]),
    ];
    let rot = DMat4::from_rotation_y(std::f64::consts::FRAC_PI_2);
    let (l, cl, _) = run_one(
        "distantlight",
        &params,
        rot,
        &[Vec3::ZERO, Vec3::splat(100.0)],
    );
    // Shader +z rotated 90° about y is camera +x; light travels +x, so L points to -x.
    for k in 0..2 {
        assert!((l[k] - Vec3::NEG_X).length() < 1e-6, "{}", l[k]);
        assert_eq!(cl[k], Vec3::splat(0.5));
    }
}

/// Listing 9.17 in f64, for a point at distance `r` and angle `a` (radians) off the axis.
fn spot_reference(r: f64, a: f64, cone: f64, delta: f64, beam: f64) -> f64 {
    if a > cone {
        return 0.0;
    }
    let cosangle = a.cos();
    let (co, ci) = (cone.cos(), (cone - delta).cos());
    let ss = if cosangle < co {
        0.0
    } else if cosangle >= ci {
        1.0
    } else {
        let t = (cosangle - co) / (ci - co);
        t * t * (3.0 - 2.0 * t)
    };
    cosangle.powf(beam) / (r * r) * ss
}

#[test]
fn spotlight_matches_listing_across_the_cone_edge() {
    let (cone, delta, beam) = (30f64.to_radians(), 5f64.to_radians(), 2.0);
    let mut pts = Vec::new();
    let mut want = Vec::new();
    for k in 0..=70 {
        let a = (k as f64 * 0.5).to_radians();
        let r = 3.0;
        pts.push(DVec3::new(r * a.sin(), 0.0, r * a.cos()).as_vec3());
        want.push(spot_reference(r, a, cone, delta, beam));
    }
    let (_, cl, lit) = run_one("spotlight", &[], DMat4::IDENTITY, &pts);
    for k in 0..pts.len() {
        assert!(
            (cl[k].x as f64 - want[k]).abs() < 1e-6,
            "angle {}: {} vs {}",
            k as f64 * 0.5,
            cl[k].x,
            want[k]
        );
        assert_eq!(
            lit[k],
            (k as f64 * 0.5) <= 30.0 + 1e-9 || want[k] > 0.0,
            "cone cull at {}",
            k as f64 * 0.5
        );
    }
    assert!(
        want.iter().any(|&w| w > 0.0 && w < 0.9 / 9.0),
        "the smoothstep band is sampled"
    );
}

#[test]
fn light_parameters_are_checked_and_bad_ones_ignored() {
    let params = [
        floats("intensity", &[1.0, 2.0]),
        string("lightcolor", "red"),
        floats("color from", &[1.0, 2.0, 3.0]),
        floats("uniform float intensity", &[3.0]),
        floats("float uv", &[0.25]),
    ];
    let (l, w) = light("pointlight", &params, DMat4::IDENTITY).unwrap();
    assert_eq!(w.len(), 3, "{w:?}");
    assert!(w[0].contains("intensity") && w[1].contains("lightcolor") && w[2].contains("from"));
    assert_eq!(
        l.param("intensity"),
        Some(&illume_shade::ParamValue::Float(3.0))
    );
    assert_eq!(l.param("uv"), Some(&illume_shade::ParamValue::Float(0.25)));
    let err = light("moonlight", &[], DMat4::IDENTITY).unwrap_err();
    assert!(err.to_string().contains("moonlight") && err.to_string().contains("spotlight"));
}

#[test]
fn category_lists_and_exclusions() {
    assert!(category_matches("", "anything"));
    assert!(category_matches("uvlight", "key,uvlight"));
    assert!(category_matches("uvlight", "key, uvlight"));
    assert!(!category_matches("uvlight", "key,uvlights"));
    assert!(!category_matches("-uvlight", "key,uvlight"));
    assert!(category_matches("-uvlight", "key"));
    assert!(category_matches("-uvlight", ""));
    assert!(!category_matches("key", ""));
}

#[test]
fn illuminance_loops_honour_category_cone_nondiffuse_and_nonspecular() {
    let key = light(
        "distantlight",
        &[
            string("__category", "key,main"),
            floats("to", &[0.0, 0.0, 1.0]),
        ],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let spec_only = light(
        "distantlight",
        &[floats("__nondiffuse", &[1.0]), floats("intensity", &[2.0])],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let diff_only = light(
        "distantlight",
        &[floats("__nonspecular", &[1.0]), floats("intensity", &[4.0])],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let amb = light(
        "ambientlight",
        &[floats("intensity", &[0.125])],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let behind = light(
        "distantlight",
        &[
            floats("to", &[0.0, 0.0, -1.0]),
            floats("intensity", &[16.0]),
        ],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let g = grid_of(&[Vec3::new(0.0, 0.0, 5.0)]);
    let cache = LightCache::run(
        &[&key, &spec_only, &diff_only, &amb, &behind],
        &g,
        &ShadingEnv::new(),
    );
    let n = Vec3::NEG_Z;
    let v = Vec3::NEG_Z;
    // All lights shine head-on except `behind`, which is culled by the N, PI/2 cone.
    assert_eq!(cache.diffuse(0, n), Vec3::splat(1.0 + 4.0));
    assert_eq!(
        cache.specular(0, n, v, 0.1, SpecularModel::Blinn),
        Vec3::splat(1.0 + 2.0)
    );
    assert_eq!(cache.ambient(0), Vec3::splat(0.125));
    let mut seen = Vec::new();
    cache.illuminance(
        0,
        Illuminance {
            category: "main",
            cone: None,
        },
        |l, _, cl| seen.push((l.name().to_string(), cl)),
    );
    assert_eq!(seen, vec![("distantlight".to_string(), Vec3::ONE)]);
    let mut total = Vec3::ZERO;
    cache.illuminance(
        0,
        Illuminance {
            category: "-key",
            cone: None,
        },
        |_, _, cl| total += cl,
    );
    assert_eq!(
        total,
        Vec3::splat(2.0 + 4.0 + 16.0),
        "no cone: the back light counts, ambient never"
    );
    let mut total = Vec3::ZERO;
    cache.illuminance(
        0,
        Illuminance {
            category: "",
            cone: Some((n, 0.1)),
        },
        |_, _, cl| total += cl,
    );
    assert_eq!(total, Vec3::splat(1.0 + 2.0 + 4.0));
}

/// Counts shadow lookups and answers a fixed occlusion.
struct CountingShadows {
    calls: AtomicUsize,
    occlusion: Option<f32>,
}

impl TextureLookup for CountingShadows {
    fn texture(
        &self,
        _: &str,
        _: usize,
        _: usize,
        _: [[f32; 2]; 4],
        _: &TextureOptions,
    ) -> Option<[f32; 4]> {
        None
    }
    fn environment(
        &self,
        _: &str,
        _: usize,
        _: usize,
        _: [Vec3; 4],
        _: &TextureOptions,
    ) -> Option<[f32; 4]> {
        None
    }
    fn shadow(&self, name: &str, _: [Vec3; 4], o: &ShadowOptions) -> Option<f32> {
        assert_eq!(name, "key.sm");
        assert_eq!(
            (o.samples, o.blur, o.bias),
            (16.0, 0.01, 0.01),
            "Listing 9.19 defaults"
        );
        self.calls.fetch_add(1, Ordering::Relaxed);
        self.occlusion
    }
}

#[test]
fn shadowspot_runs_once_per_grid_for_diffuse_and_specular_and_attenuates() {
    let spot = light(
        "shadowspot",
        &[string("shadowname", "key.sm")],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let plain = light("spotlight", &[], DMat4::IDENTITY).unwrap().0;
    let pts: Vec<Vec3> = (0..12)
        .map(|k| Vec3::new(k as f32 * 0.05, 0.0, 4.0))
        .collect();
    let (plastic, _) = surface("plastic", &[]).unwrap();
    let tex = CountingShadows {
        calls: AtomicUsize::new(0),
        occlusion: Some(0.25),
    };
    let env = ShadingEnv {
        textures: Some(&tex),
        ..ShadingEnv::new()
    };
    let mut shadowed = grid_of(&pts);
    shade_surface(&plastic, &mut shadowed, &[&spot], &env);
    assert_eq!(
        tex.calls.load(Ordering::Relaxed),
        pts.len(),
        "one lookup per point, not per illuminance loop"
    );
    let mut lit = grid_of(&pts);
    shade_surface(&plastic, &mut lit, &[&plain], &env);
    for k in 0..pts.len() {
        assert!((shadowed.ci[k] - 0.75 * lit.ci[k]).length() < 1e-6);
        assert!(lit.ci[k].x > 0.0);
    }
}

#[test]
fn missing_shadow_map_warns_once_and_is_unshadowed() {
    let spot = light(
        "shadowspot",
        &[string("shadowname", "key.sm")],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let plain = light("spotlight", &[], DMat4::IDENTITY).unwrap().0;
    let tex = CountingShadows {
        calls: AtomicUsize::new(0),
        occlusion: None,
    };
    let warnings = WarnOnce::new();
    let env = ShadingEnv {
        textures: Some(&tex),
        warnings: Some(&warnings),
        ..ShadingEnv::new()
    };
    let g = grid_of(&[Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.1, 0.0, 4.0)]);
    let a = LightCache::run(&[&spot], &g, &env);
    let b = LightCache::run(&[&plain], &g, &env);
    assert_eq!(a.lights[0].1.cl, b.lights[0].1.cl);
    assert_eq!(
        warnings.messages(),
        vec!["shadow map `key.sm` not found; unshadowed".to_string()]
    );
}

#[test]
fn arealight_samples_illuminate_their_outside_hemisphere_with_inverse_square() {
    use illume_shade::AreaSample;
    let samples = vec![
        AreaSample {
            p: Vec3::new(0.0, 0.0, 0.0),
            n: Vec3::Z,
            weight: 0.5,
        },
        AreaSample {
            p: Vec3::new(0.0, 0.0, 10.0),
            n: Vec3::Z,
            weight: 0.5,
        },
    ];
    let l = light("arealight", &[floats("intensity", &[8.0])], DMat4::IDENTITY)
        .unwrap()
        .0
        .with_area_samples(samples);
    let g = grid_of(&[Vec3::new(0.0, 0.0, 2.0)]);
    let cache = LightCache::run(&[&l], &g, &ShadingEnv::new());
    assert_eq!(cache.lights.len(), 2, "one cache entry per sample");
    let (a, b) = (&cache.lights[0].1, &cache.lights[1].1);
    assert!(a.lit[0] && (a.cl[0] - Vec3::splat(0.5 * 8.0 / 4.0)).length() < 1e-6);
    assert_eq!(a.l[0], Vec3::new(0.0, 0.0, -2.0));
    assert!(
        !b.lit[0] && b.cl[0] == Vec3::ZERO,
        "the point is behind the second sample"
    );
}
