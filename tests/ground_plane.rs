//! Issue 21: a ground plane that reaches behind the eye and far outside the screen window (as
//! exporters write them) must dice about as many micropolygons as the pixels it covers, not
//! the millions its off-screen and near-eye parts would make, and must still render exactly
//! where it is seen. The same floor as a `NuPatch` (whose sub-range bounds were the whole
//! patch: no piece was ever culled off screen), a bilinear `Patch` and a `Polygon`.
use illume_render::{render, RenderSettings};
mod support;

const W: usize = 64;
const H: usize = 48;
/// The floor's height below the eye, its far edge and the surface colour.
const DROP: f64 = 1.0;
const FAR: f64 = 100.0;
const COLOUR: [f64; 3] = [0.2, 0.6, 0.9];

/// The floor `y = −1` (camera space), `x ∈ [−100, 100]`, `z ∈ [−50, 100]`: it crosses the eye
/// plane, and its sides project far outside the 60° frame.
fn scene(floor: &str) -> String {
    format!(
        "Format {W} {H} 1\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\nShadingRate 1\n\
         Clipping 0.01 1000\nProjection \"perspective\" \"fov\" [60]\nWorldBegin\n\
         Color [{} {} {}]\nSurface \"constant\"\n{floor}\nWorldEnd\n",
        COLOUR[0], COLOUR[1], COLOUR[2]
    )
}

const FLOORS: [(&str, &str); 3] = [
    (
        "NuPatch",
        "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" \
         [-100 -1 -50 1  100 -1 -50 1  -100 -1 100 1  100 -1 100 1]",
    ),
    (
        "Patch",
        "Patch \"bilinear\" \"P\" [-100 -1 -50  100 -1 -50  -100 -1 100  100 -1 100]",
    ),
    (
        "Polygon",
        "Polygon \"P\" [-100 -1 -50  100 -1 -50  100 -1 100  -100 -1 100]",
    ),
];

/// The fraction of pixel row `row` the floor covers, in closed form: a floor point at depth
/// `z > 0` projects to screen `y = −DROP·d/z` (`d = 1/tan 30°`), so the floor covers the screen
/// below `y = −DROP·d/FAR` (its far edge) and all of the width (its sides project beyond
/// `|x| = d·100/z ≥ 1.73` for every visible depth). Rows span 2/H of screen `y`, top = +1.
fn row_coverage(row: usize) -> f64 {
    let d = 1.0 / (30f64).to_radians().tan();
    let edge = -DROP * d / FAR;
    let (top, bottom) = (1.0 - 2.0 * row as f64 / H as f64, 1.0 - 2.0 * (row + 1) as f64 / H as f64);
    ((edge - bottom) / (top - bottom)).clamp(0.0, 1.0)
}

#[test]
fn a_ground_plane_through_the_eye_plane_dices_about_its_visible_pixels() {
    // Pixel area the floor covers: ~1,510 of the 3,072.
    let visible: f64 = (0..H).map(row_coverage).sum::<f64>() * W as f64;
    for (name, floor) in FLOORS {
        let frame = &support::frames(&scene(floor), None)[0];
        let r = render(frame, &RenderSettings::default());
        assert_eq!((r.width as usize, r.height as usize), (W, H));
        let mp = r.stats.micropolygons;
        eprintln!(
            "{name}: {mp} micropolygons, {} grids, {} culled pieces for {visible:.0} visible pixels",
            r.stats.grids, r.stats.culled_pieces
        );
        // k = 4: a grid's micropolygons are ShadingRate (1 pixel) in area along its longest
        // row and column, so a foreshortened piece (its far row shorter than its near row,
        // by up to 2× before it splits again) dices up to ~2× finer, and pieces straddling the
        // frame's edges dice their off-screen part too (up to ~2× more near the horizon,
        // where the grids are wide and thin). Before the fix the NuPatch diced 60× this.
        assert!(
            (mp as f64) <= 4.0 * visible,
            "{name}: {mp} micropolygons for {visible:.0} visible pixels"
        );
        // Where the floor is seen the image is its colour times the coverage: exact in rows
        // entirely on or off the floor, within 0.3 in the row the far edge crosses (4 jittered
        // sample rows estimate a coverage of 0.41). A fix that culls too much fails here.
        for y in 0..H {
            let want = row_coverage(y);
            let tol = if want == 0.0 || want == 1.0 { 1e-4 } else { 0.3 };
            for x in 0..W {
                let px = &r.rgba[(y * W + x) * 4..][..4];
                let alpha = f64::from(px[3]);
                assert!(
                    (alpha - want).abs() <= tol,
                    "{name}: pixel ({x}, {y}) alpha {alpha}, closed form {want}"
                );
                for c in 0..3 {
                    let got = f64::from(px[c]);
                    assert!(
                        (got - COLOUR[c] * alpha).abs() <= 1e-4,
                        "{name}: pixel ({x}, {y}) channel {c} = {got}, colour × alpha {}",
                        COLOUR[c] * alpha
                    );
                }
            }
        }
    }
}
