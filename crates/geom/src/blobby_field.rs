//! The scalar field of a `Blobby` request (RI Spec 3.2 §5.6, PRMan Application Note #31):
//! the code array decoded into a small program of leaves (primitive fields, opcodes ≥ 1000)
//! and operations on earlier results, evaluated in f64 with its analytic gradient.
//!
//! # Falloff
//! Every geometric leaf uses the bounded "spherical bump" `F(s) = (1 − s)³` for `s < 1`, else
//! 0, of the squared distance `s` measured in the leaf's unit space (the space its matrix maps
//! onto the unit sphere). This is the falloff Application Note #31 describes (1 at the centre,
//! 0 with zero slope at the unit radius) and the one open implementations of `RiBlobby` use;
//! its bounded support is what gives each leaf a finite ellipsoid of influence (the bound).
//! The surface is the level set `field = 0.5` ([`THRESHOLD`], PRMan's), so a lone unit blob
//! has radius `√(1 − 0.5^⅓) ≈ 0.4542`.
//!
//! # Choices where the sources are silent
//! * 1002 segment: `F` of the squared distance to the segment divided by `radius²` (a capsule
//!   of influence), not a convolution along the segment: the capsule has a closed form a test
//!   can check, and segments joined end to end bulge slightly at the joint (a known difference).
//! * 1003 repelling plane needs a depth map: it is decoded (a leaf) but contributes no field,
//!   and `build` warns.
//! * Opcode 4 is subtract (`a − b`) and 5 divide (`a / b`), RI Spec Table 5.3's order; a
//!   division by a zero field gives 0.
//! * Varying values are blended by each leaf's own field value at the point (weights
//!   `max(0, fᵢ) / Σ max(0, fⱼ)`, equal weights where all vanish), not propagated through the
//!   operations.
use glam::{DMat3, DMat4, DVec3};

/// PRMan's isosurface level.
pub const THRESHOLD: f64 = 0.5;

/// The bump `F(s) = (1 − s)³` on `[0, 1)` and its derivative `dF/ds`.
pub fn falloff(s: f64) -> (f64, f64) {
    if !(0.0..1.0).contains(&s) {
        return (0.0, 0.0);
    }
    let w = 1.0 - s;
    (w * w * w, -3.0 * w * w)
}

/// One decoded instruction; operands are indices of earlier instructions.
#[derive(Clone, Debug, PartialEq)]
pub enum Instr {
    /// 1000: a constant field.
    Constant(f64),
    /// 1001: `F(|unit_from_object · p|²)`.
    Ellipsoid(LeafSpace),
    /// 1002: `F(dist²(unit_from_object · p, [a, b]) / r²)`.
    Segment {
        space: LeafSpace,
        a: DVec3,
        b: DVec3,
        r2: f64,
    },
    /// 1003: decoded, contributes 0 (no depth-map support).
    Repeller,
    Add(Vec<usize>),
    Mul(Vec<usize>),
    Max(Vec<usize>),
    Min(Vec<usize>),
    Sub(usize, usize),
    Div(usize, usize),
    Neg(usize),
    Identity(usize),
}

/// The affine map of a leaf: `object_from_unit` as the RIB matrix gave it, and its inverse.
#[derive(Clone, Debug, PartialEq)]
pub struct LeafSpace {
    pub object_from_unit: DMat4,
    pub unit_from_object: DMat4,
    /// Linear part of `unit_from_object`, transposed: carries a unit-space gradient to object space.
    gradient_to_object: DMat3,
}

impl LeafSpace {
    fn new(m: DMat4) -> Option<LeafSpace> {
        let inv = m.inverse();
        (m.is_finite() && inv.is_finite() && DMat3::from_mat4(m).determinant() != 0.0).then(|| {
            LeafSpace {
                object_from_unit: m,
                unit_from_object: inv,
                gradient_to_object: DMat3::from_mat4(inv).transpose(),
            }
        })
    }

    /// Object-space box of the image of the unit-space ball of radius `r` centred at `c`.
    fn ball_box(&self, c: DVec3, r: f64) -> (DVec3, DVec3) {
        let m = &self.object_from_unit;
        let centre = m.transform_point3(c);
        // Half extent along object axis i of an ellipsoid M·(ball): r·|row i of M's linear part|.
        let l = DMat3::from_mat4(*m);
        let half = DVec3::new(l.row(0).length(), l.row(1).length(), l.row(2).length()) * r;
        (centre - half, centre + half)
    }
}

/// A decoded `Blobby`: its instructions (the last one is the field) and which are leaves.
#[derive(Clone, Debug, PartialEq)]
pub struct BlobbyField {
    pub instrs: Vec<Instr>,
    /// Instruction index of each leaf, in leaf order (the order of varying values).
    pub leaves: Vec<usize>,
}

thread_local! {
    /// [`BlobbyField::eval`]'s buffer.
    static RESULTS: std::cell::RefCell<Vec<Dual>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Value and object-space gradient of one instruction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Dual {
    f: f64,
    g: DVec3,
}

impl BlobbyField {
    /// Decodes `code` against `floats`/`strings`; `Err` says what is wrong and where in `code`.
    pub fn decode(
        nleaf: i32,
        code: &[i32],
        floats: &[f32],
        strings: &[String],
    ) -> Result<BlobbyField, String> {
        let mut instrs = Vec::new();
        let mut leaves = Vec::new();
        let mut pc = 0usize;
        while pc < code.len() {
            let at = pc;
            let op = code[pc];
            pc += 1;
            let mut next = |what: &str| -> Result<i32, String> {
                let v = code.get(pc).copied().ok_or_else(|| {
                    format!("code[{at}]: opcode {op} is missing its {what} (code ends)")
                })?;
                pc += 1;
                Ok(v)
            };
            let here = instrs.len();
            let float_block = |index: i32, n: usize| -> Result<&[f32], String> {
                let i = usize::try_from(index)
                    .ok()
                    .filter(|&i| i.saturating_add(n) <= floats.len());
                i.map(|i| &floats[i..i + n]).ok_or_else(|| {
                    format!(
                        "code[{at}]: opcode {op} needs floats[{index}..{index}+{n}] but there are {} floats",
                        floats.len()
                    )
                })
            };
            let operand = |v: i32| -> Result<usize, String> {
                usize::try_from(v).ok().filter(|&i| i < here).ok_or_else(|| {
                    format!("code[{at}]: opcode {op} refers to instruction {v}, but only 0..{here} come before it")
                })
            };
            let instr = match op {
                1000 => Instr::Constant(f64::from(float_block(next("float index")?, 1)?[0])),
                1001 => {
                    let f = float_block(next("float index")?, 16)?;
                    Instr::Ellipsoid(leaf_space(f, at)?)
                }
                1002 => {
                    let f = float_block(next("float index")?, 23)?;
                    let v = |k: usize| DVec3::new(f[k].into(), f[k + 1].into(), f[k + 2].into());
                    let r = f64::from(f[6]);
                    if !(r.is_finite() && r > 0.0 && v(0).is_finite() && v(3).is_finite()) {
                        return Err(format!(
                            "code[{at}]: segment needs finite end points and a positive radius"
                        ));
                    }
                    Instr::Segment {
                        space: leaf_space(&f[7..23], at)?,
                        a: v(0),
                        b: v(3),
                        r2: r * r,
                    }
                }
                1003 => {
                    let s = next("string index")?;
                    if usize::try_from(s)
                        .ok()
                        .filter(|&s| s < strings.len())
                        .is_none()
                    {
                        return Err(format!(
                            "code[{at}]: repelling plane refers to strings[{s}] but there are {} strings",
                            strings.len()
                        ));
                    }
                    float_block(next("float index")?, 4)?;
                    Instr::Repeller
                }
                0..=3 => {
                    let n = next("operand count")?;
                    let n = usize::try_from(n)
                        .ok()
                        .filter(|&n| n >= 1 && n <= code.len())
                        .ok_or_else(|| format!("code[{at}]: opcode {op} has operand count {n}"))?;
                    let mut ops = Vec::with_capacity(n);
                    for _ in 0..n {
                        ops.push(operand(next("operands")?)?);
                    }
                    match op {
                        0 => Instr::Add(ops),
                        1 => Instr::Mul(ops),
                        2 => Instr::Max(ops),
                        _ => Instr::Min(ops),
                    }
                }
                4 | 5 => {
                    let a = operand(next("first operand")?)?;
                    let b = operand(next("second operand")?)?;
                    if op == 4 {
                        Instr::Sub(a, b)
                    } else {
                        Instr::Div(a, b)
                    }
                }
                6 => Instr::Neg(operand(next("operand")?)?),
                7 => Instr::Identity(operand(next("operand")?)?),
                _ => {
                    return Err(format!(
                        "code[{at}]: unknown opcode {op} (expected 0-7 or 1000-1003)"
                    ))
                }
            };
            if matches!(
                instr,
                Instr::Constant(_) | Instr::Ellipsoid(_) | Instr::Segment { .. } | Instr::Repeller
            ) {
                leaves.push(here);
            }
            instrs.push(instr);
        }
        if instrs.is_empty() {
            return Err("the code array is empty".to_string());
        }
        if usize::try_from(nleaf).ok() != Some(leaves.len()) {
            return Err(format!(
                "nleaf is {nleaf} but the code array has {} primitive fields (opcodes 1000-1003)",
                leaves.len()
            ));
        }
        Ok(BlobbyField { instrs, leaves })
    }

    /// Whether any leaf is a repelling plane (which this renderer ignores).
    pub fn has_repeller(&self) -> bool {
        self.instrs.iter().any(|i| matches!(i, Instr::Repeller))
    }

    /// The field at an object-space point.
    pub fn value(&self, p: DVec3) -> f64 {
        self.eval(p, None).0
    }

    /// Field and object-space gradient; when `leaf_values` is given it receives each leaf's
    /// own field value (for blending varying primitive variables).
    pub fn eval(&self, p: DVec3, leaf_values: Option<&mut Vec<f64>>) -> (f64, DVec3) {
        // This thread's buffer for the results: the field is evaluated several times per diced
        // vertex, and a heap buffer per call was a tenth of `rib/blobby.rib`'s time.
        RESULTS.with(|r| self.eval_in(&mut r.borrow_mut(), p, leaf_values))
    }

    /// [`BlobbyField::eval`] with `r` as the buffer for the instructions' results.
    fn eval_in(
        &self,
        r: &mut Vec<Dual>,
        p: DVec3,
        leaf_values: Option<&mut Vec<f64>>,
    ) -> (f64, DVec3) {
        r.clear();
        for instr in &self.instrs {
            let d = match instr {
                Instr::Constant(c) => Dual {
                    f: *c,
                    g: DVec3::ZERO,
                },
                Instr::Repeller => Dual::default(),
                Instr::Ellipsoid(space) => {
                    let q = space.unit_from_object.transform_point3(p);
                    let (f, dfds) = falloff(q.length_squared());
                    Dual {
                        f,
                        g: space.gradient_to_object * (q * (2.0 * dfds)),
                    }
                }
                Instr::Segment { space, a, b, r2 } => {
                    let q = space.unit_from_object.transform_point3(p);
                    let c = closest_on_segment(q, *a, *b);
                    let (f, dfds) = falloff((q - c).length_squared() / r2);
                    Dual {
                        f,
                        g: space.gradient_to_object * ((q - c) * (2.0 * dfds / r2)),
                    }
                }
                Instr::Add(ops) => ops.iter().fold(Dual::default(), |s, &i| Dual {
                    f: s.f + r[i].f,
                    g: s.g + r[i].g,
                }),
                Instr::Mul(ops) => ops.iter().fold(
                    Dual {
                        f: 1.0,
                        g: DVec3::ZERO,
                    },
                    |s, &i| Dual {
                        f: s.f * r[i].f,
                        g: s.g * r[i].f + r[i].g * s.f,
                    },
                ),
                // Ties go to the first operand, for the field and its gradient alike.
                Instr::Max(ops) => ops
                    .iter()
                    .map(|&i| r[i])
                    .reduce(|a, b| if b.f > a.f { b } else { a })
                    .unwrap_or_default(),
                Instr::Min(ops) => ops
                    .iter()
                    .map(|&i| r[i])
                    .reduce(|a, b| if b.f < a.f { b } else { a })
                    .unwrap_or_default(),
                Instr::Sub(a, b) => Dual {
                    f: r[*a].f - r[*b].f,
                    g: r[*a].g - r[*b].g,
                },
                Instr::Div(a, b) => {
                    let (x, y) = (r[*a], r[*b]);
                    if y.f == 0.0 {
                        Dual::default()
                    } else {
                        Dual {
                            f: x.f / y.f,
                            g: (x.g * y.f - y.g * x.f) / (y.f * y.f),
                        }
                    }
                }
                Instr::Neg(a) => Dual {
                    f: -r[*a].f,
                    g: -r[*a].g,
                },
                Instr::Identity(a) => r[*a],
            };
            r.push(d);
        }
        if let Some(out) = leaf_values {
            out.clear();
            out.extend(self.leaves.iter().map(|&i| r[i].f));
        }
        let last = r.last().copied().unwrap_or_default();
        (last.f, last.g)
    }

    /// Object-space box of the union of every geometric leaf's region of influence (field > 0);
    /// `None` when there is no geometric leaf.
    pub fn influence_box(&self) -> Option<(DVec3, DVec3)> {
        let boxes = self.instrs.iter().filter_map(|i| match i {
            Instr::Ellipsoid(space) => Some(space.ball_box(DVec3::ZERO, 1.0)),
            Instr::Segment { space, a, b, r2 } => {
                let r = r2.sqrt();
                let (l0, h0) = space.ball_box(*a, r);
                let (l1, h1) = space.ball_box(*b, r);
                Some((l0.min(l1), h0.max(h1)))
            }
            _ => None,
        });
        boxes.reduce(|(l0, h0), (l1, h1)| (l0.min(l1), h0.max(h1)))
    }

    /// Weights of the leaves at a point from their field values (see the module notes).
    pub fn blend_weights(leaf_values: &[f64]) -> Vec<f64> {
        let sum: f64 = leaf_values.iter().map(|f| f.max(0.0)).sum();
        if sum > 0.0 && sum.is_finite() {
            leaf_values.iter().map(|f| f.max(0.0) / sum).collect()
        } else {
            let n = leaf_values.len().max(1) as f64;
            vec![1.0 / n; leaf_values.len()]
        }
    }
}

/// The 16 floats of a leaf as a matrix (RIB row-vector order, like `ConcatTransform`).
fn leaf_space(f: &[f32], at: usize) -> Result<LeafSpace, String> {
    let mut m = [0.0f64; 16];
    for (d, &s) in m.iter_mut().zip(f) {
        *d = f64::from(s);
    }
    LeafSpace::new(DMat4::from_cols_array(&m))
        .ok_or_else(|| format!("code[{at}]: the leaf's matrix is singular or not finite"))
}

fn closest_on_segment(q: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let l2 = ab.length_squared();
    if l2 == 0.0 {
        return a;
    }
    a + ab * ((q - a).dot(ab) / l2).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ID: [f32; 16] = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];

    fn sphere_at(c: [f32; 3], r: f32) -> Vec<f32> {
        let mut m = ID;
        m[0] = r;
        m[5] = r;
        m[10] = r;
        m[12..15].copy_from_slice(&c);
        m.to_vec()
    }

    #[test]
    fn falloff_is_one_at_the_centre_and_flat_at_the_rim() {
        assert_eq!(falloff(0.0), (1.0, -3.0));
        assert_eq!(falloff(1.0), (0.0, 0.0));
        let (f, d) = falloff(0.5);
        assert!((f - 0.125).abs() < 1e-15 && (d + 0.75).abs() < 1e-15);
    }

    #[test]
    fn ellipsoid_field_follows_its_matrix() {
        let f = BlobbyField::decode(1, &[1001, 0], &sphere_at([1.0, 2.0, 3.0], 2.0), &[]).unwrap();
        // At distance 1 from the centre of a radius-2 blob, s = 1/4.
        let p = DVec3::new(2.0, 2.0, 3.0);
        assert!((f.value(p) - 0.75f64.powi(3)).abs() < 1e-14);
        assert_eq!(f.value(DVec3::new(3.5, 2.0, 3.0)), 0.0);
        let (lo, hi) = f.influence_box().unwrap();
        assert_eq!(
            (lo, hi),
            (DVec3::new(-1.0, 0.0, 1.0), DVec3::new(3.0, 4.0, 5.0))
        );
    }

    #[test]
    fn gradient_matches_central_differences_for_every_operation() {
        let mut floats = sphere_at([0.0, 0.0, 0.0], 1.0);
        floats.extend(sphere_at([0.6, 0.1, 0.0], 0.8));
        floats.extend([-0.5, 0.0, 0.0, 0.5, 0.3, 0.0, 0.7]);
        floats.extend(ID);
        floats.push(0.25);
        let code = [
            1001, 0, 1001, 16, 1002, 32, 1000, 55, // leaves 0..3
            0, 2, 0, 1, // 4 add
            1, 2, 1, 2, // 5 mul
            2, 2, 4, 2, // 6 max
            3, 2, 4, 2, // 7 min
            4, 6, 5, // 8 sub
            5, 0, 4, // 9 div
            6, 9, // 10 neg
            7, 10, // 11 identity
            0, 4, 7, 8, 11, 3, // 12 add
        ];
        let f = BlobbyField::decode(4, &code, &floats, &[]).unwrap();
        let h = 1e-6;
        for p in [
            DVec3::new(0.1, 0.2, 0.05),
            DVec3::new(0.4, -0.1, 0.2),
            DVec3::new(-0.3, 0.15, -0.1),
        ] {
            let (_, g) = f.eval(p, None);
            let num = DVec3::new(
                f.value(p + DVec3::X * h) - f.value(p - DVec3::X * h),
                f.value(p + DVec3::Y * h) - f.value(p - DVec3::Y * h),
                f.value(p + DVec3::Z * h) - f.value(p - DVec3::Z * h),
            ) / (2.0 * h);
            assert!(
                (g - num).length() < 1e-6 * (1.0 + g.length()),
                "{p}: {g} vs {num}"
            );
        }
    }

    #[test]
    fn bad_code_is_an_error_not_a_panic() {
        let floats = sphere_at([0.0; 3], 1.0);
        for (nleaf, code) in [
            (1, vec![1001, 1]),             // float block out of range
            (1, vec![1001]),                // missing index
            (1, vec![999, 0]),              // unknown opcode
            (2, vec![1001, 0]),             // nleaf mismatch
            (1, vec![1001, 0, 0, 2, 0, 1]), // operand refers forward
            (1, vec![1001, 0, 6, -1]),      // negative operand
            (0, vec![]),                    // empty
            (1, vec![1001, 0, 0, i32::MAX]),
        ] {
            assert!(
                BlobbyField::decode(nleaf, &code, &floats, &[]).is_err(),
                "{code:?}"
            );
        }
    }

    #[test]
    fn blend_weights_follow_leaf_fields_and_never_divide_by_zero() {
        assert_eq!(
            BlobbyField::blend_weights(&[0.25, 0.75, -1.0]),
            vec![0.25, 0.75, 0.0]
        );
        assert_eq!(BlobbyField::blend_weights(&[0.0, 0.0]), vec![0.5, 0.5]);
    }
}
