//! Summary statistics of samples (fitness values, evaluation counts).
//!
//! The one copy used by the library, the program's generation records and
//! figures, and the benchmark examples, so that the same samples give the
//! same bits wherever they are summarised.

/// Index of the first maximum; `None` for no values (a NaN is never a
/// maximum after the first value).
pub fn argmax(xs: &[f64]) -> Option<usize> {
    (0..xs.len()).reduce(|a, b| if xs[b] > xs[a] { b } else { a })
}

/// Arithmetic mean (left-to-right sum over the length); `None` for no values.
pub fn mean(xs: &[f64]) -> Option<f64> {
    (!xs.is_empty()).then(|| xs.iter().sum::<f64>() / xs.len() as f64)
}

/// Median of values already sorted (ascending or descending): the middle
/// value, or the mean of the two middle ones; `None` for no values.
pub fn median_of_sorted(sorted: &[f64]) -> Option<f64> {
    let n = sorted.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(sorted[n / 2]),
        _ => Some((sorted[n / 2 - 1] + sorted[n / 2]) / 2.0),
    }
}

/// Median of values in any order (sorted by `f64::total_cmp` in a copy); `None` for no values.
pub fn median(xs: &[f64]) -> Option<f64> {
    median_of_sorted(&sorted_descending(xs))
}

/// A copy sorted best-first (descending by `f64::total_cmp`).
pub fn sorted_descending(xs: &[f64]) -> Vec<f64> {
    let mut v = xs.to_vec();
    v.sort_by(|a, b| b.total_cmp(a));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn argmax_first_of_ties() {
        assert_eq!(argmax(&[1.0, 3.0, 3.0]), Some(1));
        assert_eq!(argmax(&[]), None);
    }
    use proptest::prelude::*;

    #[test]
    fn small_cases() {
        assert_eq!(mean(&[]), None);
        assert_eq!(median(&[]), None);
        assert_eq!(mean(&[1.0, 2.0, 6.0]), Some(3.0));
        assert_eq!(median(&[6.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 2.0, 6.0]), Some(3.0));
        assert_eq!(sorted_descending(&[1.0, 3.0, 2.0]), vec![3.0, 2.0, 1.0]);
    }

    proptest! {
        /// Both sort orders give the same bits, and the median lies within the sample.
        #[test]
        fn median_is_order_independent(xs in prop::collection::vec(-1e6f64..1e6, 1..40)) {
            let down = sorted_descending(&xs);
            let mut up = xs.clone();
            up.sort_by(f64::total_cmp);
            let m = median_of_sorted(&down).unwrap();
            prop_assert_eq!(m.to_bits(), median_of_sorted(&up).unwrap().to_bits());
            prop_assert_eq!(m.to_bits(), median(&xs).unwrap().to_bits());
            prop_assert!(up[0] <= m && m <= up[up.len() - 1]);
            let mu = mean(&xs).unwrap();
            prop_assert!(up[0] - 1e-6 <= mu && mu <= up[up.len() - 1] + 1e-6);
        }
    }
}
