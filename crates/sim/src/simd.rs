//! Run-time choice of the vector instruction set used by the hot loops
//! (surface sensors): every level gives exactly the same bits, so the choice
//! only changes speed. The binary can force a level (`set_level`) to prove it.

use std::sync::atomic::{AtomicU8, Ordering};

/// Instruction-set level of the dispatched hot loops, lowest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// Plain x86-64 (SSE2) code, the same on every CPU.
    Scalar,
    /// AVX2 (no FMA).
    Avx2,
    /// AVX-512F (no FMA).
    Avx512,
}

/// Sentinel of `ACTIVE`: no level forced yet, use the detected one.
const UNSET: u8 = u8::MAX;

/// The level `set_level` forced, or `UNSET`.
static ACTIVE: AtomicU8 = AtomicU8::new(UNSET);

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

/// The level in force (the detected one unless `set_level` chose another).
#[inline]
pub fn level() -> SimdLevel {
    match ACTIVE.load(Ordering::Relaxed) {
        0 => SimdLevel::Scalar,
        1 => SimdLevel::Avx2,
        2 => SimdLevel::Avx512,
        _ => {
            // First use: remember the detected level unless a level was forced meanwhile.
            let d = detected();
            let _ = ACTIVE.compare_exchange(UNSET, d as u8, Ordering::Relaxed, Ordering::Relaxed);
            d
        }
    }
}

/// Forces `l` (clamped to what the CPU supports) for the whole process;
/// returns the level now in force.
pub fn set_level(l: SimdLevel) -> SimdLevel {
    let l = l.min(detected());
    ACTIVE.store(l as u8, Ordering::Relaxed);
    l
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
