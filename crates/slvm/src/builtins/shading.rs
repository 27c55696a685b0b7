//! §15.6 shading and lighting built-ins: `ambient`, `diffuse`, `specular`, `phong`,
//! `specularbrdf` over the lights gathered for the grid ([`crate::Lights`]); the ray-tracing
//! calls are in `raytrace.rs`.
use super::{fl, tr, Args};
use crate::exec::Exec;
use crate::value::{zip2, Slot, Value};
use glam::Vec3;
use illume_shade::normalize_or_zero;
use illume_sl::ast::BuiltinId as B;

impl Exec<'_> {
    /// The shading family; `None` for an overload the executor does not implement.
    pub(super) fn shading(&mut self, c: &Args) -> Option<Value> {
        let (a, n) = (c.a, self.n);
        Some(match (c.id, a.len()) {
            (B::Ambient, 0) => {
                let l = self.lights;
                Value::Triple(Slot::varying((0..n).map(|i| l.ambient(i)).collect()))
            }
            (B::Diffuse, 1) => {
                let nn = tr(&a[0]);
                let unit = |i| normalize_or_zero(*nn.at(i));
                Value::Triple(Slot::varying(self.lights.diffuse_grid(n, unit)))
            }
            (B::Specular, 3) => {
                let (nn, v, r) = (tr(&a[0]), tr(&a[1]), fl(&a[2]));
                let unit = |i| normalize_or_zero(*nn.at(i));
                let l = self.lights;
                let model = self.env.specular_model;
                Value::Triple(Slot::varying(l.specular_grid(
                    n,
                    unit,
                    |i| *v.at(i),
                    |i| *r.at(i),
                    model,
                )))
            }
            (B::Phong, 3) => {
                let (nn, v, s) = (tr(&a[0]), tr(&a[1]), fl(&a[2]));
                let unit = |i| normalize_or_zero(*nn.at(i));
                let l = self.lights;
                Value::Triple(Slot::varying(l.phong_grid(
                    n,
                    unit,
                    |i| *v.at(i),
                    |i| *s.at(i),
                )))
            }
            (B::SpecularBrdf, 4) => {
                let model = self.env.specular_model;
                let ln = zip2(&tr(&a[0]), &tr(&a[1]), n, |l, nn| (*l, *nn));
                let vr = zip2(&tr(&a[2]), &fl(&a[3]), n, |v, &r| (*v, r));
                Value::Triple(zip2(&ln, &vr, n, |(l, nn), (v, r)| {
                    Vec3::splat(illume_shade::specularbrdf(*l, *nn, *v, *r, model))
                }))
            }
            (
                B::Trace
                | B::Visibility
                | B::RayHitTest
                | B::FullTrace
                | B::Transmission
                | B::Occlusion,
                _,
            ) => return self.raytrace(c),
            _ => return None,
        })
    }
}
