//! Table rows for the quadrics.
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// The quadrics.
pub(super) fn rows() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
        (
            t("Sphere 1 -1 1 360"),
            R::Sphere {
                radius: 1.0,
                zmin: -1.0,
                zmax: 1.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Cone 2 1 270"),
            R::Cone {
                height: 2.0,
                radius: 1.0,
                thetamax: 270.0,
                params: vec![],
            },
        ),
        (
            t("Cylinder 1 0 2 360"),
            R::Cylinder {
                radius: 1.0,
                zmin: 0.0,
                zmax: 2.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Hyperboloid 1 0 0 0 1 1 360"),
            R::Hyperboloid {
                point1: [1.0, 0.0, 0.0],
                point2: [0.0, 1.0, 1.0],
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Paraboloid 1 0 2 360"),
            R::Paraboloid {
                rmax: 1.0,
                zmin: 0.0,
                zmax: 2.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Disk 0 1 360"),
            R::Disk {
                height: 0.0,
                radius: 1.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Torus 1 .25 0 360 360"),
            R::Torus {
                major_radius: 1.0,
                minor_radius: 0.25,
                phimin: 0.0,
                phimax: 360.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
    ]
}
