//! Compiled shaders run on small grids without the renderer (OSL's `testshade` idea): each
//! test compiles a shader from source, runs it, and compares with an `f64` reference.
use glam::{DMat4, Vec3};
use illume_shade::{light, LightCache, ShadingEnv, ShadingGrid};
use illume_sl::types::ShaderKind;
use illume_slvm::frontend::compile_source;
use illume_slvm::library::pick_shader;
use illume_slvm::{CompiledShader, Lights, SlInstance};
use std::sync::Arc;

fn compile(src: &str, kind: ShaderKind) -> CompiledShader {
    let program = compile_source("test.sl", src).unwrap_or_else(|e| panic!("{e}"));
    let id = pick_shader(&program, kind, "").expect("a shader of that kind");
    CompiledShader {
        program: Arc::new(program),
        id,
    }
}

fn run_surface(src: &str, grid: &mut ShadingGrid) {
    let shader = compile(src, ShaderKind::Surface);
    let (inst, warnings) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
    assert!(warnings.is_empty(), "{warnings:?}");
    let env = ShadingEnv::new();
    let cache = LightCache::run(&[], grid, &env);
    let lights = Lights::from_cache(&cache);
    inst.shade_surface(grid, &lights, &env);
}

#[test]
fn constant_surface_writes_ci_and_oi() {
    let mut g = ShadingGrid::new(3, 2);
    run_surface(
        "surface c() { Oi = Os; Ci = Os * color(0.25, 0.5, 1); }",
        &mut g,
    );
    for i in 0..g.len() {
        assert_eq!(g.ci[i], Vec3::new(0.25, 0.5, 1.0));
        assert_eq!(g.oi[i], Vec3::ONE);
    }
}

/// A surface shader that sets only `Ci` leaves `Oi = Os`, as PRMan, BMRT and Aqsis start it
/// (Aqsis regression jobs Bug1664409 and Bug1741324 rely on it: with `Oi = 0` the sphere was
/// transparent and its front and back summed to twice the colour).
#[test]
fn oi_starts_as_os() {
    let mut g = ShadingGrid::new(3, 2);
    for (i, os) in g.os.iter_mut().enumerate() {
        *os = Vec3::new(1.0, 0.5, i as f32 / 8.0);
    }
    run_surface("surface c() { Ci = color(0.32); }", &mut g);
    for i in 0..g.len() {
        assert_eq!(g.ci[i], Vec3::splat(0.32));
        assert_eq!(g.oi[i], Vec3::new(1.0, 0.5, i as f32 / 8.0), "point {i}");
    }
}

#[test]
fn varying_if_writes_only_its_points() {
    let mut g = ShadingGrid::new(4, 1); // s = 0, 1/3, 2/3, 1
    run_surface(
        "surface c() { if (s > 0.5) Ci = 1; else Ci = color(0, 0.5, 0); }",
        &mut g,
    );
    let want = [0.0, 0.0, 1.0, 1.0];
    for (i, &w) in want.iter().enumerate() {
        assert_eq!(g.ci[i].x, w, "point {i}");
        assert_eq!(g.ci[i].y, if w == 1.0 { 1.0 } else { 0.5 });
    }
}

#[test]
fn plastic_matches_the_builtin_on_a_grid() {
    let src = r#"
surface plastic(float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1; color specularcolor = 1) {
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * specular(Nf, V, roughness));
}"#;
    let mut g = ShadingGrid::new(5, 5);
    for i in 0..g.len() {
        let (u, v) = (g.u[i], g.v[i]);
        g.p[i] = Vec3::new(u - 0.5, v - 0.5, 4.0);
        g.n[i] = Vec3::new(u - 0.5, v - 0.5, -1.0).normalize();
        g.ng[i] = g.n[i];
        g.cs[i] = Vec3::new(1.0, 0.5, 0.25);
    }
    g.set_incident_from_p(false);
    let (sun, _) = light("distantlight", &[], DMat4::IDENTITY).unwrap();
    let (amb, _) = light("ambientlight", &[], DMat4::IDENTITY).unwrap();
    let env = ShadingEnv::new();
    let lights = [&sun, &amb];
    let mut builtin = g.clone();
    let (plastic, _) = illume_shade::surface("plastic", &[]).unwrap();
    illume_shade::shade_surface(&plastic, &mut builtin, &lights, &env);
    let cache = LightCache::run(&lights, &g, &env);
    let view = Lights::from_cache(&cache);
    let (inst, _) = SlInstance::bind(compile(src, ShaderKind::Surface), &[], DMat4::IDENTITY);
    inst.shade_surface(&mut g, &view, &env);
    for i in 0..g.len() {
        let d = (g.ci[i] - builtin.ci[i]).abs().max_element();
        assert!(d < 1e-6, "point {i}: {:?} vs {:?}", g.ci[i], builtin.ci[i]);
    }
}

#[test]
fn a_runaway_loop_stops_and_the_shader_finishes() {
    let mut g = ShadingGrid::new(2, 2);
    run_surface(
        "surface c() { float x = 0; while (x >= 0) x += 1; Ci = color (1, 0, 0); }",
        &mut g,
    );
    assert!(g.ci.iter().all(|c| *c == Vec3::X));
}

#[test]
fn random_depends_on_the_point_not_its_grid_index() {
    let src = "surface r() { Ci = float random(); }";
    let shade_at = |z: f32| {
        let mut g = ShadingGrid::new(3, 3);
        for (i, p) in g.p.iter_mut().enumerate() {
            *p = Vec3::new(i as f32, 0.0, z);
        }
        run_surface(src, &mut g);
        g.ci
    };
    let (a, b, c) = (shade_at(1.0), shade_at(1.0), shade_at(2.0));
    assert_eq!(a, b, "repeatable");
    assert_ne!(a, c, "another grid gets other numbers");
    assert!(a.iter().all(|v| (0.0..1.0).contains(&v.x)));
    assert!(a.windows(2).any(|w| w[0] != w[1]), "varies over the grid");
}

/// Issue 18: a call to another renderer's extension (`bake`) compiles with a warning; running
/// it is an error reported through the renderer's warnings and the call gives 0 — but only
/// when a point reaches it.
#[test]
fn unknown_functions_are_an_error_only_when_reached() {
    let run = |src: &str| {
        let shader = compile(src, ShaderKind::Surface);
        let (inst, _) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
        let sink = illume_shade::WarnOnce::new();
        let mut env = ShadingEnv::new();
        env.warnings = Some(&sink);
        let mut g = ShadingGrid::new(2, 2);
        let cache = LightCache::run(&[], &g, &env);
        let lights = Lights::from_cache(&cache);
        inst.shade_surface(&mut g, &lights, &env);
        (g.ci.clone(), sink.messages())
    };
    let (ci, warnings) = run("surface c() { Ci = color (1, 0, 0) + bake(\"m.ptc\", s, t); }");
    assert!(ci.iter().all(|c| *c == Vec3::X), "{ci:?}");
    assert_eq!(
        warnings,
        ["shader `c`: error: call to unknown function `bake`; it returns 0"]
    );
    // Never reached (s never exceeds 1 on the grid): no error.
    let (_, warnings) = run("surface c() { Ci = 1; if (s > 2) Ci = bake(1); }");
    assert!(warnings.is_empty(), "{warnings:?}");
}

/// Every overload of the built-in table reaches an implementation through its `BuiltinId`
/// family: a call of each, written with arguments of that overload's types, runs without the
/// executor's "not implemented" error. `arraylength` is the one table entry the executor does
/// not implement yet (it returns 0 with that error).
#[test]
fn every_table_overload_is_dispatched_to_an_implementation() {
    use illume_sl::builtins::{all, Slot};
    use illume_sl::types::BaseType;
    let var = |b: BaseType, array: bool| match (b, array) {
        (BaseType::Float, false) => "vf",
        (BaseType::Color, false) => "vc",
        (BaseType::Point, false) => "vp",
        (BaseType::Vector, false) => "vv",
        (BaseType::Normal, false) => "vn",
        (BaseType::Matrix, false) => "vm",
        (BaseType::String, false) => "vs",
        (BaseType::Float, true) => "af",
        _ => "ac",
    };
    let bind = |s: Slot| match s {
        Slot::Fixed(b) => b,
        Slot::Generic | Slot::ContextReturn => BaseType::Color,
        Slot::Geometric => BaseType::Normal,
        Slot::Any => BaseType::Float,
    };
    let mut missing = Vec::new();
    for ov in all() {
        let args: Vec<&str> = ov
            .params
            .iter()
            .map(|p| var(bind(p.slot), p.array))
            .collect();
        let call = format!("{}({})", ov.name, args.join(", "));
        let ret = bind(ov.ret);
        let stmt = if ret == BaseType::Void {
            format!("{call};")
        } else {
            format!("{} r = {call};", ret.keyword())
        };
        // lightsource() may only be called inside illuminance; everything else runs at every
        // point, outside it.
        let body = if ov.name == "lightsource" {
            format!("illuminance (P) {{ {stmt} }}")
        } else {
            stmt
        };
        let src = format!(
            "surface c() {{ float vf = 0.5; color vc = 1; point vp = 0; vector vv = 1;
                normal vn = 1; matrix vm = 1; string vs = \"\"; float af[4] = {{1, 2, 3, 4}};
                color ac[4] = {{1, 1, 1, 1}}; {body} }}"
        );
        let shader = compile(&src, ShaderKind::Surface);
        let (inst, _) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
        let sink = illume_shade::WarnOnce::new();
        let mut env = ShadingEnv::new();
        env.warnings = Some(&sink);
        let mut g = ShadingGrid::new(3, 3);
        let (sun, _) = light("distantlight", &[], DMat4::IDENTITY).unwrap();
        let cache = LightCache::run(&[&sun], &g, &env);
        let lights = Lights::from_cache(&cache);
        inst.shade_surface(&mut g, &lights, &env);
        if sink
            .messages()
            .iter()
            .any(|m| m.contains("not implemented by the executor"))
        {
            missing.push(call);
        }
    }
    assert_eq!(missing, ["arraylength(af)"]);
}

// One noise: the built-in `dented` shader (illume-shade, native Rust) and SL `noise()` in the VM
// call the same function (`illume_core::noise`), so a built-in and its SL listing give the same
// pattern; a second noise in either would fail these comparisons.

/// A curved 9×7 grid spread over several noise cells, away from lattice points (where every
/// noise is 0.5 and a comparison would prove nothing).
fn noise_grid() -> ShadingGrid {
    let mut g = ShadingGrid::new(9, 7);
    for i in 0..g.len() {
        let (u, v) = (g.u[i], g.v[i]);
        g.p[i] = Vec3::new(3.1 * u - 1.37, 2.3 * v + 0.21, 4.0 + 0.7 * (u * v).sin());
        g.n[i] = Vec3::new(u - 0.5, v - 0.5, -1.0).normalize();
        g.ng[i] = g.n[i];
    }
    g.set_incident_from_p(false);
    g
}

#[test]
fn sl_noise_is_the_builtin_noise_bit_for_bit() {
    let shader = compile(
        "surface n() { Oi = 1; Ci = color(noise(P), noise(P * 2.5 + 0.3), 0); }",
        ShaderKind::Surface,
    );
    let (inst, warnings) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut g = noise_grid();
    let env = ShadingEnv::new();
    let cache = LightCache::run(&[], &g, &env);
    inst.shade_surface(&mut g, &Lights::from_cache(&cache), &env);
    let mut varied = 0;
    for i in 0..g.len() {
        let p = g.p[i];
        assert_eq!(g.ci[i].x, illume_shade::noise(p), "point {i} at {p}");
        assert_eq!(g.ci[i].y, illume_shade::noise(p * 2.5 + 0.3), "point {i}");
        varied += usize::from((g.ci[i].x - 0.5).abs() > 0.05);
    }
    assert!(varied > g.len() / 4, "only {varied} points away from 0.5");
}

#[test]
fn dented_listing_displaces_like_the_builtin() {
    // The RI companion's `dented`, written as the built-in documents it.
    let src = r#"
displacement dented(float Km = 1, power = 3, frequency = 1) {
    point Psh = transform("shader", P);
    float size = frequency, magnitude = 0, octave;
    for (octave = 0; octave < 6; octave += 1) {
        magnitude += abs(0.5 - noise(Psh * size)) / pow(2, octave);
        size *= 2;
    }
    P -= Km * pow(magnitude, power) * normalize(N);
    N = calculatenormal(P);
}"#;
    let params = [("Km", 0.15f32), ("frequency", 2.0)].map(|(n, v)| illume_rib::Param {
        name: format!("uniform float {n}"),
        value: illume_rib::Value::Floats(vec![v]),
    });
    let (inst, warnings) = SlInstance::bind(
        compile(src, ShaderKind::Displacement),
        &params,
        DMat4::IDENTITY,
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    let (builtin, warnings) = illume_shade::displacement("dented", &params).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let env = ShadingEnv::new();
    let before = noise_grid();
    let (mut sl, mut native) = (before.clone(), before.clone());
    inst.displace(&mut sl, &env);
    illume_shade::displace(&builtin, &mut native, &env);
    let mut moved = 0;
    for i in 0..before.len() {
        // Same noise; only the order of a few float operations differs (powf vs pow, P += a·N
        // vs P -= b·N), so the points agree to f32 rounding of the 4-unit coordinates.
        let (a, b) = (sl.p[i], native.p[i]);
        assert!((a - b).length() < 2e-6, "point {i}: SL {a} vs built-in {b}");
        moved += usize::from((b - before.p[i]).length() > 1e-4);
    }
    assert!(moved > before.len() / 2, "only {moved} points dented");
}

/// A height map `F(s, t) = a·s + b·t`, point-sampled at the footprint's first corner (the
/// point's own `s`, `t`), for `bump()`.
struct Ramp;

const RAMP: (f32, f32) = (0.05, -0.08);

impl illume_shade::TextureLookup for Ramp {
    fn texture(
        &self,
        _name: &str,
        _first: usize,
        _n: usize,
        st: [[f32; 2]; 4],
        _o: &illume_shade::TextureOptions,
    ) -> Option<[f32; 4]> {
        // The footprint's centre (the shaded point), as the texture cache filters about it.
        let centre = |c: usize| 0.25 * (st[0][c] + st[1][c] + st[2][c] + st[3][c]);
        let (s, t) = (centre(0), centre(1));
        Some([RAMP.0 * s + RAMP.1 * t; 4])
    }
    fn environment(
        &self,
        _: &str,
        _: usize,
        _: usize,
        _: [Vec3; 4],
        _: &illume_shade::TextureOptions,
    ) -> Option<[f32; 4]> {
        None
    }
    fn shadow(&self, _: &str, _: [Vec3; 4], _: &illume_shade::ShadowOptions) -> Option<f32> {
        None
    }
}

/// `bump()` (RI 3.1) and its RI 3.2 replacement `calculatenormal(P + F·normalize(N))` give the
/// same bumped normal on a plane, and both equal the closed form (the displaced plane's tangents
/// are (2, 0, F_s) and (0, 2, F_t)) within 1e-5: a linear height makes both difference schemes
/// exact, so what is left is f32 rounding.
#[test]
fn bump_tilts_the_normal_like_calculatenormal_of_the_displaced_point() {
    let (nu, nv) = (9, 9);
    let mut g = ShadingGrid::new(nu, nv);
    for i in 0..g.len() {
        let (s, t) = (g.u[i], g.v[i]);
        g.s[i] = s;
        g.t[i] = t;
        g.p[i] = Vec3::new(2.0 * s, 2.0 * t, 5.0);
        g.dpdu[i] = Vec3::new(2.0, 0.0, 0.0);
        g.dpdv[i] = Vec3::new(0.0, 2.0, 0.0);
        g.n[i] = Vec3::new(0.0, 0.0, 4.0); // dPds × dPdt
        g.ng[i] = g.n[i];
    }
    let shader = compile(
        "surface b() {
            normal Nb = normalize(N + bump(\"ramp\", N, dPdu, dPdv));
            float F = float texture(\"ramp\", s, t);
            normal Nc = normalize(calculatenormal(P + F * normalize(N)));
            Ci = color(xcomp(Nb), ycomp(Nb), zcomp(Nb));
            Oi = color(xcomp(Nc), ycomp(Nc), zcomp(Nc));
        }",
        ShaderKind::Surface,
    );
    let (inst, _) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
    let env = ShadingEnv {
        textures: Some(&Ramp),
        ..ShadingEnv::new()
    };
    let cache = LightCache::run(&[], &g, &env);
    let lights = Lights::from_cache(&cache);
    inst.shade_surface(&mut g, &lights, &env);
    for i in 0..g.len() {
        let (s, t) = (f64::from(g.s[i]), f64::from(g.t[i]));
        let (fs, ft) = (f64::from(RAMP.0), f64::from(RAMP.1));
        let exact = glam::DVec3::new(2.0, 0.0, fs)
            .cross(glam::DVec3::new(0.0, 2.0, ft))
            .normalize();
        let bumped = g.ci[i].as_dvec3();
        assert!(
            (bumped - exact).length() < 1e-5,
            "s {s} t {t}: bump {bumped} vs {exact}"
        );
        assert!(
            (g.oi[i].as_dvec3() - bumped).length() < 1e-5,
            "s {s} t {t}: calculatenormal {} vs bump {bumped}",
            g.oi[i]
        );
        // Not the flat normal: the ramp tilts it measurably.
        assert!(bumped.x < -0.02, "{bumped}");
    }
}
