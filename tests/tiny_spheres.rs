//! Issue 23's 10⁶-sphere scene came out empty: a sphere about a pixel across diced at one
//! segment per side has every vertex of a row at one pole (or both columns of the grid on one
//! meridian), so all of its micropolygons have zero area and no sample sees it. The area a
//! sphere covers is a closed form (π r² for its silhouette disk); a diced sphere covers less,
//! but never less than the polygon through three of its equator points. Checked by the sum of
//! alpha over the frame (a 1×1 box filter keeps the total), the pole toward the camera and
//! sideways, at sizes below, about and above a pixel.
use illume_render::{render, RenderSettings};
use std::f64::consts::TAU;
mod support;

/// The alpha a sphere of radius `r` pixels covers, in pixels, centred on pixel (4, 4) of an
/// 8×8 orthographic frame (one unit per pixel), rotated `tilt` degrees about x.
fn covered(r: f64, tilt: f64, shading_rate: f64) -> f64 {
    let rib = format!(
        "Format 8 8 1\nPixelSamples 64 64\nPixelFilter \"box\" 1 1\nShadingRate {shading_rate}\n\
         Projection \"orthographic\"\nScreenWindow -4 4 -4 4\nWorldBegin\nSurface \"constant\"\n\
         Translate 0.5 -0.5 5\nRotate {tilt} 1 0 0\nSphere {r} -{r} {r} 360\nWorldEnd\n"
    );
    let frame = &support::frames(&rib, None)[0];
    let img = render(frame, &RenderSettings::default());
    img.rgba.chunks(4).map(|px| f64::from(px[3])).sum()
}

#[test]
fn a_sphere_about_a_pixel_across_covers_between_its_inscribed_triangle_and_its_disk() {
    for r in [0.3, 0.46, 0.7, 1.5] {
        for tilt in [0.0, 90.0, 37.0] {
            for rate in [1.0, 4.0] {
                let got = covered(r, tilt, rate);
                let disk = std::f64::consts::PI * r * r;
                // The equilateral triangle inscribed in the silhouette: 3√3/4 r².
                let triangle = 3f64.sqrt() * 0.75 * r * r;
                eprintln!(
                    "r {r} tilt {tilt} rate {rate}: {got:.4} px² (disk {disk:.4}, triangle {triangle:.4})"
                );
                // 64×64 stratified samples in a pixel, spacing h: along an edge, the samples
                // miscount at most about a strip h wide (jittered strata are unbiased, so
                // this is slack): the triangle's perimeter 3√3 r, the disk's 2π r.
                let h = 1.0 / 64.0;
                let (low, high) = (triangle - 3f64.sqrt() * 3.0 * r * h, disk + TAU * r * h);
                assert!(
                    got >= low && got <= high,
                    "r {r} tilt {tilt} shading rate {rate}: covers {got} px², want between \
                     {triangle} and {disk}"
                );
            }
        }
    }
}
