//! Displacement through real RIB (issue 10 part 2): the built-in `ripple` and `dented` shaders,
//! `Attribute "displacementbound"` and its coordinate systems, and the hider's handling of a
//! bound that is too small (warn once, re-bucket, same image).
use illume_render::{render, RenderSettings, Rendered};
use illume_ri::{Diagnostic, Frame, Severity};
mod support;

/// Parses `rib` and returns its frames with every RI diagnostic (parse and state).
fn frames_and_diagnostics(rib: &str) -> (Vec<Frame>, Vec<Diagnostic>) {
    support::frames_and_diagnostics(rib, None)
}

/// Renders the one frame of `rib`; returns the image and every diagnostic (RI and hider).
fn render_rib(rib: &str) -> (Rendered, Vec<Diagnostic>) {
    let (frames, mut diags) = frames_and_diagnostics(rib);
    assert_eq!(frames.len(), 1);
    let r = render(&frames[0], &RenderSettings::default());
    diags.extend(r.warnings.iter().cloned());
    let errors: Vec<_> = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .collect();
    assert!(errors.is_empty(), "{errors:?}");
    (r, diags)
}

fn bound_warnings(diags: &[Diagnostic]) -> Vec<&Diagnostic> {
    diags
        .iter()
        .filter(|d| d.message.contains("displacementbound"))
        .collect()
}

/// Covered area in scene units²: the sum of alpha over the pixels, each `px`² units.
fn covered_area(r: &Rendered, px: f64) -> f64 {
    r.rgba.chunks_exact(4).map(|p| f64::from(p[3])).sum::<f64>() * px * px
}

const RES: u32 = 120;
/// Scene units per pixel: ScreenWindow −1.5…1.5 over RES pixels.
const PX: f64 = 3.0 / RES as f64;

/// An orthographic unit sphere at z = 5, displaced outward by the constant `d` (ripple with
/// `Km 0`, `offset d`), with `bound` lines before it. Small buckets (8×8) so that a bound that
/// is too small really changes which buckets list the sphere's pieces.
fn constant_sphere(d: f32, bound: &str) -> String {
    format!(
        "Format {RES} {RES} 1\nScreenWindow -1.5 1.5 -1.5 1.5\nPixelSamples 4 4\n\
         PixelFilter \"box\" 1 1\nOption \"limits\" \"bucketsize\" [8 8]\n\
         Option \"limits\" \"gridsize\" [64]\nWorldBegin\n{bound}\n\
         Displacement \"ripple\" \"Km\" [0] \"frequency\" [0] \"offset\" [{d}]\n\
         Translate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n"
    )
}

/// A sphere of radius 1 pushed out by d covers the disc π(1+d)² (orthographic). Metric: the
/// alpha sum against the closed form, within 1% (the box-filtered, 16-sample edge of a
/// 48-pixel-radius disc is good to well under that; clipping by a too-small bound at 8-pixel
/// buckets loses far more). The too-small and missing bounds must give the same image as the
/// right one, bit for bit: the same pieces are diced the same way, only bucketed differently.
#[test]
fn constant_displacement_covers_the_grown_disc_whatever_the_bound() {
    let d = 0.25f32;
    let (right, right_diags) = render_rib(&constant_sphere(
        d,
        "Attribute \"displacementbound\" \"sphere\" [0.25]",
    ));
    assert!(bound_warnings(&right_diags).is_empty(), "{right_diags:?}");
    let expected = std::f64::consts::PI * (1.0 + f64::from(d)).powi(2);
    let area = covered_area(&right, PX);
    assert!(
        (area - expected).abs() / expected < 0.01,
        "area {area}, expected {expected}"
    );
    // The undisplaced sphere would be π: make sure the displacement happened at all.
    assert!(area > 1.4 * std::f64::consts::PI);

    for bound in ["Attribute \"displacementbound\" \"sphere\" [0.05]", ""] {
        let (r, diags) = render_rib(&constant_sphere(d, bound));
        let w = bound_warnings(&diags);
        assert_eq!(w.len(), 1, "bound {bound:?}: {diags:?}");
        // At the Sphere request (line 11 of the scene), with the bound given and measured.
        let text = w[0].to_string();
        assert!(text.starts_with("test.rib:11:"), "{text}");
        let given = if bound.is_empty() { "0.0000" } else { "0.0500" };
        assert!(text.contains("0.2500") && text.contains(given), "{text}");
        let a = covered_area(&r, PX);
        assert!(
            (a - expected).abs() / expected < 0.01,
            "bound {bound:?}: area {a}"
        );
        assert!(
            r.rgba == right.rgba,
            "bound {bound:?}: image differs from the right bound's"
        );
        assert!(r.z == right.z, "bound {bound:?}: depth differs");
    }
}

/// Same bits for any thread count, also when the bound is too small and buckets re-render.
#[test]
fn too_small_bound_renders_the_same_on_one_and_many_threads() {
    let rib = constant_sphere(0.25, "Attribute \"displacementbound\" \"sphere\" [0.01]");
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| render_rib(&rib).0);
    let four = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(|| render_rib(&rib).0);
    assert!(one.rgba == four.rgba && one.z == four.z);
}

/// No cracks between displaced grids: the facing-pole scene of the crack tests (unit sphere at
/// distance 6, 25° field of view, 300×300) cut into many small grids, displaced by a ripple
/// that stays outward (offset 0.05 ± 0.04) and by dented (inward by at most Km = 0.03). Either
/// way the displaced surface covers every pixel within 0.95 of the undisplaced silhouette, so
/// every such pixel must have alpha exactly 1.
#[test]
fn displaced_grids_do_not_crack() {
    for shader in [
        "Displacement \"ripple\" \"Km\" [0.04] \"frequency\" [8] \"offset\" [0.05]",
        "Displacement \"dented\" \"Km\" [0.03] \"frequency\" [4]",
    ] {
        let rib = format!(
            "Format 300 300 1\nProjection \"perspective\" \"fov\" [25]\nPixelSamples 2 2\n\
             Option \"limits\" \"gridsize\" [16]\nOption \"limits\" \"bucketsize\" [16 16]\n\
             WorldBegin\nAttribute \"displacementbound\" \"sphere\" [0.1]\n{shader}\n\
             Translate 0 0 6\nSphere 1 -1 1 360\nWorldEnd\n"
        );
        let (r, diags) = render_rib(&rib);
        assert!(bound_warnings(&diags).is_empty(), "{diags:?}");
        assert!(r.stats.grids > 100, "only {} grids", r.stats.grids);
        let holes = support::facing_pole_holes(&r);
        assert!(
            holes.is_empty(),
            "{shader}: {} holes, first {:?}",
            holes.len(),
            &holes[..holes.len().min(5)]
        );
    }
}

/// The ripple's profile is its closed form: a plane at z = 5 facing the camera (N towards
/// it), s = (x + 1)/2 across x ∈ [−1, 1], displaced by 0.1·sin(2π·1.5·s) + 0.15 along N, so
/// its depth at x is 5 − 0.15 − 0.1·sin(2π·1.5·s). One unjittered sample per pixel centre and
/// depthfilter "min" read the depth exactly there; the only error is the micropolygons'
/// linear interpolation of the sine (ShadingRate 0.25: half-pixel micropolygons, sagitta
/// A(2πf)²h²/8 ≈ 2e-5), so the threshold is 1e-4 scene units. Without displacement the error
/// would be up to 0.25.
#[test]
fn ripple_depth_profile_matches_its_closed_form() {
    let rib = "Format 200 100 1\nScreenWindow -1 1 -0.5 0.5\nPixelSamples 1 1\n\
               Hider \"hidden\" \"jitter\" [0]\nPixelFilter \"box\" 1 1\nShadingRate 0.25\n\
               WorldBegin\nAttribute \"displacementbound\" \"sphere\" [0.25]\n\
               Displacement \"ripple\" \"Km\" [0.1] \"frequency\" [1.5] \"offset\" [0.15]\n\
               Patch \"bilinear\" \"P\" [-1 1 5  1 1 5  -1 -1 5  1 -1 5]\nWorldEnd\n";
    let (r, diags) = render_rib(rib);
    assert!(bound_warnings(&diags).is_empty(), "{diags:?}");
    let mut worst = 0.0f64;
    for y in 10..90 {
        for x in 0..200u32 {
            let sx = -1.0 + (f64::from(x) + 0.5) / 100.0;
            let s = (sx + 1.0) / 2.0;
            let expected = 5.0 - 0.15 - 0.1 * (std::f64::consts::TAU * 1.5 * s).sin();
            let z = f64::from(r.z[(y * 200 + x) as usize]);
            worst = worst.max((z - expected).abs());
        }
    }
    assert!(worst < 1e-4, "worst depth error {worst}");
}

/// `"coordinatesystem"` says where the sphere radius is measured: object (the default), world,
/// camera, shader (the Displacement's space) or a named `CoordinateSystem`; the radius becomes
/// camera space by that space's largest scale.
#[test]
fn displacementbound_coordinate_systems_scale_the_radius() {
    let rib = "WorldBegin\nScale 2 2 2\nCoordinateSystem \"twice\"\n\
               Displacement \"ripple\"\nScale 1.5 1.5 1.5\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1]\nSphere 1 -1 1 360\nAttributeEnd\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1] \"coordinatesystem\" [\"object\"]\nSphere 1 -1 1 360\nAttributeEnd\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1] \"coordinatesystem\" [\"world\"]\nSphere 1 -1 1 360\nAttributeEnd\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1] \"coordinatesystem\" [\"camera\"]\nSphere 1 -1 1 360\nAttributeEnd\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1] \"coordinatesystem\" [\"shader\"]\nSphere 1 -1 1 360\nAttributeEnd\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1] \"coordinatesystem\" [\"twice\"]\nSphere 1 -1 1 360\nAttributeEnd\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.1] \"coordinatesystem\" [\"nowhere\"]\nSphere 1 -1 1 360\nAttributeEnd\n\
               WorldEnd\n";
    let (frames, diags) = frames_and_diagnostics(rib);
    let bounds: Vec<f32> = frames[0]
        .primitives
        .iter()
        .map(|p| p.attributes.displacement_bound)
        .collect();
    let expected = [0.3, 0.3, 0.1, 0.1, 0.2, 0.2, 0.3];
    assert_eq!(bounds.len(), expected.len());
    for (b, e) in bounds.iter().zip(expected) {
        assert!((b - e).abs() < 1e-6, "{bounds:?} vs {expected:?}");
    }
    let unknown: Vec<_> = diags
        .iter()
        .filter(|d| d.message.contains("nowhere"))
        .collect();
    assert_eq!(unknown.len(), 1, "{diags:?}");
    assert_eq!(unknown[0].severity, Severity::Warning);
}

/// The same bound behaves by its space: a sphere scaled ×2 displaced 0.6 (camera units) is
/// covered by "sphere" [0.3] in object space (0.6 in camera space: no warning) but not in
/// world space (0.3: one warning, and without re-bucketing the disc would be clipped by 7
/// pixels at 4-pixel buckets), and both images are the same, the disc π·2.6² within 1%.
#[test]
fn a_world_bound_on_a_scaled_object_is_not_scaled() {
    let scene = |space: &str| {
        format!(
            "Format 160 160 1\nScreenWindow -3.2 3.2 -3.2 3.2\nPixelSamples 4 4\n\
             PixelFilter \"box\" 1 1\nOption \"limits\" \"bucketsize\" [4 4]\nWorldBegin\n\
             Translate 0 0 10\nScale 2 2 2\n\
             Attribute \"displacementbound\" \"sphere\" [0.3] \"coordinatesystem\" [\"{space}\"]\n\
             Displacement \"ripple\" \"Km\" [0] \"frequency\" [0] \"offset\" [0.6]\n\
             Sphere 1 -1 1 360\nWorldEnd\n"
        )
    };
    let (object, od) = render_rib(&scene("object"));
    let (world, wd) = render_rib(&scene("world"));
    assert!(bound_warnings(&od).is_empty(), "{od:?}");
    assert_eq!(bound_warnings(&wd).len(), 1, "{wd:?}");
    let expected = std::f64::consts::PI * 2.6f64.powi(2);
    let area = covered_area(&object, 6.4 / 160.0);
    assert!(
        (area - expected).abs() / expected < 0.01,
        "area {area} vs {expected}"
    );
    assert!(
        object.rgba == world.rgba,
        "area {} with the world bound",
        covered_area(&world, 0.04)
    );
}

/// The shared corpus (`../shared/corpus` or `$ILLUME_CORPUS`).
/// Aqsis's disp_test.rib names "brickbump", an SL shader we do not have: one warning naming
/// it, and the image is exactly the scene without the Displacement line. `render` exits 0
/// (the README's rule: warnings only), writing its file into its working directory (a temp
/// dir, never the corpus).
#[test]
fn aqsis_disp_test_warns_once_and_renders_undisplaced() {
    let Some(path) = illume_testenv::shared_file("corpus/aqsis2001/disp_test.rib") else {
        return; // skipped loudly; a failure under CI=true
    };
    let rib = std::fs::read_to_string(&path).unwrap();
    let (r, diags) = render_rib(&rib);
    let named: Vec<_> = diags
        .iter()
        .filter(|d| d.message.contains("brickbump"))
        .collect();
    assert_eq!(named.len(), 1, "{diags:?}");
    assert_eq!(named[0].request.as_deref(), Some("Displacement"));
    let without: String = rib
        .lines()
        .filter(|l| !l.trim_start().starts_with("Displacement"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(without, rib);
    let (plain, _) = render_rib(&without);
    assert!(r.rgba == plain.rgba, "brickbump must render undisplaced");
    assert!(
        r.rgba.chunks_exact(4).any(|p| p[3] > 0.0),
        "the sphere is drawn"
    );

    // Through the binary when it is built (cargo build -p render) or named by $RENDER.
    let Some(bin) = illume_testenv::require_built("render", "RENDER") else {
        return; // skipped loudly; a failure under CI=true
    };
    let dir = std::env::temp_dir().join(format!("illume-disp-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new(&bin)
        .arg("-q")
        .arg(&path)
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert_eq!(stderr.matches("brickbump").count(), 1, "{stderr}");
    assert!(dir.join("disp_test.tif").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Ray-traced shadow casters are displaced too. A sphere of radius 1 pushed out by 0.5 (so
/// 1.5) at z = 5 under a distant light along (1, 0, 1) shadows the plane z = 10 in an ellipse
/// of semi-axes 1.5 and 1.5·√2: area π·1.5²·√2 ≈ 10.0 (the undisplaced caster would give
/// 4.4). Metric: pixels on the shadow's side of the frame darker than half the lit plane,
/// times the pixel area, within 3% (the ellipse's edge pixels and the caster's tessellation).
#[test]
fn displaced_casters_cast_displaced_shadows() {
    let rib = "Format 200 100 1\nScreenWindow -5 5 -2.5 2.5\nPixelSamples 2 2\n\
               WorldBegin\nAttribute \"light\" \"shadows\" [\"on\"]\n\
               LightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [0 0 0] \"to\" [1 0 1]\n\
               Surface \"matte\" \"Ka\" [0] \"Kd\" [1]\n\
               AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [0.5]\n\
               Displacement \"ripple\" \"Km\" [0] \"frequency\" [0] \"offset\" [0.5]\n\
               Translate -2.5 0 5\nSphere 1 -1 1 360\nAttributeEnd\n\
               Patch \"bilinear\" \"P\" [-5 2.5 10  5 2.5 10  -5 -2.5 10  5 -2.5 10]\nWorldEnd\n";
    let (r, diags) = render_rib(rib);
    assert!(bound_warnings(&diags).is_empty(), "{diags:?}");
    // The lit plane: matte, N·L = cos 45°.
    let lit = std::f32::consts::FRAC_1_SQRT_2;
    let mut dark = 0usize;
    for y in 0..100 {
        for x in 100..200 {
            let p = &r.rgba[(y * 200 + x) * 4..][..4];
            dark += usize::from(p[0] < 0.5 * lit);
        }
    }
    let area = dark as f64 * 0.05 * 0.05;
    let expected = std::f64::consts::PI * 1.5 * 1.5 * std::f64::consts::SQRT_2;
    assert!(
        (area - expected).abs() / expected < 0.03,
        "shadow area {area}, expected {expected}"
    );
}

/// A displaced surface that comes nearer than its bound said is not lost to occlusion culling:
/// a sphere behind an opaque square (z = 5) is pushed out by 1 (front at z = 4.5) through the
/// square. With no bound, buckets the square fills cull the sphere's pieces by their
/// undisplaced depth; the re-render must bring them back: the image equals the one with the
/// right bound, bit for bit, and the sphere is in front at the centre (depth 4.5).
#[test]
fn displacement_towards_the_camera_is_not_occlusion_culled() {
    let scene = |bound: &str| {
        format!(
            "Format 120 120 1\nScreenWindow -3 3 -3 3\nPixelSamples 2 2\n\
             Option \"limits\" \"bucketsize\" [8 8]\nWorldBegin\n\
             Patch \"bilinear\" \"P\" [-1.2 1.2 5  1.2 1.2 5  -1.2 -1.2 5  1.2 -1.2 5]\n\
             AttributeBegin\n{bound}\nColor [1 0 0]\n\
             Displacement \"ripple\" \"Km\" [0] \"frequency\" [0] \"offset\" [1]\n\
             Translate 0 0 6.5\nSphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n"
        )
    };
    let (right, rd) = render_rib(&scene("Attribute \"displacementbound\" \"sphere\" [1]"));
    let (none, nd) = render_rib(&scene(""));
    assert!(bound_warnings(&rd).is_empty(), "{rd:?}");
    assert_eq!(bound_warnings(&nd).len(), 1, "{nd:?}");
    let centre = 60 * 120 + 60;
    assert!((right.z[centre] - 4.5).abs() < 1e-3, "{}", right.z[centre]);
    assert!(none.z == right.z, "depth at the centre {}", none.z[centre]);
    assert!(none.rgba == right.rgba);
}

/// Depth passes (`Surface "null"`, as for shadow maps) see the displaced surface: the front of
/// a unit sphere at z = 5 pushed out by 0.25 is at depth 3.75 (undisplaced: 4), within the
/// micropolygon chord error at the pole (1e-3).
#[test]
fn null_surface_depth_passes_are_displaced() {
    let rib = constant_sphere(0.25, "Attribute \"displacementbound\" \"sphere\" [0.25]")
        .replace("WorldBegin\n", "WorldBegin\nSurface \"null\"\n");
    let (r, _) = render_rib(&rib);
    let centre = (RES / 2 * RES + RES / 2) as usize;
    assert!((r.z[centre] - 3.75).abs() < 1e-3, "depth {}", r.z[centre]);
}
