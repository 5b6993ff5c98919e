//! The `VIVAE_SIMD` environment variable: which vector instructions the hot loops use.
//!
//! Every level gives the same bits (see `vivae_neat::simd` and
//! `vivae_sim::simd`, which it sets both); forcing a lower
//! one is for checking exactly that, and for timing the levels against each
//! other.

/// The environment variable that forces a level.
pub const VAR: &str = "VIVAE_SIMD";

/// Why `VIVAE_SIMD` cannot be applied.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SimdError {
    /// The variable holds no known level.
    #[error("environment variable {VAR}={0:?}: expected scalar, avx2 or avx512")]
    Unknown(String),
}

/// The level named `name` (`scalar`, `avx2` or `avx512`).
pub fn parse(name: &str) -> Result<vivae_neat::simd::SimdLevel, SimdError> {
    vivae_neat::simd::SimdLevel::from_name(name).ok_or_else(|| SimdError::Unknown(name.to_string()))
}

/// Applies `VIVAE_SIMD` if it is set (a level above what the CPU supports
/// gives the best it does support); an unknown value is an error.
pub fn apply_env() -> Result<(), SimdError> {
    match std::env::var_os(VAR) {
        None => Ok(()),
        Some(value) => {
            let level = parse(&value.to_string_lossy())?;
            vivae_neat::simd::set_level(level);
            // The simulator's sensor reads dispatch on their own copy of the switch.
            vivae_sim::simd::set_level(match level {
                vivae_neat::simd::SimdLevel::Scalar => vivae_sim::simd::SimdLevel::Scalar,
                vivae_neat::simd::SimdLevel::Avx2 => vivae_sim::simd::SimdLevel::Avx2,
                vivae_neat::simd::SimdLevel::Avx512 => vivae_sim::simd::SimdLevel::Avx512,
            });
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_neat::simd::SimdLevel;

    #[test]
    fn level_names_parse_and_others_are_refused() {
        assert_eq!(parse("scalar"), Ok(SimdLevel::Scalar));
        assert_eq!(parse("avx2"), Ok(SimdLevel::Avx2));
        assert_eq!(parse("avx512"), Ok(SimdLevel::Avx512));
        let e = parse("AVX9").unwrap_err();
        assert_eq!(
            e.to_string(),
            "environment variable VIVAE_SIMD=\"AVX9\": expected scalar, avx2 or avx512"
        );
        assert!(crate::Error::from(e).is_bad_input());
    }
}
