//! The Shading Language versions of RI's standard surfaces (the files of
//! `crates/sl/tests/shaders`) on a grid lit by an ambient light, two distant lights and a
//! spotlight whose cone leaves part of the grid dark:
//!
//! * `plastic`, `matte`, `metal` give exactly the bits of the shader's expression evaluated
//!   point by point in plain `f32` code here, with `illume_shade`'s `LightCache` sums for
//!   `ambient()`/`diffuse()`/`specular()`: the executor's speed work (shared lanes, in-place
//!   operators, grid-level light sums) must not change a bit of what the text says;
//! * all four, `paintedplastic` reading a mipmap made here, agree with the built-in Rust
//!   shaders to 1e-6 (the built-ins group the same sums differently: an ulp or so apart).
use glam::{DMat4, Vec3};
use illume_imageio::Image;
use illume_rib::{Param, Value};
use illume_shade::{
    faceforward, light, normalize_or_zero, shade_surface, surface, LightCache, ShadingEnv,
    ShadingGrid, SpecularModel,
};
use illume_sl::types::ShaderKind;
use illume_slvm::frontend::compile_source;
use illume_slvm::library::pick_shader;
use illume_slvm::{CompiledShader, Lights, SlInstance};
use illume_texture::{make_texture, MakeOptions, TextureCache};
use std::sync::Arc;

fn floats(name: &str, v: &[f32]) -> Param {
    Param {
        name: name.into(),
        value: Value::Floats(v.to_vec()),
    }
}

/// A curved, unevenly coloured 12×9 grid (normals not unit, some facing away from the eye).
fn grid() -> ShadingGrid {
    let mut g = ShadingGrid::new(12, 9);
    for i in 0..g.len() {
        let (u, v) = (g.u[i], g.v[i]);
        g.p[i] = Vec3::new(u - 0.5, v - 0.5, 4.0 + u * v);
        g.n[i] = Vec3::new(2.0 * u - 1.0, v - 0.5, if u > 0.8 { 0.5 } else { -1.0 });
        g.ng[i] = g.n[i];
        g.cs[i] = Vec3::new(0.8, 0.4 + 0.5 * u, 0.2);
        g.os[i] = Vec3::new(1.0, 0.9, 0.8 + 0.2 * v);
        g.s[i] = u;
        g.t[i] = v;
    }
    g.set_incident_from_p(false);
    g
}

/// `name`'s SL text evaluated at point `i` in `f32` (defaults; `roughness` 0.25), operand by
/// operand as written: `Ka*ambient()` is `splat(Ka) * ambient`, `a*b*c` is `(a*b)*c`.
fn by_the_text(
    name: &str,
    g: &ShadingGrid,
    lit: &LightCache,
    model: SpecularModel,
    i: usize,
) -> Vec3 {
    let nf = faceforward(normalize_or_zero(g.n[i]), g.i[i], g.ng[i]);
    let v = -normalize_or_zero(g.i[i]);
    let unit = normalize_or_zero(nf);
    let (os, cs) = (g.os[i], g.cs[i]);
    let splat = Vec3::splat;
    let amb = lit.ambient(i);
    match name {
        "plastic" => {
            let spec = lit.specular(i, unit, v, 0.25, model);
            let diff = lit.diffuse(i, unit);
            os * (cs * (splat(1.0) * amb + splat(0.5) * diff) + Vec3::ONE * splat(0.5) * spec)
        }
        "matte" => os * cs * (splat(1.0) * amb + splat(1.0) * lit.diffuse(i, unit)),
        "metal" => {
            let spec = lit.specular(i, unit, v, 0.25, model);
            os * cs * (splat(1.0) * amb + splat(1.0) * spec)
        }
        _ => unreachable!("only the shaders without textures"),
    }
}

#[test]
fn standard_surfaces_in_sl_give_their_texts_bits_and_the_builtins_values() {
    let dir = std::env::temp_dir().join(format!("illume-slvm-bits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut img = Image::new(32, 32, "rgb");
    for (k, px) in img.data.chunks_mut(3).enumerate() {
        let (x, y) = ((k % 32) as f32 / 32.0, (k / 32) as f32 / 32.0);
        px.copy_from_slice(&[0.5 + 0.5 * (x * 9.0).sin(), y, 1.0 - x * y]);
    }
    let map = dir.join("bits.tx");
    make_texture(&img, &map, &MakeOptions::default()).unwrap();
    let lights = [
        light(
            "ambientlight",
            &[floats("intensity", &[0.1])],
            DMat4::IDENTITY,
        ),
        light(
            "distantlight",
            &[floats("from", &[-4.0, 5.0, -3.0]), floats("to", &[0.0; 3])],
            DMat4::IDENTITY,
        ),
        light(
            "distantlight",
            &[floats("from", &[5.0, 1.0, -2.0]), floats("to", &[0.0; 3])],
            DMat4::IDENTITY,
        ),
        light(
            "spotlight",
            &[
                floats("from", &[0.0, 0.0, 0.0]),
                floats("to", &[0.3, 0.2, 4.0]),
                floats("coneangle", &[0.1]),
            ],
            DMat4::IDENTITY,
        ),
    ]
    .map(|l| l.unwrap().0);
    let refs: Vec<_> = lights.iter().collect();
    let cache = TextureCache::new(8 << 20);
    let mut env = ShadingEnv::new();
    env.textures = Some(&cache);
    let shaders = [
        ("plastic", include_str!("../../sl/tests/shaders/plastic.sl")),
        ("matte", include_str!("../../sl/tests/shaders/matte.sl")),
        ("metal", include_str!("../../sl/tests/shaders/metal.sl")),
        (
            "paintedplastic",
            include_str!("../../sl/tests/shaders/paintedplastic.sl"),
        ),
    ];
    let texturename = Param {
        name: "texturename".into(),
        value: Value::Strings(vec![map.to_string_lossy().into_owned()]),
    };
    for (name, source) in shaders {
        let params = match name {
            "paintedplastic" => vec![texturename.clone()],
            _ => vec![floats("roughness", &[0.25])],
        };
        let params = if name == "matte" { vec![] } else { params };
        let mut builtin = grid();
        let (b, warnings) = surface(name, &params).unwrap();
        assert!(warnings.is_empty(), "{name}: {warnings:?}");
        shade_surface(&b, &mut builtin, &refs, &env);

        let program = compile_source(&format!("{name}.sl"), source).unwrap();
        let id = pick_shader(&program, ShaderKind::Surface, name).unwrap();
        let compiled = CompiledShader {
            program: Arc::new(program),
            id,
        };
        let (sl, warnings) = SlInstance::bind(compiled, &params, DMat4::IDENTITY);
        assert!(warnings.is_empty(), "{name}: {warnings:?}");
        let mut g = grid();
        let lit = LightCache::run(&refs, &g, &env);
        sl.shade_surface(&mut g, &Lights::from_cache(&lit), &env);

        let dark = (0..g.len())
            .filter(|&i| builtin.ci[i] == Vec3::ZERO)
            .count();
        assert!(dark < g.len(), "{name}: the grid is lit somewhere");
        for i in 0..g.len() {
            let d = (g.ci[i] - builtin.ci[i]).abs().max_element();
            assert!(
                d < 1e-6,
                "{name}: Ci at point {i}: {} vs {}",
                g.ci[i],
                builtin.ci[i]
            );
            assert_eq!(g.oi[i], builtin.oi[i], "{name}: Oi at point {i}");
            if name != "paintedplastic" {
                let text = by_the_text(name, &g, &lit, env.specular_model, i);
                assert_eq!(g.ci[i], text, "{name}: Ci at point {i} bit for bit");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
