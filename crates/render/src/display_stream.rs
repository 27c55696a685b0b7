//! Streaming output (issue 21): the frame's displays fed row band by row band while the hider
//! renders, so memory does not grow with the frame. A TIFF display writes each strip as soon
//! as its rows arrive ([`TiffRows`]); a window rendered in column blocks
//! ([`illume_reyes::column_block_width`]) makes a tiled TIFF, each tile written as soon as its
//! block's rows are in. The other kinds need the whole frame at the end (PNG's
//! one zlib stream as `write_displays` makes it, OpenEXR, zfile, shadow maps, framebuffer
//! pictures): they share one whole-frame buffer, kept only when such a display exists.
//! Every file is the one [`crate::write_displays`] writes from the whole image, byte for byte,
//! but for one case: a window rendered in column blocks whose displacement leaves its bound is
//! rendered again in full-width bands (the displacement-bound loop), and its tiled TIFF then has
//! the same pixels with its tiles in row order.
use crate::display::{plan_displays, DisplayError, DisplayPlan, WrittenDisplay};
use crate::Rendered;
use illume_imageio::TiffRows;
use illume_reyes::{AovLayout, FrameCollector, PixelRows, RowSink};
use illume_ri::Frame;

/// One display being written.
enum Output {
    /// Rows go to the file as they arrive (`None` before the first pass).
    Rows(Option<Box<TiffRows>>),
    /// Written from the whole-frame buffer at the end.
    Whole,
}

/// The frame's displays as a [`RowSink`]; [`DisplayStream::finish`] closes them.
pub struct DisplayStream<'f> {
    frame: &'f Frame,
    crop: [u32; 4],
    layout: AovLayout,
    displays: Vec<Result<(DisplayPlan, Output), DisplayError>>,
    /// The whole crop window, when some display needs it.
    whole: Option<FrameCollector>,
}

impl<'f> DisplayStream<'f> {
    /// The displays of `frame`, for the crop window rendered with these AOVs.
    pub fn new(frame: &'f Frame, layout: &AovLayout) -> DisplayStream<'f> {
        let crop = frame.camera.crop;
        let displays: Vec<_> = plan_displays(frame, layout)
            .into_iter()
            .map(|p| {
                p.map(|plan| {
                    let out = if plan.streams() {
                        Output::Rows(None)
                    } else {
                        Output::Whole
                    };
                    (plan, out)
                })
            })
            .collect();
        let whole = displays
            .iter()
            .any(|d| matches!(d, Ok((_, Output::Whole))))
            .then(|| FrameCollector::new(crop, layout.stride));
        DisplayStream {
            frame,
            crop,
            layout: layout.clone(),
            displays,
            whole,
        }
    }

    /// Finishes every display, in the frame's order: streamed files are completed and renamed
    /// into place, the others written from the whole-frame buffer.
    pub fn finish(self) -> Vec<Result<WrittenDisplay, DisplayError>> {
        let [cx0, cx1, cy0, cy1] = self.crop;
        let whole = self.whole.map(|w| Rendered {
            x0: cx0,
            y0: cy0,
            width: cx1 - cx0,
            height: cy1 - cy0,
            rgba: w.rgba,
            z: w.z,
            aov_layout: self.layout.clone(),
            aov: w.aov,
            stats: Default::default(),
            warnings: Vec::new(),
        });
        let frame = self.frame;
        self.displays
            .into_iter()
            .map(|d| {
                let (plan, out) = d?;
                match (out, &whole) {
                    (Output::Rows(Some(rows)), _) => {
                        rows.finish()?;
                        Ok(plan.written())
                    }
                    (Output::Whole, Some(r)) => plan.write(frame, r),
                    _ => Err(DisplayError::Channels {
                        name: plan.name.clone(),
                        message: "no rows were rendered".into(),
                    }),
                }
            })
            .collect()
    }
}

impl RowSink for DisplayStream<'_> {
    fn begin_pass(&mut self) {
        let [cx0, cx1, cy0, cy1] = self.crop;
        for d in &mut self.displays {
            let Ok((plan, Output::Rows(rows))) = d else {
                continue;
            };
            // A pass that starts over drops (and so removes) the previous pass's file first.
            *rows = None;
            let channels = match plan.image(&band(&self.layout, PixelRows::default())) {
                Ok(image) => image.channels,
                Err(e) => {
                    *d = Err(e);
                    continue;
                }
            };
            let (size, origin) = ([cx1 - cx0, cy1 - cy0], [cx0, cy0]);
            // A window rendered in column blocks arrives a block at a time: a tiled file.
            let file = match plan.tile_width(size[0]) {
                Some(w) => {
                    TiffRows::create_tiled(&plan.path, size, &channels, plan.quantize, origin, w)
                }
                None => TiffRows::create(&plan.path, size, &channels, plan.quantize, origin),
            };
            match file {
                Ok(r) => *rows = Some(Box::new(r)),
                Err(e) => *d = Err(e.into()),
            }
        }
    }

    fn rows(&mut self, rows: PixelRows) {
        let r = band(&self.layout, rows);
        let streamed = |d: &Result<(DisplayPlan, Output), DisplayError>| {
            matches!(d, Ok((_, Output::Rows(Some(_)))))
        };
        if self.displays.iter().any(streamed) {
            // A few rows at a time: each display's channels and quantized bytes are then a few
            // rows, not the band's (a 5120-pixel band of 16 rows is 1.3 MB of float channels
            // and as much again quantized). The files are the same bytes: strips are cut from
            // the rows received, and dither is keyed on full-frame pixels.
            let step = rows_per_write(&r);
            for y in (0..r.height).step_by(step as usize) {
                let chunk = rows_of(&r, y, step.min(r.height - y));
                for d in &mut self.displays {
                    let Ok((plan, Output::Rows(Some(out)))) = d else {
                        continue;
                    };
                    let x = chunk.x0 - self.crop[0];
                    if let Err(e) = plan
                        .image(&chunk)
                        .and_then(|image| out.write_block(&image, x).map_err(DisplayError::from))
                    {
                        *d = Err(e);
                    }
                }
            }
        }
        if let Some(whole) = &mut self.whole {
            whole.rows(PixelRows {
                x0: r.x0,
                y0: r.y0,
                width: r.width,
                height: r.height,
                rgba: r.rgba,
                z: r.z,
                aov: r.aov,
            });
        }
    }
}

/// Rows of `r` a streamed display converts and writes at once (see [`DisplayStream::rows`]):
/// as many as fit in [`BYTES_PER_WRITE`] of float pixels, at least one. Why a byte budget
/// and not a row count: the copies are the peak heap's share of a wide frame's output (four
/// 5120-pixel rows were 0.7 MB of copies and channels), while a narrow frame's rows are
/// better written a few at a time than one call per row.
fn rows_per_write(r: &Rendered) -> u32 {
    let row_bytes = r.width as usize * (5 + r.aov_layout.stride) * std::mem::size_of::<f32>();
    (BYTES_PER_WRITE / row_bytes.max(1)).clamp(1, r.height.max(1) as usize) as u32
}

/// See [`rows_per_write`].
const BYTES_PER_WRITE: usize = 64 << 10;

/// Rows `y..y + n` of the band `r` (a copy).
fn rows_of(r: &Rendered, y: u32, n: u32) -> Rendered {
    let (w, s) = (r.width as usize, r.aov_layout.stride);
    let px = y as usize * w..(y + n) as usize * w;
    Rendered {
        x0: r.x0,
        y0: r.y0 + y,
        width: r.width,
        height: n,
        rgba: r.rgba[px.start * 4..px.end * 4].to_vec(),
        z: r.z[px.clone()].to_vec(),
        aov_layout: r.aov_layout.clone(),
        aov: r
            .aov
            .get(px.start * s..px.end * s)
            .unwrap_or_default()
            .to_vec(),
        stats: Default::default(),
        warnings: Vec::new(),
    }
}

/// Rows as a [`Rendered`] image, for the display code that builds a display's channels.
fn band(layout: &AovLayout, rows: PixelRows) -> Rendered {
    Rendered {
        x0: rows.x0,
        y0: rows.y0,
        width: rows.width,
        height: rows.height,
        rgba: rows.rgba,
        z: rows.z,
        aov_layout: layout.clone(),
        aov: rows.aov,
        stats: Default::default(),
        warnings: Vec::new(),
    }
}
