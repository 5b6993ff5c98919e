//! The cells of MAP-Elites' archive: a regular grid over a box of the
//! behaviour space, or a centroidal Voronoi tessellation ([`Cells::cvt`]).

use serde::{Deserialize, Serialize};

use super::knn::KdTree;
use crate::error::NeatError;
use crate::strategies::invalid;

/// Most cells an archive may have (each holds an optional genome).
pub const MAX_CELLS: usize = 1_000_000;

/// How the behaviour space is cut into cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Cells {
    /// `bins[d]` equal cells from `lower[d]` to `upper[d]` along each
    /// dimension d (the first most significant in the cell index); a
    /// behaviour outside the bounds falls in the nearest edge cell.
    Grid {
        /// Lower bound per dimension.
        lower: Vec<f64>,
        /// Upper bound per dimension.
        upper: Vec<f64>,
        /// Cells per dimension.
        bins: Vec<usize>,
    },
    /// A behaviour's cell is its nearest centroid (the lowest index on a tie).
    Cvt(KdTree),
}

impl Cells {
    /// A regular grid (see [`Cells::Grid`]); bounds finite with `lower < upper`.
    pub fn grid(lower: Vec<f64>, upper: Vec<f64>, bins: Vec<usize>) -> Result<Cells, NeatError> {
        check_bounds(&lower, &upper)?;
        if bins.len() != lower.len() || bins.contains(&0) {
            return Err(invalid(
                "bins",
                format!("{bins:?}"),
                "one count ≥ 1 per dimension",
            ));
        }
        let cells = bins.iter().try_fold(1usize, |n, &b| n.checked_mul(b));
        if cells.is_none_or(|n| n > MAX_CELLS) {
            return Err(invalid(
                "bins",
                format!("{bins:?}"),
                "more than 1,000,000 cells",
            ));
        }
        Ok(Cells::Grid { lower, upper, bins })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        match self {
            Cells::Grid { bins, .. } => bins.iter().product(),
            Cells::Cvt(tree) => tree.len(),
        }
    }

    /// Whether there are no cells (never, once built).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Coordinates of a behaviour.
    pub fn dims(&self) -> usize {
        match self {
            Cells::Grid { bins, .. } => bins.len(),
            Cells::Cvt(tree) => tree.dims(),
        }
    }

    /// The cell of `behaviour` (of [`Cells::dims`] coordinates).
    pub fn cell_of(&self, behaviour: &[f64]) -> usize {
        match self {
            Cells::Grid { lower, upper, bins } => {
                let mut cell = 0;
                for (d, &x) in behaviour.iter().enumerate() {
                    let t = (x - lower[d]) / (upper[d] - lower[d]) * bins[d] as f64;
                    // NaN goes to 0 with the cast; ±∞ to the edge cells.
                    let i = (t.max(0.0) as usize).min(bins[d] - 1);
                    cell = cell * bins[d] + i;
                }
                cell
            }
            Cells::Cvt(tree) => tree.nearest(behaviour).unwrap_or(0),
        }
    }

    /// Checks restored cells as their constructors check new ones.
    pub(crate) fn check(&self) -> Result<(), NeatError> {
        match self {
            Cells::Grid { lower, upper, bins } => {
                Cells::grid(lower.clone(), upper.clone(), bins.clone()).map(|_| ())
            }
            Cells::Cvt(tree) if tree.is_empty() => Err(invalid("cells", 0, "no centroids")),
            Cells::Cvt(_) => Ok(()),
        }
    }
}

/// Bounds of a behaviour box: as many lower as upper, finite, `lower < upper`.
pub(super) fn check_bounds(lower: &[f64], upper: &[f64]) -> Result<(), NeatError> {
    let ok = !lower.is_empty()
        && lower.len() == upper.len()
        && lower
            .iter()
            .zip(upper)
            .all(|(l, u)| l.is_finite() && u.is_finite() && l < u);
    if ok {
        Ok(())
    } else {
        let value = format!("{lower:?}..{upper:?}");
        Err(invalid(
            "bounds",
            value,
            "finite, lower < upper, ≥ 1 dimension",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_cells_are_row_major_and_clamped() {
        let cells = Cells::grid(vec![0.0, -1.0], vec![10.0, 1.0], vec![5, 2]).unwrap();
        assert_eq!(cells.len(), 10);
        assert_eq!(cells.cell_of(&[0.0, -1.0]), 0);
        assert_eq!(
            cells.cell_of(&[3.9, 0.5]),
            2 + 1,
            "row 1 of 2 cells, column 1"
        );
        assert_eq!(
            cells.cell_of(&[10.0, 1.0]),
            9,
            "the upper bound is in the last cell"
        );
        assert_eq!(
            cells.cell_of(&[-5.0, 7.0]),
            1,
            "outside: the nearest edge cell"
        );
        assert_eq!(cells.cell_of(&[f64::NAN, f64::INFINITY]), 1);
        assert!(Cells::grid(vec![0.0], vec![0.0], vec![3]).is_err());
        assert!(Cells::grid(vec![0.0], vec![1.0], vec![0]).is_err());
        let huge = Cells::grid(vec![0.0; 2], vec![1.0; 2], vec![1_000_000, 1_000_000]);
        assert!(huge.is_err(), "refused, not allocated");
        assert!(Cells::cvt(&[0.0], &[1.0], 10, usize::MAX, 1, 0).is_err());
    }
}
