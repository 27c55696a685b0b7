//! Streaming output: the hider hands finished pixel rows, top to bottom, to a [`RowSink`] as
//! soon as a band of buckets is done, so the film never holds more than one band of buckets
//! (issue 21: memory that does not grow with the frame). [`FrameCollector`] is the sink that
//! keeps the whole crop window, for callers that want a [`crate::Rendered`] image in memory.

/// Finished, exposed pixels: whole rows of the crop window, top row first.
#[derive(Clone, Debug, Default)]
pub struct PixelRows {
    /// Full-frame position of the first pixel, and the size in pixels.
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
    /// Premultiplied RGBA, exposed (`RiExposure`).
    pub rgba: Vec<f32>,
    /// Camera-space depth per pixel after `depthfilter`; `f32::MAX` where nothing was hit.
    pub z: Vec<f32>,
    /// The arbitrary output variables, `stride` floats per pixel (not exposed).
    pub aov: Vec<f32>,
}

/// Where the hider delivers finished rows. Rows arrive in order, each band right below the
/// previous one, covering the crop window exactly once per pass: bands as wide as the window,
/// or, for a window rendered in column blocks ([`crate::column_block_width`]), each block's
/// bands top to bottom, block after block from the left.
pub trait RowSink {
    /// A pass over the frame starts. The displacement-bound loop may render the frame again
    /// (a displaced grid left its bound): then everything delivered since the previous call
    /// is void and rows start again from the top.
    fn begin_pass(&mut self);
    /// The next band of rows.
    fn rows(&mut self, rows: PixelRows);
}

/// A sink that keeps the whole crop window (`Rendered`'s buffers).
pub struct FrameCollector {
    x0: u32,
    width: u32,
    y0: u32,
    stride: usize,
    pub rgba: Vec<f32>,
    pub z: Vec<f32>,
    pub aov: Vec<f32>,
}

impl FrameCollector {
    /// A collector for the crop window x0 x1 y0 y1 with `stride` AOV floats per pixel.
    pub fn new(crop: [u32; 4], stride: usize) -> FrameCollector {
        let [cx0, cx1, cy0, cy1] = crop;
        let pixels = ((cx1 - cx0) * (cy1 - cy0)) as usize;
        FrameCollector {
            x0: cx0,
            width: cx1 - cx0,
            y0: cy0,
            stride,
            rgba: vec![0.0; pixels * 4],
            z: vec![f32::MAX; pixels],
            aov: vec![0.0; pixels * stride],
        }
    }
}

impl RowSink for FrameCollector {
    fn begin_pass(&mut self) {}

    fn rows(&mut self, rows: PixelRows) {
        let (w, s) = (rows.width as usize, self.stride);
        for r in 0..rows.height as usize {
            let o = (rows.y0 - self.y0) as usize * self.width as usize
                + r * self.width as usize
                + (rows.x0 - self.x0) as usize;
            let src = r * w..(r + 1) * w;
            self.rgba[o * 4..(o + w) * 4].copy_from_slice(&rows.rgba[src.start * 4..src.end * 4]);
            self.z[o..o + w].copy_from_slice(&rows.z[src.clone()]);
            self.aov[o * s..(o + w) * s].copy_from_slice(&rows.aov[src.start * s..src.end * s]);
        }
    }
}
