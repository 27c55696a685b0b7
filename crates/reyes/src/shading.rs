//! Placeholder grid shading behind a small seam (`shade_grid`), until the hider calls
//! `illume-shade`: `defaultsurface` without a Surface, `constant`, `null` (no shading, for depth
//! passes), and a Lambert + Blinn "plastic" for every other surface, lit by the frame's
//! ambient/distant/point/spot lights or, with none, by one distant light from the camera.
use glam::Vec3;
use illume_geom::Grid;
use illume_ri::{paramlist, Attributes, Light};

pub(crate) struct Shaded {
    pub ci: Vec<Vec3>,
    pub oi: Vec<Vec3>,
}

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from(a)
}

pub(crate) fn shade_grid(grid: &Grid, attrs: &Attributes, lights: &[Light], flip: f32) -> Shaded {
    let n = grid.len();
    let cs: Vec<Vec3> = grid.cs.clone().unwrap_or_else(|| vec![v3(attrs.color); n]);
    let os: Vec<Vec3> = grid
        .os
        .clone()
        .unwrap_or_else(|| vec![v3(attrs.opacity); n]);
    let surface = attrs.surface.as_deref();
    let name = surface.map_or("defaultsurface", |s| s.name.as_str());
    let f = |p: &str, d: f32| {
        surface
            .and_then(|s| paramlist::float(&s.params, p))
            .unwrap_or(d)
    };
    let mut ci = Vec::with_capacity(n);
    for k in 0..n {
        let p = grid.p[k];
        let i_dir = p.normalize_or(Vec3::Z);
        let mut nn = (grid.n[k] * flip).normalize_or(Vec3::Z);
        if nn.dot(i_dir) > 0.0 {
            nn = -nn; // faceforward
        }
        let c = match name {
            "null" => Vec3::ZERO,
            "constant" => os[k] * cs[k],
            "defaultsurface" => {
                let d = i_dir.dot(nn);
                os[k] * cs[k] * (0.2 + 0.8 * d * d)
            }
            _ => {
                let (ka, kd, ks, rough) = (
                    f("Ka", 1.0),
                    f("Kd", 0.5),
                    f("Ks", 0.5),
                    f("roughness", 0.1),
                );
                let (amb, diff, spec) = illuminate(p, nn, -i_dir, rough, lights, &attrs.lights);
                os[k] * (cs[k] * (ka * amb + kd * diff) + ks * spec)
            }
        };
        ci.push(c);
    }
    Shaded { ci, oi: os }
}

/// Sums the lights: (ambient, Lambert diffuse, Blinn specular `max(0,N·H)^(1/roughness)`).
fn illuminate(
    p: Vec3,
    n: Vec3,
    v: Vec3,
    rough: f32,
    lights: &[Light],
    on: &[usize],
) -> (Vec3, Vec3, Vec3) {
    let mut amb = Vec3::ZERO;
    let mut diff = Vec3::ZERO;
    let mut spec = Vec3::ZERO;
    let mut add = |l: Vec3, cl: Vec3| {
        let nl = n.dot(l);
        if nl > 0.0 {
            diff += cl * nl;
            let h = (l + v).normalize_or(n);
            spec += cl * n.dot(h).max(0.0).powf(1.0 / rough.max(1e-3));
        }
    };
    if on.is_empty() {
        add(v, Vec3::ONE);
        return (amb, diff, spec);
    }
    for &i in on {
        let Some(light) = lights.get(i) else { continue };
        let s = &light.shader;
        let g = |name: &str, d: [f32; 3]| -> Vec3 {
            paramlist::floats(&s.params, name)
                .filter(|v| v.len() >= 3)
                .map_or(v3(d), |v| Vec3::new(v[0], v[1], v[2]))
        };
        let m = s.camera_from_shader.as_mat4();
        let intensity = paramlist::float(&s.params, "intensity").unwrap_or(1.0);
        let cl = g("lightcolor", [1.0; 3]) * intensity;
        match s.name.as_str() {
            "ambientlight" => amb += cl,
            "distantlight" => {
                let from = m.transform_point3(g("from", [0.0; 3]));
                let to = m.transform_point3(g("to", [0.0, 0.0, 1.0]));
                add((from - to).normalize_or(Vec3::Z), cl);
            }
            _ => {
                let from = m.transform_point3(g("from", [0.0; 3]));
                let d = from - p;
                let d2 = d.length_squared().max(1e-12);
                add(d / d2.sqrt(), cl / d2);
            }
        }
    }
    (amb, diff, spec)
}
