//! Cube-face environment geometry: OpenEXR's cube layout and the chapter's Table 9.1 input faces.
//!
//! OpenEXR (`ImfEnvmap`, `CubeMap`) stacks six square faces vertically, +X, −X, +Y, −Y, +Z, −Z,
//! and places texel *centres* on the cube edges: texel 0 and texel `n−1` of a face sit exactly at
//! face coordinates −1 and +1, so the border texels of adjacent faces describe the same
//! directions. That duplication is what makes bilinear lookups seamless without reading the
//! neighbouring face. The per-face axis assignment below mirrors `CubeMap::faceAndPixelPosition`
//! and `CubeMap::pixelPosition`.
//!
//! Input faces (`MakeCubeFaceEnvironment px nx py ny pz nz`) are rendered images whose
//! (view axis; axis toward top; axis toward right) follow Table 9.1.

use glam::Vec3;

/// One face of a cube environment, in OpenEXR's storage order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CubeFace {
    PosX = 0,
    NegX = 1,
    PosY = 2,
    NegY = 3,
    PosZ = 4,
    NegZ = 5,
}

impl CubeFace {
    pub const ALL: [CubeFace; 6] = [
        CubeFace::PosX,
        CubeFace::NegX,
        CubeFace::PosY,
        CubeFace::NegY,
        CubeFace::PosZ,
        CubeFace::NegZ,
    ];

    /// The face a direction hits (the major axis; ties resolve x, then y, then z, like OpenEXR).
    pub fn of(d: Vec3) -> CubeFace {
        let a = d.abs();
        if a.x >= a.y && a.x >= a.z {
            if d.x > 0.0 {
                CubeFace::PosX
            } else {
                CubeFace::NegX
            }
        } else if a.y >= a.z {
            if d.y > 0.0 {
                CubeFace::PosY
            } else {
                CubeFace::NegY
            }
        } else if d.z > 0.0 {
            CubeFace::PosZ
        } else {
            CubeFace::NegZ
        }
    }
}

/// Direction → (face, column, row) with column/row in `[-1,1]` (−1 = left/top texel centre).
pub fn face_coords(d: Vec3) -> (CubeFace, f32, f32) {
    let face = CubeFace::of(d);
    let (col, row) = face_coords_on(face, d);
    (face, col, row)
}

/// Coordinates of `d` projected onto the plane of `face` (may lie outside `[-1,1]`).
pub fn face_coords_on(face: CubeFace, d: Vec3) -> (f32, f32) {
    let (m, a, b) = match face {
        CubeFace::PosX | CubeFace::NegX => (d.x.abs(), d.y, d.z),
        CubeFace::PosY | CubeFace::NegY => (d.y.abs(), d.x, d.z),
        CubeFace::PosZ | CubeFace::NegZ => (d.z.abs(), d.x, d.y),
    };
    let m = m.max(1e-30);
    let (a, b) = (a / m, b / m);
    match face {
        CubeFace::PosX => (b, -a),
        CubeFace::NegX => (-b, -a),
        CubeFace::PosY => (a, -b),
        CubeFace::NegY => (a, b),
        CubeFace::PosZ => (-a, -b),
        CubeFace::NegZ => (a, -b),
    }
}

/// Inverse of [`face_coords`]: the (unnormalised) direction of face coordinates `(col, row)`.
pub fn face_direction(face: CubeFace, col: f32, row: f32) -> Vec3 {
    match face {
        CubeFace::PosX => Vec3::new(1.0, -row, col),
        CubeFace::NegX => Vec3::new(-1.0, -row, -col),
        CubeFace::PosY => Vec3::new(col, 1.0, -row),
        CubeFace::NegY => Vec3::new(col, -1.0, row),
        CubeFace::PosZ => Vec3::new(-col, -row, 1.0),
        CubeFace::NegZ => Vec3::new(col, -row, -1.0),
    }
}

/// Face coordinate in `[-1,1]` → continuous texel index in `[0, n−1]` (texel centres on edges).
#[inline]
pub fn coord_to_texel(c: f32, n: usize) -> f32 {
    (c + 1.0) * 0.5 * (n.max(2) - 1) as f32
}

/// Texel index → face coordinate.
#[inline]
pub fn texel_to_coord(i: f32, n: usize) -> f32 {
    if n < 2 {
        0.0
    } else {
        i / (n - 1) as f32 * 2.0 - 1.0
    }
}

/// Table 9.1: (view axis, axis toward top, axis toward right) of input faces px nx py ny pz nz.
pub const TABLE_9_1: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::Y, Vec3::NEG_Z),
    (Vec3::NEG_X, Vec3::Y, Vec3::Z),
    (Vec3::Y, Vec3::NEG_Z, Vec3::X),
    (Vec3::NEG_Y, Vec3::Z, Vec3::X),
    (Vec3::Z, Vec3::Y, Vec3::X),
    (Vec3::NEG_Z, Vec3::Y, Vec3::NEG_X),
];

/// Where direction `d` lands in input face `k` (Table 9.1 order) rendered with field of view
/// `fov` degrees: continuous pixel coordinates `(x, y)` with pixel centres at `i + 0.5`,
/// or `None` when `d` points away from that face's view axis.
pub fn input_face_pixel(
    k: usize,
    d: Vec3,
    fov_degrees: f32,
    w: usize,
    h: usize,
) -> Option<(f32, f32)> {
    let (view, up, right) = TABLE_9_1[k];
    let z = d.dot(view);
    if z <= 0.0 {
        return None;
    }
    let scale = 1.0 / (0.5 * fov_degrees.to_radians()).tan();
    let sx = d.dot(right) / z * scale;
    let sy = d.dot(up) / z * scale;
    Some(((sx + 1.0) * 0.5 * w as f32, (1.0 - sy) * 0.5 * h as f32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_coords_invert_face_direction_on_every_face() {
        for face in CubeFace::ALL {
            for &(c, r) in &[(0.0, 0.0), (0.3, -0.7), (-1.0, 1.0), (0.99, 0.5)] {
                let d = face_direction(face, c, r);
                let (f2, c2, r2) = face_coords(d * 3.0);
                if c.abs() < 1.0 && r.abs() < 1.0 {
                    assert_eq!(f2, face);
                }
                let (c3, r3) = face_coords_on(face, d);
                assert!((c3 - c).abs() < 1e-6 && (r3 - r).abs() < 1e-6, "{face:?}");
                let _ = (c2, r2);
            }
        }
    }

    #[test]
    fn openexr_orientation_matches_cubemap_pixel_position() {
        // OpenEXR: +X face, pixel x = positionInFace.y (from z), y = max - positionInFace.x (from y).
        let n = 9;
        let (f, c, r) = face_coords(Vec3::new(1.0, 0.5, -0.25));
        assert_eq!(f, CubeFace::PosX);
        let pif_x = (0.5 + 1.0) / 2.0 * (n - 1) as f32;
        let pif_y = (-0.25 + 1.0) / 2.0 * (n - 1) as f32;
        assert!((coord_to_texel(c, n) - pif_y).abs() < 1e-5);
        assert!((coord_to_texel(r, n) - ((n - 1) as f32 - pif_x)).abs() < 1e-5);
        // −Y face: x = positionInFace.x (from x), y = min + positionInFace.y (from z).
        let (f, c, r) = face_coords(Vec3::new(0.2, -1.0, 0.6));
        assert_eq!(f, CubeFace::NegY);
        assert!((c - 0.2).abs() < 1e-6 && (r - 0.6).abs() < 1e-6);
    }

    #[test]
    fn table_9_1_faces_are_left_handed_cameras() {
        // right × up = view, the RenderMan (left-handed) camera convention.
        for (view, up, right) in TABLE_9_1 {
            assert_eq!(right.cross(up), view);
        }
        // The view axis lands in the centre of its face.
        let (x, y) = input_face_pixel(0, Vec3::X, 90.0, 64, 64).unwrap();
        assert_eq!((x, y), (32.0, 32.0));
        assert!(input_face_pixel(0, Vec3::NEG_X, 90.0, 64, 64).is_none());
    }
}
