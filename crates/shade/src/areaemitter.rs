//! The geometry of an area light (`AreaLightSource` followed by primitives), as points to
//! sample: Listing 9.18's light shader runs at points `P` (with normals `N`) on that surface.
//!
//! The diced grids become rows of quads; a sample picks a row by a cumulative area table over
//! every row, then a quad of the row by that row's table, each with one of the two uniform
//! numbers (pbrt's piecewise-constant 2D distribution over the grids' parameter domain), so
//! stratified numbers give samples stratified over the surface and uniform in area.
use glam::{DVec3, Vec3};

#[derive(Clone, Debug, Default, PartialEq)]
pub struct AreaEmitter {
    rows: Vec<Row>,
    /// Cumulative area at the end of each row.
    row_cdf: Vec<f64>,
}

#[derive(Clone, Debug, PartialEq)]
struct Row {
    /// Corners (i,j), (i+1,j), (i+1,j+1), (i,j+1) and the oriented normal of each quad.
    quads: Vec<([Vec3; 4], Vec3)>,
    /// Cumulative area at the end of each quad.
    cdf: Vec<f64>,
}

impl AreaEmitter {
    pub fn new() -> AreaEmitter {
        AreaEmitter::default()
    }

    /// Adds a diced grid: `nu × nv` camera-space vertices, u fastest. `flip` (±1) orients the
    /// normal `dPdu × dPdv` as the hider orients the grid's `Ng`.
    pub fn add_grid(&mut self, nu: usize, nv: usize, p: &[Vec3], flip: f32) {
        if nu < 2 || nv < 2 || p.len() != nu * nv {
            return;
        }
        for j in 0..nv - 1 {
            let mut row = Row {
                quads: Vec::with_capacity(nu - 1),
                cdf: Vec::with_capacity(nu - 1),
            };
            let mut acc = 0.0;
            for i in 0..nu - 1 {
                let k = j * nu + i;
                let c = [p[k], p[k + 1], p[k + nu + 1], p[k + nu]];
                let d = c.map(Vec3::as_dvec3);
                // A planar quad's area is half the cross product of its diagonals.
                let area = 0.5 * (d[2] - d[0]).cross(d[3] - d[1]).length();
                let n = (d[1] - d[0]).cross(d[3] - d[0]).normalize_or_zero() * f64::from(flip);
                if !(area.is_finite() && area > 0.0) {
                    continue;
                }
                acc += area;
                row.quads.push((c, n.as_vec3()));
                row.cdf.push(acc);
            }
            if acc > 0.0 {
                let total = self.area() + acc;
                self.rows.push(row);
                self.row_cdf.push(total);
            }
        }
    }

    /// Total area of the geometry.
    pub fn area(&self) -> f64 {
        self.row_cdf.last().copied().unwrap_or(0.0)
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The point and oriented normal at `(u1, u2) ∈ [0,1)²`, uniform in area: `u2` picks the
    /// row, `u1` the quad in it, their remainders the spot in the quad (bilinear).
    pub fn sample(&self, u1: f64, u2: f64) -> Option<(Vec3, Vec3)> {
        let (r, t) = pick(&self.row_cdf, u2)?;
        let row = &self.rows[r];
        let (q, s) = pick(&row.cdf, u1)?;
        let (c, n) = row.quads[q];
        let c = c.map(Vec3::as_dvec3);
        let p: DVec3 = c[0] * ((1.0 - s) * (1.0 - t))
            + c[1] * (s * (1.0 - t))
            + c[2] * (s * t)
            + c[3] * ((1.0 - s) * t);
        Some((p.as_vec3(), n))
    }
}

/// The entry of cumulative table `cdf` that `u ∈ [0,1)` falls in, and where in it (0..1).
fn pick(cdf: &[f64], u: f64) -> Option<(usize, f64)> {
    let total = *cdf.last()?;
    let x = u.clamp(0.0, 1.0) * total;
    let k = cdf.partition_point(|&c| c <= x).min(cdf.len() - 1);
    let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
    let w = cdf[k] - lo;
    let f = if w > 0.0 { (x - lo) / w } else { 0.5 };
    Some((k, f.clamp(0.0, 1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat annulus sector diced as a polar grid: area-uniform samples have the closed-form
    /// moments E[r²] = (R⁴−r⁴)/(2(R²−r²)) and mean angle at the sector's middle.
    #[test]
    fn samples_on_a_polar_grid_are_uniform_in_area() {
        let (r0, r1, n) = (0.5f64, 2.0f64, 64usize);
        let p: Vec<Vec3> = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| {
                let th = i as f64 / (n - 1) as f64 * std::f64::consts::PI;
                let r = r0 + (r1 - r0) * j as f64 / (n - 1) as f64;
                DVec3::new(r * th.cos(), r * th.sin(), 3.0).as_vec3()
            })
            .collect();
        let mut e = AreaEmitter::new();
        e.add_grid(n, n, &p, 1.0);
        let m = 200usize;
        let (mut r2, mut count) = (0.0, 0.0);
        for a in 0..m {
            for b in 0..m {
                let (q, normal) = e
                    .sample((a as f64 + 0.5) / m as f64, (b as f64 + 0.5) / m as f64)
                    .unwrap();
                assert!((normal.z.abs() - 1.0).abs() < 1e-5);
                r2 += f64::from(q.x * q.x + q.y * q.y);
                count += 1.0;
            }
        }
        let expected = (r1.powi(4) - r0.powi(4)) / (2.0 * (r1 * r1 - r0 * r0));
        assert!(((r2 / count) - expected).abs() / expected < 2e-3);
        let area = std::f64::consts::PI * (r1 * r1 - r0 * r0) / 2.0;
        assert!(
            (e.area() - area).abs() / area < 2e-3,
            "{} vs {area}",
            e.area()
        );
    }
}
