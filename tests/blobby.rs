//! Blobby end to end (RIB text → parser → RI state → hider) against f64 closed forms and an
//! f64 reference silhouette written here from the field formulas.
//!
//! Scenes: orthographic 200×200 over [-2,2]² (50 pixels per unit), box filter 1×1, 4×4
//! jittered samples per pixel, so a pixel's alpha is its covered fraction to ±1/16 on an edge.
use illume_render::{render, RenderSettings, Rendered};
use illume_ri::{from_rib_diagnostic, Ri, Severity};
mod support;
use support::frames;

const PX: f64 = 50.0;

fn bump(s: f64) -> f64 {
    if s < 1.0 {
        (1.0 - s).powi(3)
    } else {
        0.0
    }
}

/// The surface radius of a lone unit blob: bump(r²) = ½.
fn r_star() -> f64 {
    (1.0 - 0.5f64.cbrt()).sqrt()
}

fn render_one(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

fn ortho_scene(body: &str) -> String {
    format!(
        "Format 200 200 1\nScreenWindow -2 2 -2 2\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\n\
         WorldBegin\nTranslate 0 0 5\n{body}\nWorldEnd\n"
    )
}

fn alpha(r: &Rendered, x: usize, y: usize) -> f64 {
    f64::from(r.rgba[(y * 200 + x) * 4 + 3])
}

/// `Blobby` text for spheres (centre, radius) combined by `op` (`"0"` add, `"2"` max, …).
fn spheres(blobs: &[([f64; 3], f64)], op: &str, extra: &str) -> String {
    let mut code = String::new();
    let mut floats = String::new();
    for (k, (c, r)) in blobs.iter().enumerate() {
        code += &format!("1001 {} ", 16 * k);
        floats += &format!(
            "{r} 0 0 0  0 {r} 0 0  0 0 {r} 0  {} {} {} 1 ",
            c[0], c[1], c[2]
        );
    }
    let ids: Vec<String> = (0..blobs.len()).map(|k| k.to_string()).collect();
    let tail = match op {
        "" => String::new(),
        "4" | "5" => format!("{op} 0 1"),
        _ => format!("{op} {} {}", blobs.len(), ids.join(" ")),
    };
    format!(
        "Blobby {} [{code}{tail}] [{floats}] [\"\"] {extra}",
        blobs.len()
    )
}

#[test]
fn one_blob_covers_pi_r_star_squared() {
    // Radius-2 blob: surface radius 2r* ≈ 0.908 (45 pixels). Threshold 2e-3 relative: the
    // quadric sphere reaches 1e-3 (tests/geometry.rs); the chords between ~1-pixel diced
    // vertices on the exact surface add < 1e-4.
    let r = render_one(&ortho_scene(&spheres(&[([0.0; 3], 2.0)], "", "")));
    let area: f64 = r.rgba.chunks_exact(4).map(|p| f64::from(p[3])).sum();
    let rs = 2.0 * r_star() * PX;
    let exact = std::f64::consts::PI * rs * rs;
    let rel = (area - exact).abs() / exact;
    assert!(
        rel < 2e-3,
        "area {area} px, expected {exact} (rel {rel:.1e})"
    );
}

/// The half height of the surface of two radius-`r` blobs at x = ±d, added, in the plane x = 0:
/// 2·bump((d² + y²)/r²) = ½; `None` when even the centre point is outside.
fn bridge_half_height(d: f64, r: f64) -> Option<f64> {
    let s = 1.0 - 0.25f64.cbrt();
    let y2 = s * r * r - d * d;
    (y2 > 0.0).then(|| y2.sqrt())
}

/// Covered pixels in the column straddling x = 0 (columns 99 and 100 average to x = 0).
fn midpoint_height(r: &Rendered) -> f64 {
    (0..200)
        .map(|y| 0.5 * (alpha(r, 99, y) + alpha(r, 100, y)))
        .sum()
}

#[test]
fn two_added_blobs_bridge_with_the_closed_form_width() {
    let rad = 1.6;
    // Bridged: d = 0.8 → the waist at x = 0 is 2·y* tall. Columns 99/100 cover x ∈ [−0.02,
    // 0.02], where the waist grows by under 0.01 px; threshold 0.5 px (edge sampling ±1/16
    // per edge pixel, two edges, plus the 4×4 jitter).
    let d = 0.8;
    let r = render_one(&ortho_scene(&spheres(
        &[([-d, 0.0, 0.0], rad), ([d, 0.0, 0.0], rad)],
        "0",
        "",
    )));
    let expect = 2.0 * bridge_half_height(d, rad).unwrap() * PX;
    let got = midpoint_height(&r);
    assert!(
        (got - expect).abs() < 0.5,
        "waist {got} px, expected {expect}"
    );
    // Apart: at d = 1.05 the closed form has no bridge, and nothing is drawn at x = 0…
    let d = 1.05;
    assert!(bridge_half_height(d, rad).is_none());
    let r = render_one(&ortho_scene(&spheres(
        &[([-d, 0.0, 0.0], rad), ([d, 0.0, 0.0], rad)],
        "0",
        "",
    )));
    assert_eq!(midpoint_height(&r), 0.0);
    // …while each blob is still drawn at its centre (its own radius is 1.6·r* ≈ 0.73).
    assert_eq!(alpha(&r, 100 - (d * PX) as usize, 100), 1.0);
    assert_eq!(alpha(&r, 100 + (d * PX) as usize, 100), 1.0);
}

#[test]
fn segment_blob_silhouette_has_the_capsule_length() {
    // Segment (−1,0,0)–(1,0,0), radius 1.5: a capsule of radius 1.5·r*, length 2 + 3r*.
    // Rows 99/100 straddle y = 0; threshold 0.5 px as for the waist.
    let body = "Blobby 1 [1002 0] [-1 0 0  1 0 0  1.5  1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] [\"\"]";
    let r = render_one(&ortho_scene(body));
    let len: f64 = (0..200)
        .map(|x| 0.5 * (alpha(&r, x, 99) + alpha(&r, x, 100)))
        .sum();
    let expect = (2.0 + 3.0 * r_star()) * PX;
    assert!(
        (len - expect).abs() < 0.5,
        "length {len} px, expected {expect}"
    );
    let thick: f64 = (0..200).map(|y| alpha(&r, 100, y)).sum();
    let expect = 3.0 * r_star() * PX;
    assert!(
        (thick - expect).abs() < 0.5,
        "thickness {thick} px, expected {expect}"
    );
}

/// Pixels fully covered must have their centre inside the f64 reference silhouette and empty
/// pixels outside it (edge pixels are left alone), and the areas must agree to 1%.
fn check_silhouette(rib_body: &str, field: &dyn Fn(f64, f64, f64) -> f64) {
    let r = render_one(&ortho_scene(rib_body));
    let (mut area, mut ref_area) = (0.0, 0.0);
    for y in 0..200 {
        for x in 0..200 {
            let (px, py) = ((x as f64 + 0.5) / PX - 2.0, 2.0 - (y as f64 + 0.5) / PX);
            // Seen along z: inside where the field exceeds ½ somewhere on the ray (z ∈ [−3, 3],
            // 600 steps of 0.01: far finer than any feature here).
            let inside = (0..=600).any(|k| field(px, py, -3.0 + 0.01 * k as f64) > 0.5);
            let a = alpha(&r, x, y);
            if a == 1.0 {
                assert!(inside, "pixel {x},{y} covered but outside the reference");
            }
            if a == 0.0 {
                assert!(!inside, "pixel {x},{y} empty but inside the reference");
            }
            area += a;
            ref_area += f64::from(u8::from(inside));
        }
    }
    assert!(ref_area > 500.0);
    assert!(
        (area - ref_area).abs() / ref_area < 0.01,
        "{area} vs {ref_area}"
    );
}

fn sphere(x: f64, y: f64, z: f64, c: [f64; 3], r: f64) -> f64 {
    bump(((x - c[0]).powi(2) + (y - c[1]).powi(2) + (z - c[2]).powi(2)) / (r * r))
}

#[test]
fn max_min_subtract_multiply_render_their_fields() {
    let (a, b) = ([-0.5, 0.0, 0.0], [0.5, 0.2, 0.0]);
    let pair = [(a, 2.0), (b, 2.0)];
    check_silhouette(&spheres(&pair, "2", ""), &|x, y, z| {
        sphere(x, y, z, a, 2.0).max(sphere(x, y, z, b, 2.0))
    });
    check_silhouette(&spheres(&pair, "3", ""), &|x, y, z| {
        sphere(x, y, z, a, 2.0).min(sphere(x, y, z, b, 2.0))
    });
    // A big blob with a bite taken from its right side.
    let (big, bite) = ([0.0, 0.0, 0.0], [1.0, 0.25, 0.0]);
    check_silhouette(&spheres(&[(big, 3.0), (bite, 1.5)], "4", ""), &|x, y, z| {
        sphere(x, y, z, big, 3.0) - sphere(x, y, z, bite, 1.5)
    });
    check_silhouette(&spheres(&pair, "1", ""), &|x, y, z| {
        sphere(x, y, z, a, 2.0) * sphere(x, y, z, b, 2.0)
    });
}

#[test]
fn varying_cs_colours_each_blob_by_its_field() {
    // Red and blue leaves; ambient-only matte, so a pixel's colour is Cs at the visible point.
    let (a, b, rad) = ([-0.6, 0.0, 0.0], [0.6, 0.0, 0.0], 1.6);
    let body = spheres(
        &[(a, rad), (b, rad)],
        "0",
        "\"varying color Cs\" [1 0 0  0 0 1]",
    );
    let r = render_one(&ortho_scene(&format!(
        "LightSource \"ambientlight\" 1 \"intensity\" 1\nSurface \"matte\" \"Ka\" 1 \"Kd\" 0\n{body}"
    )));
    for x in [60, 75, 90, 100, 110, 125, 140] {
        let (px, py) = ((x as f64 + 0.5) / PX - 2.0, -0.5 / PX);
        // The visible point: the first z (from the camera) where the sum reaches ½, bisected.
        let f = |z: f64| sphere(px, py, z, a, rad) + sphere(px, py, z, b, rad) - 0.5;
        let mut z0 = -2.0;
        while f(z0 + 0.01) <= 0.0 {
            z0 += 0.01;
        }
        let (mut lo, mut hi) = (z0, z0 + 0.01);
        for _ in 0..60 {
            let m = 0.5 * (lo + hi);
            if f(m) > 0.0 {
                hi = m
            } else {
                lo = m
            }
        }
        let (fa, fb) = (sphere(px, py, hi, a, rad), sphere(px, py, hi, b, rad));
        let (red, blue) = (fa / (fa + fb), fb / (fa + fb));
        let c = &r.rgba[(100 * 200 + x) * 4..(100 * 200 + x) * 4 + 3];
        // 0.02: the weights change by < 0.01 across a pixel; 8-bit-free float output.
        assert!(
            (f64::from(c[0]) - red).abs() < 0.02 && (f64::from(c[2]) - blue).abs() < 0.02,
            "x {x}: {c:?} vs ({red}, 0, {blue})"
        );
    }
}

/// Runs RIB through the RI state and returns its diagnostics and the primitive count.
fn diagnose(rib: &str) -> (Vec<String>, usize) {
    let mut ri = Ri::new();
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "bad.rib");
    for item in parser {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    let d = ri
        .drain_diagnostics()
        .into_iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| d.to_string())
        .collect();
    let prims = ri.take_frames().iter().map(|f| f.primitives.len()).sum();
    (d, prims)
}

#[test]
fn bad_blobby_reports_file_line_col_and_is_skipped() {
    let id = "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1";
    for (code, nleaf, needle) in [
        ("[1001 3]", 1, "floats[3"),
        ("[1001 0 999 0]", 1, "unknown opcode 999"),
        ("[1001 0]", 2, "nleaf is 2"),
        ("[1001 0 0 2 0 5]", 1, "instruction 5"),
    ] {
        let rib = format!(
            "WorldBegin\nSphere 1 -1 1 360\n  Blobby {nleaf} {code} [{id}] [\"\"]\nWorldEnd\n"
        );
        let (errors, prims) = diagnose(&rib);
        assert_eq!(errors.len(), 1, "{errors:?}");
        assert!(
            errors[0].starts_with("bad.rib:3:3: error: Blobby: "),
            "{}",
            errors[0]
        );
        assert!(errors[0].contains(needle), "{}", errors[0]);
        assert_eq!(prims, 1, "only the sphere is kept");
    }
}
