//! Display images that hold arbitrary output variables: the file channels of each mode item,
//! the per-format rules, and a display's own `"exposure"`/`"quantize"`/`"dither"` parameters.
//!
//! Exposure (RI Spec 3.2 `RiExposure`, or the display's `"exposure" [gain gamma]`) applies to
//! colour variables only, as to the beauty's colour: `N`, `P`, `z`, `s`, `t` and other
//! non-colour values reach the file as the shader computed them. The `rgba` letters of a
//! display are the beauty, exposed by the frame's `Exposure`.
//!
//! Channel naming (OpenEXR): letters stay `R G B A Z`; a colour variable is `name.R name.G
//! name.B`, a point, vector or normal `name.X name.Y name.Z`, a float plain `name`: the
//! `layer.channel` naming Nuke and OpenImageIO group into layers. TIFF (up to four channels)
//! and PNG (one colour variable, 8-bit) carry a single colour variable as `r g b`, so viewers
//! show it as a picture.
use crate::aov::{ModeItem, VarKind};
use crate::Rendered;
use illume_imageio::{Image, Quantize};
use illume_ri::DisplaySpec;

/// Why a display's channels cannot be written.
pub(crate) type ChannelError = String;

/// The float image of display `d` from its mode `items`, named for file `kind`; colour
/// variables exposed by `exposure` (gain, gamma).
pub(crate) fn aov_image(
    r: &Rendered,
    items: &[ModeItem],
    kind: &str,
    exposure: (f32, f32),
) -> Result<Image, ChannelError> {
    let exr = matches!(kind, "openexr" | "exr");
    let png = matches!(kind, "png" | "framebuffer");
    let colours = items
        .iter()
        .filter(|i| matches!(i, ModeItem::Var(v) if v.kind == VarKind::Colour))
        .count();
    let vars = items
        .iter()
        .filter(|i| matches!(i, ModeItem::Var(_)))
        .count();
    let only_alpha_letters = items
        .iter()
        .all(|i| matches!(i, ModeItem::Var(_)) || matches!(i, ModeItem::Letters(l) if l == "a"));
    let picture = !exr && colours == 1 && vars == 1 && only_alpha_letters;
    if png && !picture {
        return Err(
            "PNG holds 8-bit colour only: expected one colour variable (and \"a\"); use openexr or tiff"
                .into(),
        );
    }
    // (source channel, name) per file channel: `None` source is a letter, resolved below.
    let layout = &r.aov_layout;
    let mut columns: Vec<(Column, String)> = Vec::new();
    for item in items {
        match item {
            ModeItem::Letters(l) => {
                for c in l.chars() {
                    columns.push((Column::Letter(c), c.to_string()));
                }
            }
            ModeItem::Var(v) => {
                let colour = v.kind == VarKind::Colour;
                let k = layout
                    .channels
                    .iter()
                    .position(|c| c.name == v.name)
                    .ok_or_else(|| format!("variable \"{}\" was not rendered", v.name))?;
                let off = layout.offsets[k];
                let suffix: &[&str] = match v.kind {
                    VarKind::Float => &[""],
                    VarKind::Colour if picture => &["r", "g", "b"],
                    VarKind::Colour => &[".R", ".G", ".B"],
                    VarKind::Direction => &[".X", ".Y", ".Z"],
                };
                for (j, s) in suffix.iter().enumerate() {
                    let name = if picture {
                        s.to_string()
                    } else {
                        format!("{}{s}", v.name)
                    };
                    columns.push((Column::Aov(off + j, colour), name));
                }
            }
        }
    }
    if !exr && columns.len() > 4 {
        return Err(format!(
            "{kind} holds at most 4 channels, found {} ({}); use openexr",
            columns.len(),
            columns
                .iter()
                .map(|c| c.1.as_str())
                .collect::<Vec<_>>()
                .join(",")
        ));
    }
    let pixels = (r.width * r.height) as usize;
    let stride = layout.stride;
    let mut data = Vec::with_capacity(pixels * columns.len());
    for p in 0..pixels {
        for (col, _) in &columns {
            data.push(match *col {
                Column::Letter('r') => r.rgba[p * 4],
                Column::Letter('g') => r.rgba[p * 4 + 1],
                Column::Letter('b') => r.rgba[p * 4 + 2],
                Column::Letter('a') => r.rgba[p * 4 + 3],
                Column::Letter(_) => r.z[p],
                Column::Aov(k, colour) => {
                    let v = r.aov.get(p * stride + k).copied().unwrap_or(0.0);
                    if colour {
                        expose(v, exposure)
                    } else {
                        v
                    }
                }
            });
        }
    }
    Ok(Image {
        width: r.width,
        height: r.height,
        channels: columns.into_iter().map(|c| c.1).collect(),
        data,
    })
}

#[derive(Clone, Copy)]
enum Column {
    Letter(char),
    /// Offset in the record; whether the variable is a colour (exposed).
    Aov(usize, bool),
}

/// `RiExposure` on one colour value: `(gain·c)^(1/gamma)`, as the film exposes the beauty.
fn expose(c: f32, (gain, gamma): (f32, f32)) -> f32 {
    if gain == 1.0 && gamma == 1.0 {
        c
    } else {
        (c * gain).max(0.0).powf(1.0 / gamma)
    }
}

/// The display's own `"exposure" [gain gamma]` over the frame's `Exposure`; a non-positive
/// gamma (which would divide by zero) keeps the frame's.
pub(crate) fn display_exposure(d: &DisplaySpec, frame: (f32, f32)) -> (f32, f32) {
    match illume_ri::paramlist::floats(&d.params, "exposure").as_deref() {
        Some([gain, gamma, ..]) if *gamma > 0.0 && gain.is_finite() => (*gain, *gamma),
        _ => frame,
    }
}

/// Whether the items hold a variable that is not a colour (never quantized or dithered).
pub(crate) fn has_non_colour(items: &[ModeItem]) -> bool {
    items
        .iter()
        .any(|i| matches!(i, ModeItem::Var(v) if v.kind != VarKind::Colour))
}

/// The display's own `"quantize" [one min max]` (or `[one min max dither]`) and `"dither"`
/// parameters over the frame's `Quantize` setting.
pub(crate) fn display_quantize(d: &DisplaySpec, mut q: Quantize) -> Quantize {
    if let Some(v) = illume_ri::paramlist::floats(&d.params, "quantize") {
        if v.len() >= 3 {
            q.one = v[0] as i32;
            q.min = v[1] as i32;
            q.max = v[2] as i32;
            if let Some(&d) = v.get(3) {
                q.dither = d;
            }
        }
    }
    if let Some(dither) = illume_ri::paramlist::float(&d.params, "dither") {
        q.dither = dither;
    }
    q
}
