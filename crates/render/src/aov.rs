//! Arbitrary output variables (issue 20): what a `Display` mode names, the types those names
//! have, the frame's [`AovLayout`] the hider carries, and the per-vertex records the shading
//! stage fills in.
//!
//! A mode is `rgb`, `rgba`, `a`, `z`, … as before, or a comma-separated list of such letter
//! groups and variables (`"rgba,__diffuse,N"`); a variable may carry an inline declaration
//! (`"varying color __spec"`). A variable's type comes from, in order: its inline declaration,
//! a `DisplayChannel` of that name, the built-in globals and material components below, a
//! `Declare` in force at the `Display`, the `output` parameters of the frame's SL surfaces.
use illume_core::filter::PixelFilter;
use illume_reyes::{AovChannel, AovLayout};
use illume_ri::{Diagnostic, DisplaySpec, Frame, Severity};
use illume_rib::{Declaration, Type};

/// What a variable is, for compositing and for naming its file channels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarKind {
    Float,
    Colour,
    /// Point, vector or normal: channels `.X .Y .Z`.
    Direction,
}

/// One variable a display writes.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayVar {
    pub name: String,
    pub kind: VarKind,
    /// Already multiplied by `Oi` by whoever computed it (see [`AovChannel::premultiplied`]).
    pub premultiplied: bool,
    /// Its own reconstruction filter (`None`: the frame's `PixelFilter`); see
    /// [`illume_reyes::display_filter`].
    pub filter: Option<PixelFilter>,
}

impl DisplayVar {
    pub fn components(&self) -> usize {
        if self.kind == VarKind::Float {
            1
        } else {
            3
        }
    }
}

/// One item of a display mode.
#[derive(Clone, Debug, PartialEq)]
pub enum ModeItem {
    /// Letters of `rgbaz`: the beauty colour, alpha and depth.
    Letters(String),
    Var(DisplayVar),
}

/// The shading globals a display may name: (name, kind, premultiplied).
const GLOBALS: &[(&str, VarKind, bool)] = &[
    ("Ci", VarKind::Colour, true),
    ("Oi", VarKind::Colour, true),
    ("Cs", VarKind::Colour, false),
    ("Os", VarKind::Colour, false),
    ("P", VarKind::Direction, false),
    ("N", VarKind::Direction, false),
    ("Ng", VarKind::Direction, false),
    ("I", VarKind::Direction, false),
    ("E", VarKind::Direction, false),
    ("dPdu", VarKind::Direction, false),
    ("dPdv", VarKind::Direction, false),
    ("s", VarKind::Float, false),
    ("t", VarKind::Float, false),
    ("u", VarKind::Float, false),
    ("v", VarKind::Float, false),
    ("du", VarKind::Float, false),
    ("dv", VarKind::Float, false),
];

fn is_letters(item: &str) -> bool {
    !item.is_empty() && item.len() <= 5 && item.chars().all(|c| "rgbaz".contains(c))
}

fn kind_of(ty: Type) -> Option<VarKind> {
    match ty {
        Type::Float | Type::Integer => Some(VarKind::Float),
        Type::Color => Some(VarKind::Colour),
        Type::Point | Type::Vector | Type::Normal => Some(VarKind::Direction),
        _ => None,
    }
}

/// The `output` parameters of the frame's SL surfaces: (name, floats, is colour).
pub type SlOutputs = Vec<(String, usize, bool)>;

/// The items of display `d`'s mode, or what is wrong with it.
pub fn mode_items(d: &DisplaySpec, frame: &Frame, sl: &SlOutputs) -> Result<Vec<ModeItem>, String> {
    let mut items = Vec::new();
    for raw in d.mode.split(',') {
        let item = raw.trim();
        if is_letters(item) {
            items.push(ModeItem::Letters(item.to_string()));
            continue;
        }
        let mut var = variable(item, d, frame, sl)?;
        let channel = frame
            .options
            .display_channels
            .iter()
            .find(|c| c.name == var.name);
        var.filter = illume_reyes::display_filter(
            &d.params,
            channel.map(|c| &c.params),
            &primary_filter(frame),
        )?;
        items.push(ModeItem::Var(var));
    }
    Ok(items)
}

fn variable(
    item: &str,
    d: &DisplaySpec,
    frame: &Frame,
    sl: &SlOutputs,
) -> Result<DisplayVar, String> {
    let var = |name: &str, kind, premultiplied| DisplayVar {
        name: name.to_string(),
        kind,
        premultiplied,
        filter: None,
    };
    let typed = |name: &str, ty: Type| {
        kind_of(ty).map(|k| var(name, k, true)).ok_or_else(|| {
            format!("variable \"{name}\" is declared {ty}, expected float, color, point, vector or normal")
        })
    };
    if item.contains(' ') {
        let decl = Declaration::parse(item).map_err(|e| format!("\"{item}\": {e}"))?;
        let name = decl
            .name
            .clone()
            .ok_or_else(|| format!("\"{item}\": expected a variable name after the type"))?;
        if let Some(&(_, k, p)) = GLOBALS.iter().find(|g| g.0 == name) {
            return Ok(var(&name, k, p));
        }
        return typed(&name, decl.ty);
    }
    if let Some(c) = frame
        .options
        .display_channels
        .iter()
        .find(|c| c.name == item)
    {
        return typed(item, c.declaration.ty);
    }
    if let Some(&(_, k, p)) = GLOBALS.iter().find(|g| g.0 == item) {
        return Ok(var(item, k, p));
    }
    if illume_shade::COMPONENT_NAMES.contains(&item) {
        return Ok(var(item, VarKind::Colour, true));
    }
    // The built-in lights' shadow output, summed over the lights (unless an SL surface of
    // the frame writes its own `__shadow`, found below). Composited like `s`: by opacity.
    if item == "__shadow" && !sl.iter().any(|(n, _, _)| n == item) {
        return Ok(var(item, VarKind::Float, false));
    }
    if let Some((_, decl)) = d.declared.iter().find(|(n, _)| n == item) {
        return typed(item, decl.ty);
    }
    if let Some((_, comps, colour)) = sl.iter().find(|(n, _, _)| n == item) {
        let kind = match (comps, colour) {
            (1, _) => VarKind::Float,
            (_, true) => VarKind::Colour,
            _ => VarKind::Direction,
        };
        return Ok(var(item, kind, true));
    }
    Err(format!(
        "unknown output variable \"{item}\" (expected rgba/z letters, a global such as N or P, \
         __ambient/__diffuse/__specular/__reflection/__shadow, a DisplayChannel or Declare'd name, or an \
         output parameter of the surface shader)"
    ))
}

/// The frame's `PixelFilter`.
fn primary_filter(frame: &Frame) -> PixelFilter {
    let (name, xw, yw) = &frame.options.filter;
    PixelFilter::new(name, *xw, *yw)
}

/// Every variable some display of the frame names, once each in first-named order: the
/// layout the hider carries. Displays whose mode is bad are skipped here (the display stage
/// reports them). A variable has one filter per frame: a later display asking for another
/// gets the first one's pixels, with a warning.
pub fn frame_layout(frame: &Frame, sl: &SlOutputs) -> (AovLayout, Vec<Diagnostic>) {
    let mut vars: Vec<DisplayVar> = Vec::new();
    let mut warnings = Vec::new();
    for d in &frame.options.displays {
        let Ok(items) = mode_items(d, frame, sl) else {
            continue;
        };
        for item in items {
            let ModeItem::Var(v) = item else { continue };
            match vars.iter().find(|w| w.name == v.name) {
                None => vars.push(v),
                Some(w) if w.filter != v.filter => warnings.push(Diagnostic {
                    severity: Severity::Warning,
                    kind: illume_ri::ErrorKind::Incapable,
                    span: illume_rib::Span::synthetic(),
                    request: Some("Display".into()),
                    message: format!(
                        "Display \"{}\": \"{}\" is already filtered {} by an earlier display \
                         (one filter per variable per frame); using that",
                        d.name,
                        v.name,
                        describe(w.filter.clone().unwrap_or_else(|| primary_filter(frame)))
                    ),
                }),
                Some(_) => {}
            }
        }
    }
    let channels = vars
        .iter()
        .map(|v| AovChannel {
            name: v.name.clone(),
            components: v.components(),
            colour: v.kind == VarKind::Colour,
            premultiplied: v.premultiplied,
            filter: v.filter.clone(),
        })
        .collect();
    (AovLayout::new(channels), warnings)
}

fn describe(f: PixelFilter) -> String {
    format!("\"{}\" {}×{}", f.kind.name(), f.xwidth, f.ywidth)
}

/// One shaded grid's AOV records, `layout.stride` floats per vertex: an SL surface's `output`
/// parameter of that name first (`sl`, values as the shader left them), then the globals, then
/// the built-in material's components (already times the surface's `Oi`) and the lights'
/// summed `__shadow`; black for a variable nothing provides.
pub(crate) fn records(
    layout: &AovLayout,
    g: &illume_shade::ShadingGrid,
    components: Option<&illume_shade::Components>,
    shadow: Option<&[f32]>,
    sl: &[(&str, Vec<f32>)],
) -> Vec<f32> {
    use glam::Vec3;
    let n = g.len();
    let stride = layout.stride;
    let mut out = vec![0.0f32; n * stride];
    for (c, &off) in layout.channels.iter().zip(&layout.offsets) {
        let mut put = |i: usize, v: &[f32]| {
            out[i * stride + off..i * stride + off + c.components].copy_from_slice(v);
        };
        if let Some((_, v)) = sl
            .iter()
            .find(|(name, v)| *name == c.name && v.len() == n * c.components)
        {
            for i in 0..n {
                put(i, &v[i * c.components..(i + 1) * c.components]);
            }
            continue;
        }
        let triple: Option<&[Vec3]> = match c.name.as_str() {
            "Ci" => Some(&g.ci),
            "Oi" => Some(&g.oi),
            "Cs" => Some(&g.cs),
            "Os" => Some(&g.os),
            "P" => Some(&g.p),
            "N" => Some(&g.n),
            "Ng" => Some(&g.ng),
            "I" => Some(&g.i),
            "dPdu" => Some(&g.dpdu),
            "dPdv" => Some(&g.dpdv),
            _ => None,
        };
        let float: Option<Box<dyn Fn(usize) -> f32 + '_>> = match c.name.as_str() {
            "s" => Some(Box::new(|i| g.s[i])),
            "t" => Some(Box::new(|i| g.t[i])),
            "u" => Some(Box::new(|i| g.u[i])),
            "v" => Some(Box::new(|i| g.v[i])),
            "du" => Some(Box::new(|_| g.du)),
            "dv" => Some(Box::new(|_| g.dv)),
            "__shadow" => shadow.map(|s| Box::new(|i: usize| s[i]) as Box<dyn Fn(usize) -> f32>),
            _ => None,
        };
        let component = illume_shade::COMPONENT_NAMES
            .iter()
            .position(|&k| k == c.name)
            .and_then(|k| components?.by_index(k));
        for i in 0..n {
            match (triple, &float, component) {
                (Some(t), _, _) if c.components == 3 => put(i, &t[i].to_array()),
                (_, Some(f), _) if c.components == 1 => put(i, &[f(i)]),
                (_, _, Some(k)) if c.components == 3 => put(i, &k[i].to_array()),
                _ => {}
            }
        }
    }
    out
}
