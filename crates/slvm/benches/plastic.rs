//! Compiled-shader time against the built-in Rust shader on the same grids: RI `plastic`
//! (Listing 9.1 with `specularcolor`) as Shading Language vs `illume_shade`'s, on 16×16 and
//! 64×64 grids lit by two distant lights and an ambient light. Both sides include running the
//! lights once per grid (the `LightCache`), as the renderer does.
//!
//! `cargo bench -p illume-slvm --bench plastic` prints, per grid size, the time per grid of
//! each and their ratio (the issue's target: SL within 2× of the built-in).
use glam::{DMat4, Vec3};
use illume_rib::{Param, Value};
use illume_shade::{light, shade_surface, surface, LightCache, ShadingEnv, ShadingGrid};
use illume_sl::types::ShaderKind;
use illume_slvm::frontend::compile_source;
use illume_slvm::library::pick_shader;
use illume_slvm::{CompiledShader, Lights, SlInstance};
use std::hint::black_box;
use std::sync::Arc;
use std::time::{Duration, Instant};

const PLASTIC: &str = r#"
surface plastic (float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1; color specularcolor = 1) {
    normal Nf = faceforward (normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * (Ka*ambient() + Kd*diffuse(Nf)) + specularcolor * Ks*specular(Nf, V, roughness));
}
"#;

fn grid(n: usize) -> ShadingGrid {
    let mut g = ShadingGrid::new(n, n);
    for i in 0..g.len() {
        let (u, v) = (g.u[i], g.v[i]);
        g.p[i] = Vec3::new(u - 0.5, v - 0.5, 4.0 + u * v);
        g.n[i] = Vec3::new(u - 0.5, v - 0.5, -1.0);
        g.ng[i] = g.n[i];
        g.cs[i] = Vec3::new(0.8, 0.4, 0.2);
    }
    g.set_incident_from_p(false);
    g
}

fn floats(name: &str, v: &[f32]) -> Param {
    Param {
        name: name.into(),
        value: Value::Floats(v.to_vec()),
    }
}

/// Median of `runs` timings of `f`, each over enough repetitions to last ~20 ms.
fn time(mut f: impl FnMut()) -> Duration {
    let start = Instant::now();
    let mut reps = 0u32;
    while start.elapsed() < Duration::from_millis(20) {
        f();
        reps += 1;
    }
    let mut samples: Vec<Duration> = (0..9)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed() / reps
        })
        .collect();
    samples.sort();
    samples[samples.len() / 2]
}

fn main() {
    let lights = [
        light(
            "ambientlight",
            &[floats("intensity", &[0.1])],
            DMat4::IDENTITY,
        )
        .unwrap()
        .0,
        light(
            "distantlight",
            &[
                floats("from", &[-4.0, 5.0, -3.0]),
                floats("to", &[0.0, 0.0, 0.0]),
            ],
            DMat4::IDENTITY,
        )
        .unwrap()
        .0,
        light(
            "distantlight",
            &[
                floats("from", &[5.0, 1.0, -2.0]),
                floats("to", &[0.0, 0.0, 0.0]),
            ],
            DMat4::IDENTITY,
        )
        .unwrap()
        .0,
    ];
    let refs: Vec<_> = lights.iter().collect();
    let env = ShadingEnv::new();
    let (builtin, _) = surface("plastic", &[]).unwrap();
    let program = compile_source("plastic.sl", PLASTIC).unwrap();
    let id = pick_shader(&program, ShaderKind::Surface, "plastic").unwrap();
    let compiled = CompiledShader {
        program: Arc::new(program),
        id,
    };
    let (sl, _) = SlInstance::bind(compiled, &[], DMat4::IDENTITY);
    println!("grid     built-in/grid   SL/grid   SL/built-in");
    for n in [16, 64] {
        let base = grid(n);
        let tb = time(|| {
            let mut g = base.clone();
            shade_surface(&builtin, &mut g, &refs, &env);
            black_box(&g.ci);
        });
        let ts = time(|| {
            let mut g = base.clone();
            let cache = LightCache::run(&refs, &g, &env);
            let view = Lights::from_cache(&cache);
            sl.shade_surface(&mut g, &view, &env);
            black_box(&g.ci);
        });
        println!(
            "{n:>2}x{n:<2}   {:>10.1} µs  {:>8.1} µs   {:.2}x",
            tb.as_secs_f64() * 1e6,
            ts.as_secs_f64() * 1e6,
            ts.as_secs_f64() / tb.as_secs_f64()
        );
    }
}
