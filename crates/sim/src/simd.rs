//! Run-time choice of the vector instruction set used by the hot loops
//! (surface sensors): every level gives exactly the same bits, so the choice
//! only changes speed. The binary can force a level (`set_level`) to prove it.
//! The levels and the CPU detection are vivae-simd's, shared with vivae-neat.

use vivae_simd::LevelSetting;
pub use vivae_simd::{SimdLevel, detected};

/// This library's level (vivae-neat keeps its own).
static ACTIVE: LevelSetting = LevelSetting::new();

/// The level in force (the detected one unless `set_level` chose another).
#[inline]
pub fn level() -> SimdLevel {
    ACTIVE.get()
}

/// Forces `l` (clamped to what the CPU supports) for the whole process;
/// returns the level now in force.
pub fn set_level(l: SimdLevel) -> SimdLevel {
    ACTIVE.set(l)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_level_clamps_to_the_detected_level() {
        let d = detected();
        assert_eq!(set_level(SimdLevel::Scalar), SimdLevel::Scalar);
        assert_eq!(level(), SimdLevel::Scalar);
        assert_eq!(set_level(SimdLevel::Avx512), d);
        assert_eq!(level(), d);
    }
}
