//! Dicing throughput: grid vertices (P, derivatives, normals, variables) produced per second
//! for a sphere, the teapot and a quad mesh. Run: `cargo bench -p illume-geom --bench dice`.
use glam::DMat4;
use illume_geom::{basis_matrix, build, BuildContext, Primitive};
use illume_rib::{Declaration, Param, Request, Value};
use std::time::Instant;

fn no_decls(_: &str) -> Option<Declaration> {
    None
}

fn measure(label: &str, prims: &[Box<dyn Primitive>], n: usize) {
    let reps = (2_000_000 / (prims.len() * n * n)).max(1);
    let start = Instant::now();
    let mut vertices = 0usize;
    for _ in 0..reps {
        for p in prims {
            let g = std::hint::black_box(p.dice(n, n));
            vertices += g.len();
        }
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{label:<28} {:>6} grids of {n}x{n}: {:>7.2} M vertices/s",
        prims.len() * reps,
        vertices as f64 / secs / 1e6
    );
}

fn main() {
    let bezier = basis_matrix("bezier").unwrap().0;
    let ctx = BuildContext {
        camera_from_object: DMat4::from_translation(glam::DVec3::new(0.0, 0.0, 5.0)),
        declarations: &no_decls,
        basis: (bezier, 3, bezier, 3),
        texture_coordinates: [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        trim_curves: None,
        warnings: None,
    };
    let sphere = Request::Sphere {
        radius: 1.0,
        zmin: -1.0,
        zmax: 1.0,
        thetamax: 360.0,
        params: vec![],
    };
    measure("sphere", &build(&sphere, &ctx).unwrap(), 32);
    let teapot = Request::Geometry {
        kind: "teapot".into(),
        params: vec![],
    };
    measure("teapot (32 bicubic)", &build(&teapot, &ctx).unwrap(), 16);
    let side = 100;
    let p: Vec<f32> = (0..(side + 1) * (side + 1))
        .flat_map(|k| [(k % (side + 1)) as f32, (k / (side + 1)) as f32, 0.0])
        .collect();
    let mut verts = Vec::new();
    for j in 0..side {
        for i in 0..side {
            let a = (j * (side + 1) + i) as i32;
            verts.extend([a, a + 1, a + side as i32 + 2, a + side as i32 + 1]);
        }
    }
    let mesh = Request::PointsPolygons {
        nverts: vec![4; side * side],
        verts,
        params: vec![
            Param {
                name: "P".into(),
                value: Value::Floats(p.clone()),
            },
            Param {
                name: "Cs".into(),
                value: Value::Floats(p),
            },
        ],
    };
    let start = Instant::now();
    let prims = build(&mesh, &ctx).unwrap();
    println!(
        "PointsPolygons 100x100 quads built in {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    measure("PointsPolygons quads + Cs", &prims, 4);
}
