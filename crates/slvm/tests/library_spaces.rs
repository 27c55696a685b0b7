//! Coordinate spaces the book shader libraries rely on, checked on a small grid against f64
//! closed forms: `transform("NDC", P)` (Advanced RenderMan's `reflections.h` flat reflection
//! maps, `woodblockprint.sl`), `vtransform("screen", v)`, a point given in `"screen"` space,
//! the Companion's `"eye"` space, and `clamp` with crossed bounds (ARman's ray marchers).
//! Before these fixes the projective transforms inverted a singular matrix and gave NaN.
use glam::{DMat4, Vec3};
use illume_core::spaces::CameraProjection;
use illume_shade::{LightCache, ShadingEnv, ShadingGrid};
use illume_sl::types::ShaderKind;
use illume_slvm::frontend::compile_source;
use illume_slvm::library::pick_shader;
use illume_slvm::{CompiledShader, Lights, SlInstance};
use std::sync::Arc;

/// A 64×48 camera with a 40° field of view: the screen window is `[-4/3, 4/3] × [-1, 1]`.
fn projection() -> CameraProjection {
    CameraProjection {
        perspective_scale: Some(illume_core::spaces::perspective_scale(40.0)),
        screen_window: [-4.0 / 3.0, 4.0 / 3.0, -1.0, 1.0],
        xres: 64,
        yres: 48,
    }
}

fn env<'a>() -> ShadingEnv<'a> {
    let p = projection();
    let mut env = ShadingEnv::new();
    env.screen_from_camera = p.screen_from_camera();
    env.ndc_from_camera = p.ndc_from_camera();
    env.raster_from_camera = p.raster_from_camera();
    env.clipping = (0.5, f32::INFINITY);
    env
}

/// Runs surface `src` on a 3×2 grid of camera-space points `P = (s - 0.5, t - 0.5, 2 + s)`;
/// returns the grid (its `Ci`). The shader must run without a run-time warning.
fn shade(src: &str) -> ShadingGrid {
    let program = compile_source("test.sl", src).unwrap_or_else(|e| panic!("{e}"));
    let id = pick_shader(&program, ShaderKind::Surface, "").expect("a surface");
    let shader = CompiledShader {
        program: Arc::new(program),
        id,
    };
    let (inst, warnings) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut g = ShadingGrid::new(3, 2);
    for i in 0..g.len() {
        let (s, t) = (g.s[i], g.t[i]);
        g.p[i] = Vec3::new(s - 0.5, t - 0.5, 2.0 + s);
        g.dpdu[i] = Vec3::new(0.3, 0.1, 0.2);
    }
    let sink = illume_shade::WarnOnce::new();
    let mut env = env();
    env.warnings = Some(&sink);
    let cache = LightCache::run(&[], &g, &env);
    inst.shade_surface(&mut g, &Lights::from_cache(&cache), &env);
    // No run-time problem either (an unknown space is a warning and is taken as current).
    assert!(sink.messages().is_empty(), "{:?}", sink.messages());
    g
}

fn close(got: Vec3, want: [f64; 3], what: &str) {
    for (g, w) in got.to_array().iter().zip(want) {
        assert!(
            (f64::from(*g) - w).abs() < 1e-4 * w.abs().max(1.0),
            "{what}: got {got}, want {want:?}"
        );
    }
}

#[test]
fn transform_to_ndc_and_raster_is_the_projection_of_p() {
    let g = shade(r#"surface t(float which = 0) { Ci = color(transform("NDC", P)); }"#);
    let r = shade(r#"surface t(float which = 0) { Ci = color(transform("raster", P)); }"#);
    let d = illume_core::spaces::perspective_scale(40.0);
    let [l, rt, b, top] = projection().screen_window;
    for i in 0..g.len() {
        let p = g.p[i].as_dvec3();
        let (sx, sy) = (d * p.x / p.z, d * p.y / p.z);
        let (nx, ny) = ((sx - l) / (rt - l), (top - sy) / (top - b));
        // Screen depth is PRMan's: 0 at the near plane (0.5), 1 at an infinite far plane.
        let depth = (p.z - 0.5) / p.z;
        close(g.ci[i], [nx, ny, depth], "NDC");
        close(r.ci[i], [nx * 64.0, ny * 48.0, depth], "raster");
    }
}

#[test]
fn vtransform_to_screen_scales_by_the_perspective_factor() {
    let g = shade(r#"surface t() { Ci = color(vtransform("screen", dPdu)); }"#);
    let d = illume_core::spaces::perspective_scale(40.0);
    for i in 0..g.len() {
        let v = g.dpdu[i].as_dvec3();
        // The upper 3×3 of the projection: (d·x, d·y, z) for an infinite far plane.
        close(g.ci[i], [d * v.x, d * v.y, v.z], "vtransform screen");
        assert!(g.ci[i].is_finite());
    }
}

#[test]
fn a_point_given_in_screen_space_comes_back_to_camera_space() {
    // transform("screen", P) then `point "screen" (…)` back: P again (the inverse exists).
    let g = shade(
        r#"surface t() { point S = transform("screen", P);
           Ci = color(point "screen" (xcomp(S), ycomp(S), zcomp(S))); }"#,
    );
    for i in 0..g.len() {
        let p = g.p[i].as_dvec3();
        close(g.ci[i], [p.x, p.y, p.z], "screen round trip");
    }
}

#[test]
fn eye_space_is_camera_space() {
    let g =
        shade(r#"surface t() { Ci = color(point "eye" (0, 1, 0)) + color(transform("eye", P)); }"#);
    for i in 0..g.len() {
        let p = g.p[i].as_dvec3();
        close(g.ci[i], [p.x, 1.0 + p.y, p.z], "eye");
    }
}

#[test]
fn clamp_with_crossed_bounds_keeps_a_ray_march_moving() {
    // cellclouds.sl: `ss = clamp(ss, 0.005, end - d)` once d has reached end. The loop below
    // ends after a handful of steps; with a zero step it would hit the runaway-loop guard.
    let g = shade(
        r#"surface t() {
            float d = 0, end = 0.02, ss = 0.1, steps = 0;
            while (d <= end) { ss = clamp(ss, 0.005, end - d); d += ss; steps += 1; }
            Ci = color(steps, clamp(0.003, 0.005, 0), clamp(0.1, 0.005, 0));
        }"#,
    );
    for i in 0..g.len() {
        // Steps: 0.02 (to end); 0 (0.02 is above the upper bound end - d = 0); then 0 is
        // below the lower bound, so 0.005, past the end: three. `min(max(ss, 0.005), end - d)`
        // gives 0 forever.
        assert_eq!(g.ci[i], Vec3::new(3.0, 0.005, 0.0), "point {i}");
    }
}
