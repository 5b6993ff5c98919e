//! Centroidal Voronoi tessellation (CVT, Vassiliades et al. 2018) of a box
//! of the behaviour space: the cells of a [`Cells::Cvt`] archive.

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

use super::grid::{Cells, MAX_CELLS, check_bounds};
use super::knn::KdTree;
use crate::error::NeatError;
use crate::strategies::invalid;

/// Most samples a CVT may be built from.
pub const MAX_SAMPLES: usize = 10_000_000;

impl Cells {
    /// A CVT of `cells` centroids in the box `lower`..`upper`: `samples`
    /// points drawn uniformly from a `Pcg64` seeded with `seed`, the first
    /// `cells` of them as initial centroids, then `iterations` of Lloyd's
    /// algorithm (each centroid moves to the mean of the samples nearest to
    /// it; one with none stays). The same arguments give the same bits.
    pub fn cvt(
        lower: &[f64],
        upper: &[f64],
        cells: usize,
        samples: usize,
        iterations: usize,
        seed: u64,
    ) -> Result<Cells, NeatError> {
        check_bounds(lower, upper)?;
        if cells == 0 || samples < cells || cells > MAX_CELLS || samples > MAX_SAMPLES {
            let value = format!("{cells} cells from {samples} samples");
            let reason = "need 1 ≤ cells ≤ samples, at most 1,000,000 cells and 10,000,000 samples";
            return Err(invalid("cells", value, reason));
        }
        let dims = lower.len();
        let mut rng = Pcg64::seed_from_u64(seed);
        let points: Vec<f64> = (0..samples * dims)
            .map(|i| {
                let d = i % dims;
                lower[d] + (upper[d] - lower[d]) * rng.random::<f64>()
            })
            .collect();
        let mut tree = KdTree::new(dims, points[..cells * dims].to_vec());
        let (mut sums, mut counts) = (vec![0.0; cells * dims], vec![0usize; cells]);
        for _ in 0..iterations {
            sums.fill(0.0);
            counts.fill(0);
            for p in points.chunks_exact(dims) {
                let c = tree.nearest(p).unwrap_or(0);
                counts[c] += 1;
                for (s, x) in sums[c * dims..(c + 1) * dims].iter_mut().zip(p) {
                    *s += x;
                }
            }
            let centroids = (0..cells * dims).map(|i| match counts[i / dims] {
                0 => tree.point(i / dims)[i % dims],
                n => sums[i] / n as f64,
            });
            let centroids: Vec<f64> = centroids.collect();
            tree.reset(centroids);
        }
        Ok(Cells::Cvt(tree))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cvt_is_deterministic_and_its_centroids_spread_over_the_box() {
        let make = || Cells::cvt(&[0.0, 0.0], &[1.0, 2.0], 16, 2000, 10, 5).unwrap();
        let (a, b) = (make(), make());
        assert_eq!(a, b);
        let Cells::Cvt(tree) = &a else { unreachable!() };
        assert_eq!(tree.len(), 16);
        // Lloyd's centroids are means of samples in the box; with 16 cells
        // over 2000 samples each one's region holds some of them.
        for i in 0..16 {
            let c = tree.point(i);
            assert!(
                (0.0..=1.0).contains(&c[0]) && (0.0..=2.0).contains(&c[1]),
                "{c:?}"
            );
            assert_eq!(a.cell_of(c), i, "a centroid is in its own cell");
        }
        let other = Cells::cvt(&[0.0, 0.0], &[1.0, 2.0], 16, 2000, 10, 6).unwrap();
        assert_ne!(a, other, "the seed matters");
    }
}
