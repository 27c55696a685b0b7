//! The camera fixed at `WorldBegin`: world → camera → screen → NDC → raster (RI Spec 3.2 §4.1.1).
//! Camera space is left-handed (+z forward, +y up); raster y points down.
use crate::options::{Options, Projection};
use glam::{DMat4, DVec3};
use illume_core::spaces::{self, CameraProjection};

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
            Projection::Perspective { fov } => Some(spaces::perspective_scale(fov)),
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

    /// The camera → raster maps of this camera ([`illume_core::spaces`]).
    #[inline]
    pub fn projection(&self) -> CameraProjection {
        CameraProjection {
            perspective_scale: self.perspective_scale,
            screen_window: self.screen_window,
            xres: self.xres,
            yres: self.yres,
        }
    }

    /// Camera space → screen space (x, y) before the screen window; `None` behind the eye.
    #[inline]
    pub fn screen_from_camera(&self, p: DVec3) -> Option<(f64, f64)> {
        self.projection().screen_from_camera_point(p)
    }

    /// Camera space → raster (x right, y down, in pixels), keeping camera z.
    #[inline]
    pub fn raster_from_camera(&self, p: DVec3) -> Option<DVec3> {
        self.projection().raster_from_camera_point(p)
    }

    /// The matrix PRMan zfiles record as `Np`: world → screen with the screen window mapped to
    /// [-1,1]², y up (homogeneous; divide by w).
    pub fn screen_from_world(&self) -> DMat4 {
        self.projection().np_from_world(self.camera_from_world)
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
