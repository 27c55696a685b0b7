//! Shared by the integration tests: RIB text through the real parser into the RI state.
use illume_ri::{from_rib_diagnostic, Diagnostic, Frame, Ri, Severity};

/// Parses `rib` (named `test.rib` in diagnostics) and returns its frames with every diagnostic
/// of the parser and the RI state. `crop` overrides every frame's `CropWindow`, as
/// `render --crop` does.
#[allow(dead_code)] // not every test binary parses without rendering
pub fn frames_and_diagnostics(rib: &str, crop: Option<[f32; 4]>) -> (Vec<Frame>, Vec<Diagnostic>) {
    let mut ri = Ri::new();
    ri.set_crop_override(crop);
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "test.rib");
    for item in parser {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    let diags = ri.drain_diagnostics();
    (ri.take_frames(), diags)
}

/// Parses `rib` and returns its frames, asserting that neither the parser nor the RI state
/// reported an error (warnings are allowed: real scenes have them). `crop` as in
/// [`frames_and_diagnostics`].
#[allow(dead_code)] // not every test binary parses without rendering
pub fn frames(rib: &str, crop: Option<[f32; 4]>) -> Vec<Frame> {
    let (frames, diags) = frames_and_diagnostics(rib, crop);
    let errors: Vec<_> = diags
        .into_iter()
        .filter(|d| d.severity == Severity::Error)
        .collect();
    assert!(errors.is_empty(), "{errors:?}");
    frames
}

/// What `render` does with one RIB stream, through the same library loop
/// (`illume_render::render_frames_in_order`): frames render in file order as soon as they end,
/// their displays are written, and Make* requests between frames see the files earlier frames
/// wrote. Asserts that no parse, RI, render or display error occurred.
#[allow(dead_code)] // each test binary compiles this module; not all of them render pipelines
pub fn run_rib(rib: &str) -> Vec<illume_render::Rendered> {
    let mut ri = Ri::new();
    ri.set_texture_maker(illume_render::texture_maker(|_, _| {}));
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "test.rib");
    let mut out = Vec::new();
    illume_render::render_frames_in_order(
        &mut ri,
        parser,
        |d| assert!(d.severity != Severity::Error, "{d}"),
        |frame| {
            let cache =
                illume_texture::TextureCache::new(frame.options.texture_memory as usize * 1024);
            let settings = illume_render::RenderSettings {
                progress: None,
                textures: Some(&cache),
            };
            let r = illume_render::render(&frame, &settings);
            let errors: Vec<_> = r
                .warnings
                .iter()
                .filter(|d| d.severity == Severity::Error)
                .collect();
            assert!(errors.is_empty(), "{errors:?}");
            for w in illume_render::write_displays(&frame, &r) {
                w.unwrap();
            }
            out.push(r);
        },
    );
    out
}

/// Pixels of a 300×300 render whose centre lies within 0.95 of the silhouette radius of a unit
/// sphere at distance 6 seen with a 25° field of view, and that are not fully covered: the
/// crack detector of the facing-pole tests (quadric and NURBS spheres).
#[allow(dead_code)] // only the render and geometry tests look for cracks
pub fn facing_pole_holes(r: &illume_render::Rendered) -> Vec<(usize, usize, f32)> {
    // Silhouette radius in raster: tan(asin(1/6)) against the 12.5° half field of view.
    let rad = (1.0f64 / 6.0).asin().tan() / 12.5f64.to_radians().tan() * 150.0;
    let mut holes = Vec::new();
    for y in 0..300 {
        for x in 0..300 {
            let (dx, dy) = (x as f64 + 0.5 - 150.0, y as f64 + 0.5 - 150.0);
            let a = r.rgba[(y * 300 + x) * 4 + 3];
            if (dx * dx + dy * dy).sqrt() < 0.95 * rad && a != 1.0 {
                holes.push((x, y, a));
            }
        }
    }
    holes
}

/// Where the reflection of the orthographic camera ray at camera `(x, y)` (direction +z) off a
/// unit mirror sphere centred at camera `(0, 0, sphere_z)` meets the plane `z = plane_z` behind
/// the eye, in f64: `None` off the sphere or when the reflected ray runs (nearly) parallel to
/// the plane or away from it. The closed form the ray-tracing tests compare pixels with.
#[allow(dead_code)] // only the ray-tracing tests use it
pub fn mirror_sphere_reflection(x: f64, y: f64, sphere_z: f64, plane_z: f64) -> Option<(f64, f64)> {
    let r2 = x * x + y * y;
    if r2 >= 1.0 {
        return None;
    }
    let z = sphere_z - (1.0 - r2).sqrt();
    let n = [x, y, z - sphere_z];
    // I = (0, 0, 1): R = I − 2(I·N)N.
    let r = [
        -2.0 * n[2] * n[0],
        -2.0 * n[2] * n[1],
        1.0 - 2.0 * n[2] * n[2],
    ];
    if r[2] >= -1e-3 {
        return None;
    }
    let t = (plane_z - z) / r[2];
    Some((x + t * r[0], y + t * r[1]))
}
