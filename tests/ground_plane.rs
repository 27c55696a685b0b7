//! Issue 21: a ground plane that reaches behind the eye and far outside the screen window (as
//! exporters write them) must dice about as many micropolygons as the pixels it covers, not
//! the millions its off-screen and near-eye parts would make, and must still render exactly
//! where it is seen (checked against an f64 ray cast, so a fix that culls too much fails).
//! The same floor as a `NuPatch` (whose sub-range bounds were the whole patch: no piece was
//! ever culled off screen), a bilinear `Patch` and a `Polygon`.
use glam::DVec3;
use illume_render::{render, RenderSettings};
mod support;

const W: usize = 64;
const H: usize = 48;
const COLOUR: [f64; 3] = [0.2, 0.6, 0.9];
/// The camera looks this far down (degrees) at the floor `y = −1`.
const PITCH: f64 = 40.0;

/// The floor's corners in camera space: world `x ∈ [−100, 0.5]`, `z ∈ [−50, 100]` on `y = −1`,
/// seen by a camera pitched down. It crosses the eye plane (world `z ≈ −0.84`), its left side
/// and both ends project far outside the 60° frame, and its right side `x = 0.5` crosses the
/// frame as a slanted edge.
fn corners() -> [DVec3; 4] {
    let (s, c) = PITCH.to_radians().sin_cos();
    let cam = |x: f64, z: f64| DVec3::new(x, -c + z * s, s + z * c);
    [
        cam(-100.0, -50.0),
        cam(0.5, -50.0),
        cam(-100.0, 100.0),
        cam(0.5, 100.0),
    ]
}

fn scene(floor: &str) -> String {
    format!(
        "Format {W} {H} 1\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\nShadingRate 1\n\
         Clipping 0.01 1000\nProjection \"perspective\" \"fov\" [60]\nWorldBegin\n\
         Color [{} {} {}]\nSurface \"constant\"\n{floor}\nWorldEnd\n",
        COLOUR[0], COLOUR[1], COLOUR[2]
    )
}

fn floors() -> [(&'static str, String); 3] {
    let [a, b, c, d] = corners();
    let p = |q: DVec3| format!("{} {} {}", q.x, q.y, q.z);
    [
        (
            "NuPatch",
            format!(
                "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [{} 1 {} 1 {} 1 {} 1]",
                p(a),
                p(b),
                p(c),
                p(d)
            ),
        ),
        (
            "Patch",
            format!(
                "Patch \"bilinear\" \"P\" [{} {} {} {}]",
                p(a),
                p(b),
                p(c),
                p(d)
            ),
        ),
        (
            "Polygon",
            format!("Polygon \"P\" [{} {} {} {}]", p(a), p(b), p(d), p(c)),
        ),
    ]
}

/// The fraction of pixel `(x, y)` the floor covers, by an f64 ray cast through 16 × 16 points
/// of the pixel: the ray `t·(sx/d, sy/d, 1)` (`d = 1/tan 30°`, screen `x ∈ [−4/3, 4/3]`,
/// `y ∈ [−1, 1]` up) meets the floor's plane at `t > 0.01` (the hither plane) inside the
/// parallelogram of [`corners`].
fn coverage(x: usize, y: usize) -> f64 {
    let [a, b, c, _] = corners();
    let (eu, ev) = (b - a, c - a);
    let n = eu.cross(ev);
    let d = 1.0 / 30f64.to_radians().tan();
    let mut hits = 0;
    for j in 0..16 {
        for i in 0..16 {
            let px = x as f64 + (i as f64 + 0.5) / 16.0;
            let py = y as f64 + (j as f64 + 0.5) / 16.0;
            let sx = -4.0 / 3.0 + px / W as f64 * 8.0 / 3.0;
            let sy = 1.0 - py / H as f64 * 2.0;
            let dir = DVec3::new(sx / d, sy / d, 1.0);
            let t = n.dot(a) / n.dot(dir);
            if t.is_nan() || t <= 0.01 {
                continue;
            }
            let q = dir * t - a;
            // Parallelogram coordinates: q = u·eu + v·ev.
            let (uu, uv, vv) = (eu.dot(eu), eu.dot(ev), ev.dot(ev));
            let (qu, qv) = (q.dot(eu), q.dot(ev));
            let det = uu * vv - uv * uv;
            let u = (qu * vv - qv * uv) / det;
            let v = (qv * uu - qu * uv) / det;
            if (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v) {
                hits += 1;
            }
        }
    }
    f64::from(hits) / 256.0
}

#[test]
fn a_ground_plane_through_the_eye_plane_dices_about_its_visible_pixels() {
    let cover: Vec<f64> = (0..H * W).map(|k| coverage(k % W, k / W)).collect();
    let visible: f64 = cover.iter().sum();
    // The floor's edge crosses the frame: some pixels are off it, some on.
    assert!(visible > 0.3 * (W * H) as f64 && visible < 0.9 * (W * H) as f64);
    for (name, floor) in floors() {
        let frame = &support::frames(&scene(&floor), None)[0];
        let r = render(frame, &RenderSettings::default());
        assert_eq!((r.width as usize, r.height as usize), (W, H));
        let mp = r.stats.micropolygons;
        eprintln!(
            "{name}: {mp} micropolygons, {} grids, {} culled pieces for {visible:.0} visible pixels",
            r.stats.grids, r.stats.culled_pieces
        );
        // k = 4: a grid's micropolygons are ShadingRate (1 pixel) long along its longest row
        // and column, so a foreshortened piece (its far row shorter than its near row, up to
        // ~2× before it splits again) dices up to ~2× more finely than its area needs, and
        // a piece may dice its off-screen part while less than half of it lies outside
        // (`refine::mostly_outside`), up to ~2× more. Before the fix the NuPatch diced ~60×.
        assert!(
            (mp as f64) <= 4.0 * visible,
            "{name}: {mp} micropolygons for {visible:.0} visible pixels"
        );
        // The image is the colour times the coverage: within 1e-4 where the ray cast sees all
        // or nothing, within 0.3 on the edge (16 jittered samples against 256 rays).
        for y in 0..H {
            for x in 0..W {
                let want = cover[y * W + x];
                let tol = if want == 0.0 || want == 1.0 {
                    1e-4
                } else {
                    0.3
                };
                let px = &r.rgba[(y * W + x) * 4..][..4];
                let alpha = f64::from(px[3]);
                assert!(
                    (alpha - want).abs() <= tol,
                    "{name}: pixel ({x}, {y}) alpha {alpha}, ray cast {want}"
                );
                for (c, &colour) in COLOUR.iter().enumerate() {
                    let got = f64::from(px[c]);
                    assert!(
                        (got - colour * alpha).abs() <= 1e-4,
                        "{name}: pixel ({x}, {y}) channel {c} = {got}, colour × alpha {}",
                        colour * alpha
                    );
                }
            }
        }
    }
}
