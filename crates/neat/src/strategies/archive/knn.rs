//! Nearest neighbours in a behaviour space: a k-d tree over a fixed set of points.
//!
//! Novelty search needs, every generation, the k nearest neighbours of each
//! of P genomes among the A archived behaviours and the P current ones.
//! Brute force costs P·(A+P) distances per generation and grows without
//! bound with the archive; rebuilding a balanced k-d tree over the A+P
//! points costs O((A+P)·log(A+P)) and each query about O(log(A+P) + k) in
//! the low dimensions behaviours have (end positions, a few trajectory
//! samples), so a generation's cost grows only logarithmically with the
//! archive. MAP-Elites' CVT archive uses the same tree to find the nearest
//! centroid.
//!
//! Results do not depend on the tree's shape: the k smallest distances are a
//! multiset fixed by the points, and they are summed in ascending order, so
//! the tree and [`brute_force_sparseness`] give the same bits (a property
//! test checks both against sorting every distance).

use serde::{Deserialize, Serialize};

/// Points of a common dimension, indexed by a balanced k-d tree. It
/// serialises as its dimension and points, and is rebuilt when read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawTree", into = "RawTree")]
pub struct KdTree {
    dims: usize,
    points: Vec<f64>,
    /// A permutation of the point indices laid out as an implicit tree: the
    /// node of `order[lo..hi]` is `order[(lo + hi) / 2]`, split on `depth % dims`.
    order: Vec<usize>,
}

/// A tree as stored: its points, not their order.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTree {
    dims: usize,
    points: Vec<f64>,
}

impl From<KdTree> for RawTree {
    fn from(tree: KdTree) -> RawTree {
        RawTree {
            dims: tree.dims,
            points: tree.points,
        }
    }
}

impl TryFrom<RawTree> for KdTree {
    type Error = String;

    fn try_from(raw: RawTree) -> Result<KdTree, String> {
        if raw.dims == 0 || !raw.points.len().is_multiple_of(raw.dims) {
            return Err(format!(
                "{} coordinates are not points of {}",
                raw.points.len(),
                raw.dims
            ));
        }
        if raw.points.iter().any(|x| !x.is_finite()) {
            return Err("a point has a non-finite coordinate".into());
        }
        Ok(KdTree::new(raw.dims, raw.points))
    }
}

/// Subtrees this small are scanned rather than descended.
const LEAF: usize = 8;

impl KdTree {
    /// A tree over `points`, `dims` coordinates each, laid end to end
    /// (`points.len()` must be a multiple of `dims`; `dims` ≥ 1).
    pub fn new(dims: usize, points: Vec<f64>) -> KdTree {
        assert!(
            dims > 0 && points.len().is_multiple_of(dims),
            "points of {dims} coordinates"
        );
        let mut tree = KdTree {
            dims,
            order: (0..points.len() / dims).collect(),
            points,
        };
        tree.rebuild();
        tree
    }

    /// Replaces the points (same dimension) and rebuilds, reusing the buffers.
    pub fn reset(&mut self, points: impl IntoIterator<Item = f64>) {
        self.points.clear();
        self.points.extend(points);
        assert!(
            self.points.len().is_multiple_of(self.dims),
            "points of {} coordinates",
            self.dims
        );
        self.order.clear();
        self.order.extend(0..self.points.len() / self.dims);
        self.rebuild();
    }

    fn rebuild(&mut self) {
        let mut stack = vec![(0, self.order.len(), 0)];
        while let Some((lo, hi, depth)) = stack.pop() {
            if hi - lo <= LEAF {
                continue;
            }
            let (d, dims, points) = (depth % self.dims, self.dims, &self.points);
            let mid = (lo + hi) / 2;
            self.order[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
                points[a * dims + d]
                    .total_cmp(&points[b * dims + d])
                    .then(a.cmp(&b))
            });
            stack.push((lo, mid, depth + 1));
            stack.push((mid + 1, hi, depth + 1));
        }
    }

    /// Coordinates per point.
    pub fn dims(&self) -> usize {
        self.dims
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// Coordinates of point `i`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dims..(i + 1) * self.dims]
    }

    /// Squared Euclidean distance from `q` to point `i`.
    fn distance2(&self, q: &[f64], i: usize) -> f64 {
        squared_distance(q, self.point(i))
    }

    /// Fills `best` with the squared distances from `q` to its `best.k`
    /// nearest points other than point `exclude` (if given), ascending.
    pub fn nearest_k(&self, q: &[f64], exclude: Option<usize>, best: &mut Nearest) {
        best.clear();
        best.off.clear();
        best.off.resize(self.dims, 0.0);
        if best.k > 0 {
            self.search_k(q, exclude, 0, self.order.len(), 0, best);
        }
    }

    /// Offers point `i` unless a partial sum already shows it refused.
    fn offer_point(&self, q: &[f64], i: usize, best: &mut Nearest) {
        // The terms are squares summed in the order of `squared_distance`,
        // and rounding is monotone, so a partial sum never exceeds the full
        // one: a point given up early would have been refused anyway.
        let worst = best.worst();
        let mut d2 = 0.0;
        for (x, y) in q.iter().zip(self.point(i)) {
            d2 += (x - y) * (x - y);
            if d2 > worst {
                return;
            }
        }
        best.offer(d2);
    }

    fn search_k(
        &self,
        q: &[f64],
        exclude: Option<usize>,
        lo: usize,
        hi: usize,
        depth: usize,
        best: &mut Nearest,
    ) {
        if hi - lo <= LEAF {
            for &i in &self.order[lo..hi] {
                if Some(i) != exclude {
                    self.offer_point(q, i, best);
                }
            }
            return;
        }
        let Split {
            node,
            axis: d,
            diff,
            near,
            far,
        } = self.split(q, lo, hi, depth);
        if Some(node) != exclude {
            self.offer_point(q, node, best);
        }
        self.search_k(q, exclude, near.0, near.1, depth + 1, best);
        // Every point beyond the split is at least |diff| away on axis d, and
        // at least `off` away on the others (its cell's earlier splits), so
        // the sum of the offsets' squares, in `squared_distance`'s order,
        // bounds its rounded distance from below (rounding is monotone): a
        // strictly farther bound never hides one of the k.
        // The split's distance alone is the cheap test, and it is part of the bound.
        if diff * diff > best.worst() {
            return;
        }
        let saved = best.off[d];
        best.off[d] = saved.max(diff.abs());
        let bound: f64 = best.off.iter().map(|o| o * o).sum();
        if bound <= best.worst() {
            self.search_k(q, exclude, far.0, far.1, depth + 1, best);
        }
        best.off[d] = saved;
    }

    /// How the subtree `order[lo..hi]` at `depth` splits, seen from `q`.
    fn split(&self, q: &[f64], lo: usize, hi: usize, depth: usize) -> Split {
        let mid = (lo + hi) / 2;
        let node = self.order[mid];
        let axis = depth % self.dims;
        let diff = q[axis] - self.points[node * self.dims + axis];
        let (near, far) = if diff < 0.0 {
            ((lo, mid), (mid + 1, hi))
        } else {
            ((mid + 1, hi), (lo, mid))
        };
        Split {
            node,
            axis,
            diff,
            near,
            far,
        }
    }

    /// The point nearest to `q`, the lowest index among equally near ones.
    pub fn nearest(&self, q: &[f64]) -> Option<usize> {
        let mut best = None;
        self.search_1(q, 0, self.order.len(), 0, &mut best);
        best.map(|(_, i)| i)
    }

    fn search_1(
        &self,
        q: &[f64],
        lo: usize,
        hi: usize,
        depth: usize,
        best: &mut Option<(f64, usize)>,
    ) {
        let mut offer = |d2: f64, i: usize| {
            if best.is_none_or(|(b, j)| d2 < b || (d2 == b && i < j)) {
                *best = Some((d2, i));
            }
        };
        if hi - lo <= LEAF {
            for &i in &self.order[lo..hi] {
                offer(self.distance2(q, i), i);
            }
            return;
        }
        let Split {
            node,
            diff,
            near,
            far,
            ..
        } = self.split(q, lo, hi, depth);
        offer(self.distance2(q, node), node);
        self.search_1(q, near.0, near.1, depth + 1, best);
        if best.is_none_or(|(b, _)| diff * diff <= b) {
            self.search_1(q, far.0, far.1, depth + 1, best);
        }
    }
}

/// A subtree's split: the point at its middle, the axis it splits on,
/// the query's offset from that point on the axis, and the `(lo, hi)` ranges
/// of the half on the query's side and of the other half.
struct Split {
    node: usize,
    axis: usize,
    diff: f64,
    near: (usize, usize),
    far: (usize, usize),
}

/// Squared Euclidean distance between two points of the same dimension.
pub fn squared_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// The k smallest squared distances offered so far, ascending (a reusable buffer).
#[derive(Debug, Clone)]
pub struct Nearest {
    k: usize,
    d2: Vec<f64>,
    /// Scratch of a tree search: the current cell's distance from the query on each axis.
    off: Vec<f64>,
}

impl PartialEq for Nearest {
    fn eq(&self, other: &Nearest) -> bool {
        self.k == other.k && self.d2 == other.d2
    }
}

impl Nearest {
    /// An empty collector of the `k` smallest distances.
    pub fn new(k: usize) -> Nearest {
        Nearest {
            k,
            // Grows as needed beyond this: a huge k allocates only what is found.
            d2: Vec::with_capacity(k.min(1024)),
            off: Vec::new(),
        }
    }

    fn clear(&mut self) {
        self.d2.clear();
    }

    /// The bound beyond which an offer is refused.
    fn worst(&self) -> f64 {
        if self.d2.len() < self.k {
            f64::INFINITY
        } else {
            self.d2[self.k - 1]
        }
    }

    fn offer(&mut self, d2: f64) {
        if self.d2.len() == self.k {
            if d2 >= self.d2[self.k - 1] {
                return;
            }
            self.d2.pop();
        }
        let at = self.d2.partition_point(|&x| x <= d2);
        self.d2.insert(at, d2);
    }

    /// The squared distances found, ascending.
    pub fn squared(&self) -> &[f64] {
        &self.d2
    }

    /// Mean Euclidean distance of the neighbours found (0 if none), summed
    /// in ascending order so that equal neighbour sets give equal bits.
    pub fn mean_distance(&self) -> f64 {
        if self.d2.is_empty() {
            return 0.0;
        }
        self.d2.iter().map(|d| d.sqrt()).sum::<f64>() / self.d2.len() as f64
    }
}

/// Sparseness of point `i` of `points` (mean distance to its `k` nearest
/// others) by brute force, every point visited: what the tree saves.
pub fn brute_force_sparseness(dims: usize, points: &[f64], i: usize, k: usize) -> f64 {
    let q = &points[i * dims..(i + 1) * dims];
    let mut best = Nearest::new(k);
    for (j, p) in points.chunks_exact(dims).enumerate() {
        if j != i {
            best.offer(squared_distance(q, p));
        }
    }
    best.mean_distance()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Sparseness by sorting every distance: the plainest reference.
    fn sorted_sparseness(dims: usize, points: &[f64], i: usize, k: usize) -> f64 {
        let q = &points[i * dims..(i + 1) * dims];
        let mut d2: Vec<f64> = (0..points.len() / dims)
            .filter(|&j| j != i)
            .map(|j| squared_distance(q, &points[j * dims..(j + 1) * dims]))
            .collect();
        d2.sort_by(f64::total_cmp);
        d2.truncate(k);
        if d2.is_empty() {
            return 0.0;
        }
        d2.iter().map(|d| d.sqrt()).sum::<f64>() / d2.len() as f64
    }

    #[test]
    fn sparseness_of_a_hand_computed_line() {
        // Points 0, 1, 3, 7 on a line: point 1's two nearest are 0 (1 away) and 3 (2 away).
        let tree = KdTree::new(1, vec![0.0, 1.0, 3.0, 7.0]);
        let mut best = Nearest::new(2);
        tree.nearest_k(&[1.0], Some(1), &mut best);
        assert_eq!(best.squared(), [1.0, 4.0]);
        assert_eq!(best.mean_distance(), 1.5);
        // Fewer points than k: the mean of those there are.
        let mut best = Nearest::new(10);
        tree.nearest_k(&[7.0], Some(3), &mut best);
        assert_eq!(best.mean_distance(), (7.0 + 6.0 + 4.0) / 3.0);
        assert_eq!(tree.nearest(&[2.1]), Some(2));
        assert_eq!(
            tree.nearest(&[2.0]),
            Some(1),
            "a tie goes to the lower index"
        );
    }

    fn points(dims: usize) -> impl Strategy<Value = Vec<f64>> {
        // Coarse values make ties and duplicates common.
        prop::collection::vec(
            (-20i32..20).prop_map(|v| f64::from(v) * 0.25),
            dims..dims * 300,
        )
        .prop_map(move |mut v| {
            v.truncate(v.len() / dims * dims);
            v
        })
    }

    proptest! {
        #[test]
        fn tree_and_brute_force_sparseness_equal_the_sorted_reference_bit_for_bit(
            k in 1usize..20, seed in any::<u64>(),
            // Up to 9 dimensions: there the cell bound prunes on every axis.
            (dims, pts) in (1usize..10).prop_flat_map(|d| (Just(d), points(d))),
        ) {
            prop_assume!(!pts.is_empty());
            let tree = KdTree::new(dims, pts.clone());
            let mut best = Nearest::new(k);
            let n = pts.len() / dims;
            for i in (0..n).filter(|i| (*i as u64 ^ seed).is_multiple_of(3) || n < 30) {
                tree.nearest_k(&pts[i * dims..(i + 1) * dims], Some(i), &mut best);
                let expect = sorted_sparseness(dims, &pts, i, k);
                prop_assert_eq!(best.mean_distance().to_bits(), expect.to_bits());
                prop_assert_eq!(brute_force_sparseness(dims, &pts, i, k).to_bits(), expect.to_bits());
            }
        }

        #[test]
        fn nearest_is_the_lowest_index_at_the_least_distance(
            pts in points(2), q in (-6.0f64..6.0, -6.0f64..6.0),
        ) {
            prop_assume!(!pts.is_empty());
            let tree = KdTree::new(2, pts.clone());
            let q = [q.0, q.1];
            let expect = (0..pts.len() / 2)
                .min_by(|&a, &b| {
                    squared_distance(&q, &pts[a * 2..a * 2 + 2])
                        .total_cmp(&squared_distance(&q, &pts[b * 2..b * 2 + 2]))
                        .then(a.cmp(&b))
                });
            prop_assert_eq!(tree.nearest(&q), expect);
        }
    }
}
