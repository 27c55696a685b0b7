//! `SolidBegin`/`SolidEnd` constructive solid geometry (RI Spec 3.2 §5.8) through real RIB,
//! orthographic, against closed forms.
//!
//! Every scene is 200×200 pixels over [-2, 2]² (one object unit = 50 pixels), 4×4 samples per
//! pixel and a box filter of one pixel, so the alpha sum is the covered area in pixels. The
//! threshold is 0.1% relative, as for the plain sphere in `render.rs`: the sampling error of
//! a silhouette is a fraction of its ring of partly covered pixels (measured: ≤ 0.04%).
use illume_render::{render, RenderSettings, Rendered};
use illume_ri::{from_rib_diagnostic, Ri, Severity};
use std::f64::consts::PI;
mod support;

/// Object space is camera space moved 5 units along +z (the view direction).
fn scene(body: &str) -> String {
    format!(
        "Format 200 200 1\nScreenWindow -2 2 -2 2\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\n\
         WorldBegin\nLightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [0 0 0] \"to\" [0 0 1]\n\
         Surface \"matte\"\nTranslate 0 0 5\n{body}\nWorldEnd\n"
    )
}

fn render_one(rib: &str) -> Rendered {
    let f = support::frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

fn alpha_sum(r: &Rendered) -> f64 {
    r.rgba.chunks_exact(4).map(|p| f64::from(p[3])).sum()
}

/// Object-space (x, y) of pixel (px, py)'s centre.
fn at(px: usize, py: usize) -> (f64, f64) {
    (
        -2.0 + (px as f64 + 0.5) / 50.0,
        2.0 - (py as f64 + 0.5) / 50.0,
    )
}

fn assert_area(r: &Rendered, object_area: f64, what: &str) {
    let expected = object_area * 2500.0;
    let got = alpha_sum(r);
    let rel = (got - expected).abs() / expected;
    eprintln!("{what}: {got:.1} px covered, closed form {expected:.1} (rel {rel:.2e})");
    assert!(
        rel < 1e-3,
        "{what}: {got} px covered, expected {expected} (rel {rel})"
    );
}

/// A closed tube along z: a cylinder and its two caps, oriented outward.
fn tube(radius: f64, z0: f64, z1: f64) -> String {
    format!(
        "SolidBegin \"primitive\"\nCylinder {radius} {z0} {z1} 360\n\
         AttributeBegin ReverseOrientation Disk {z0} {radius} 360 AttributeEnd\n\
         Disk {z1} {radius} 360\nSolidEnd\n"
    )
}

fn sphere(radius: f64, [x, y, z]: [f64; 3]) -> String {
    format!(
        "SolidBegin \"primitive\"\nTransformBegin Translate {x} {y} {z} Sphere {radius} -{radius} {radius} 360 TransformEnd\nSolidEnd\n"
    )
}

/// Area of the intersection of two disks of radius `r` whose centres are `d` apart.
fn lens_area(r: f64, d: f64) -> f64 {
    2.0 * r * r * (d / (2.0 * r)).acos() - 0.5 * d * (4.0 * r * r - d * d).sqrt()
}

#[test]
fn sphere_minus_a_tube_is_an_annulus_with_a_see_through_hole() {
    let r = render_one(&scene(&format!(
        "SolidBegin \"difference\"\n{}{}SolidEnd",
        sphere(1.5, [0.0; 3]),
        tube(0.5, -2.0, 2.0)
    )));
    assert_area(&r, PI * (1.5 * 1.5 - 0.5 * 0.5), "annulus");
    for py in 0..200 {
        for px in 0..200 {
            let (x, y) = at(px, py);
            // Pixels wholly inside the hole (half a diagonal away from its rim) see nothing.
            if x.hypot(y) < 0.5 - 0.015 {
                let a = r.rgba[(py * 200 + px) * 4 + 3];
                assert_eq!(a, 0.0, "pixel ({px}, {py}) in the hole has alpha {a}");
            }
        }
    }
}

#[test]
fn intersection_of_two_spheres_is_a_lens_with_the_later_entry_depth() {
    let r = render_one(&scene(&format!(
        "SolidBegin \"intersection\"\n{}{}SolidEnd",
        sphere(1.0, [-0.5, 0.0, 0.0]),
        sphere(1.0, [0.5, 0.0, 0.0])
    )));
    assert_area(&r, lens_area(1.0, 1.0), "lens");
    let mut checked = 0;
    for py in 0..200 {
        for px in 0..200 {
            let (x, y) = at(px, py);
            let ha = 1.0 - (x + 0.5).powi(2) - y * y;
            let hb = 1.0 - (x - 0.5).powi(2) - y * y;
            // Well inside the lens, where the depth varies slowly across a pixel.
            if ha.min(hb) < 0.3 {
                continue;
            }
            // The composite's near surface is where the ray has entered both spheres.
            let expected = 5.0 - ha.min(hb).sqrt();
            let got = f64::from(r.z[py * 200 + px]);
            // Min-depth over the pixel: slope ≤ 1.4 at h ≥ 0.3 times half a pixel diagonal,
            // plus the dicing's chord error.
            assert!(
                (got - expected).abs() < 0.025,
                "pixel ({px}, {py}): depth {got}, expected {expected}"
            );
            checked += 1;
        }
    }
    assert!(checked > 1000, "only {checked} pixels checked");
}

#[test]
fn union_looks_like_the_spheres_without_solid_blocks() {
    let a = sphere(1.0, [-0.5, 0.2, 0.3]);
    let b = sphere(1.0, [0.6, 0.2, 0.0]);
    let csg = render_one(&scene(&format!("SolidBegin \"union\"\n{a}{b}SolidEnd")));
    let plain = render_one(&scene(
        &format!("{a}{b}")
            .replace("SolidBegin \"primitive\"\n", "")
            .replace("SolidEnd\n", ""),
    ));
    // Inside the silhouettes both see the same front-most micropolygon with the same shading.
    // On a silhouette a sample may hit only a grazing back-facing micropolygon: the plain
    // render (Sides 2) counts it, black, while the union drops it as an exit from a solid the
    // ray never entered. So: differences only within 1.5 pixels of a rim, at most two of the
    // pixel's 16 samples' worth.
    let mut changed = 0;
    for k in 0..200 * 200 {
        let d = (0..4)
            .map(|c| (csg.rgba[k * 4 + c] - plain.rgba[k * 4 + c]).abs())
            .fold(0.0f32, f32::max);
        if d == 0.0 {
            continue;
        }
        changed += 1;
        let (x, y) = at(k % 200, k / 200);
        let rim = |cx: f64, cy: f64| ((x - cx).hypot(y - cy) - 1.0).abs() < 0.03;
        assert!(
            rim(-0.5, 0.2) || rim(0.6, 0.2),
            "({x}, {y}) differs by {d} off the silhouettes"
        );
        assert!(d <= 2.0 / 16.0, "({x}, {y}) differs by {d}");
    }
    eprintln!("union vs plain: {changed} silhouette pixels differ");
    assert_area(&csg, 2.0 * PI - lens_area(1.0, 1.1), "union");
}

#[test]
fn subtracted_spheres_inner_wall_is_at_its_far_depth_and_lit_from_inside() {
    // A unit sphere with a bite of radius 0.5 taken out at its front pole (camera z 4).
    let r = render_one(&scene(&format!(
        "SolidBegin \"difference\"\n{}{}SolidEnd",
        sphere(1.0, [0.0; 3]),
        sphere(0.5, [0.0, 0.0, -1.0])
    )));
    assert_area(&r, PI, "bitten sphere");
    let mut checked = 0;
    for py in 0..200 {
        for px in 0..200 {
            let (x, y) = at(px, py);
            let rho2 = x * x + y * y;
            // Inside the bite's rim (ρ = 0.484), away from it: the bite's far wall, seen
            // from inside the hollow: depth 4 + √(0.25 − ρ²).
            if rho2 > 0.35 * 0.35 {
                continue;
            }
            let h = (0.25 - rho2).sqrt();
            let expected = 4.0 + h;
            let got = f64::from(r.z[py * 200 + px]);
            // Depth slope ρ/h ≤ 1 here, times half a pixel diagonal, plus chord error.
            assert!(
                (got - expected).abs() < 0.02,
                "pixel ({px}, {py}): depth {got}, expected {expected}"
            );
            // Matte under a headlight: Kd·cosθ, with the wall's normal faced to the camera
            // (cosθ = h / 0.5); a normal left pointing away would give black.
            let c = f64::from(r.rgba[(py * 200 + px) * 4]);
            let lit = h / 0.5;
            assert!(
                (c - lit).abs() < 0.03,
                "pixel ({px}, {py}): colour {c}, expected {lit}"
            );
            checked += 1;
        }
    }
    assert!(checked > 800, "only {checked} pixels checked");
}

#[test]
fn union_of_two_spheres_minus_a_tube() {
    let r = render_one(&scene(&format!(
        "SolidBegin \"difference\"\nSolidBegin \"union\"\n{}{}SolidEnd\n{}SolidEnd",
        sphere(1.0, [-0.5, 0.0, 0.0]),
        sphere(1.0, [0.5, 0.0, 0.0]),
        tube(0.3, -2.0, 2.0)
    )));
    // The hole (radius 0.3 about the origin) lies inside both disks.
    let union = 2.0 * PI - lens_area(1.0, 1.0);
    assert_area(&r, union - PI * 0.09, "(A ∪ B) − C");
    let centre = r.rgba[(100 * 200 + 100) * 4 + 3];
    assert_eq!(centre, 0.0, "the hole is see-through");
    // Beside the hole, still inside both spheres: covered.
    let side = r.rgba[(100 * 200 + 125) * 4 + 3];
    assert_eq!(side, 1.0);
}

fn diagnostics(rib: &str) -> Vec<illume_ri::Diagnostic> {
    let mut ri = Ri::new();
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "bad.rib");
    for item in parser {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    let d = ri.drain_diagnostics();
    for f in ri.take_frames() {
        let _ = render(&f, &RenderSettings::default());
    }
    d
}

#[test]
fn bad_nesting_is_reported_with_its_position_and_renders() {
    let rib = "Format 20 20 1\nWorldBegin\nSolidEnd\n\
               SolidBegin \"primitive\"\n  SolidBegin \"union\"\n    Sphere 1 -1 1 360\n  SolidEnd\nSolidEnd\n\
               SolidBegin \"xor\"\nSphere 1 -1 1 360\nWorldEnd\nSolidEnd\n";
    let d = diagnostics(rib);
    let text: Vec<String> = d.iter().map(|d| d.to_string()).collect();
    let has = |needle: &str, line: usize, sev: Severity| {
        d.iter().any(|x| {
            x.severity == sev
                && x.to_string().contains(needle)
                && x.to_string().starts_with(&format!("bad.rib:{line}:"))
        })
    };
    assert!(
        has("no matching SolidBegin", 3, Severity::Error),
        "{text:#?}"
    );
    assert!(has("primitive solid", 5, Severity::Warning), "{text:#?}");
    assert!(
        has("unknown operation `xor`", 9, Severity::Error),
        "{text:#?}"
    );
    assert!(has("SolidBegin at", 11, Severity::Error), "{text:#?}");
    assert!(
        has("no matching SolidBegin", 12, Severity::Error),
        "{text:#?}"
    );
}

/// Perspective: a unit sphere 5 units ahead minus a tube of radius 0.3 along the view axis.
/// A ray of radial slope t (radius t·z at depth z) sees, in closed form: the sphere's entry
/// when it never is inside the tube there; the tube's inner wall at depth 0.3/t where it
/// leaves the tube inside the sphere; nothing (alpha 0) where it leaves it behind the sphere.
#[test]
fn perspective_difference_shows_the_tube_wall_at_its_analytic_depth() {
    let rib = format!(
        "Format 100 100 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 4 4\n\
         PixelFilter \"box\" 1 1\nWorldBegin\nSurface \"matte\"\nTranslate 0 0 5\n\
         SolidBegin \"difference\"\n{}{}SolidEnd\nWorldEnd\n",
        sphere(1.0, [0.0; 3]),
        tube(0.3, -2.0, 2.0)
    );
    let r = render_one(&rib);
    let half = 20f64.to_radians().tan();
    // Sphere entry and exit depths along slope t: (1 + t²)z² − 10z + 24 = 0.
    let sphere_hits = |t: f64| {
        let a = 1.0 + t * t;
        let disc = (100.0 - 96.0 * a).sqrt();
        ((10.0 - disc) / (2.0 * a), (10.0 + disc) / (2.0 * a))
    };
    // One pixel is 0.02 in screen units; samples reach half a diagonal from the centre.
    let dt = 0.0142 * half;
    let (mut wall, mut hole, mut front) = (0, 0, 0);
    for py in 0..100 {
        for px in 0..100 {
            let (sx, sy) = (
                -1.0 + (px as f64 + 0.5) / 50.0,
                1.0 - (py as f64 + 0.5) / 50.0,
            );
            let t = sx.hypot(sy) * half;
            let z_in = sphere_hits(t).0;
            // Which surface the ray sees, judged at both ends of the pixel's slope range.
            let kind = |t: f64| {
                let (z_in, z_out) = sphere_hits(t);
                let z_wall = 0.3 / t;
                if t >= 0.1 || z_wall < z_in {
                    0 // enters the sphere outside the tube
                } else if z_wall < z_out {
                    1 // leaves the tube inside the sphere: the wall
                } else {
                    2 // leaves it behind the sphere: see-through
                }
            };
            if sphere_hits(t + 2.0 * dt).0.is_nan() || kind(t - 2.0 * dt) != kind(t + 2.0 * dt) {
                continue;
            }
            let k = py * 100 + px;
            let (z, a) = (f64::from(r.z[k]), r.rgba[k * 4 + 3]);
            match kind(t) {
                0 => {
                    // The pixel's depth range plus the dicing's chord error.
                    let spread = [t - dt, t + dt]
                        .map(|t| (sphere_hits(t).0 - z_in).abs())
                        .into_iter()
                        .fold(0.0, f64::max);
                    let tol = spread + 0.01;
                    assert!((z - z_in).abs() < tol, "({px}, {py}) front: {z} vs {z_in}");
                    front += 1;
                }
                1 => {
                    let z_wall = 0.3 / t;
                    // The wall's depth changes by 0.3/t² per unit slope across the pixel.
                    let tol = 0.3 / (t * t) * dt + 0.01;
                    assert!(
                        (z - z_wall).abs() < tol,
                        "({px}, {py}) wall: {z} vs {z_wall}"
                    );
                    assert_eq!(a, 1.0, "({px}, {py}) wall alpha");
                    wall += 1;
                }
                _ => {
                    assert_eq!(a, 0.0, "({px}, {py}) see-through alpha");
                    hole += 1;
                }
            }
        }
    }
    eprintln!("perspective: {front} front, {wall} wall, {hole} see-through pixels checked");
    assert!(
        front > 1000 && wall > 20 && hole > 50,
        "{front} {wall} {hole}"
    );
}

/// What the RI state hands the hider: one leaf per primitive solid (however many requests
/// bound it), a leaf of its own for a bare surface inside an operation, and the surfaces of a
/// solid nested in a primitive solid joining that primitive.
#[test]
fn frames_carry_the_solid_tree() {
    let f = support::frames(
        "WorldBegin\nSphere 1 -1 1 360\nSolidBegin \"difference\"\n\
         SolidBegin \"primitive\"\nCylinder 1 0 1 360\nDisk 0 1 360\nDisk 1 1 360\n\
         SolidBegin \"union\"\nSphere 2 -2 2 360\nSolidEnd\nSolidEnd\n\
         Sphere 0.5 -0.5 0.5 360\nSolidEnd\nWorldEnd\n",
        None,
    );
    let solids: Vec<Option<u32>> = f[0].primitives.iter().map(|p| p.solid).collect();
    let t = &f[0].solids;
    assert_eq!(solids.len(), 6);
    assert_eq!(solids[0], None);
    let leaf = solids[1].unwrap();
    assert!(solids[1..5].iter().all(|&s| s == Some(leaf)), "{solids:?}");
    let bare = solids[5].unwrap();
    assert_ne!(bare, leaf);
    let root = t.root(leaf);
    assert_eq!(t.root(bare), root);
    assert_eq!(t.nodes[root as usize].op, illume_ri::SolidOp::Difference);
    assert_eq!(t.nodes[root as usize].children, vec![leaf, bare]);
    // Inside the first child only: inside the difference; inside both: not.
    assert!(t.contains(root, &|l| l == leaf));
    assert!(!t.contains(root, &|_| true));
}

/// A primitive solid on its own is its closed surface seen from outside: the same depth as
/// rendering the surface `Sides 1`, whatever the primitive type, and under a mirroring
/// transform whose orientation is set back to "outside" (the raster winding flips, and so
/// must the entering test). This checks that the hider's entering/exiting test agrees with its
/// back-face culling. Compared where both renders cover the whole pixel (silhouette pixels may
/// differ by a grazing sample). Convex solids only: where a surface folds over itself (a
/// torus's inner rim) `Sides 1` culls by corner-vertex normals and the solid by each
/// triangle's winding, which differ for micropolygons straddling the fold.
#[test]
fn a_lone_primitive_solid_matches_its_one_sided_surface() {
    let cube =
        "PointsPolygons [4 4 4 4 4 4] [0 3 2 1  4 5 6 7  0 1 5 4  3 7 6 2  0 4 7 3  1 2 6 5] \
                \"P\" [-1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1]";
    let surfaces = [
        "Sphere 1.2 -1.2 1.2 360".to_string(),
        format!("Rotate 30 1 1 0 Scale 0.8 0.8 0.8 {cube}"),
    ];
    for surface in &surfaces {
        for prefix in [
            "",
            "Scale -1 1 1 Orientation \"outside\"",
            "ReverseOrientation ReverseOrientation",
        ] {
            let body = format!("{prefix} {surface}");
            let csg = render_one(&scene(&format!(
                "SolidBegin \"primitive\"\n{body}\nSolidEnd"
            )));
            let one_sided = render_one(&scene(&format!("Sides 1\n{body}")));
            let mut compared = 0;
            for k in 0..200 * 200 {
                if csg.rgba[k * 4 + 3] < 1.0 || one_sided.rgba[k * 4 + 3] < 1.0 {
                    continue;
                }
                let (a, b) = (csg.z[k], one_sided.z[k]);
                assert!(
                    (a - b).abs() < 1e-5,
                    "{body}: pixel {k}: depth {a} as a solid, {b} one-sided"
                );
                compared += 1;
            }
            assert!(compared > 1000, "{body}: only {compared} pixels compared");
        }
    }
}
