//! Triangulation of a planar polygon with holes by ear clipping (Meisters 1975), holes first
//! joined to the outer loop by a bridge to a mutually visible vertex (Eberly, "Triangulation
//! by Ear Clipping", 2002). O(n²), which is fine for the polygons RIB files contain.
//!
//! Works on 2-D projections; indices refer to the concatenation of the loops, so callers can
//! look up per-corner data (vertex indices, facevarying values) of each triangle.
use glam::DVec2;

fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

fn signed_area(pts: &[DVec2], idx: &[usize]) -> f64 {
    let n = idx.len();
    (0..n)
        .map(|i| pts[idx[i]].perp_dot(pts[idx[(i + 1) % n]]))
        .sum::<f64>()
        * 0.5
}

/// Triangles `[a, b, c]` (counter-clockwise in the projection) covering the polygon whose
/// loops are `loops` (first the outer boundary, then holes), as indices into the concatenated
/// loop points. Degenerate input yields fewer (possibly no) triangles, never a panic.
pub fn triangulate(loops: &[Vec<DVec2>]) -> Vec<[usize; 3]> {
    let pts: Vec<DVec2> = loops.iter().flatten().copied().collect();
    if pts.iter().any(|p| !p.is_finite()) || loops.is_empty() {
        return Vec::new();
    }
    let mut start = 0;
    let mut rings: Vec<Vec<usize>> = loops
        .iter()
        .map(|l| {
            let r: Vec<usize> = (start..start + l.len()).collect();
            start += l.len();
            r
        })
        .collect();
    // Outer counter-clockwise, holes clockwise.
    for (k, ring) in rings.iter_mut().enumerate() {
        let area = signed_area(&pts, ring);
        if (k == 0) != (area > 0.0) {
            ring.reverse();
        }
    }
    let mut outer = rings.remove(0);
    let mut holes: Vec<Vec<usize>> = rings.into_iter().filter(|h| h.len() >= 3).collect();
    holes.sort_by(|a, b| max_x(&pts, b).total_cmp(&max_x(&pts, a)));
    for hole in holes {
        bridge(&pts, &mut outer, &hole);
    }
    clip_ears(&pts, outer)
}

fn max_x(pts: &[DVec2], ring: &[usize]) -> f64 {
    ring.iter()
        .map(|&i| pts[i].x)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Splices `hole` into `outer` through a bridge from the hole's rightmost vertex `m` to a
/// vertex of `outer` that `m` sees: the end of the first edge hit by the ray from `m` toward
/// +x, or the reflex vertex inside (m, hit, end) closest in angle to the ray.
fn bridge(pts: &[DVec2], outer: &mut Vec<usize>, hole: &[usize]) {
    let (hm, &m) = hole
        .iter()
        .enumerate()
        .max_by(|a, b| pts[*a.1].x.total_cmp(&pts[*b.1].x))
        .expect("hole has vertices");
    let mp = pts[m];
    let n = outer.len();
    let mut best: Option<(f64, usize)> = None; // (hit x, position in outer of the chosen end)
    for i in 0..n {
        let (a, b) = (pts[outer[i]], pts[outer[(i + 1) % n]]);
        // Edges crossing the horizontal line through m, seen from its right side.
        if (a.y > mp.y) == (b.y > mp.y) {
            continue;
        }
        let x = a.x + (mp.y - a.y) / (b.y - a.y) * (b.x - a.x);
        if x >= mp.x && best.is_none_or(|(bx, _)| x < bx) {
            let end = if a.x > b.x { i } else { (i + 1) % n };
            best = Some((x, end));
        }
    }
    let pos = match best {
        Some((hx, end)) => {
            let p = pts[outer[end]];
            let hit = DVec2::new(hx, mp.y);
            let mut choice = end;
            let mut best_cos = f64::NEG_INFINITY;
            for k in 0..n {
                let r = pts[outer[k]];
                let reflex = cross(pts[outer[(k + n - 1) % n]], r, pts[outer[(k + 1) % n]]) <= 0.0;
                if k == end || !reflex || r == mp || !in_triangle(r, mp, hit, p) {
                    continue;
                }
                let d = r - mp;
                let cos = d.x / d.length().max(f64::MIN_POSITIVE);
                if cos > best_cos {
                    best_cos = cos;
                    choice = k;
                }
            }
            choice
        }
        // No edge to the right (degenerate input): bridge to the nearest vertex.
        None => (0..n)
            .min_by(|&a, &b| {
                pts[outer[a]]
                    .distance_squared(mp)
                    .total_cmp(&pts[outer[b]].distance_squared(mp))
            })
            .unwrap_or(0),
    };
    let k = hole.len();
    let mut splice: Vec<usize> = (0..=k).map(|t| hole[(hm + t) % k]).collect();
    splice.push(outer[pos]);
    outer.splice(pos + 1..pos + 1, splice);
}

/// Whether `p` lies in the triangle `abc` (either orientation), edges included.
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let (d1, d2, d3) = (cross(a, b, p), cross(b, c, p), cross(c, a, p));
    let neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(neg && pos)
}

fn clip_ears(pts: &[DVec2], mut ring: Vec<usize>) -> Vec<[usize; 3]> {
    let mut tris = Vec::with_capacity(ring.len().saturating_sub(2));
    while ring.len() >= 3 {
        let n = ring.len();
        if n == 3 {
            push_if_area(pts, &mut tris, [ring[0], ring[1], ring[2]]);
            break;
        }
        let ear = (0..n).find(|&i| is_ear(pts, &ring, i));
        // Without an ear the rest is degenerate (collinear, self-touching): drop the flattest
        // corner so the loop always ends.
        let i = ear.unwrap_or_else(|| {
            (0..n)
                .min_by(|&a, &b| {
                    corner(pts, &ring, a)
                        .abs()
                        .total_cmp(&corner(pts, &ring, b).abs())
                })
                .unwrap_or(0)
        });
        if ear.is_some() {
            push_if_area(
                pts,
                &mut tris,
                [ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]],
            );
        }
        ring.remove(i);
    }
    tris
}

fn corner(pts: &[DVec2], ring: &[usize], i: usize) -> f64 {
    let n = ring.len();
    cross(
        pts[ring[(i + n - 1) % n]],
        pts[ring[i]],
        pts[ring[(i + 1) % n]],
    )
}

fn push_if_area(pts: &[DVec2], tris: &mut Vec<[usize; 3]>, t: [usize; 3]) {
    if cross(pts[t[0]], pts[t[1]], pts[t[2]]) > 0.0 {
        tris.push(t);
    }
}

fn is_ear(pts: &[DVec2], ring: &[usize], i: usize) -> bool {
    let n = ring.len();
    let (a, b, c) = (
        pts[ring[(i + n - 1) % n]],
        pts[ring[i]],
        pts[ring[(i + 1) % n]],
    );
    if cross(a, b, c) <= 0.0 {
        return false;
    }
    ring.iter().all(|&k| {
        let p = pts[k];
        p == a || p == b || p == c || !in_triangle(p, a, b, c)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(pts: &[DVec2], tris: &[[usize; 3]]) -> f64 {
        tris.iter()
            .map(|t| 0.5 * cross(pts[t[0]], pts[t[1]], pts[t[2]]))
            .sum()
    }

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    fn concave_polygon_with_two_holes_keeps_its_area() {
        // An L shape (area 3) with two unit-ish square holes of area 0.25 each, clockwise
        // outer to check reorientation.
        let outer = vec![
            v(0., 0.),
            v(0., 2.),
            v(1., 2.),
            v(1., 1.),
            v(2., 1.),
            v(2., 0.),
        ];
        let h1 = vec![v(0.25, 0.25), v(0.75, 0.25), v(0.75, 0.75), v(0.25, 0.75)];
        let h2 = vec![v(1.25, 0.25), v(1.75, 0.25), v(1.75, 0.75), v(1.25, 0.75)];
        let loops = vec![outer, h1, h2];
        let pts: Vec<DVec2> = loops.iter().flatten().copied().collect();
        let tris = triangulate(&loops);
        assert!(
            (area(&pts, &tris) - 2.5).abs() < 1e-12,
            "{}",
            area(&pts, &tris)
        );
        assert!(tris
            .iter()
            .all(|t| cross(pts[t[0]], pts[t[1]], pts[t[2]]) > 0.0));
    }

    #[test]
    fn comb_polygon_and_degenerate_input_terminate() {
        let mut comb = vec![v(0., 0.), v(10., 0.)];
        for k in (0..5).rev() {
            let x = 2.0 * k as f64;
            comb.extend([v(x + 2.0, 3.0), v(x + 1.0, 1.0)]);
        }
        comb.pop();
        comb.push(v(0.0, 3.0));
        let pts = comb.clone();
        let tris = triangulate(&[comb]);
        let expected = {
            let idx: Vec<usize> = (0..pts.len()).collect();
            signed_area(&pts, &idx).abs()
        };
        assert!((area(&pts, &tris) - expected).abs() < 1e-9);
        let line = vec![v(0., 0.), v(1., 0.), v(2., 0.), v(3., 0.)];
        assert!(triangulate(&[line]).is_empty());
        assert!(triangulate(&[vec![v(f64::NAN, 0.), v(1., 0.), v(0., 1.)]]).is_empty());
    }

    proptest::proptest! {
        #[test]
        fn star_polygons_with_a_hole_keep_their_area(
            radii in proptest::collection::vec(0.5f64..3.0, 3..40),
            hole_fraction in 0.0f64..0.9,
            hole_sides in 3usize..9,
        ) {
            // Star-shaped about the origin (angles increase), so the polygon is simple. Every
            // edge spans an angle of 2π/n between vertices at radius ≥ min(radii), so it stays
            // at least min(radii)·cos(π/n) from the origin: a hole inside that radius lies
            // inside the polygon (a radius-0.5 triangle's inscribed circle is only 0.25).
            let n = radii.len();
            let inradius = radii.iter().copied().fold(f64::INFINITY, f64::min)
                * (std::f64::consts::PI / n as f64).cos();
            let hole = hole_fraction * inradius;
            let outer: Vec<DVec2> = radii
                .iter()
                .enumerate()
                .map(|(i, r)| DVec2::from_angle(i as f64 / n as f64 * std::f64::consts::TAU) * *r)
                .collect();
            let mut loops = vec![outer];
            if hole_fraction > 0.05 {
                loops.push(
                    (0..hole_sides)
                        .map(|i| DVec2::from_angle(i as f64 / hole_sides as f64 * std::f64::consts::TAU) * hole)
                        .collect(),
                );
            }
            let pts: Vec<DVec2> = loops.iter().flatten().copied().collect();
            let shoelace = |l: &[DVec2]| {
                let idx: Vec<usize> = (0..l.len()).collect();
                signed_area(l, &idx).abs()
            };
            let expected = shoelace(&loops[0]) - loops.get(1).map_or(0.0, |h| shoelace(h));
            let tris = triangulate(&loops);
            let got = area(&pts, &tris);
            proptest::prop_assert!((got - expected).abs() < 1e-9 * expected.max(1.0), "{got} vs {expected}");
            // Every triangle is positively oriented and none overlaps a hole vertex's interior.
            proptest::prop_assert!(tris.iter().all(|t| cross(pts[t[0]], pts[t[1]], pts[t[2]]) > 0.0));
        }
    }
}
