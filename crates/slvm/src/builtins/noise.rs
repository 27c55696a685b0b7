//! The noise family: `noise`, `pnoise`, `cellnoise`, `random`. Each is a thin mapping of its
//! argument list onto coordinates and a call of the per-point kernel in [`crate::noise`], so the
//! kernel can be swapped without touching the dispatch.
use super::{fl, Args};
use crate::exec::Exec;
use crate::noise as kernel;
use crate::value::{zip2, Slot, Value};
use glam::Vec3;
use illume_sl::ast::BuiltinId as B;
use illume_sl::types::BaseType;

impl Exec<'_> {
    /// The noise family; `None` for an overload the executor does not implement.
    pub(super) fn noise(&mut self, c: &Args) -> Option<Value> {
        let (a, n, ret) = (c.a, self.n, c.ret);
        Some(match (c.id, a.len()) {
            (B::Noise, _) => {
                let c = noise_coords(a, n);
                let d = dims_of(a);
                noise_result(ret, &c, |c, seed| kernel::noise(&c[..d], seed))
            }
            (B::CellNoise, _) => {
                let c = noise_coords(a, n);
                let d = dims_of(a);
                noise_result(ret, &c, |c, seed| kernel::cellnoise(&c[..d], seed))
            }
            (B::PNoise, k) if k >= 2 && k % 2 == 0 => {
                let half = k / 2;
                let c = noise_coords(&a[..half], n);
                let p = noise_coords(&a[half..], n);
                let d = dims_of(&a[..half]);
                let cp = zip2(&c, &p, n, |c, p| (*c, *p));
                if ret == BaseType::Float {
                    Value::Float(cp.map(|(c, p)| kernel::pnoise(&c[..d], &p[..d], 0)))
                } else {
                    Value::Triple(cp.map(|(c, p)| {
                        Vec3::new(
                            kernel::pnoise(&c[..d], &p[..d], 0),
                            kernel::pnoise(&c[..d], &p[..d], 1),
                            kernel::pnoise(&c[..d], &p[..d], 2),
                        )
                    }))
                }
            }
            (B::Random, 0) => self.random(ret),
            _ => return None,
        })
    }

    /// `random()`: keyed by the point's undisplaced position (not its index in the grid, which
    /// every grid shares), the call site and the frame: the same bits whatever the dicing order
    /// or thread count.
    fn random(&mut self, ret: BaseType) -> Value {
        let n = self.n;
        self.random_site += 1;
        let (site, seed) = (self.random_site, self.env.seed);
        let key = |i: usize| {
            let p = self.grid.p[i];
            illume_shade::lowbias32(
                p.x.to_bits()
                    ^ illume_shade::lowbias32(
                        p.y.to_bits() ^ illume_shade::lowbias32(p.z.to_bits()),
                    ),
            ) as usize
        };
        let f = |i: usize, c: u32| kernel::random(key(i), site.wrapping_mul(3) + c, seed);
        if ret == BaseType::Float {
            Value::Float(Slot::varying((0..n).map(|i| f(i, 0)).collect()))
        } else {
            Value::Triple(Slot::varying(
                (0..n)
                    .map(|i| Vec3::new(f(i, 0), f(i, 1), f(i, 2)))
                    .collect(),
            ))
        }
    }
}

/// The coordinates of a noise argument list (`float`, `float, float`, `point`, `point, float`).
fn noise_coords(args: &[Value], n: usize) -> Slot<[f32; 4]> {
    let mut acc: Slot<([f32; 4], usize)> = Slot::Uniform(([0.0; 4], 0));
    for a in args {
        acc = match a {
            Value::Triple(s) => zip2(&acc, s, n, |(c, k), p| {
                let mut c = *c;
                for (j, x) in [p.x, p.y, p.z].into_iter().enumerate() {
                    if k + j < 4 {
                        c[k + j] = x;
                    }
                }
                (c, k + 3)
            }),
            v => zip2(&acc, &fl(v), n, |(c, k), &x| {
                let mut c = *c;
                if *k < 4 {
                    c[*k] = x;
                }
                (c, k + 1)
            }),
        };
    }
    let dims: usize = args
        .iter()
        .map(|a| if matches!(a, Value::Triple(_)) { 3 } else { 1 })
        .sum::<usize>()
        .min(4);
    acc.map(move |(c, _)| {
        let mut c = *c;
        for x in c.iter_mut().skip(dims) {
            *x = 0.0;
        }
        c
    })
}

/// How many coordinates an argument list gives (1 to 4).
fn dims_of(args: &[Value]) -> usize {
    args.iter()
        .map(|a| if matches!(a, Value::Triple(_)) { 3 } else { 1 })
        .sum::<usize>()
        .clamp(1, 4)
}

/// A noise-family result of type `ret` from a per-point scalar kernel with a component seed.
fn noise_result(
    ret: BaseType,
    coords: &Slot<[f32; 4]>,
    f: impl Fn(&[f32; 4], u32) -> f32,
) -> Value {
    if ret == BaseType::Float {
        Value::Float(coords.map(|c| f(c, 0)))
    } else {
        Value::Triple(coords.map(|c| Vec3::new(f(c, 0), f(c, 1), f(c, 2))))
    }
}
