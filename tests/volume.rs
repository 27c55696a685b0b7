//! Volume shaders through real RIB (issue 19 part 3): `Atmosphere` runs on every shaded point
//! after the surface, before the hider composites.
//!
//! * `fog` over a constant plane at depth d: every pixel equals
//!   `mix(background, C, exp(-|P|/distance))` for the f64 point `P` its centre ray hits, within
//!   1e-4 (smooth shading interpolation over one-pixel micropolygons: the interpolation error
//!   of the smooth `exp` is ~1e-6; 1e-4 leaves room for f32 rounding).
//! * `depthcue`: planes at several depths are unchanged before `mindistance`, the background
//!   beyond `maxdistance`, and linear in `depth()` between, within 1e-5.
//! * An SL fog (the RI 3.2 text) equals the built-in fog within 1e-4 per channel.
//! * A smoke-like SL volume ray-marching toward `E` with `illuminance(Pmarch)`: rays through a
//!   spotlight's beam are brighter than rays beside it (≥ 10×: outside the cone `Cl = 0`), and
//!   the half of the beam behind a ray-traced occluder is dark (< 10% of the lit half) while
//!   without the occluder both halves agree within 25% (the beam is symmetric).
//! * The same volume marched in steps of 0.01 equals the f64 single-scattering integral of the
//!   spotlight's `Cl` along the pixel's centre ray within 2% (smooth shading interpolation;
//!   the midpoint rule's error at the cone's 0.01 rad soft edge is well under that).
//! * Where no surface is hit the atmosphere does not run: background pixels stay 0, alpha 0.
use illume_render::{render, RenderSettings, Rendered};
use std::path::{Path, PathBuf};
mod support;

use support::frames;

const RES: u32 = 24;
/// Half the field of view's tangent (`Projection "perspective" "fov" 20`).
const FOV: f64 = 20.0;

fn render_rib(rib: &str) -> Rendered {
    let f = frames(rib, None);
    assert_eq!(f.len(), 1);
    let r = render(&f[0], &RenderSettings::default());
    for w in &r.warnings {
        assert!(!w.to_string().contains("volume"), "{w}");
    }
    r
}

fn pixel(r: &Rendered, x: u32, y: u32) -> [f64; 4] {
    let k = ((y * r.width + x) * 4) as usize;
    std::array::from_fn(|c| f64::from(r.rgba[k + c]))
}

/// A constant plane of colour `c` filling the view at camera depth `d`, under `atmosphere`.
fn plane(d: f64, c: [f64; 3], atmosphere: &str, options: &str) -> String {
    let [r, g, b] = c;
    format!(
        "{options}Format {RES} {RES} 1\nProjection \"perspective\" \"fov\" {FOV}\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         WorldBegin\n{atmosphere}\nShadingInterpolation \"smooth\"\nShadingRate 1\n\
         Color {r} {g} {b}\nSurface \"constant\"\n\
         Polygon \"P\" [-10 -10 {d}  10 -10 {d}  10 10 {d}  -10 10 {d}]\nWorldEnd\n"
    )
}

/// `|P|` of the plane point at depth `d` seen through the centre of pixel (x, y).
fn distance_through(x: u32, y: u32, d: f64) -> f64 {
    let t = (FOV / 2.0).to_radians().tan();
    let sx = (2.0 * (f64::from(x) + 0.5) / f64::from(RES) - 1.0) * t;
    let sy = (2.0 * (f64::from(y) + 0.5) / f64::from(RES) - 1.0) * t;
    d * (1.0 + sx * sx + sy * sy).sqrt()
}

const C: [f64; 3] = [0.9, 0.5, 0.2];
const BG: [f64; 3] = [0.2, 0.3, 0.7];

#[test]
fn fog_is_the_closed_form_exponential_of_distance() {
    for (d, dist) in [(4.0, 3.0), (7.0, 20.0)] {
        let fog = format!("Atmosphere \"fog\" \"distance\" [{dist}] \"background\" [0.2 0.3 0.7]");
        let r = render_rib(&plane(d, C, &fog, ""));
        let mut worst = 0.0f64;
        for y in 0..RES {
            for x in 0..RES {
                let e = (-distance_through(x, y, d) / dist).exp();
                let p = pixel(&r, x, y);
                for c in 0..3 {
                    worst = worst.max((p[c] - (BG[c] + (C[c] - BG[c]) * e)).abs());
                }
                assert!((p[3] - 1.0).abs() < 1e-6, "alpha {}", p[3]);
            }
        }
        assert!(worst < 1e-4, "d {d} distance {dist}: worst {worst}");
    }
}

#[test]
fn depthcue_is_linear_in_depth_between_its_distances() {
    // Clipping 1 11: depth(P) = (z − 1)/10. mindistance .2 (z = 3), maxdistance .6 (z = 7).
    let cue = "Atmosphere \"depthcue\" \"mindistance\" [0.2] \"maxdistance\" [0.6] \
               \"background\" [0.2 0.3 0.7]";
    for z in [2.0, 3.0, 4.0, 5.5, 7.0, 9.0] {
        let r = render_rib(&plane(z, C, cue, "Clipping 1 11\n"));
        let depth: f64 = (z - 1.0) / 10.0;
        let t = ((depth - 0.2) / 0.4).clamp(0.0, 1.0);
        for (x, y) in [(0, 0), (12, 12), (23, 5)] {
            let p = pixel(&r, x, y);
            for c in 0..3 {
                let want = C[c] + (BG[c] - C[c]) * t;
                assert!(
                    (p[c] - want).abs() < 1e-5,
                    "z {z} ({x},{y}) c{c}: {} vs {want}",
                    p[c]
                );
            }
        }
    }
}

/// A fresh directory for one test's shaders.
fn shader_dir(case: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("illume-volume-{}-{case}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    for (name, text) in files {
        std::fs::write(d.join(name), text).unwrap();
    }
    d
}

fn searchpath(dir: &Path) -> String {
    format!("Option \"searchpath\" \"shader\" [\"{}\"]\n", dir.display())
}

/// RI 3.2's `fog`, word for word, under another name.
const SL_FOG: &str = "volume slfog(float distance = 1; color background = 0;)
{
    float d = 1 - exp(-length(I)/distance);
    Ci = mix(Ci, background, d);
    Oi = mix(Oi, color(1,1,1), d);
}
";

#[test]
fn an_sl_fog_equals_the_built_in_fog() {
    let dir = shader_dir("fog", &[("slfog.sl", SL_FOG)]);
    let params = "\"distance\" [5] \"background\" [0.2 0.3 0.7]";
    let sl = render_rib(&plane(
        6.0,
        C,
        &format!("Atmosphere \"slfog\" {params}"),
        &searchpath(&dir),
    ));
    let builtin = render_rib(&plane(6.0, C, &format!("Atmosphere \"fog\" {params}"), ""));
    let worst = sl
        .rgba
        .iter()
        .zip(&builtin.rgba)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    // Both differ from the plain plane (the fog ran in both).
    assert!((sl.rgba[0] - C[0] as f32).abs() > 0.1);
    assert!(worst < 1e-4, "worst {worst}");
}

#[test]
fn atmosphere_does_not_run_where_no_surface_is_hit() {
    let rib = format!(
        "Format {RES} {RES} 1\nProjection \"perspective\" \"fov\" {FOV}\nPixelSamples 1 1\n\
         PixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\nWorldBegin\n\
         Atmosphere \"fog\" \"distance\" [1] \"background\" [1 1 1]\nSurface \"constant\"\n\
         Translate 0 0 5\nSphere 0.3 -0.3 0.3 360\nWorldEnd\n"
    );
    let r = render_rib(&rib);
    assert_eq!(pixel(&r, 0, 0), [0.0; 4], "background untouched");
    let centre = pixel(&r, 12, 12);
    // The sphere's front at ~4.7: almost fully fogged toward white.
    assert!(centre[0] > 0.95 && centre[3] > 0.99, "{centre:?}");
}

/// The book's smoke pattern, homogeneous: march from `P` toward `E`, gathering `Cl` from every
/// light at each step (`illuminance(Pmarch)`), and add the in-scattered light.
const SL_BEAM: &str = "volume beam(float density = 1; float stepsize = 0.05;)
{
    color Cv = 0;
    float len = length(I);
    vector dir = -normalize(I);
    float t;
    for (t = stepsize / 2; t < len; t += stepsize) {
        point Pm = P + t * dir;
        illuminance(Pm) {
            Cv += Cl * density * stepsize;
        }
    }
    Ci += Cv;
}
";

const BEAM_RES: u32 = 32;
const SPOT_FROM: [f64; 3] = [-6.0, 0.0, 5.0];
const CONE: f64 = 0.15;
const CONE_DELTA: f64 = 0.01;
const INTENSITY: f64 = 40.0;

/// A spot along +x through (0, 0, 5) with a 0.15 rad cone, ray-traced shadows; a black wall at
/// z = 10 under the `beam` atmosphere; with `occluder`, a square in the plane x = −4 covering
/// the upper half (y > 0) of the beam, outside the view.
fn beam_scene(dir: &Path, occluder: bool, stepsize: f64) -> Rendered {
    render_rib(&beam_rib(dir, occluder, stepsize))
}

/// The RIB of [`beam_scene`].
fn beam_rib(dir: &Path, occluder: bool, stepsize: f64) -> String {
    let [fx, fy, fz] = SPOT_FROM;
    let occluder = if occluder {
        "Polygon \"P\" [-4 0 3  -4 2 3  -4 2 7  -4 0 7]\n"
    } else {
        ""
    };
    format!(
        "{}Format {BEAM_RES} {BEAM_RES} 1\nProjection \"perspective\" \"fov\" 40\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\nWorldBegin\n\
         AttributeBegin\nAttribute \"light\" \"shadows\" [\"on\"]\n\
         LightSource \"spotlight\" 1 \"intensity\" [{INTENSITY}] \"from\" [{fx} {fy} {fz}] \
         \"to\" [0 0 5] \"coneangle\" [{CONE}] \"conedeltaangle\" [{CONE_DELTA}]\nAttributeEnd\n\
         Illuminate 1 1\nAtmosphere \"beam\" \"stepsize\" [{stepsize}]\n\
         ShadingInterpolation \"smooth\"\nColor 0 0 0\nSurface \"constant\"\n\
         Polygon \"P\" [-10 -10 10  10 -10 10  10 10 10  -10 10 10]\n{occluder}WorldEnd\n",
        searchpath(dir)
    )
}

/// Mean red over columns 20..30 (x > 0) of `rows`.
fn band(r: &Rendered, rows: std::ops::Range<u32>) -> f64 {
    let n = (rows.len() * 10) as f64;
    rows.flat_map(|y| (20..30).map(move |x| (x, y)))
        .map(|(x, y)| pixel(r, x, y)[0])
        .sum::<f64>()
        / n
}

#[test]
fn a_marched_volume_shows_the_spotlight_beam_and_the_occluders_shadow() {
    let dir = shader_dir("beam", &[("beam.sl", SL_BEAM)]);
    // Screen y of a raster row (raster y grows downward): tan(20°)·(1 − 2(y+.5)/32). Rows
    // 17..20 look at y ≈ −0.4 at z = 5 (lower half of the beam), rows 12..15 at y ≈ +0.4
    // (upper half), rows 28..32 at |y| > 1.4 at every depth (outside the cone).
    let open = beam_scene(&dir, false, 0.05);
    let (lower, upper, outside) = (
        band(&open, 17..20),
        band(&open, 12..15),
        band(&open, 28..32),
    );
    assert!(lower > 0.01, "the beam scatters light: {lower}");
    assert!(lower > 10.0 * outside, "lit {lower} vs outside {outside}");
    // The beam is symmetric about y = 0: both halves within 25% (the rows are mirror images
    // up to a third of a row).
    assert!(
        (upper / lower - 1.0).abs() < 0.25,
        "upper {upper} lower {lower}"
    );
    let blocked = beam_scene(&dir, true, 0.05);
    let (lower_b, upper_b) = (band(&blocked, 17..20), band(&blocked, 12..15));
    assert!(
        (lower_b - lower).abs() < 1e-6 * lower,
        "{lower_b} vs {lower}"
    );
    assert!(
        upper_b < 0.1 * lower_b,
        "shadowed {upper_b} vs lit {lower_b}"
    );
}

/// `Cl` of the built-in spotlight at `p` (Listing 9.17, f64, unshadowed).
fn spot_cl(p: [f64; 3]) -> f64 {
    let l = [
        p[0] - SPOT_FROM[0],
        p[1] - SPOT_FROM[1],
        p[2] - SPOT_FROM[2],
    ];
    let r2 = l.iter().map(|v| v * v).sum::<f64>();
    let cosangle = l[0] / r2.sqrt(); // the axis is +x
    let (cos_out, cos_in) = (CONE.cos(), (CONE - CONE_DELTA).cos());
    if cosangle < cos_out {
        return 0.0;
    }
    let t = ((cosangle - cos_out) / (cos_in - cos_out)).clamp(0.0, 1.0);
    INTENSITY * cosangle * cosangle * t * t * (3.0 - 2.0 * t) / r2
}

#[test]
fn marched_in_scattering_equals_the_single_scattering_integral() {
    let dir = shader_dir("scatter", &[("beam.sl", SL_BEAM)]);
    let r = beam_scene(&dir, false, 0.01);
    let t = 20f64.to_radians().tan();
    for (x, y) in [(25, 18), (21, 17), (28, 19), (24, 14)] {
        // The f64 integral of Cl along the pixel's centre ray, wall (z = 10) to eye.
        let sx = (2.0 * (f64::from(x) + 0.5) / f64::from(BEAM_RES) - 1.0) * t;
        let sy = (1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(BEAM_RES)) * t;
        let len = 10.0 * (1.0 + sx * sx + sy * sy).sqrt();
        let steps = 200_000;
        let h = len / f64::from(steps);
        let want: f64 = (0..steps)
            .map(|k| {
                let z = 10.0 * (1.0 - (f64::from(k) + 0.5) * h / len);
                spot_cl([sx * z, sy * z, z]) * h
            })
            .sum();
        let got = pixel(&r, x, y)[0];
        assert!(want > 0.1, "({x},{y}) crosses the beam: {want}");
        assert!(
            (got / want - 1.0).abs() < 0.02,
            "({x},{y}): marched {got} vs integral {want}"
        );
    }
}

/// RI 3.2 §15.6 message passing: the surface's `atmosphere("level", x)` reads the SL
/// atmosphere's parameter as bound (here its RIB value), and answers 0 without an atmosphere.
#[test]
fn the_surface_reads_the_atmospheres_parameters() {
    let dir = shader_dir(
        "message",
        &[
            ("tag.sl", "volume tag(float level = 0.5) { }\n"),
            (
                "reader.sl",
                "surface reader() {
                    float x = -1;
                    Oi = 1;
                    if (atmosphere(\"level\", x) == 1) Ci = x; else Ci = 0.9;
                }\n",
            ),
        ],
    );
    let scene = |atmosphere: &str| {
        let rib = format!(
            "{}Format 4 4 1\nProjection \"perspective\" \"fov\" 20\nWorldBegin\n{atmosphere}\n\
             Surface \"reader\"\nPolygon \"P\" [-9 -9 5  9 -9 5  9 9 5  -9 9 5]\nWorldEnd\n",
            searchpath(&dir)
        );
        pixel(&render_rib(&rib), 1, 1)[0]
    };
    assert!((scene("Atmosphere \"tag\" \"level\" [0.3]") - 0.3).abs() < 1e-6);
    assert!((scene("Atmosphere \"tag\"") - 0.5).abs() < 1e-6);
    assert!((scene("") - 0.9).abs() < 1e-6);
}

/// Re-running the lights inside a volume (shadow rays included) gives the same bits with one
/// and two threads.
#[test]
fn marched_volumes_are_identical_for_one_and_two_threads() {
    let dir = shader_dir("threads", &[("beam.sl", SL_BEAM)]);
    let f = frames(&beam_rib(&dir, true, 0.05), None);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&f[0], &RenderSettings::default()))
    };
    let bits = |r: &Rendered| r.rgba.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let (one, two) = (run(1), run(2));
    assert!(one.rgba.iter().any(|&v| v > 0.01), "the beam shows");
    assert_eq!(bits(&one), bits(&two));
}
