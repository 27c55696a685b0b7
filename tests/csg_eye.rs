//! CSG with the eye inside a solid (RI Spec 3.2 §5.8; Aqsis's `csg_test2` is a camera in a
//! room modelled as an intersection). Every sample ray starts inside the solids that contain
//! the eye, so the first surface it meets is where it *leaves* the composite.
//!
//! Closed form: the eye at the centre of a cube of half-size 1 intersected with a sphere of
//! radius 1.2, looking along +z with a 90° field of view. A ray through screen point (a, b)
//! leaves the cube through its z = 1 face at distance √(1+a²+b²) and the sphere at 1.2, so the
//! pixel shows the cube where √(1+a²+b²) < 1.2 and the sphere elsewhere (the image's corners).
//! Pixels within 0.02 of that boundary (in the distance) are not judged: they straddle it.
use illume_render::{render, RenderSettings, Rendered};
mod support;

const SIZE: usize = 100;

fn render_one(rib: &str) -> Rendered {
    let f = support::frames(rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

/// The cube (red) and sphere (green) as `op`'s two children, drawn with `constant`, seen from
/// their common centre.
fn scene(op: &str) -> String {
    // The outward-facing cube of `csg.rs`, [-1, 1]³.
    let cube =
        "PointsPolygons [4 4 4 4 4 4] [0 3 2 1  4 5 6 7  0 1 5 4  3 7 6 2  0 4 7 3  1 2 6 5] \
                \"P\" [-1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1  -1 -1 1  1 -1 1  1 1 1  -1 1 1]\n";
    format!(
        "Format {SIZE} {SIZE} 1\nPixelSamples 3 3\nPixelFilter \"box\" 1 1\n\
         Projection \"perspective\" \"fov\" [90]\nClipping 0.01 100\nWorldBegin\n\
         Surface \"constant\"\nSolidBegin \"{op}\"\n\
         SolidBegin \"primitive\"\nColor [1 0 0]\n{cube}SolidEnd\n\
         SolidBegin \"primitive\"\nColor [0 1 0]\nSphere 1.2 -1.2 1.2 360\nSolidEnd\n\
         SolidEnd\nWorldEnd\n"
    )
}

/// Distance to the cube's far face through pixel (px, py)'s centre.
fn cube_exit(px: usize, py: usize) -> f64 {
    let a = -1.0 + 2.0 * (px as f64 + 0.5) / SIZE as f64;
    let b = 1.0 - 2.0 * (py as f64 + 0.5) / SIZE as f64;
    (1.0 + a * a + b * b).sqrt()
}

/// (pixels checked, pixels that disagree with `expected_red(cube exit distance)`).
fn compare(r: &Rendered, expected_red: impl Fn(f64) -> Option<bool>) -> (usize, usize) {
    let (mut checked, mut wrong) = (0, 0);
    for py in 0..SIZE {
        for px in 0..SIZE {
            let Some(red) = expected_red(cube_exit(px, py)) else {
                continue;
            };
            let p = &r.rgba[(py * SIZE + px) * 4..][..4];
            checked += 1;
            let ok = if red {
                p[0] > 0.99 && p[1] < 0.01
            } else {
                p[1] > 0.99 && p[0] < 0.01
            };
            if !ok {
                wrong += 1;
            }
        }
    }
    (checked, wrong)
}

#[test]
fn the_eye_inside_an_intersection_sees_where_the_ray_leaves_it() {
    let r = render_one(&scene("intersection"));
    // The ray leaves the intersection at the nearer exit: the cube's wall, or the sphere.
    let (checked, wrong) = compare(&r, |d| {
        if (d - 1.2).abs() < 0.02 {
            None
        } else {
            Some(d < 1.2)
        }
    });
    assert!(checked > 9000, "{checked}");
    assert_eq!(wrong, 0, "{wrong} of {checked} pixels show the wrong solid");
}

#[test]
fn the_eye_inside_a_union_sees_the_farther_exit() {
    let r = render_one(&scene("union"));
    let (checked, wrong) = compare(&r, |d| {
        if (d - 1.2).abs() < 0.02 {
            None
        } else {
            Some(d > 1.2)
        }
    });
    assert!(checked > 9000, "{checked}");
    assert_eq!(wrong, 0, "{wrong} of {checked} pixels show the wrong solid");
}

#[test]
fn the_eye_inside_a_difference_sees_nothing_of_it() {
    // The eye is inside the subtracted sphere: the ray is outside cube − sphere until it
    // leaves the sphere, where it enters the difference only if still inside the cube.
    let r = render_one(&scene("difference"));
    let (checked, wrong) = compare(&r, |d| {
        if (d - 1.2).abs() < 0.02 {
            None
        } else if d > 1.2 {
            // Leaves the sphere (green wall of the hole) while still inside the cube.
            Some(false)
        } else {
            // Leaves the cube first: never inside the difference; nothing drawn.
            None
        }
    });
    assert!(checked > 1000, "{checked}");
    assert_eq!(wrong, 0, "{wrong} of {checked} pixels show the wrong solid");
    // Where the cube is left first, the pixel is empty.
    let empty = (0..SIZE * SIZE)
        .filter(|&k| cube_exit(k % SIZE, k / SIZE) < 1.18)
        .all(|k| r.rgba[k * 4 + 3] == 0.0);
    assert!(
        empty,
        "the difference shows something where the ray never enters it"
    );
}
