//! Lazy refinement (issue 21): the hider splits a primitive only when the band of buckets its
//! bound first touches comes, and drops pieces and grids when the last band that needs them is
//! done. So the pieces and grids held at once grow with one band of buckets (the image width),
//! not with the frame: these tests render a scene of many primitives at 1x and 4x its Format
//! and compare the peaks the hider reports against the totals it made.
use illume_render::{render, RenderSettings, Stats};
mod support;

/// A wall of 12 x 9 spheres over a floor, at `width` x `height` pixels.
fn spheres(width: u32, height: u32) -> String {
    let mut rib = format!(
        "Format {width} {height} 1\nPixelSamples 1 1\nShadingRate 4\n\
         Option \"limits\" \"bucketsize\" [16 16]\n\
         Projection \"perspective\" \"fov\" [40]\nTranslate 0 0 20\nWorldBegin\n\
         LightSource \"distantlight\" 1 \"from\" [0 1 -1] \"to\" [0 0 0]\nSurface \"matte\"\n\
         Patch \"bilinear\" \"P\" [-12 -7 3  12 -7 3  -12 7 3  12 7 3]\n"
    );
    for j in 0..9 {
        for i in 0..12 {
            let (x, y) = (-6.6 + 1.2 * i as f32, -4.8 + 1.2 * j as f32);
            rib += &format!(
                "AttributeBegin Translate {x} {y} 0 Sphere 0.55 -0.55 0.55 360 AttributeEnd\n"
            );
        }
    }
    rib + "WorldEnd\n"
}

fn stats(width: u32, height: u32) -> Stats {
    let frame = &support::frames(&spheres(width, height), None)[0];
    let r = render(frame, &RenderSettings::default());
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    r.stats
}

#[test]
fn live_pieces_and_grids_grow_with_the_width_not_the_frame() {
    let small = stats(160, 120);
    let large = stats(640, 480);
    // The frame really grows: 16x the pixels give many times the pieces and grids.
    assert!(
        large.pieces >= 8 * small.pieces && large.grids >= 8 * small.grids,
        "pieces {} -> {}, grids {} -> {}",
        small.pieces,
        large.pieces,
        small.grids,
        large.grids
    );
    // Held at once: about one band's worth, 4x wider at 4x the Format. An up-front refine
    // holds every piece (the ratio of totals, over 8); 5 leaves room for the 109 primitives
    // that wait at their first band in both.
    let ratio = |a: u64, b: u64| b as f64 / a.max(1) as f64;
    let live = ratio(small.peak_live_pieces, large.peak_live_pieces);
    let grids = ratio(small.peak_live_grids, large.peak_live_grids);
    assert!(
        live <= 5.0 && grids <= 5.0,
        "live pieces {} -> {} ({live:.2}x), live grids {} -> {} ({grids:.2}x)",
        small.peak_live_pieces,
        large.peak_live_pieces,
        small.peak_live_grids,
        large.peak_live_grids
    );
    // And well below the totals: a band of 30 is a small part of the frame.
    assert!(
        large.peak_live_pieces * 4 < large.pieces && large.peak_live_grids * 4 < large.grids,
        "live pieces {} of {}, live grids {} of {}",
        large.peak_live_pieces,
        large.pieces,
        large.peak_live_grids,
        large.grids
    );
}
