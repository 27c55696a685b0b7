//! The tables `option()` and `attribute()` read in Shading Language shaders (RI 3.2 §15.7):
//! the frame's options once per frame, each distinct attribute set once.
use illume_ri::{Attributes, Frame};
use illume_shade::RenderInfo;

/// `"Format"` / `"DeviceResolution"` (xres yres pixelaspect), `"FrameAspectRatio"`,
/// `"CropWindow"` (xmin xmax ymin ymax), `"Clipping"` (near far) and `"Frame"` when numbered.
pub(crate) fn options(frame: &Frame) -> RenderInfo {
    let o = &frame.options;
    let format = [o.xres as f32, o.yres as f32, o.pixel_aspect];
    let aspect = o
        .frame_aspect
        .unwrap_or(o.xres as f32 * o.pixel_aspect / o.yres.max(1) as f32);
    let mut info = RenderInfo::new()
        .with_floats("Format", &format)
        .with_floats("DeviceResolution", &format)
        .with_floats("FrameAspectRatio", &[aspect])
        .with_floats("CropWindow", &o.crop)
        .with_floats(
            "Clipping",
            &[frame.camera.near as f32, frame.camera.far as f32],
        );
    if let Some(n) = frame.number {
        info = info.with_floats("Frame", &[n as f32]);
    }
    info
}

/// `"ShadingRate"`, `"Sides"`, `"displacementbound:sphere"`, `"Matte"`, and
/// `"identifier:name"` when the primitive is named.
pub(crate) fn attributes(a: &Attributes) -> RenderInfo {
    let mut info = RenderInfo::new()
        .with_floats("ShadingRate", &[a.shading_rate])
        .with_floats("Sides", &[a.sides as f32])
        .with_floats("displacementbound:sphere", &[a.displacement_bound])
        .with_floats("Matte", &[a.matte as u8 as f32]);
    if let Some(name) = &a.identifier {
        info = info.with_string("identifier:name", name);
    }
    info
}
