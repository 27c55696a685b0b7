//! The Pareto front of (time, error) points: the settings no other setting beats on both.

/// Indices of the points on the lower-left Pareto front, in increasing time. A point is on
/// the front when no other point is at most as slow and at most as wrong while strictly better
/// in one of the two. Points with a non-finite coordinate are never on it (a failed render).
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    // Ties in time: the smaller error first, so the sweep below keeps only it.
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in order {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force definition, to check the sweep against.
    fn dominated(points: &[(f64, f64)], i: usize) -> bool {
        let (t, e) = points[i];
        points
            .iter()
            .enumerate()
            .any(|(j, &(tj, ej))| j != i && tj <= t && ej <= e && (tj < t || ej < e))
    }

    #[test]
    fn front_of_a_known_set() {
        let p = [
            (1.0, 10.0), // front
            (2.0, 5.0),  // front
            (2.5, 6.0),  // dominated by (2, 5)
            (3.0, 1.0),  // front
            (4.0, 1.0),  // dominated by (3, 1): as wrong, slower
            (0.5, 20.0), // front
            (5.0, f64::NAN),
        ];
        assert_eq!(pareto_front(&p), vec![5, 0, 1, 3]);
    }

    #[test]
    fn front_matches_the_brute_force_definition() {
        // A deterministic scatter with many ties and dominated points.
        let p: Vec<(f64, f64)> = (0..200u32)
            .map(|i| {
                let a = f64::from((i * 7919) % 97) / 10.0;
                let b = f64::from((i * 104_729) % 89) / 10.0;
                (a, b)
            })
            .collect();
        let front = pareto_front(&p);
        for i in 0..p.len() {
            let on = front.contains(&i);
            // Duplicated points: only one copy is kept, and it is not dominated.
            let duplicate_kept = p
                .iter()
                .enumerate()
                .any(|(j, q)| j != i && *q == p[i] && front.contains(&j));
            if on {
                assert!(
                    !dominated(&p, i),
                    "{i} {:?} on the front but dominated",
                    p[i]
                );
            } else if !duplicate_kept {
                assert!(
                    dominated(&p, i),
                    "{i} {:?} off the front but not dominated",
                    p[i]
                );
            }
        }
        assert!(front
            .windows(2)
            .all(|w| p[w[0]].0 < p[w[1]].0 && p[w[0]].1 > p[w[1]].1));
    }
}
