//! Shared helpers for the geometry tests: a build context and micropolygon areas.
#![allow(dead_code)]
use glam::{DMat4, DVec3, Vec3};
use illume_geom::{build, BuildContext, Grid, Primitive};
use illume_rib::{Declaration, Param, Request, Value};

pub fn no_decls(_: &str) -> Option<Declaration> {
    None
}

pub const BEZIER: [f32; 16] = [
    -1.0, 3.0, -3.0, 1.0, 3.0, -6.0, 3.0, 0.0, -3.0, 3.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
];

pub fn ctx_with(m: DMat4) -> BuildContext<'static> {
    BuildContext {
        camera_from_object: m,
        declarations: &no_decls,
        basis: (BEZIER, 3, BEZIER, 3),
        texture_coordinates: [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        trim_curves: None,
        warnings: None,
    }
}

pub fn ctx() -> BuildContext<'static> {
    ctx_with(DMat4::IDENTITY)
}

pub fn floats(name: &str, v: &[f32]) -> Param {
    Param {
        name: name.to_string(),
        value: Value::Floats(v.to_vec()),
    }
}

pub fn build_ok(r: &Request) -> Vec<Box<dyn Primitive>> {
    build(r, &ctx()).unwrap_or_else(|e| panic!("{e}"))
}

/// Sum of the two triangles of every micropolygon, in f64.
pub fn grid_area(g: &Grid) -> f64 {
    let p = |i: usize, j: usize| g.p[j * g.nu + i].as_dvec3();
    let mut a = 0.0;
    for j in 0..g.nv - 1 {
        for i in 0..g.nu - 1 {
            let (p00, p10, p01, p11) = (p(i, j), p(i + 1, j), p(i, j + 1), p(i + 1, j + 1));
            a += 0.5 * (p10 - p00).cross(p11 - p00).length();
            a += 0.5 * (p11 - p00).cross(p01 - p00).length();
        }
    }
    a
}

/// Splits aggregates until diceable, then dices every piece at `n × n` and sums the areas.
pub fn area(prims: &[Box<dyn Primitive>], n: usize) -> f64 {
    all_grids(prims, n).iter().map(grid_area).sum()
}

pub fn all_grids(prims: &[Box<dyn Primitive>], n: usize) -> Vec<Grid> {
    let mut out = Vec::new();
    for p in prims {
        if p.diceable() {
            out.push(p.dice(n, n));
        } else {
            out.extend(all_grids(&p.split(), n));
        }
    }
    out
}

pub fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-12)
}

pub fn v3(p: Vec3) -> DVec3 {
    p.as_dvec3()
}
