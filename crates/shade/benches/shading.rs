//! Shading throughput: every built-in surface on a 32×32 grid over a sphere under a
//! distantlight, a pointlight and a spotlight (plus an ambientlight). Prints points per second;
//! run with `cargo bench -p illume-shade`.
use glam::{DMat4, Vec3};
use illume_shade::{light, shade_surface, surface, ShadingEnv, ShadingGrid, Surface};
use std::time::Instant;

fn sphere_grid(nu: usize, nv: usize) -> ShadingGrid {
    let mut g = ShadingGrid::new(nu, nv);
    for k in 0..g.len() {
        let phi = g.u[k] * std::f32::consts::TAU;
        let theta = g.v[k] * std::f32::consts::FRAC_PI_2;
        let n = Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            -theta.cos(),
        );
        g.p[k] = Vec3::new(0.0, 0.0, 5.0) + n;
        g.n[k] = n;
        g.ng[k] = n;
        g.dpdu[k] = Vec3::new(-phi.sin(), phi.cos(), 0.0);
    }
    g.set_incident_from_p(false);
    g
}

fn main() {
    let lights = [
        light("ambientlight", &[], DMat4::IDENTITY).unwrap().0,
        light("distantlight", &[], DMat4::IDENTITY).unwrap().0,
        light(
            "pointlight",
            &[],
            DMat4::from_translation(glam::DVec3::new(2.0, 2.0, 0.0)),
        )
        .unwrap()
        .0,
        light("spotlight", &[], DMat4::IDENTITY).unwrap().0,
    ];
    let refs: Vec<_> = lights.iter().collect();
    let env = ShadingEnv::new();
    let template = sphere_grid(32, 32);
    for &name in Surface::names() {
        let (s, _) = surface(name, &[]).unwrap();
        let mut g = template.clone();
        // Warm up, then time enough grids for ~0.2 s.
        shade_surface(&s, &mut g, &refs, &env);
        let mut grids = 0usize;
        let start = Instant::now();
        while start.elapsed().as_secs_f64() < 0.2 {
            shade_surface(&s, &mut g, &refs, &env);
            grids += 1;
        }
        let secs = start.elapsed().as_secs_f64();
        let pts = (grids * g.len()) as f64 / secs;
        println!(
            "{name:>16}: {:>7.2} M points/s ({} lights, {grids} grids of {})",
            pts / 1e6,
            refs.len(),
            g.len()
        );
    }
}
