//! Geometry attributes (RI Spec 3.2 §4.2.6–9): orientation and sides, the spline basis, trim
//! curves, bounds and level of detail, geometric approximation.
use crate::state::Ri;
use illume_rib::{BasisSpec, Request, Span};
use std::sync::Arc;

impl Ri {
    /// The geometry attributes of RI Spec 3.2 §4.2.6–8 (bases, trim curves, orientation,
    /// sides) and level of detail (§4.2.9).
    pub(crate) fn geometry_attribute(&mut self, req: Request, span: &Span) {
        let name = req.name().to_string();
        use Request::*;
        match req {
            Sides(s) => {
                if s == 1 || s == 2 {
                    self.attrs().sides = s;
                } else {
                    self.diagnostics
                        .error(span, &name, format!("expected 1 or 2, found {s}"));
                }
            }
            Orientation(o) => {
                // Camera space is left-handed: "lh" is "outside" exactly when the current
                // coordinate system is left-handed too.
                let inside = match o.as_str() {
                    "lh" => self.current_is_rh(),
                    "rh" => !self.current_is_rh(),
                    "outside" => false,
                    "inside" => true,
                    other => {
                        self.diagnostics.error(
                            span,
                            &name,
                            format!("expected lh, rh, inside or outside, found \"{other}\""),
                        );
                        return;
                    }
                };
                self.attrs().orientation_inside = inside;
            }
            ReverseOrientation => {
                let a = self.attrs();
                a.orientation_inside = !a.orientation_inside;
            }
            TrimCurve {
                ncurves,
                order,
                knot,
                min,
                max,
                n,
                u,
                v,
                w,
            } => {
                let args = illume_geom::TrimCurveArgs {
                    ncurves: &ncurves,
                    order: &order,
                    knot: &knot,
                    min: &min,
                    max: &max,
                    n: &n,
                    u: &u,
                    v: &v,
                    w: &w,
                };
                match illume_geom::TrimCurves::new(args) {
                    Ok(t) => self.attrs().trim_curves = (!t.is_empty()).then(|| Arc::new(t)),
                    Err(e) => self.diagnostics.error(span, &name, e),
                }
            }
            Basis {
                ubasis,
                ustep,
                vbasis,
                vstep,
            } => {
                let (Some(u), Some(v)) = (basis_matrix(&ubasis), basis_matrix(&vbasis)) else {
                    self.diagnostics.error(
                        span,
                        &name,
                        "unknown basis, expected bezier, b-spline, catmull-rom, hermite, power or 16 numbers",
                    );
                    return;
                };
                if ustep < 1 || vstep < 1 {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("steps must be positive, found {ustep} {vstep}"),
                    );
                    return;
                }
                self.attrs().basis = (u, ustep, v, vstep);
            }
            Bound(_) => {}
            Detail(b) => {
                let ctm = self.ctm;
                self.attrs().detail = Some((b, ctm));
            }
            DetailRange(r) => {
                if r[0] <= r[1] && r[1] <= r[2] && r[2] <= r[3] {
                    self.attrs().detail_range = Some(r);
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        "expected minvisible ≤ lowertransition ≤ uppertransition ≤ maxvisible",
                    );
                }
            }
            GeometricApproximation { kind, value } => {
                if kind == "flatness" {
                    self.attrs().flatness = Some(value);
                } else {
                    self.diagnostics.warn(
                        span,
                        &name,
                        format!("\"{kind}\" not supported (ignored)"),
                    );
                }
            }
            GeometricRepresentation(_) => {
                self.diagnostics
                    .warn(span, &name, "not supported yet (ignored)")
            }
            other => self.diagnostics.error_kind(
                crate::ErrorKind::Bug,
                span,
                other.name(),
                "request not handled here (internal)",
            ),
        }
    }

    /// The handedness of the current object space relative to (left-handed) camera space.
    pub(crate) fn current_is_rh(&self) -> bool {
        self.ctm.determinant() < 0.0
    }
}

/// A `Basis` argument as a matrix: one of the named bases of RI Spec 3.2 §5.2.1 (their
/// default steps are ignored: `Basis` carries explicit steps) or the explicit 16 numbers.
fn basis_matrix(b: &BasisSpec) -> Option<[f32; 16]> {
    match b {
        BasisSpec::Matrix(m) => Some(*m),
        BasisSpec::Named(n) => illume_geom::basis::basis_matrix(n).map(|(m, _)| m),
    }
}
