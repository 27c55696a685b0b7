//! `shadow()` without a `"bias"` parameter takes the frame's `Option "shadow" "bias"` (PRMan's
//! option, 0.225 by default as in PRMan and Aqsis), handed over as `ShadingEnv::shadow_bias`;
//! an explicit `"bias"` wins. The texture system here answers every shadow lookup with the
//! bias it was given, so `Ci` shows which bias the call used.
use glam::{DMat4, Vec3};
use illume_shade::{
    LightCache, ShadingEnv, ShadingGrid, ShadowOptions, TextureLookup, TextureOptions,
};
use illume_sl::types::ShaderKind;
use illume_slvm::frontend::compile_source;
use illume_slvm::library::pick_shader;
use illume_slvm::{CompiledShader, Lights, SlInstance};
use std::sync::Arc;

struct EchoBias;

impl TextureLookup for EchoBias {
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
    fn shadow(&self, _: &str, _: [Vec3; 4], o: &ShadowOptions) -> Option<f32> {
        Some(o.bias)
    }
}

/// `Ci` of `src` at the first point with the frame's shadow bias `bias`.
fn ci(src: &str, bias: Option<f32>) -> f32 {
    let program = compile_source("test.sl", src).unwrap_or_else(|e| panic!("{e}"));
    let id = pick_shader(&program, ShaderKind::Surface, "").expect("a surface");
    let shader = CompiledShader {
        program: Arc::new(program),
        id,
    };
    let (inst, warnings) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut g = ShadingGrid::new(2, 2);
    let textures = EchoBias;
    let mut env = ShadingEnv::new();
    env.textures = Some(&textures);
    if let Some(b) = bias {
        env.shadow_bias = b;
    }
    let cache = LightCache::run(&[], &g, &env);
    let lights = Lights::from_cache(&cache);
    inst.shade_surface(&mut g, &lights, &env);
    g.ci[0].x
}

#[test]
fn shadow_without_bias_uses_the_frame_option() {
    let plain = "surface s() { Ci = color(shadow(\"m.shd\", P)); }";
    assert_eq!(ci(plain, Some(0.5)), 0.5);
    assert_eq!(ci(plain, Some(0.04)), 0.04);
    // PRMan's and Aqsis's default.
    assert_eq!(ci(plain, None), 0.225);
    let explicit = "surface s() { Ci = color(shadow(\"m.shd\", P, \"bias\", 0.02)); }";
    assert_eq!(ci(explicit, Some(0.5)), 0.02);
}
