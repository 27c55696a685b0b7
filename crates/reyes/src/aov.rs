//! Arbitrary output variables through the hider (issue 20): which variables the displays ask
//! for, how a grid's per-vertex values become per-sample records, and how a sample's records
//! are composited front to back like `Ci`.
//!
//! Memory: a visible point carries only a 30-bit index into its bucket's AOV store (packed into
//! [`crate::visible::VisiblePoint`]'s tag, so the point stays 40 bytes); the store holds
//! `stride` floats per visible point and exists only when some display names an AOV, so a
//! render without AOVs pays nothing, and a shader's outputs no display asks for are never
//! copied out of the shading grid.
//!
//! Filtering: a channel develops with `PixelFilter` unless its display (or `DisplayChannel`)
//! names its own `"filter"`/`"filterwidth"` ([`display_filter`]); one filter per variable per
//! frame. The hider grows its sample reach to the widest display filter of the frame
//! ([`frame_reach`]), so a wide AOV filter sees the same samples in every bucket.
use illume_core::filter::{filter_names_list, FilterKind, PixelFilter};
use illume_ri::{paramlist, Options};
use illume_rib::ParamList;

/// One output variable as the hider carries it.
#[derive(Clone, Debug, PartialEq)]
pub struct AovChannel {
    /// The variable's name (`N`, `__diffuse`, an SL `output varying` parameter).
    pub name: String,
    /// Floats per point: 1 (float) or 3 (colour, point, vector, normal).
    pub components: usize,
    /// A colour composites channel by channel with the colour transmittance, like `Ci`;
    /// anything else with the average opacity (as alpha does).
    pub colour: bool,
    /// Whether the shader already multiplied the value by `Oi` (`Ci`, `Oi`, the built-in
    /// materials' components, shader outputs: PRMan's convention). Other variables (`P`, `N`,
    /// `s`, …) are multiplied by the point's opacity when composited, so an opaque surface's
    /// pixel holds the value itself.
    pub premultiplied: bool,
    /// The display's own `"filter"`/`"filterwidth"` when they differ from `PixelFilter`
    /// (`None`: filtered like the colour). Tiles do not carry it: their pixels are developed.
    pub filter: Option<PixelFilter>,
}

/// The channels of a frame and where each starts in a record.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AovLayout {
    pub channels: Vec<AovChannel>,
    /// Start of each channel in a record.
    pub offsets: Vec<usize>,
    /// Floats per record (0: no AOVs).
    pub stride: usize,
}

impl AovLayout {
    pub fn new(channels: Vec<AovChannel>) -> AovLayout {
        let mut offsets = Vec::with_capacity(channels.len());
        let mut stride = 0;
        for c in &channels {
            offsets.push(stride);
            stride += c.components;
        }
        AovLayout {
            channels,
            offsets,
            stride,
        }
    }

    /// Whether some channel is a built-in material component (`__ambient` …), so the shading
    /// stage splits the surface's colour only when a display asks.
    pub fn wants_components(&self) -> bool {
        self.channels.iter().any(|c| {
            matches!(
                c.name.as_str(),
                "__ambient" | "__diffuse" | "__specular" | "__reflection"
            )
        })
    }

    /// The half-widths the film needs around a pixel: the primary filter's `primary`, grown to
    /// the widest channel filter.
    pub(crate) fn reach(&self, primary: (f32, f32)) -> (f32, f32) {
        self.channels
            .iter()
            .filter_map(|c| c.filter.as_ref().map(|f| f.radius()))
            .fold(primary, |(x, y), (fx, fy)| (x.max(fx), y.max(fy)))
    }

    /// Adds one visible point's record `rec` over what lies in front of it: `t` is the colour
    /// transmittance and `ta` the alpha transmittance in front, `o` the point's opacity.
    pub(crate) fn over(&self, acc: &mut [f32], rec: &[f32], t: [f32; 3], ta: f32, o: [f32; 3]) {
        let om = (o[0] + o[1] + o[2]) / 3.0;
        for (c, &off) in self.channels.iter().zip(&self.offsets) {
            for k in 0..c.components {
                let (tk, ok) = if c.colour && c.components == 3 {
                    (t[k], o[k])
                } else {
                    (ta, om)
                };
                let v = if c.premultiplied {
                    rec[off + k]
                } else {
                    rec[off + k] * ok
                };
                acc[off + k] += tk * v;
            }
        }
    }
}

/// Interpolates a grid's per-vertex records at barycentric weights `w` of vertices `idx` (or
/// takes vertex `first`'s when shading is flat) and appends the result to `store`.
pub(crate) fn push_record(
    store: &mut Vec<f32>,
    values: &[f32],
    stride: usize,
    smooth: Option<([usize; 3], [f32; 3])>,
    first: usize,
) {
    match smooth {
        Some((idx, w)) => {
            for k in 0..stride {
                let v = |i: usize| values[idx[i] * stride + k];
                store.push(v(0) * w[0] + v(1) * w[1] + v(2) * w[2]);
            }
        }
        None => store.extend_from_slice(&values[first * stride..(first + 1) * stride]),
    }
}

/// The filter of a display variable: `own` (the display's parameters) over `channel` (its
/// `DisplayChannel`'s), each `"filter" "name"` and `"filterwidth" [xw yw]` (or one width for
/// both). A named filter without a width takes the kernel's default width; a width without a
/// name keeps `primary`'s kernel. `None` when the result is `primary` itself; an unknown name
/// is an error listing the known ones.
pub fn display_filter(
    own: &ParamList,
    channel: Option<&ParamList>,
    primary: &PixelFilter,
) -> Result<Option<PixelFilter>, String> {
    let lists = [Some(own), channel];
    let lists = lists.iter().flatten();
    let name = lists.clone().find_map(|p| paramlist::string(p, "filter"));
    let width = lists
        .clone()
        .find_map(|p| paramlist::floats(p, "filterwidth"));
    if name.is_none() && width.is_none() {
        return Ok(None);
    }
    let kind = match &name {
        Some(n) => FilterKind::parse(n).ok_or_else(|| {
            format!(
                "unknown display filter \"{n}\" (expected one of {})",
                filter_names_list()
            )
        })?,
        None => primary.kind,
    };
    let (xw, yw) = match width.as_deref() {
        Some([w]) => (*w, *w),
        Some([x, y, ..]) => (*x, *y),
        Some([]) => return Err("\"filterwidth\" needs one or two widths".into()),
        None if name.is_some() => (kind.default_width(), kind.default_width()),
        None => (primary.xwidth, primary.ywidth),
    };
    if !(xw > 0.0 && yw > 0.0 && xw.is_finite() && yw.is_finite()) {
        return Err(format!(
            "\"filterwidth\" [{xw} {yw}]: expected positive widths"
        ));
    }
    let f = PixelFilter::new(kind.name(), xw, yw);
    Ok((f != *primary).then_some(f))
}

/// The widest reach (half-widths) any display or `DisplayChannel` of the frame may ask for,
/// at least the pixel filter's: how far beyond the crop window the hider keeps geometry.
pub(crate) fn frame_reach(opts: &Options, primary: &PixelFilter) -> (f32, f32) {
    let own = opts.displays.iter().map(|d| &d.params);
    let channels = opts.display_channels.iter().map(|c| &c.params);
    own.chain(channels)
        .filter_map(|p| display_filter(p, None, primary).ok().flatten())
        .map(|f| f.radius())
        .fold(primary.radius(), |(x, y), (fx, fy)| (x.max(fx), y.max(fy)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout() -> AovLayout {
        AovLayout::new(vec![
            AovChannel {
                name: "__diffuse".into(),
                components: 3,
                colour: true,
                premultiplied: true,
                filter: None,
            },
            AovChannel {
                name: "s".into(),
                components: 1,
                colour: false,
                premultiplied: false,
                filter: None,
            },
        ])
    }

    #[test]
    fn premultiplied_colours_composite_like_ci_and_others_by_opacity() {
        let l = layout();
        assert_eq!((l.stride, l.offsets.clone()), (4, vec![0, 3]));
        let mut acc = vec![0.0; 4];
        // A half-transparent red point in front of an opaque one.
        l.over(&mut acc, &[0.5, 0.0, 0.0, 0.2], [1.0; 3], 1.0, [0.5; 3]);
        l.over(&mut acc, &[0.0, 1.0, 0.0, 0.8], [0.5; 3], 0.5, [1.0; 3]);
        let expect = [0.5, 0.5, 0.0, 0.2 * 0.5 + 0.5 * 0.8];
        for (a, b) in acc.iter().zip(expect) {
            assert!((a - b).abs() < 1e-7, "{acc:?}");
        }
    }

    #[test]
    fn records_interpolate_per_component() {
        let values = [0.0, 10.0, 1.0, 20.0, 2.0, 30.0];
        let mut store = Vec::new();
        push_record(
            &mut store,
            &values,
            2,
            Some(([0, 1, 2], [0.5, 0.25, 0.25])),
            0,
        );
        push_record(&mut store, &values, 2, None, 2);
        assert_eq!(store, vec![0.75, 17.5, 2.0, 30.0]);
    }
}
