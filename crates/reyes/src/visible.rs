//! Visible-point compositing: each sample's list of visible points sorted front to back,
//! resolved against the frame's solids (CSG, `csg.rs`), and composited with the
//! over operator into one colour, alpha and depth per sample for the film. Matte points hide
//! what is behind them but add nothing.
use crate::aov::AovLayout;
use crate::csg::SolidResolver;
use crate::film::Composited;
use crate::visible_lists::VisibleLists;
use glam::Vec3;

/// One micropolygon seen by one sample.
#[derive(Clone, Copy)]
pub(crate) struct VisiblePoint {
    /// Camera-space depth.
    pub(crate) z: f32,
    /// Piece index (high 32 bits) and micropolygon index: the tie-break at equal depth, so
    /// the order does not depend on which bucket or thread sampled first.
    pub(crate) order: u64,
    /// Colour (premultiplied) and opacity.
    pub(crate) c: Vec3,
    pub(crate) o: Vec3,
    /// Bit 31: matte; bit 30: for CSG (see `csg.rs`) an entering hit; bits 0–29: the index of
    /// the point's record in the bucket's AOV store ([`NO_AOV`] when no AOV is asked for).
    /// Packed so that AOVs keep the point at 40 bytes: unused AOVs cost nothing per point.
    /// The primitive solid is found through the piece index in `order`.
    pub(crate) tag: u32,
}

const _: () = assert!(std::mem::size_of::<VisiblePoint>() <= 40);

/// The AOV index of a point that carries no AOV record.
pub(crate) const NO_AOV: u32 = (1 << 30) - 1;

impl VisiblePoint {
    pub(crate) fn tag(matte: bool, entering: bool, aov: u32) -> u32 {
        (u32::from(matte) << 31) | (u32::from(entering) << 30) | aov.min(NO_AOV)
    }
    pub(crate) fn matte(&self) -> bool {
        self.tag >> 31 != 0
    }
    pub(crate) fn entering(&self) -> bool {
        (self.tag >> 30) & 1 != 0
    }
    pub(crate) fn aov(&self) -> Option<usize> {
        let a = self.tag & NO_AOV;
        (a != NO_AOV).then_some(a as usize)
    }
}

/// Composites every sample of a bucket. `opaque_z[s]` is finite when an opaque point outside
/// any solid cut sample `s`'s list short; `solid_of(order)` names the primitive solid of a
/// point ([`crate::csg::NO_SOLID`] for none).
///
/// With `aov` (the layout and the bucket's AOV store), each sample's AOV records are
/// composited the same way into the second result (`stride` floats per sample; empty without).
pub(crate) fn composite(
    lists: &VisibleLists,
    opaque_z: &[f32],
    solids: Option<&SolidResolver>,
    solid_of: impl Fn(u64) -> u32,
    aov: Option<(&AovLayout, &[f32])>,
) -> (Vec<Composited>, Vec<f32>) {
    let stride = aov.map_or(0, |(l, _)| l.stride);
    let mut aov_out = vec![0.0f32; lists.len() * stride];
    // One sample's points at a time, in one reused buffer.
    let mut list = Vec::new();
    let composited = opaque_z
        .iter()
        .enumerate()
        .map(|(s, &oz)| {
            lists.collect(s, &mut list);
            let acc = &mut aov_out[s * stride..(s + 1) * stride];
            let aov = aov.map(|(layout, store)| (layout, store, acc));
            composite_sample(&mut list, oz, solids, &solid_of, aov)
        })
        .collect();
    (composited, aov_out)
}

/// Sorts one sample's visible points (depth, then order), drops the solid hits that are not
/// on a composite surface, and composites front to back until the sample is opaque.
fn composite_sample(
    l: &mut Vec<VisiblePoint>,
    opaque_z: f32,
    solids: Option<&SolidResolver>,
    solid_of: &impl Fn(u64) -> u32,
    mut aov: Option<(&AovLayout, &[f32], &mut [f32])>,
) -> Composited {
    l.sort_by(|a, b| a.z.total_cmp(&b.z).then(a.order.cmp(&b.order)));
    if let Some(s) = solids {
        // Only opaque surfaces outside solids set `opaque_z` and cut lists short.
        s.resolve(l, opaque_z.is_infinite(), |vp| {
            (solid_of(vp.order), vp.entering())
        });
    }
    let mut c = Vec3::ZERO;
    let mut t = Vec3::ONE;
    let mut alpha = 0.0f32;
    let mut ta = 1.0f32;
    for vp in l.iter() {
        let om = (vp.o.x + vp.o.y + vp.o.z) / 3.0;
        if !vp.matte() {
            c += t * vp.c;
            alpha += ta * om;
            if let (Some((layout, store, acc)), Some(k)) = (aov.as_mut(), vp.aov()) {
                let rec = &store[k * layout.stride..(k + 1) * layout.stride];
                layout.over(acc, rec, t.to_array(), ta, vp.o.to_array());
            }
        }
        t *= Vec3::ONE - vp.o;
        ta *= 1.0 - om;
        if t.max_element() <= 0.0 {
            break;
        }
    }
    let z1 = l.first().map_or(f32::MAX, |v| v.z);
    let z2 = l.get(1).map_or(z1, |v| v.z);
    Composited {
        rgba: [c.x, c.y, c.z, alpha],
        z: z1,
        z_mid: 0.5 * (z1 + z2),
    }
}
