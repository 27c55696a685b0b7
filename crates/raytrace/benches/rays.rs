//! BVH build time and occlusion rays per second over a tessellated scene: a grid of
//! spheres above a ground plane, ~2·10⁵ triangles, shadow rays from the ground toward a
//! distant light (a mix of blocked and unblocked rays, as a shadow pass sees them).
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DVec3, Vec3};
use illume_raytrace::{Bvh, Triangle};
use std::hint::black_box;

fn sphere(c: Vec3, r: f32, n: usize, out: &mut Vec<Triangle>) {
    let at = |i: usize, j: usize| {
        let th = i as f32 / n as f32 * std::f32::consts::TAU;
        let ph = j as f32 / n as f32 * std::f32::consts::PI;
        c + r * Vec3::new(ph.sin() * th.cos(), ph.cos(), ph.sin() * th.sin())
    };
    for j in 0..n {
        for i in 0..n {
            let (a, b, cc, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            out.push(Triangle::new(a, b, cc));
            out.push(Triangle::new(a, cc, d));
        }
    }
}

fn scene() -> Vec<Triangle> {
    let mut t = Vec::new();
    for k in 0..100 {
        let c = Vec3::new((k % 10) as f32 * 2.5, 1.0, (k / 10) as f32 * 2.5);
        sphere(c, 1.0, 32, &mut t);
    }
    let (a, b) = (Vec3::new(-5.0, 0.0, -5.0), Vec3::new(30.0, 0.0, 30.0));
    t.push(Triangle::new(a, Vec3::new(b.x, 0.0, a.z), b));
    t.push(Triangle::new(a, b, Vec3::new(a.x, 0.0, b.z)));
    t
}

fn bench(c: &mut Criterion) {
    let tris = scene();
    let mut g = c.benchmark_group("bvh");
    g.sample_size(10);
    g.throughput(Throughput::Elements(tris.len() as u64));
    g.bench_function("build_204k_triangles", |b| {
        b.iter(|| Bvh::new(black_box(tris.clone())))
    });
    g.finish();
    let bvh = Bvh::new(tris);
    let n = 100_000usize;
    let origins: Vec<DVec3> = (0..n)
        .map(|k| {
            let (x, z) = ((k % 316) as f64 * 0.08, (k / 316) as f64 * 0.08);
            DVec3::new(x, 1e-4, z)
        })
        .collect();
    let dir = DVec3::new(0.3, 1.0, 0.2).normalize();
    let mut g = c.benchmark_group("occlusion");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("shadow_rays_100k", |b| {
        b.iter(|| {
            origins
                .iter()
                .filter(|&&o| bvh.occluded(o, dir, 0.0, f64::INFINITY))
                .count()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
