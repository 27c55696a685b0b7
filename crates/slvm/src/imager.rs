//! Shading Language imager shaders (RI Spec 3.2 §4.1.4, table 11.6): run on a block of
//! finished pixels after the pixel filter, before exposure and quantization.
//!
//! The pixels are a grid of `width × height` points, one per pixel, rows first. What the shader
//! sees: `P` the pixel centre in raster space (`x + 0.5, y + 0.5, 0`, full-frame pixels, y
//! down), `s`, `t` the same position over the frame (`P.x / xres`, `P.y / yres`), `Ci` the
//! premultiplied filtered colour, `alpha` the coverage and `Oi` the coverage as a colour. What
//! it may write: `Ci`, `Oi`, `alpha`.
//!
//! The output alpha is `alpha` where the shader changed it; elsewhere the mean of `Oi`, which
//! starts as the coverage, so a shader that writes only `Oi` (Aqsis's `imageralphabug.sl`,
//! `bluescreen.sl`'s `Oi = 1`) sets the file's alpha as PRMan and Aqsis 1.8 do, and one that
//! writes neither leaves it alone.
use crate::exec::{Exec, Messages};
use crate::instance::{triple_vec, SlInstance, SlStats};
use crate::lights::Lights;
use crate::value::{Slot, Value};
use glam::Vec3;
use illume_shade::{ShadingEnv, ShadingGrid};
use illume_sl::ast::Global;

/// The pixels `rect` (x0 x1 y0 y1, exclusive ends, full frame) of a `resolution` frame as a
/// shading grid: `P` at the pixel centres in raster space, `s`, `t` across the frame.
pub fn imager_grid(rect: [u32; 4], resolution: [u32; 2]) -> ShadingGrid {
    let [x0, x1, y0, y1] = rect;
    let (nu, nv) = ((x1 - x0) as usize, (y1 - y0) as usize);
    let mut g = ShadingGrid::new(nu, nv);
    let (xres, yres) = (resolution[0].max(1) as f32, resolution[1].max(1) as f32);
    for (i, (p, (s, t))) in
        g.p.iter_mut()
            .zip(g.s.iter_mut().zip(g.t.iter_mut()))
            .enumerate()
    {
        let x = (x0 as usize + i % nu.max(1)) as f32 + 0.5;
        let y = (y0 as usize + i / nu.max(1)) as f32 + 0.5;
        *p = Vec3::new(x, y, 0.0);
        *s = x / xres;
        *t = y / yres;
    }
    g.i = vec![Vec3::ZERO; g.len()];
    g
}

impl SlInstance {
    /// Runs this imager on premultiplied RGBA pixels `rgba` (index-aligned with `grid`, from
    /// [`imager_grid`]), in place. Non-finite colours become black and non-finite alphas keep
    /// the coverage, counted in the returned stats.
    pub fn run_imager(
        &self,
        grid: &ShadingGrid,
        rgba: &mut [[f32; 4]],
        env: &ShadingEnv,
    ) -> SlStats {
        let n = grid.len().min(rgba.len());
        let alpha_in: Vec<f32> = rgba.iter().map(|px| px[3]).collect();
        let mut g = grid.clone();
        g.os = alpha_in.iter().map(|&a| Vec3::splat(a)).collect();
        let ci_in: Vec<Vec3> = rgba
            .iter()
            .map(|px| Vec3::new(px[0], px[1], px[2]))
            .collect();
        let lights = Lights::default();
        let (ci, oi, alpha) = {
            let mut exec = Exec::new(&self.shader.program, &g, env, &lights);
            exec.messages = Messages::default();
            exec.set_global(Global::Ci, Value::Triple(Slot::varying(ci_in)));
            exec.set_global(Global::Oi, Value::Triple(Slot::varying(g.os.clone())));
            exec.set_global(Global::alpha, Value::Float(Slot::varying(alpha_in.clone())));
            let params = self.params_for(&mut exec, &g);
            exec.run_shader(self.shader.id, params);
            Self::report_problems(&exec, env, self.name());
            let len = g.len();
            let alpha = match exec.global(Global::alpha) {
                Value::Float(s) => s.to_varying(len),
                _ => alpha_in.clone(),
            };
            (
                triple_vec(exec.global(Global::Ci), len),
                triple_vec(exec.global(Global::Oi), len),
                alpha,
            )
        };
        let mut stats = SlStats::default();
        for i in 0..n {
            let (c, o, a) = (ci[i], oi[i], alpha[i]);
            let out_alpha = if a != alpha_in[i] {
                a
            } else {
                (o.x + o.y + o.z) / 3.0
            };
            stats.nonfinite += (!c.is_finite() || !out_alpha.is_finite()) as usize;
            let c = if c.is_finite() { c } else { Vec3::ZERO };
            rgba[i] = [
                c.x,
                c.y,
                c.z,
                if out_alpha.is_finite() {
                    out_alpha
                } else {
                    alpha_in[i]
                },
            ];
        }
        stats
    }
}
