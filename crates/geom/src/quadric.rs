//! The seven quadrics of RI Spec 3.2 §5.3 (Sphere, Cone, Cylinder, Hyperboloid, Paraboloid,
//! Disk, Torus), each a surface of revolution about object z with `θ = u · thetamax`.
//!
//! Positions and derivatives are analytic in f64 in object space and then transformed.
//! Bounds use the surfaces' cylindrical form: over a parameter sub-range the radius ρ and
//! height z lie in intervals found from the end points and the critical points of the profile,
//! and the θ interval is a sector; the box of that annular sector is transformed by its corners.
use crate::parametric::{default_st, with_default_st, Interp, Parametric, Surface};
use crate::primvar::{element64, resolve, surface_vars, ClassCounts};
use crate::{Bound, BuildContext, GeomError, Primitive};
use glam::{DMat4, DVec2, DVec3};
use illume_rib::{Class, ParamList};
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

/// A quadric's profile, angles in radians (converted from the RIB's degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// `φ = φmin + v(φmax−φmin)`, `P = r(cosθ cosφ, sinθ cosφ, sinφ)`.
    Sphere {
        radius: f64,
        phimin: f64,
        phimax: f64,
        thetamax: f64,
    },
    /// `P = (r(1−v) cosθ, r(1−v) sinθ, v·height)`.
    Cone {
        height: f64,
        radius: f64,
        thetamax: f64,
    },
    /// `P = (r cosθ, r sinθ, zmin + v(zmax−zmin))`.
    Cylinder {
        radius: f64,
        zmin: f64,
        zmax: f64,
        thetamax: f64,
    },
    /// The segment `p1 + v(p2−p1)` rotated by θ about z.
    Hyperboloid {
        point1: DVec3,
        point2: DVec3,
        thetamax: f64,
    },
    /// `z = zmin + v(zmax−zmin)`, `r = rmax·sqrt(z/zmax)`.
    Paraboloid {
        rmax: f64,
        zmin: f64,
        zmax: f64,
        thetamax: f64,
    },
    /// `P = (r(1−v) cosθ, r(1−v) sinθ, height)`.
    Disk {
        height: f64,
        radius: f64,
        thetamax: f64,
    },
    /// `φ = φmin + v(φmax−φmin)`, `P = ((R + r cosφ) cosθ, (R + r cosφ) sinθ, r sinφ)`.
    Torus {
        major: f64,
        minor: f64,
        phimin: f64,
        phimax: f64,
        thetamax: f64,
    },
}

/// A quadric's profile at one `v` ([`Shape::profile`]).
enum Profile {
    /// A point `(ρ, z)` of the profile curve and its derivative `(dρ/dv, dz/dv)`.
    Revolve(f64, f64, f64, f64),
    /// The hyperboloid's line: its point at `v` and its direction.
    Line(DVec3, DVec3),
}

impl Shape {
    fn thetamax(&self) -> f64 {
        match *self {
            Shape::Sphere { thetamax, .. }
            | Shape::Cone { thetamax, .. }
            | Shape::Cylinder { thetamax, .. }
            | Shape::Hyperboloid { thetamax, .. }
            | Shape::Paraboloid { thetamax, .. }
            | Shape::Disk { thetamax, .. }
            | Shape::Torus { thetamax, .. } => thetamax,
        }
    }

    /// Object-space `(P, dP/du, dP/dv)`.
    pub fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        self.swept(&self.profile(v), self.angle(u))
    }

    /// `(sin θ, cos θ)` at `θ = u·θmax`: the part of [`Shape::eval`] that depends on `u`.
    fn angle(&self, u: f64) -> (f64, f64) {
        (u * self.thetamax()).sin_cos()
    }

    /// The part of [`Shape::eval`] that depends on `v` only: the profile point swept about z.
    /// A grid evaluates it once per row and [`Shape::angle`] once per column
    /// ([`Surface::eval_grid`]) instead of both per vertex: two `sin_cos` per vertex were a
    /// third of a sphere's dicing (callgrind).
    fn profile(&self, v: f64) -> Profile {
        match *self {
            Shape::Sphere {
                radius,
                phimin,
                phimax,
                ..
            } => {
                let d = phimax - phimin;
                let (sp, cp) = (phimin + v * d).sin_cos();
                Profile::Revolve(radius * cp, radius * sp, -radius * sp * d, radius * cp * d)
            }
            Shape::Cone { height, radius, .. } => {
                Profile::Revolve(radius * (1.0 - v), v * height, -radius, height)
            }
            Shape::Cylinder {
                radius, zmin, zmax, ..
            } => Profile::Revolve(radius, zmin + v * (zmax - zmin), 0.0, zmax - zmin),
            Shape::Hyperboloid { point1, point2, .. } => {
                let d = point2 - point1;
                Profile::Line(point1 + v * d, d)
            }
            Shape::Paraboloid {
                rmax, zmin, zmax, ..
            } => {
                let dz = zmax - zmin;
                let z = zmin + v * dz;
                let ratio = (z / zmax).max(0.0);
                let rho = rmax * ratio.sqrt();
                // dρ/dz = rmax / (2 sqrt(z·zmax)) is infinite at the apex; the normal there is
                // found by nudging (see parametric.rs), so a zero derivative is harmless.
                let drho = if ratio > 1e-300 {
                    rmax / (2.0 * (ratio.sqrt() * zmax)) * dz
                } else {
                    0.0
                };
                Profile::Revolve(rho, z, drho, dz)
            }
            Shape::Disk { height, radius, .. } => {
                Profile::Revolve(radius * (1.0 - v), height, -radius, 0.0)
            }
            Shape::Torus {
                major,
                minor,
                phimin,
                phimax,
                ..
            } => {
                let d = phimax - phimin;
                let (sp, cp) = (phimin + v * d).sin_cos();
                Profile::Revolve(
                    major + minor * cp,
                    minor * sp,
                    -minor * sp * d,
                    minor * cp * d,
                )
            }
        }
    }

    /// A profile swept to angle `(sin, cos)`: `(P, dP/du, dP/dv)`.
    #[inline]
    fn swept(&self, profile: &Profile, (sin, cos): (f64, f64)) -> [DVec3; 3] {
        let tm = self.thetamax();
        match *profile {
            // A profile point (ρ, z) with derivative (dρ/dv, dz/dv), swept by θ.
            Profile::Revolve(rho, z, drho, dz) => [
                DVec3::new(rho * cos, rho * sin, z),
                DVec3::new(-rho * sin * tm, rho * cos * tm, 0.0),
                DVec3::new(drho * cos, drho * sin, dz),
            ],
            Profile::Line(p, d) => [
                DVec3::new(p.x * cos - p.y * sin, p.x * sin + p.y * cos, p.z),
                DVec3::new(
                    (-p.x * sin - p.y * cos) * tm,
                    (p.x * cos - p.y * sin) * tm,
                    0.0,
                ),
                DVec3::new(d.x * cos - d.y * sin, d.x * sin + d.y * cos, d.z),
            ],
        }
    }

    /// Profile samples `(ρ, z)` whose hull bounds the profile over `[v0, v1]`, and the extra
    /// angle the profile adds to θ (only the hyperboloid's twisted segment has one).
    fn profile_extremes(&self, [v0, v1]: [f64; 2]) -> (Vec<(f64, f64)>, [f64; 2]) {
        let ends = |f: &dyn Fn(f64) -> (f64, f64)| vec![f(v0), f(v1)];
        match *self {
            Shape::Sphere {
                radius,
                phimin,
                phimax,
                ..
            } => {
                let phi = |v: f64| phimin + v * (phimax - phimin);
                let at = |p: f64| (radius * p.cos(), radius * p.sin());
                let mut s = vec![at(phi(v0)), at(phi(v1))];
                let (a, b) = (phi(v0).min(phi(v1)), phi(v0).max(phi(v1)));
                if a < 0.0 && b > 0.0 {
                    s.push(at(0.0));
                }
                (s, [0.0; 2])
            }
            Shape::Torus {
                major,
                minor,
                phimin,
                phimax,
                ..
            } => {
                let phi = |v: f64| phimin + v * (phimax - phimin);
                let at = |p: f64| (major + minor * p.cos(), minor * p.sin());
                let (a, b) = (phi(v0).min(phi(v1)), phi(v0).max(phi(v1)));
                let mut s = vec![at(a), at(b)];
                s.extend(quarter_turns_within(a, b).map(at));
                (s, [0.0; 2])
            }
            Shape::Hyperboloid { point1, point2, .. } => {
                let a = point1 + v0 * (point2 - point1);
                let b = point1 + v1 * (point2 - point1);
                let (a2, b2) = (a.truncate(), b.truncate());
                let closest = closest_to_origin(a2, b2);
                let s = vec![(a2.length(), a.z), (b2.length(), b.z), (closest, a.z)];
                if closest <= 1e-9 * a2.length().max(b2.length()) {
                    return (s, [0.0, std::f64::consts::TAU]);
                }
                // Along a segment that misses the axis the angle moves monotonically by less
                // than π, from atan2(a) to atan2(a) + the signed angle between a and b.
                let alpha = a2.y.atan2(a2.x);
                let turn = a2.perp_dot(b2).atan2(a2.dot(b2));
                (s, [alpha.min(alpha + turn), alpha.max(alpha + turn)])
            }
            Shape::Cone { height, radius, .. } => {
                (ends(&|v| (radius * (1.0 - v), v * height)), [0.0; 2])
            }
            Shape::Cylinder {
                radius, zmin, zmax, ..
            } => (ends(&|v| (radius, zmin + v * (zmax - zmin))), [0.0; 2]),
            Shape::Paraboloid { .. } | Shape::Disk { .. } => (
                ends(&|v| {
                    let p = self.eval(0.0, v)[0];
                    (p.x, p.z)
                }),
                [0.0; 2],
            ),
        }
    }

    /// Object-space box of the sub-range.
    pub fn object_bound(&self, [u0, u1]: [f64; 2], v: [f64; 2]) -> (DVec3, DVec3) {
        let (profile, [alo, ahi]) = self.profile_extremes(v);
        let tm = self.thetamax();
        let (t0, t1) = ((u0 * tm).min(u1 * tm) + alo, (u0 * tm).max(u1 * tm) + ahi);
        let rho = |f: fn(f64, f64) -> f64| profile.iter().map(|p| p.0).fold(profile[0].0, f);
        let z = |f: fn(f64, f64) -> f64| profile.iter().map(|p| p.1).fold(profile[0].1, f);
        let (rlo, rhi) = (rho(f64::min), rho(f64::max));
        let angles: Vec<f64> = if t1 - t0 >= std::f64::consts::TAU {
            vec![0.0, FRAC_PI_2, 2.0 * FRAC_PI_2, 3.0 * FRAC_PI_2]
        } else {
            [t0, t1]
                .into_iter()
                .chain(quarter_turns_within(t0, t1))
                .collect()
        };
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for a in angles {
            let dir = DVec2::new(a.cos(), a.sin());
            for r in [rlo, rhi] {
                lo = lo.min(dir * r);
                hi = hi.max(dir * r);
            }
        }
        (lo.extend(z(f64::min)), hi.extend(z(f64::max)))
    }
}

/// The multiples of π/2 in `[a, b]` (at most five: enough to cover every axis direction).
fn quarter_turns_within(a: f64, b: f64) -> impl Iterator<Item = f64> {
    let k0 = (a / FRAC_PI_2).ceil();
    let k1 = (b / FRAC_PI_2).floor().min(k0 + 4.0);
    let n = if k1 >= k0 { (k1 - k0) as usize + 1 } else { 0 };
    (0..n).map(move |i| (k0 + i as f64) * FRAC_PI_2)
}

/// Distance from the origin to the segment `ab` (2-D).
fn closest_to_origin(a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 {
        (-a.dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * d).length()
}

/// A quadric placed in camera space.
#[derive(Clone, Debug)]
pub struct Quadric {
    pub shape: Shape,
    pub camera_from_object: DMat4,
}

impl Quadric {
    /// Object-space `(P, dP/du, dP/dv)` to camera space.
    #[inline]
    fn to_camera(&self, [p, du, dv]: [DVec3; 3]) -> [DVec3; 3] {
        let m = &self.camera_from_object;
        [
            m.transform_point3(p),
            m.transform_vector3(du),
            m.transform_vector3(dv),
        ]
    }
}

impl Surface for Quadric {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        self.to_camera(self.shape.eval(u, v))
    }

    /// Each column's angle and each row's profile once (the same values [`Shape::eval`]
    /// computes per vertex, so the same bits): `rib/sphere.rib` at 2× diced in 291 M
    /// instructions, now 212 M (callgrind; the frame 3.27 G → 3.20 G).
    fn eval_grid(&self, us: &[f64], vs: &[f64], out: &mut Vec<[DVec3; 3]>) {
        let angles: Vec<(f64, f64)> = us.iter().map(|&u| self.shape.angle(u)).collect();
        out.reserve(us.len() * vs.len());
        for &v in vs {
            let profile = self.shape.profile(v);
            for &a in &angles {
                out.push(self.to_camera(self.shape.swept(&profile, a)));
            }
        }
    }

    fn bound(&self, u: [f64; 2], v: [f64; 2]) -> Bound {
        let (lo, hi) = self.shape.object_bound(u, v);
        Bound::of_transformed_box(&self.camera_from_object, lo, hi)
    }

    fn quadric(&self) -> Option<(Shape, DMat4)> {
        Some((self.shape, self.camera_from_object))
    }
}

impl Shape {
    /// Builds the shape from a quadric request, degrees converted; `Ok(None)` for a surface of
    /// zero area (radius 0, zmin == zmax, thetamax 0, …), which renders nothing.
    pub fn from_request(request: &illume_rib::Request) -> Result<Option<Shape>, GeomError> {
        use illume_rib::Request as R;
        let rad = |deg: f32| (deg as f64).clamp(-360.0, 360.0).to_radians();
        let shape = match *request {
            R::Sphere {
                radius,
                zmin,
                zmax,
                thetamax,
                ..
            } => {
                let r = radius as f64;
                let phi = |z: f32| (z as f64 / r).clamp(-1.0, 1.0).asin();
                let (a, b) = (zmin.min(zmax), zmin.max(zmax));
                Shape::Sphere {
                    radius: r,
                    phimin: phi(a),
                    phimax: phi(b),
                    thetamax: rad(thetamax),
                }
            }
            R::Cone {
                height,
                radius,
                thetamax,
                ..
            } => Shape::Cone {
                height: height as f64,
                radius: radius as f64,
                thetamax: rad(thetamax),
            },
            R::Cylinder {
                radius,
                zmin,
                zmax,
                thetamax,
                ..
            } => Shape::Cylinder {
                radius: radius as f64,
                zmin: zmin as f64,
                zmax: zmax as f64,
                thetamax: rad(thetamax),
            },
            R::Hyperboloid {
                point1,
                point2,
                thetamax,
                ..
            } => Shape::Hyperboloid {
                point1: DVec3::from_array(point1.map(f64::from)),
                point2: DVec3::from_array(point2.map(f64::from)),
                thetamax: rad(thetamax),
            },
            R::Paraboloid {
                rmax,
                zmin,
                zmax,
                thetamax,
                ..
            } => Shape::Paraboloid {
                rmax: rmax as f64,
                zmin: zmin as f64,
                zmax: zmax as f64,
                thetamax: rad(thetamax),
            },
            R::Disk {
                height,
                radius,
                thetamax,
                ..
            } => Shape::Disk {
                height: height as f64,
                radius: radius as f64,
                thetamax: rad(thetamax),
            },
            R::Torus {
                major_radius,
                minor_radius,
                phimin,
                phimax,
                thetamax,
                ..
            } => Shape::Torus {
                major: major_radius as f64,
                minor: minor_radius as f64,
                phimin: (phimin as f64).to_radians(),
                phimax: (phimax as f64).to_radians(),
                thetamax: rad(thetamax),
            },
            _ => return Err(GeomError::Unsupported(request.name().to_string())),
        };
        shape.validated(request.name())
    }

    /// Rejects non-finite parameters; `None` when the surface has no area.
    fn validated(self, request: &str) -> Result<Option<Shape>, GeomError> {
        let nums: Vec<f64> = match self {
            Shape::Sphere {
                radius,
                phimin,
                phimax,
                thetamax,
            } => vec![radius, phimin, phimax, thetamax],
            Shape::Cone {
                height,
                radius,
                thetamax,
            } => vec![height, radius, thetamax],
            Shape::Cylinder {
                radius,
                zmin,
                zmax,
                thetamax,
            } => vec![radius, zmin, zmax, thetamax],
            Shape::Hyperboloid {
                point1,
                point2,
                thetamax,
            } => vec![
                point1.x, point1.y, point1.z, point2.x, point2.y, point2.z, thetamax,
            ],
            Shape::Paraboloid {
                rmax,
                zmin,
                zmax,
                thetamax,
            } => vec![rmax, zmin, zmax, thetamax],
            Shape::Disk {
                height,
                radius,
                thetamax,
            } => vec![height, radius, thetamax],
            Shape::Torus {
                major,
                minor,
                phimin,
                phimax,
                thetamax,
            } => vec![major, minor, phimin, phimax, thetamax],
        };
        if nums.iter().any(|x| !x.is_finite()) {
            return Err(GeomError::Invalid {
                request: request.to_string(),
                message: format!("parameters must be finite, found {nums:?}"),
            });
        }
        let empty = self.thetamax() == 0.0
            || match self {
                Shape::Sphere {
                    radius,
                    phimin,
                    phimax,
                    ..
                } => radius == 0.0 || phimin == phimax,
                Shape::Cone { radius, .. } | Shape::Disk { radius, .. } => radius == 0.0,
                Shape::Cylinder {
                    radius, zmin, zmax, ..
                } => radius == 0.0 || zmin == zmax,
                Shape::Hyperboloid { point1, point2, .. } => {
                    point1 == point2
                        || (point1.truncate() == DVec2::ZERO && point2.truncate() == DVec2::ZERO)
                }
                Shape::Paraboloid {
                    rmax, zmin, zmax, ..
                } => rmax == 0.0 || zmax == 0.0 || zmin == zmax,
                Shape::Torus {
                    minor,
                    phimin,
                    phimax,
                    ..
                } => minor == 0.0 || phimin == phimax,
            };
        Ok((!empty).then_some(self))
    }
}

/// Builds a quadric request: one [`Parametric`] over the whole surface, or nothing for a
/// zero-area one. Primitive variables: constant/uniform one value, varying/vertex/facevarying
/// four (the corners of the (u,v) square, interpolated bilinearly).
pub fn build_quadric(
    request: &illume_rib::Request,
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    let name = request.name();
    let vars = resolve(
        name,
        params,
        ctx.declarations,
        &ClassCounts::surface(4),
        ctx.warnings,
    )?;
    let Some(shape) = Shape::from_request(request)? else {
        return Ok(Vec::new());
    };
    let svars = surface_vars(&vars, &ctx.camera_from_object, |v| match v.class {
        Class::Constant | Class::Uniform => Interp::Constant(element64(v, 0)),
        _ => Interp::Bilinear([0, 1, 2, 3].map(|i| element64(v, i))),
    });
    let svars = with_default_st(
        svars,
        default_st(
            &ctx.texture_coordinates,
            [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
        ),
    );
    let surface = Quadric {
        shape,
        camera_from_object: ctx.camera_from_object,
    };
    Ok(vec![Box::new(Parametric::new(
        Arc::new(surface),
        Arc::new(svars),
    ))])
}
