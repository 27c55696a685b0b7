//! `texture`, `environment`, `shadow` (RI 3.2 §15.7) through `illume_shade`'s
//! [`TextureLookup`](illume_shade::TextureLookup): each point's filter footprint is the
//! quadrilateral of its own and its grid neighbours' coordinates (as the built-in shaders do,
//! `ShadingGrid::footprint`), or the four corners the shader passes explicitly.
use crate::exec::{zero_of, Exec};
use crate::value::{Mask, Slot, Value};
use glam::Vec3;
use illume_sl::ast::{Global, TextureCall, TextureKind};
use illume_sl::types::{BaseType, Type};
use illume_texture::{ShadowOptions, TextureFilter, TextureOptions};

/// The optional `"name", value` parameters, read as uniform values.
#[derive(Default)]
struct Options {
    texture: TextureOptions,
    shadow: ShadowOptions,
    /// `"blur"` as given (ray-traced shadows are sharp unless asked, unlike map lookups whose
    /// default blur hides the map's texels).
    blur: Option<f32>,
}

impl Exec<'_> {
    fn texture_options(&mut self, call: &TextureCall, mask: &Mask) -> Options {
        let mut o = Options::default();
        // Without a "bias" parameter, shadow() takes the frame's Option "shadow" "bias".
        o.shadow.bias = self.env.shadow_bias;
        let (mut sw, mut tw) = (None, None);
        for p in &call.params {
            let name = match self.eval(&p.name, mask) {
                Value::String(s) => s.at(0).to_string(),
                _ => continue,
            };
            let value = self.eval(&p.value, mask);
            let f = match &value {
                Value::Float(s) => Some(*s.at(0)),
                _ => None,
            };
            match (name.as_str(), f) {
                ("blur", Some(x)) => {
                    o.texture.blur = x;
                    o.shadow.blur = x;
                    o.blur = Some(x);
                }
                ("width", Some(x)) => {
                    o.texture.width = x;
                    o.shadow.width = x;
                }
                ("swidth", Some(x)) => sw = Some(x),
                ("twidth", Some(x)) => tw = Some(x),
                ("fill", Some(x)) => o.texture.fill = x,
                ("samples", Some(x)) => o.shadow.samples = x,
                ("bias", Some(x)) => o.shadow.bias = x,
                ("filter", None) => {
                    let Value::String(s) = &value else { continue };
                    o.texture.filter = match s.at(0).as_ref() {
                        "box" => TextureFilter::Box,
                        "triangle" => TextureFilter::Triangle,
                        "gaussian" => TextureFilter::Gaussian,
                        other => {
                            self.problem(format!(
                                "{}: unknown filter \"{other}\"",
                                call.kind.name()
                            ));
                            TextureFilter::Gaussian
                        }
                    };
                }
                (other, _) => {
                    self.problem(format!(
                        "{}: unknown or mistyped optional parameter \"{other}\"; ignored",
                        call.kind.name()
                    ));
                }
            }
        }
        // TextureOptions has one width: `swidth`/`twidth` given alone set it; both, their mean.
        match (sw, tw) {
            (Some(s), Some(t)) => o.texture.width = 0.5 * (s + t),
            (Some(x), None) | (None, Some(x)) => o.texture.width = x,
            _ => {}
        }
        o
    }

    /// Per point, the four footprint corners of a coordinate given once per point (its grid
    /// neighbours) or four times (explicit corners).
    /// Grid neighbours are centred on the point (`ShadingGrid::centred_footprint`).
    pub(super) fn corners<T>(&self, coords: &[Slot<T>], i: usize) -> [T; 4]
    where
        T: Copy
            + std::ops::Add<Output = T>
            + std::ops::Sub<Output = T>
            + std::ops::Mul<f32, Output = T>,
    {
        if coords.len() >= 4 {
            return [
                *coords[0].at(i),
                *coords[1].at(i),
                *coords[2].at(i),
                *coords[3].at(i),
            ];
        }
        let c = &coords[0];
        self.grid.centred_footprint(i, |k| *c.at(k))
    }

    /// `Du(p)·du` and `Dv(p)·dv` per point (grid differences; zero for a uniform point).
    fn footprint_edges(&self, p: &Slot<Vec3>) -> (Vec<Vec3>, Vec<Vec3>) {
        let g = self.grid;
        match p {
            Slot::Uniform(_) => (vec![Vec3::ZERO; self.n], vec![Vec3::ZERO; self.n]),
            // The surface position itself: its analytic derivatives, as the built-in lights.
            Slot::Varying(v) if *v == g.p => (
                g.dpdu.iter().map(|d| *d * g.du).collect(),
                g.dpdv.iter().map(|d| *d * g.dv).collect(),
            ),
            Slot::Varying(v) => {
                let (du, dv) = (g.deriv_u(v), g.deriv_v(v));
                (
                    du.into_iter().map(|d| d * g.du).collect(),
                    dv.into_iter().map(|d| d * g.dv).collect(),
                )
            }
        }
    }

    pub(crate) fn texture_call(&mut self, call: &TextureCall, mask: &Mask, ty: Type) -> Value {
        let n = self.n;
        let name = match self.eval(&call.map, mask) {
            Value::String(s) => s.at(0).to_string(),
            _ => String::new(),
        };
        let first = match &call.channel {
            Some(c) => match self.eval(c, mask) {
                Value::Float(s) => s.at(0).max(0.0) as usize,
                _ => 0,
            },
            None => 0,
        };
        let opts = self.texture_options(call, mask);
        let coords: Vec<Value> = call.coords.iter().map(|c| self.eval(c, mask)).collect();
        let nch = if ty.base == BaseType::Float { 1 } else { 3 };
        if name == "raytrace" {
            if let Some(v) = self.raytraced_lookup(call.kind, &coords, &opts, mask, nch) {
                return v;
            }
        }
        let Some(tex) = self.env.textures else {
            self.env.warn(&format!(
                "{} `{name}`: no texture system; black",
                call.kind.name()
            ));
            return zero_of(ty);
        };
        let mut missing = false;
        let out: Vec<[f32; 4]> = match call.kind {
            TextureKind::Texture => {
                let (s, t): (Vec<Slot<f32>>, Vec<Slot<f32>>) = if coords.is_empty() {
                    (
                        vec![float_slot(self.global(Global::s))],
                        vec![float_slot(self.global(Global::t))],
                    )
                } else {
                    let fs: Vec<Slot<f32>> = coords.iter().map(float_slot).collect();
                    (
                        fs.iter().step_by(2).cloned().collect(),
                        fs.iter().skip(1).step_by(2).cloned().collect(),
                    )
                };
                (0..n)
                    .map(|i| {
                        if !mask.get(i) {
                            return [0.0; 4];
                        }
                        let (cs, ct) = (self.corners(&s, i), self.corners(&t, i));
                        let st = [0, 1, 2, 3].map(|k| [cs[k], ct[k]]);
                        tex.texture(&name, first, nch, st, &opts.texture)
                            .unwrap_or_else(|| {
                                missing = true;
                                [0.0; 4]
                            })
                    })
                    .collect()
            }
            TextureKind::Environment => {
                let r: Vec<Slot<Vec3>> = coords.iter().map(triple_slot).collect();
                if r.is_empty() {
                    return zero_of(ty);
                }
                (0..n)
                    .map(|i| {
                        if !mask.get(i) {
                            return [0.0; 4];
                        }
                        let d = self.corners(&r, i);
                        tex.environment(&name, first, nch, d, &opts.texture)
                            .unwrap_or_else(|| {
                                missing = true;
                                [0.0; 4]
                            })
                    })
                    .collect()
            }
            TextureKind::Shadow => {
                let world_from_camera = self.env.camera_from_world.inverse();
                let to_world = |p: Vec3| world_from_camera.transform_point3(p.as_dvec3()).as_vec3();
                let p: Vec<Slot<Vec3>> = coords.iter().map(triple_slot).collect();
                if p.is_empty() {
                    return zero_of(ty);
                }
                // One point: its footprint is the parallelogram of edges Du(P)du, Dv(P)dv about P,
                // as the built-in shadow lights take it (from dPdu du, dPdv dv).
                let edges = (p.len() < 4).then(|| self.footprint_edges(&p[0]));
                (0..n)
                    .map(|i| {
                        if !mask.get(i) {
                            return [0.0; 4];
                        }
                        let pw = match &edges {
                            Some((eu, ev)) => {
                                let (eu, ev) = (eu[i], ev[i]);
                                // Centred on the point, as `corners` centres grid neighbours.
                                let c = *p[0].at(i) - 0.5 * (eu + ev);
                                [c, c + eu, c + ev, c + eu + ev].map(to_world)
                            }
                            None => self.corners(&p, i).map(to_world),
                        };
                        let v = tex.shadow(&name, pw, &opts.shadow).unwrap_or_else(|| {
                            missing = true;
                            0.0
                        });
                        [v; 4]
                    })
                    .collect()
            }
            TextureKind::Bump => {
                return self.bump_call(tex, (&name, first), &opts.texture, &coords, mask);
            }
        };
        if missing {
            self.env
                .warn(&format!("{} `{name}` not found; black", call.kind.name()));
        }
        let clean = |x: f32| if x.is_finite() { x } else { 0.0 };
        if nch == 1 {
            Value::Float(Slot::Varying(out.iter().map(|c| clean(c[0])).collect()))
        } else {
            Value::Triple(Slot::Varying(
                out.iter()
                    .map(|c| Vec3::new(clean(c[0]), clean(c[1]), clean(c[2])))
                    .collect(),
            ))
        }
    }
}

impl Exec<'_> {
    /// BMRT's `shadow("raytrace", Ps)` and `environment("raytrace", R)`: rays instead of a
    /// map (`samples`/`blur` shape the shadow rays). `None` for `texture("raytrace")`, which
    /// is an ordinary file name.
    fn raytraced_lookup(
        &mut self,
        kind: TextureKind,
        coords: &[Value],
        opts: &Options,
        mask: &Mask,
        nch: usize,
    ) -> Option<Value> {
        let first = coords.first().map(triple_slot)?;
        match kind {
            TextureKind::Shadow => {
                let v = self.raytraced_shadow(
                    mask,
                    &first,
                    opts.shadow.samples,
                    opts.blur.unwrap_or(0.0),
                );
                Some(if nch == 1 {
                    Value::Float(Slot::Varying(v))
                } else {
                    Value::Triple(Slot::Varying(v.into_iter().map(Vec3::splat).collect()))
                })
            }
            TextureKind::Environment => {
                let c = self.raytraced_environment(
                    mask,
                    &first,
                    opts.shadow.samples,
                    opts.blur.unwrap_or(0.0),
                );
                Some(if nch == 1 {
                    Value::Float(Slot::Varying(c.into_iter().map(|c| c.x).collect()))
                } else {
                    Value::Triple(Slot::Varying(c))
                })
            }
            _ => None,
        }
    }
}

fn float_slot(v: &Value) -> Slot<f32> {
    match v {
        Value::Float(s) => s.clone(),
        _ => Slot::Uniform(0.0),
    }
}

fn triple_slot(v: &Value) -> Slot<Vec3> {
    match v {
        Value::Triple(s) => s.clone(),
        Value::Float(s) => s.map(|&x| Vec3::splat(x)),
        _ => Slot::Uniform(Vec3::ZERO),
    }
}
