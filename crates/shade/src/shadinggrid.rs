//! The shading context: one grid of `nu × nv` points in camera ("current") space, stored as a
//! structure of arrays so per-point loops vectorise (DESIGN.md, “Shading”).
use glam::Vec3;

/// The global variables of a surface or displacement shader over a whole grid.
///
/// Index `i = iv * nu + iu` (u varies fastest). Every per-point `Vec` has `nu * nv` elements;
/// [`ShadingGrid::new`] allocates them with neutral values (`Cs = Os = 1`, `N = Ng = (0,0,-1)`…),
/// the hider then overwrites what it knows.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadingGrid {
    pub nu: usize,
    pub nv: usize,
    /// Surface position `P`.
    pub p: Vec<Vec3>,
    /// Shading normal `N` (not necessarily unit length).
    pub n: Vec<Vec3>,
    /// Geometric normal `Ng`.
    pub ng: Vec<Vec3>,
    /// Incident ray `I`: `P - E` (perspective) or `(0,0,1)` scaled by nothing (orthographic).
    pub i: Vec<Vec3>,
    pub dpdu: Vec<Vec3>,
    pub dpdv: Vec<Vec3>,
    pub s: Vec<f32>,
    pub t: Vec<f32>,
    pub u: Vec<f32>,
    pub v: Vec<f32>,
    /// Parametric spacing between grid points (uniform over the grid).
    pub du: f32,
    pub dv: f32,
    /// Surface colour `Cs` and opacity `Os`.
    pub cs: Vec<Vec3>,
    pub os: Vec<Vec3>,
    /// Outputs: premultiplied colour `Ci` and opacity `Oi`.
    pub ci: Vec<Vec3>,
    pub oi: Vec<Vec3>,
    /// User primitive variables `(name, components per point, values)`: `values.len()` is
    /// `components * nu * nv` (varying) or `components` (constant/uniform). A variable binds to the
    /// shader parameter of the same name and overrides its value, as RI Spec §5 says.
    pub vars: Vec<(String, usize, Vec<f32>)>,
}

impl ShadingGrid {
    /// A grid of `nu × nv` points with neutral values: `P = 0`, `N = Ng = (0,0,-1)` (facing the
    /// camera), `I = (0,0,1)`, `dPdu = (1,0,0)`, `dPdv = (0,1,0)`, `s,t,u,v` the regular
    /// parametric lattice over `[0,1]²`, `Cs = Os = 1`, `Ci = Oi = 0`.
    pub fn new(nu: usize, nv: usize) -> ShadingGrid {
        let n = nu * nv;
        let du = if nu > 1 { 1.0 / (nu - 1) as f32 } else { 1.0 };
        let dv = if nv > 1 { 1.0 / (nv - 1) as f32 } else { 1.0 };
        let mut u = Vec::with_capacity(n);
        let mut v = Vec::with_capacity(n);
        for iv in 0..nv {
            for iu in 0..nu {
                u.push(iu as f32 * du);
                v.push(iv as f32 * dv);
            }
        }
        ShadingGrid {
            nu,
            nv,
            p: vec![Vec3::ZERO; n],
            n: vec![Vec3::NEG_Z; n],
            ng: vec![Vec3::NEG_Z; n],
            i: vec![Vec3::Z; n],
            dpdu: vec![Vec3::X; n],
            dpdv: vec![Vec3::Y; n],
            s: u.clone(),
            t: v.clone(),
            u,
            v,
            du,
            dv,
            cs: vec![Vec3::ONE; n],
            os: vec![Vec3::ONE; n],
            ci: vec![Vec3::ZERO; n],
            oi: vec![Vec3::ZERO; n],
            vars: Vec::new(),
        }
    }

    /// Number of shading points `nu * nv`.
    pub fn len(&self) -> usize {
        self.nu * self.nv
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sets `I` from `P`: `P - E` with the eye at the camera-space origin (perspective), or the
    /// view direction `(0,0,1)` (orthographic).
    pub fn set_incident_from_p(&mut self, orthographic: bool) {
        if orthographic {
            self.i.iter_mut().for_each(|i| *i = Vec3::Z);
        } else {
            self.i.clone_from(&self.p);
        }
    }

    /// Adds (or replaces) a user primitive variable; see [`ShadingGrid::vars`].
    pub fn set_var(&mut self, name: &str, components: usize, values: Vec<f32>) {
        self.vars.retain(|(n, _, _)| n != name);
        self.vars.push((name.to_string(), components, values));
    }

    /// The user primitive variable `name`, if bound with `components` per point.
    pub fn var(&self, name: &str, components: usize) -> Option<&[f32]> {
        self.vars
            .iter()
            .find(|(n, c, vals)| {
                n == name
                    && *c == components
                    && (vals.len() == components || vals.len() == components * self.len())
            })
            .map(|(_, _, vals)| vals.as_slice())
    }
}

impl ShadingGrid {
    /// The four grid points spanning point `i`'s footprint, in the order `(u,v)`, `(u+du,v)`,
    /// `(u,v+dv)`, `(u+du,v+dv)`; on the last row/column the previous one is used, so filtered
    /// lookups (`texture`, `environment`, `shadow`) see the grid spacing everywhere.
    pub fn footprint(&self, i: usize) -> [usize; 4] {
        let (iu, iv) = (i % self.nu.max(1), i / self.nu.max(1));
        let u1 = if iu + 1 < self.nu {
            iu + 1
        } else {
            iu.saturating_sub(1)
        };
        let v1 = if iv + 1 < self.nv {
            iv + 1
        } else {
            iv.saturating_sub(1)
        };
        let at = |u: usize, v: usize| v * self.nu + u;
        [at(iu, iv), at(u1, iv), at(iu, v1), at(u1, v1)]
    }

    /// Point `i`'s footprint corners of a per-point quantity `value` ([`ShadingGrid::footprint`]),
    /// moved so that their centre is the point's own value: a filtered lookup (`texture`,
    /// `environment`, reflection maps) covers one micropolygon's extent centred on the shaded
    /// point. Uncentred, it would cover the micropolygon ahead of the point, and a
    /// micropolygon's colour — the mean of its four vertices under "constant", their blend
    /// under "smooth" — would show its lookups half a micropolygon ahead (issue 21).
    pub fn centred_footprint<T>(&self, i: usize, value: impl Fn(usize) -> T) -> [T; 4]
    where
        T: Copy
            + std::ops::Add<Output = T>
            + std::ops::Sub<Output = T>
            + std::ops::Mul<f32, Output = T>,
    {
        let q = self.footprint(i).map(&value);
        let shift = value(i) - (q[0] + q[1] + q[2] + q[3]) * 0.25;
        q.map(|c| c + shift)
    }

    /// `calculatenormal(P)`: `Du(P) × Dv(P)` from grid differences, oriented like `reference`
    /// (the surface's normal before displacement) so that sidedness survives.
    pub fn calculatenormal(&self, reference: &[Vec3]) -> Vec<Vec3> {
        (0..self.len())
            .map(|i| {
                let [a, b, c, _] = self.footprint(i);
                let (iu, iv) = (i % self.nu.max(1), i / self.nu.max(1));
                let mut du = self.p[b] - self.p[a];
                let mut dv = self.p[c] - self.p[a];
                if iu + 1 >= self.nu {
                    du = -du;
                }
                if iv + 1 >= self.nv {
                    dv = -dv;
                }
                let n = du.cross(dv);
                let n = if n.length_squared() > 0.0 {
                    n
                } else {
                    reference[i]
                };
                if n.dot(reference[i]) < 0.0 {
                    -n
                } else {
                    n
                }
            })
            .collect()
    }
}

impl ShadingGrid {
    /// `Du(x)`: the derivative of a per-point quantity along u by grid differences (forward,
    /// backward on the last column), divided by `du`. A one-column grid has zero derivative.
    pub fn deriv_u<T>(&self, x: &[T]) -> Vec<T>
    where
        T: Copy + std::ops::Sub<Output = T> + std::ops::Mul<f32, Output = T>,
    {
        self.deriv(x, true)
    }

    /// `Dv(x)`, as [`ShadingGrid::deriv_u`] along v.
    pub fn deriv_v<T>(&self, x: &[T]) -> Vec<T>
    where
        T: Copy + std::ops::Sub<Output = T> + std::ops::Mul<f32, Output = T>,
    {
        self.deriv(x, false)
    }

    fn deriv<T>(&self, x: &[T], along_u: bool) -> Vec<T>
    where
        T: Copy + std::ops::Sub<Output = T> + std::ops::Mul<f32, Output = T>,
    {
        let (count, step, spacing) = if along_u {
            (self.nu, 1, self.du)
        } else {
            (self.nv, self.nu, self.dv)
        };
        let inv = if spacing != 0.0 { 1.0 / spacing } else { 0.0 };
        (0..self.len())
            .map(|i| {
                let k = if along_u { i % self.nu } else { i / self.nu };
                if count < 2 {
                    x[i] * 0.0
                } else if k + 1 < count {
                    (x[i + step] - x[i]) * inv
                } else {
                    (x[i] - x[i - step]) * inv
                }
            })
            .collect()
    }

    /// `area(P)`: `|Du(P) × Dv(P)| du dv`, the micropolygon area at each point.
    pub fn area(&self) -> Vec<f32> {
        let (pu, pv) = (self.deriv_u(&self.p), self.deriv_v(&self.p));
        pu.iter()
            .zip(&pv)
            .map(|(a, b)| a.cross(*b).length() * self.du * self.dv)
            .collect()
    }
}
