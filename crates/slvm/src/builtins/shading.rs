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
                Value::Triple(Slot::Varying((0..n).map(|i| l.ambient(i)).collect()))
            }
            (B::Diffuse, 1) => {
                let (l, nn) = (self.lights, tr(&a[0]));
                Value::Triple(Slot::Varying(
                    (0..n)
                        .map(|i| l.diffuse(i, normalize_or_zero(*nn.at(i))))
                        .collect(),
                ))
            }
            (B::Specular, 3) => {
                let (l, nn, v, r) = (self.lights, tr(&a[0]), tr(&a[1]), fl(&a[2]));
                let model = self.env.specular_model;
                Value::Triple(Slot::Varying(
                    (0..n)
                        .map(|i| {
                            l.specular(i, normalize_or_zero(*nn.at(i)), *v.at(i), *r.at(i), model)
                        })
                        .collect(),
                ))
            }
            (B::Phong, 3) => {
                let (l, nn, v, s) = (self.lights, tr(&a[0]), tr(&a[1]), fl(&a[2]));
                Value::Triple(Slot::Varying(
                    (0..n)
                        .map(|i| l.phong(i, normalize_or_zero(*nn.at(i)), *v.at(i), *s.at(i)))
                        .collect(),
                ))
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
