//! Which primitive solids contain the eye (RI Spec 3.2 §5.8 with the camera inside a solid).
//!
//! The CSG resolver walks each sample's hits front to back from an initial inside/outside
//! state per primitive solid. With the eye inside a solid (a camera in a room modelled as a
//! solid, Aqsis's `csg_test2`), the first hit of that solid is an exit: starting "outside"
//! would drop it and lose the whole composite. The state is found once per frame from the
//! generalized winding number of each solid's boundary around the eye: the sum of the signed
//! solid angles of its diced triangles over 4π. It is 1 inside a closed surface whose normals
//! point out and 0 outside, and it degrades gracefully (stays near 0 or 1) where the dicing
//! leaves small cracks or a cap is oriented the wrong way, unlike a ray's crossing parity.
//!
//! Perspective cameras only: an orthographic camera's rays start on the near plane, each at its
//! own point, so there the eye is taken to be outside every solid as before.
use glam::DVec3;
use illume_geom::{Grid, Primitive};
use illume_ri::Frame;

/// Vertices per side of the dice used for the winding number: the polygonal boundary only has
/// to separate the eye from the surface, not to look smooth.
const DICE: usize = 17;

/// Split depth limit for primitives that are not diceable as given (meshes, patch arrays).
const MAX_SPLIT_DEPTH: u32 = 16;

/// The primitive solids (leaves of [`Frame::solids`]) whose boundary encloses the eye, in
/// increasing order.
pub(crate) fn solids_containing_eye(frame: &Frame) -> Vec<u32> {
    if frame.solids.is_empty() || !frame.camera.is_perspective() {
        return Vec::new();
    }
    let mut winding = vec![0.0f64; frame.solids.nodes.len()];
    for fp in &frame.primitives {
        let Some(leaf) = fp.solid else { continue };
        let Some(w) = winding.get_mut(leaf as usize) else {
            continue;
        };
        let mut grids = Vec::new();
        dice_into(fp.primitive.as_ref(), 0, &mut grids);
        let sign = f64::from(fp.normal_sign());
        *w += sign * grids.iter().map(solid_angle_of_grid).sum::<f64>();
    }
    winding
        .iter()
        .enumerate()
        .filter(|(_, &w)| w / (4.0 * std::f64::consts::PI) > 0.5)
        .map(|(leaf, _)| leaf as u32)
        .collect()
}

fn dice_into(prim: &dyn Primitive, depth: u32, out: &mut Vec<Grid>) {
    if prim.bound().is_empty() {
        return;
    }
    if !prim.diceable() {
        if depth < MAX_SPLIT_DEPTH {
            for child in prim.split() {
                dice_into(child.as_ref(), depth + 1, out);
            }
        }
        return;
    }
    let g = prim.dice(DICE, DICE);
    if g.nu >= 2 && g.nv >= 2 && g.p.len() == g.nu * g.nv {
        out.push(g);
    }
}

/// The signed solid angle the grid's triangles subtend at the eye (camera-space origin),
/// positive where `dPdu × dPdv` points away from the eye. Trimmed-away micropolygons are left
/// out.
fn solid_angle_of_grid(g: &Grid) -> f64 {
    let at = |i: usize, j: usize| g.p[j * g.nu + i].as_dvec3();
    let hidden = g.hidden.len() == (g.nu - 1) * (g.nv - 1);
    let mut sum = 0.0;
    for j in 0..g.nv - 1 {
        for i in 0..g.nu - 1 {
            if hidden && g.hidden[j * (g.nu - 1) + i] {
                continue;
            }
            let (p00, p10, p01, p11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
            // Both triangles keep the quad's (u, v) winding, so their normals are dPdu × dPdv.
            sum += solid_angle(p00, p10, p11) + solid_angle(p00, p11, p01);
        }
    }
    sum
}

/// The signed solid angle of triangle `abc` seen from the origin (Van Oosterom and Strackee,
/// 1983): positive when `(b − a) × (c − a)` points away from the origin. Degenerate triangles
/// give 0.
fn solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let num = a.dot(b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    let omega = 2.0 * num.atan2(den);
    if omega.is_finite() {
        omega
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The eight octant triangles of the octahedron |x|+|y|+|z| = 1 around a point, outward
    /// oriented: the winding number is 1 inside and 0 outside.
    fn octahedron_winding(centre: DVec3) -> f64 {
        let mut sum = 0.0;
        for sx in [-1.0, 1.0] {
            for sy in [-1.0, 1.0] {
                for sz in [-1.0f64, 1.0] {
                    let (a, b, c) = (
                        DVec3::new(sx, 0.0, 0.0) - centre,
                        DVec3::new(0.0, sy, 0.0) - centre,
                        DVec3::new(0.0, 0.0, sz) - centre,
                    );
                    // x→y→z is outward in the (+,+,+) octant; each sign flip mirrors it.
                    let w = solid_angle(a, b, c);
                    sum += if sx * sy * sz > 0.0 { w } else { -w };
                }
            }
        }
        sum / (4.0 * PI)
    }

    #[test]
    fn winding_number_is_one_inside_and_zero_outside() {
        for (p, expected) in [
            (DVec3::ZERO, 1.0),
            (DVec3::new(0.2, -0.3, 0.1), 1.0),
            (DVec3::new(0.9, 0.9, 0.0), 0.0),
            (DVec3::new(0.0, 0.0, 3.0), 0.0),
        ] {
            let w = octahedron_winding(p);
            assert!((w - expected).abs() < 1e-9, "{p}: {w}");
        }
    }

    #[test]
    fn an_octant_subtends_an_eighth_of_the_sphere() {
        // Closed form: the triangle (x, y, z) seen from the origin covers one octant, 4π/8.
        let w = solid_angle(DVec3::X, DVec3::Y, DVec3::Z);
        assert!((w - PI / 2.0).abs() < 1e-12, "{w}");
        assert_eq!(solid_angle(DVec3::X, DVec3::X, DVec3::Z), 0.0);
    }
}
