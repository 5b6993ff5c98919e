//! The vector instruction levels the hot loops of vivae-neat (batched
//! controller step, batched CPPN queries) and vivae-sim (surface sensors) can
//! run at, chosen at run time.
//!
//! Every level gives the same bits (the same IEEE operations in the same
//! order, no fused multiply-add), so a level only changes speed. This crate
//! is the one definition of the levels, of what the CPU supports, and of a
//! process-wide [`LevelSetting`]; each library keeps its own setting (they
//! never depend on each other) and re-exports these from its `simd` module.
//! No I/O, no dependencies: reading `VIVAE_SIMD` is the program's job.

use std::sync::atomic::{AtomicU8, Ordering};

/// A vector instruction level of the hot loops, lowest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// The baseline instruction set (SSE2 on x86_64), the same on every CPU.
    Scalar,
    /// AVX2 (256-bit vectors), without FMA.
    Avx2,
    /// AVX-512F (512-bit vectors), without FMA.
    Avx512,
}

impl SimdLevel {
    /// The level named `name` (`scalar`, `avx2` or `avx512`: `VIVAE_SIMD`'s values).
    pub fn from_name(name: &str) -> Option<SimdLevel> {
        match name {
            "scalar" => Some(SimdLevel::Scalar),
            "avx2" => Some(SimdLevel::Avx2),
            "avx512" => Some(SimdLevel::Avx512),
            _ => None,
        }
    }
}

/// The best level this CPU supports.
pub fn detected() -> SimdLevel {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            return SimdLevel::Avx512;
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            return SimdLevel::Avx2;
        }
    }
    SimdLevel::Scalar
}

/// The levels this CPU can run, lowest first (for tests that compare them).
pub fn available() -> Vec<SimdLevel> {
    [SimdLevel::Scalar, SimdLevel::Avx2, SimdLevel::Avx512]
        .into_iter()
        .filter(|&l| l <= detected())
        .collect()
}

/// Marks "not chosen yet": the first [`LevelSetting::get`] picks [`detected`].
const UNSET: u8 = u8::MAX;

/// The level a library's hot loops use, for the whole process: the detected
/// one until [`LevelSetting::set`] chooses another (kept in a `static`).
#[derive(Debug)]
pub struct LevelSetting(AtomicU8);

impl LevelSetting {
    /// Not chosen yet: reads as [`detected`].
    pub const fn new() -> LevelSetting {
        LevelSetting(AtomicU8::new(UNSET))
    }

    /// The level in force (the detected one unless [`set`](Self::set) chose another).
    #[inline]
    pub fn get(&self) -> SimdLevel {
        match self.0.load(Ordering::Relaxed) {
            0 => SimdLevel::Scalar,
            1 => SimdLevel::Avx2,
            2 => SimdLevel::Avx512,
            _ => {
                // First use: remember the detected level unless one was set meanwhile.
                let d = detected();
                let _ =
                    (self.0).compare_exchange(UNSET, d as u8, Ordering::Relaxed, Ordering::Relaxed);
                d
            }
        }
    }

    /// Makes `wanted`, clamped to what the CPU supports ([`detected`]), the
    /// level in force; returns it.
    pub fn set(&self, wanted: SimdLevel) -> SimdLevel {
        let l = wanted.min(detected());
        self.0.store(l as u8, Ordering::Relaxed);
        l
    }
}

impl Default for LevelSetting {
    /// Not chosen yet, as [`LevelSetting::new`].
    fn default() -> Self {
        LevelSetting::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_named_as_vivae_simd_takes_them() {
        assert_eq!(SimdLevel::from_name("scalar"), Some(SimdLevel::Scalar));
        assert_eq!(SimdLevel::from_name("avx2"), Some(SimdLevel::Avx2));
        assert_eq!(SimdLevel::from_name("avx512"), Some(SimdLevel::Avx512));
        for bad in ["", "AVX2", "avx9", "avx512 "] {
            assert_eq!(SimdLevel::from_name(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn a_setting_starts_detected_and_is_clamped_to_the_cpu() {
        let setting = LevelSetting::new();
        assert_eq!(setting.get(), detected());
        assert_eq!(setting.set(SimdLevel::Scalar), SimdLevel::Scalar);
        assert_eq!(setting.get(), SimdLevel::Scalar);
        assert_eq!(setting.set(SimdLevel::Avx512), detected());
        assert_eq!(setting.get(), detected());
        assert_eq!(available().first(), Some(&SimdLevel::Scalar));
        assert_eq!(available().last(), Some(&detected()));
    }
}
