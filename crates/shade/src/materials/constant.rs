//! RI 3.2 `constant`: `Oi = Os; Ci = Os * Cs`. No parameters.
//!
//! Its one term is light-independent, so it is exported as `__ambient` (PRMan writes it to
//! `Ci` only; putting it in a component keeps the rule "the components add up to `Ci`" true
//! for every built-in surface, which is what a compositor rebuilding the beauty relies on).
use super::{Components, SurfaceContext};

/// `Cs` as the ambient component; the others black.
pub(super) fn components(ctx: &SurfaceContext) -> Components {
    let mut out = Components::new(ctx.grid.len());
    out.ambient.clone_from(&ctx.grid.cs);
    out
}
