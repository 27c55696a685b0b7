//! Visible-point compositing: each sample's list of visible points sorted front to back,
//! resolved against the frame's solids (CSG, `csg.rs`), and composited with the
//! over operator into one colour, alpha and depth per sample for the film. Matte points hide
//! what is behind them but add nothing.
use crate::csg::SolidResolver;
use crate::film::Composited;
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
    pub(crate) matte: bool,
    /// For CSG (see `csg.rs`): an entering hit. The primitive solid is found through the
    /// piece index in `order`, which keeps the point at 40 bytes, as without CSG.
    pub(crate) entering: bool,
}

const _: () = assert!(std::mem::size_of::<VisiblePoint>() <= 40);

/// Composites every sample of a bucket. `opaque_z[s]` is finite when an opaque point outside
/// any solid cut sample `s`'s list short; `solid_of(order)` names the primitive solid of a
/// point ([`crate::csg::NO_SOLID`] for none).
pub(crate) fn composite(
    lists: &mut [Vec<VisiblePoint>],
    opaque_z: &[f32],
    solids: Option<&SolidResolver>,
    solid_of: impl Fn(u64) -> u32,
) -> Vec<Composited> {
    lists
        .iter_mut()
        .zip(opaque_z)
        .map(|(l, &oz)| composite_sample(l, oz, solids, &solid_of))
        .collect()
}

/// Sorts one sample's visible points (depth, then order), drops the solid hits that are not
/// on a composite surface, and composites front to back until the sample is opaque.
fn composite_sample(
    l: &mut Vec<VisiblePoint>,
    opaque_z: f32,
    solids: Option<&SolidResolver>,
    solid_of: &impl Fn(u64) -> u32,
) -> Composited {
    l.sort_by(|a, b| a.z.total_cmp(&b.z).then(a.order.cmp(&b.order)));
    if let Some(s) = solids {
        // Only opaque surfaces outside solids set `opaque_z` and cut lists short.
        s.resolve(l, opaque_z.is_infinite(), |vp| {
            (solid_of(vp.order), vp.entering)
        });
    }
    let mut c = Vec3::ZERO;
    let mut t = Vec3::ONE;
    let mut alpha = 0.0f32;
    let mut ta = 1.0f32;
    for vp in l.iter() {
        let om = (vp.o.x + vp.o.y + vp.o.z) / 3.0;
        if !vp.matte {
            c += t * vp.c;
            alpha += ta * om;
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
