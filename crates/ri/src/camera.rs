//! The camera fixed at `WorldBegin`: world → camera → screen → NDC → raster (RI Spec 3.2 §4.1.1).
//! Camera space is left-handed (+z forward, +y up); raster y points down.
use crate::options::{Options, Projection};
use glam::{DMat4, DVec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub camera_from_world: DMat4,
    /// `None` for orthographic; else `1 / tan(fov/2)`.
    pub perspective_scale: Option<f64>,
    /// left, right, bottom, top.
    pub screen_window: [f64; 4],
    pub xres: u32,
    pub yres: u32,
    /// Half-open pixel range `[x0,x1)×[y0,y1)` that is rendered and written.
    pub crop: [u32; 4],
    pub near: f64,
    pub far: f64,
}

impl Camera {
    pub fn new(options: &Options, camera_from_world: DMat4) -> Camera {
        let perspective_scale = match options.projection {
            Projection::Perspective { fov } => {
                Some(1.0 / (f64::from(fov).to_radians() * 0.5).tan())
            }
            Projection::Orthographic => None,
        };
        Camera {
            camera_from_world,
            perspective_scale,
            screen_window: options.screen_window().map(f64::from),
            xres: options.xres,
            yres: options.yres,
            crop: options.crop_pixels(),
            near: f64::from(options.near),
            far: f64::from(options.far),
        }
    }

    pub fn is_perspective(&self) -> bool {
        self.perspective_scale.is_some()
    }

    /// Camera space → screen space (x, y) before the screen window; `None` behind the eye.
    pub fn screen_from_camera(&self, p: DVec3) -> Option<(f64, f64)> {
        match self.perspective_scale {
            Some(d) => (p.z > 0.0).then(|| (p.x * d / p.z, p.y * d / p.z)),
            None => Some((p.x, p.y)),
        }
    }

    /// Camera space → raster (x right, y down, in pixels), keeping camera z.
    pub fn raster_from_camera(&self, p: DVec3) -> Option<DVec3> {
        let (sx, sy) = self.screen_from_camera(p)?;
        let [l, r, b, t] = self.screen_window;
        let x = (sx - l) / (r - l) * f64::from(self.xres);
        let y = (t - sy) / (t - b) * f64::from(self.yres);
        Some(DVec3::new(x, y, p.z))
    }

    /// The matrix PRMan zfiles record as `Np`: world → screen with the screen window mapped to
    /// [-1,1]², y up (homogeneous; divide by w).
    pub fn screen_from_world(&self) -> DMat4 {
        let [l, r, b, t] = self.screen_window;
        let window = DMat4::from_cols_array(&[
            2.0 / (r - l),
            0.0,
            0.0,
            0.0,
            0.0,
            2.0 / (t - b),
            0.0,
            0.0,
            0.0,
            0.0,
            1.0,
            0.0,
            -(r + l) / (r - l),
            -(t + b) / (t - b),
            0.0,
            1.0,
        ]);
        let projection = match self.perspective_scale {
            // x' = d·x, y' = d·y, w = z; depth kept as z so the matrix stays invertible.
            Some(d) => DMat4::from_cols_array(&[
                d, 0.0, 0.0, 0.0, 0.0, d, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0,
            ]),
            None => DMat4::IDENTITY,
        };
        window * projection * self.camera_from_world
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perspective_fov_spans_the_shorter_axis() {
        let o = Options {
            projection: Projection::Perspective { fov: 90.0 },
            ..Options::default()
        };
        let cam = Camera::new(&o, DMat4::IDENTITY);
        // 45° up at z = 1 reaches the top edge of the 640×480 frame.
        let top = cam.raster_from_camera(DVec3::new(0.0, 1.0, 1.0)).unwrap();
        assert!((top.x - 320.0).abs() < 1e-9 && top.y.abs() < 1e-9, "{top}");
        assert!(cam.raster_from_camera(DVec3::new(0.0, 0.0, -1.0)).is_none());
    }

    #[test]
    fn asymmetric_screen_window_maps_to_raster_corners() {
        let o = Options {
            xres: 100,
            yres: 50,
            screen_window: Some([0.0, 4.0, -1.0, 1.0]),
            ..Options::default()
        };
        let cam = Camera::new(&o, DMat4::IDENTITY);
        let p = cam.raster_from_camera(DVec3::new(4.0, -1.0, 1.0)).unwrap();
        assert!((p.x - 100.0).abs() < 1e-12 && (p.y - 50.0).abs() < 1e-12);
    }
}
