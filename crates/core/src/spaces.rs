//! Camera space → screen → NDC → raster (RI Spec 3.2 §4.1.1) and the matrices files record for
//! them, in one place: the RIB front end's camera, the hider's raster projection, the shaders'
//! `transform("NDC", P)`, zfiles' `Np` and OpenEXR/shadow-map `worldToNDC` all come from here.
//!
//! Conventions: camera space is left-handed (+z forward, +y up). Screen space is camera space
//! after the projection (perspective: `(d·x/z, d·y/z)` with `d = 1/tan(fov/2)`; orthographic:
//! `(x, y)`), the screen window `[l, r] × [b, t]` lies in it. NDC is `(0,0)` at the window's
//! top-left and `(1,1)` bottom-right; raster is NDC scaled by the resolution (x right, y down,
//! in pixels). The zfile `Np` matrix maps world space to the screen window as `[-1,1]²`, y up.
//!
//! Matrices are glam (column-vector) `DMat4`s unless the function says it takes the row-vector
//! (RIB/Imath) `[f32; 16]` that files carry.
use glam::{DMat4, DVec3, DVec4};

/// The frame aspect ratio of an `xres × yres` image with pixels `pixel_aspect` wide (RI Spec
/// `RiFormat`), the default of `FrameAspectRatio`.
pub fn frame_aspect(xres: u32, yres: u32, pixel_aspect: f32) -> f32 {
    xres as f32 * pixel_aspect / yres as f32
}

/// The default screen window for frame aspect `a`: `[-a,a]×[-1,1]` for `a ≥ 1`, else
/// `[-1,1]×[-1/a,1/a]` (the shorter axis spans `[-1,1]`). Order: left, right, bottom, top.
pub fn default_screen_window(a: f32) -> [f32; 4] {
    if a >= 1.0 {
        [-a, a, -1.0, 1.0]
    } else {
        [-1.0, 1.0, -1.0 / a, 1.0 / a]
    }
}

/// The perspective scale `d = 1/tan(fov/2)` of a field of view in degrees (spanning the
/// shorter screen axis, whose window edge is at ±1).
pub fn perspective_scale(fov_degrees: f32) -> f64 {
    1.0 / (f64::from(fov_degrees).to_radians() * 0.5).tan()
}

/// A camera's projection onto its raster: everything the camera → raster maps depend on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraProjection {
    /// `None` for orthographic; else `1 / tan(fov/2)`.
    pub perspective_scale: Option<f64>,
    /// Left, right, bottom, top, in screen space.
    pub screen_window: [f64; 4],
    pub xres: u32,
    pub yres: u32,
}

impl CameraProjection {
    /// Camera space → screen space (x, y); `None` behind the eye of a perspective camera.
    #[inline]
    pub fn screen_from_camera_point(&self, p: DVec3) -> Option<(f64, f64)> {
        match self.perspective_scale {
            Some(d) => (p.z > 0.0).then(|| (p.x * d / p.z, p.y * d / p.z)),
            None => Some((p.x, p.y)),
        }
    }

    /// Camera space → raster (x right, y down, in pixels), keeping camera z; `None` behind the
    /// eye. The per-point form of [`Self::raster_from_camera`], used where speed matters.
    #[inline]
    pub fn raster_from_camera_point(&self, p: DVec3) -> Option<DVec3> {
        let (sx, sy) = self.screen_from_camera_point(p)?;
        let [l, r, b, t] = self.screen_window;
        let x = (sx - l) / (r - l) * f64::from(self.xres);
        let y = (t - sy) / (t - b) * f64::from(self.yres);
        Some(DVec3::new(x, y, p.z))
    }

    /// Camera → screen as a homogeneous matrix: `(d·x, d·y, z, z)` (divide by w = z) for a
    /// perspective camera, the identity for an orthographic one. Depth stays z, so the matrix
    /// is invertible (the shaders' `transform("screen", …)` inverts it).
    pub fn screen_from_camera(&self) -> DMat4 {
        match self.perspective_scale {
            Some(d) => DMat4::from_cols(
                DVec4::new(d, 0.0, 0.0, 0.0),
                DVec4::new(0.0, d, 0.0, 0.0),
                DVec4::new(0.0, 0.0, 1.0, 1.0),
                DVec4::new(0.0, 0.0, 0.0, 0.0),
            ),
            None => DMat4::IDENTITY,
        }
    }

    /// Screen → NDC: the screen window onto `[0,1]²`, (0,0) top-left.
    pub fn ndc_from_screen(&self) -> DMat4 {
        let [l, r, b, t] = self.screen_window;
        DMat4::from_cols(
            DVec4::new(1.0 / (r - l), 0.0, 0.0, 0.0),
            DVec4::new(0.0, -1.0 / (t - b), 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(-l / (r - l), t / (t - b), 0.0, 1.0),
        )
    }

    /// NDC → raster: scale by the resolution.
    pub fn raster_from_ndc(&self) -> DMat4 {
        DMat4::from_scale(DVec3::new(f64::from(self.xres), f64::from(self.yres), 1.0))
    }

    /// Camera → NDC (homogeneous; divide by w).
    pub fn ndc_from_camera(&self) -> DMat4 {
        self.ndc_from_screen() * self.screen_from_camera()
    }

    /// Camera → raster (homogeneous; divide by w).
    pub fn raster_from_camera(&self) -> DMat4 {
        self.raster_from_ndc() * self.ndc_from_camera()
    }

    /// Screen → the `Np` window: the screen window onto `[-1,1]²`, y up.
    pub fn np_from_screen(&self) -> DMat4 {
        let [l, r, b, t] = self.screen_window;
        DMat4::from_cols(
            DVec4::new(2.0 / (r - l), 0.0, 0.0, 0.0),
            DVec4::new(0.0, 2.0 / (t - b), 0.0, 0.0),
            DVec4::new(0.0, 0.0, 1.0, 0.0),
            DVec4::new(-(r + l) / (r - l), -(t + b) / (t - b), 0.0, 1.0),
        )
    }

    /// The matrix PRMan zfiles record as `Np` for a camera at `camera_from_world`: world →
    /// screen window as `[-1,1]²`, y up (homogeneous; divide by w).
    pub fn np_from_world(&self, camera_from_world: DMat4) -> DMat4 {
        self.np_from_screen() * self.screen_from_camera() * camera_from_world
    }
}

/// OpenEXR's `worldToNDC` ((0,0) top-left, (1,1) bottom-right) from a zfile's world → `Np`
/// matrix (`[-1,1]²`, y up), both row-vector (RIB/Imath) order: `Np · S` with
/// `x' = (x+1)/2`, `y' = (1−y)/2`. The map is affine in x and y, so it applies to homogeneous
/// coordinates before the divide: `x_ndc·w = 0.5·x + 0.5·w`, `y_ndc·w = −0.5·y + 0.5·w`.
/// Products are summed in f64 and rounded once to f32.
pub fn world_to_ndc_from_np(world_to_np: &[f32; 16]) -> [f32; 16] {
    const S: [f64; 16] = [
        0.5, 0.0, 0.0, 0.0, //
        0.0, -0.5, 0.0, 0.0, //
        0.0, 0.0, 1.0, 0.0, //
        0.5, 0.5, 0.0, 1.0,
    ];
    let mut out = [0f32; 16];
    for r in 0..4 {
        for c in 0..4 {
            out[r * 4 + c] = (0..4)
                .map(|k| f64::from(world_to_np[r * 4 + k]) * S[k * 4 + c])
                .sum::<f64>() as f32;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn projection(d: Option<f64>, window: [f64; 4], xres: u32, yres: u32) -> CameraProjection {
        CameraProjection {
            perspective_scale: d,
            screen_window: window,
            xres,
            yres,
        }
    }

    #[test]
    fn default_window_spans_the_shorter_axis() {
        assert_eq!(
            default_screen_window(4.0 / 3.0),
            [-4.0 / 3.0, 4.0 / 3.0, -1.0, 1.0]
        );
        assert_eq!(default_screen_window(0.5), [-1.0, 1.0, -2.0, 2.0]);
        assert_eq!(frame_aspect(640, 480, 1.0), 640.0 / 480.0);
        assert_eq!(frame_aspect(100, 100, 2.0), 2.0);
    }

    #[test]
    fn ninety_degrees_reaches_the_window_edge_at_45_degrees() {
        let d = perspective_scale(90.0);
        assert!((d - 1.0).abs() < 1e-12);
        let cam = projection(Some(d), [-4.0 / 3.0, 4.0 / 3.0, -1.0, 1.0], 640, 480);
        let top = cam
            .raster_from_camera_point(DVec3::new(0.0, 1.0, 1.0))
            .unwrap();
        assert!((top.x - 320.0).abs() < 1e-9 && top.y.abs() < 1e-9, "{top}");
        assert!(cam
            .raster_from_camera_point(DVec3::new(0.0, 0.0, -1.0))
            .is_none());
    }

    #[test]
    fn matrices_agree_with_the_per_point_form() {
        // An asymmetric window and both projections: the homogeneous matrices, divided by w,
        // land where the scalar formula does.
        for d in [Some(1.7), None] {
            let cam = projection(d, [-0.5, 2.0, -1.2, 0.8], 300, 200);
            let m = cam.raster_from_camera();
            for p in [
                DVec3::new(0.3, -0.2, 2.0),
                DVec3::new(-1.0, 0.7, 5.5),
                DVec3::new(0.0, 0.0, 1.0),
            ] {
                let want = cam.raster_from_camera_point(p).unwrap();
                let got = m.project_point3(p);
                assert!((got.x - want.x).abs() < 1e-9 && (got.y - want.y).abs() < 1e-9);
                // NDC is raster over the resolution.
                let ndc = cam.ndc_from_camera().project_point3(p);
                assert!((ndc.x * 300.0 - want.x).abs() < 1e-9);
                // Np is NDC remapped to [-1,1]², y up.
                let np = cam.np_from_world(DMat4::IDENTITY).project_point3(p);
                assert!((np.x - (2.0 * ndc.x - 1.0)).abs() < 1e-9);
                assert!((np.y - (1.0 - 2.0 * ndc.y)).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn world_to_ndc_maps_np_corners_to_ndc_corners() {
        // Row-vector Np = identity: the point (x, y) in [-1,1]² maps to ((x+1)/2, (1−y)/2).
        let id: [f32; 16] = std::array::from_fn(|k| if k % 5 == 0 { 1.0 } else { 0.0 });
        let m = world_to_ndc_from_np(&id);
        let apply = |x: f32, y: f32| {
            let v = [x, y, 0.0, 1.0];
            let o: [f32; 4] = std::array::from_fn(|c| (0..4).map(|k| v[k] * m[k * 4 + c]).sum());
            (o[0] / o[3], o[1] / o[3])
        };
        assert_eq!(apply(-1.0, 1.0), (0.0, 0.0));
        assert_eq!(apply(1.0, -1.0), (1.0, 1.0));
        assert_eq!(apply(0.0, 0.0), (0.5, 0.5));
    }

    #[test]
    fn world_to_ndc_equals_the_matrix_product_bit_for_bit() {
        // The texture crate used to compute `Np · S` as a glam product (S^T · M^T); the f64 sum
        // here must give the same bits (zeros included: -0.0 vs 0.0 would change file bytes).
        let s_t = DMat4::from_cols_array(&[
            0.5, 0.0, 0.0, 0.0, //
            0.0, -0.5, 0.0, 0.0, //
            0.0, 0.0, 1.0, 0.0, //
            0.5, 0.5, 0.0, 1.0,
        ]);
        let cam = CameraProjection {
            perspective_scale: Some(1.3),
            screen_window: [-1.5, 1.5, -1.0, 1.0],
            xres: 64,
            yres: 48,
        };
        let world =
            DMat4::from_rotation_y(0.3) * DMat4::from_translation(DVec3::new(0.1, -2.0, 5.0));
        let np = cam.np_from_world(world);
        for m in [np, DMat4::IDENTITY, -np, DMat4::ZERO] {
            // Row-vector order, as zfiles carry it: the transpose of glam's column matrix.
            let rows: [f32; 16] = m.transpose().to_cols_array().map(|v| v as f32);
            let glam = (s_t * DMat4::from_cols_array(&rows.map(f64::from)))
                .to_cols_array()
                .map(|v| v as f32);
            assert_eq!(
                world_to_ndc_from_np(&rows).map(f32::to_bits),
                glam.map(f32::to_bits)
            );
        }
    }
}
