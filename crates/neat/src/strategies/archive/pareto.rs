//! The Pareto front and the ranking NSGA-II selects by: non-dominated
//! sorting into fronts and Deb's crowding distance (every objective maximised).

/// Whether `a` dominates `b` (all objectives maximised): no worse in any, better in one.
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (x, y) in a.iter().zip(b) {
        if x < y {
            return false;
        }
        better |= x > y;
    }
    better
}

/// The non-dominated fronts, best first, each in index order: front 0 is
/// dominated by none, front k + 1 only by members of fronts ≤ k.
///
/// The same fronts as Deb's fast non-dominated sort
/// ([`fast_non_dominated_sort`]), found without comparing every pair: the
/// efficient non-dominated sort with binary search (ENS-BS, Zhang et al.
/// 2015). Sorted lexicographically best first, a member can only be
/// dominated by members before it; each joins the first front none of whose
/// members dominates it, and since being dominated by some member of front k
/// holds for every k below a member's front and none from it on, that front
/// is found by bisection.
pub fn non_dominated_fronts(objectives: &[&[f64]]) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..objectives.len()).collect();
    order.sort_by(|&a, &b| {
        let lexicographic = objectives[b].iter().zip(objectives[a]);
        // partial_cmp, so that −0 and 0 tie as they do for dominance.
        let by_value = lexicographic.fold(std::cmp::Ordering::Equal, |o, (x, y)| {
            o.then(x.partial_cmp(y).unwrap_or_else(|| x.total_cmp(y)))
        });
        by_value.then(a.cmp(&b))
    });
    let mut fronts: Vec<Vec<usize>> = Vec::new();
    for p in order {
        // Later members are likelier dominators: check a front from its end.
        let dominated_in = |f: &Vec<usize>| {
            f.iter()
                .rev()
                .any(|&q| dominates(objectives[q], objectives[p]))
        };
        let k = fronts.partition_point(dominated_in);
        match fronts.get_mut(k) {
            Some(front) => front.push(p),
            None => fronts.push(vec![p]),
        }
    }
    for front in &mut fronts {
        front.sort_unstable();
    }
    fronts
}

/// Deb's fast non-dominated sort (O(M·N²), every pair compared): the
/// reference [`non_dominated_fronts`] is checked against.
pub fn fast_non_dominated_sort(objectives: &[&[f64]]) -> Vec<Vec<usize>> {
    let n = objectives.len();
    let mut dominated: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut count = vec![0usize; n];
    for p in 0..n {
        for q in p + 1..n {
            if dominates(objectives[p], objectives[q]) {
                dominated[p].push(q);
                count[q] += 1;
            } else if dominates(objectives[q], objectives[p]) {
                dominated[q].push(p);
                count[p] += 1;
            }
        }
    }
    let mut fronts = Vec::new();
    let mut front: Vec<usize> = (0..n).filter(|&p| count[p] == 0).collect();
    while !front.is_empty() {
        let mut next = Vec::new();
        for &p in &front {
            for &q in &dominated[p] {
                count[q] -= 1;
                if count[q] == 0 {
                    next.push(q);
                }
            }
        }
        next.sort_unstable();
        fronts.push(std::mem::replace(&mut front, next));
    }
    fronts
}

/// Deb's crowding distance of each member of `front`, written to
/// `out[i]`: per objective, the extremes get ∞ and the others the gap
/// between their neighbours over the front's range, summed.
pub fn crowding_distances(front: &[usize], objectives: &[&[f64]], out: &mut [f64]) {
    for &i in front {
        out[i] = 0.0;
    }
    let Some(&first) = front.first() else {
        return;
    };
    let mut sorted = front.to_vec();
    // `m` picks an objective within each member's row; clippy reads it as a row index.
    #[allow(clippy::needless_range_loop)]
    for m in 0..objectives[first].len() {
        let v = |i: usize| objectives[i][m];
        sorted.sort_by(|&a, &b| v(a).total_cmp(&v(b)).then(a.cmp(&b)));
        let (lo, hi) = (sorted[0], sorted[sorted.len() - 1]);
        out[lo] = f64::INFINITY;
        out[hi] = f64::INFINITY;
        let range = v(hi) - v(lo);
        if range > 0.0 {
            for k in 1..sorted.len().saturating_sub(1) {
                out[sorted[k]] += (v(sorted[k + 1]) - v(sorted[k - 1])) / range;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::{prop, prop_assert, prop_assert_eq, proptest};
    use proptest::strategy::Strategy as _;

    #[test]
    fn hand_computed_fronts_and_crowding() {
        // Maximising both: A, B, C trade off; C and B dominate D; D dominates E.
        let pts: [&[f64]; 5] = [
            &[1.0, 5.0],
            &[2.0, 4.0],
            &[3.0, 3.0],
            &[2.0, 2.0],
            &[1.0, 1.0],
        ];
        let fronts = non_dominated_fronts(&pts);
        assert_eq!(fronts, [vec![0, 1, 2], vec![3], vec![4]]);
        let mut crowd = [0.0; 5];
        crowding_distances(&fronts[0], &pts, &mut crowd);
        // B: (3 − 1)/2 on the first objective + (5 − 3)/2 on the second.
        assert_eq!(crowd[..3], [f64::INFINITY, 2.0, f64::INFINITY]);
        let dup: [&[f64]; 2] = [&[1.0, 1.0], &[1.0, 1.0]];
        assert_eq!(
            non_dominated_fronts(&dup),
            [vec![0, 1]],
            "equals do not dominate"
        );
    }

    fn points() -> impl proptest::strategy::Strategy<Value = Vec<Vec<f64>>> {
        // Few distinct values (−0 among them) make ties and duplicates common.
        let value = (0i32..6).prop_map(|v| if v == 5 { -0.0 } else { f64::from(v) });
        let point = prop::collection::vec(value, 3);
        prop::collection::vec(point, 0..40)
    }

    proptest! {
        #[test]
        fn fronts_partition_and_each_is_dominated_only_by_earlier_ones(pts in points()) {
            let objectives: Vec<&[f64]> = pts.iter().map(|p| &p[..]).collect();
            let fronts = non_dominated_fronts(&objectives);
            let mut rank = vec![usize::MAX; pts.len()];
            for (r, front) in fronts.iter().enumerate() {
                for &i in front {
                    prop_assert_eq!(rank[i], usize::MAX, "in two fronts");
                    rank[i] = r;
                }
            }
            prop_assert!(rank.iter().all(|&r| r != usize::MAX), "not in any front");
            for i in 0..pts.len() {
                for j in 0..pts.len() {
                    if dominates(objectives[i], objectives[j]) {
                        prop_assert!(rank[i] < rank[j]);
                    }
                }
                if rank[i] > 0 {
                    let by_previous = fronts[rank[i] - 1]
                        .iter()
                        .any(|&j| dominates(objectives[j], objectives[i]));
                    prop_assert!(by_previous, "front {} member not dominated by front {}", rank[i], rank[i] - 1);
                }
            }
        }

        #[test]
        fn bisected_fronts_equal_debs_fast_non_dominated_sort(pts in points()) {
            let objectives: Vec<&[f64]> = pts.iter().map(|p| &p[..]).collect();
            prop_assert_eq!(non_dominated_fronts(&objectives), fast_non_dominated_sort(&objectives));
        }

        #[test]
        fn crowding_gives_extremes_infinity_and_others_at_most_one_per_objective(pts in points()) {
            let objectives: Vec<&[f64]> = pts.iter().map(|p| &p[..]).collect();
            let mut out = vec![-1.0; pts.len()];
            for front in non_dominated_fronts(&objectives) {
                crowding_distances(&front, &objectives, &mut out);
                for m in [0, 1, 2] {
                    let value = |i: usize| pts[i][m];
                    let max = front.iter().map(|&i| value(i)).fold(f64::MIN, f64::max);
                    let min = front.iter().map(|&i| value(i)).fold(f64::MAX, f64::min);
                    for extreme in [min, max] {
                        let at = front.iter().filter(|&&i| value(i) == extreme);
                        prop_assert!(at.clone().any(|&i| out[i].is_infinite()));
                    }
                }
                for &i in &front {
                    prop_assert!(out[i].is_infinite() || (0.0..=3.0).contains(&out[i]));
                }
            }
        }
    }
}
