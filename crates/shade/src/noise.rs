//! Shading Language `noise(point)` (RI Spec 3.2 §15.1) for the built-in shaders: the renderer's
//! one noise, [`illume_core::noise::noise`], so `dented` and an SL `dented` listing displace by
//! the same pattern.
use glam::Vec3;

/// `float noise(point p)`: in [0, 1], 0.5 at every lattice point.
pub fn noise(p: Vec3) -> f32 {
    illume_core::noise::noise(&p.to_array(), 0)
}
