//! The C math symbols, routed to the portable `libm` crate: the `vivae`
//! program's (and any program's that runs `vivae::run_cli`), and the Python
//! module's (python/src/lib.rs includes this file).
//!
//! Our own code calls portable functions (`vivae_neat::math`, `libm`)
//! directly, but the SVG stack we load scenarios with (usvg, tiny-skia,
//! kurbo) calls `sinf`, `atan2`, `acos`, … through the platform's libm, and
//! glibc picks FMA or non-FMA code for those per CPU. A scenario's geometry
//! (a rotated robot, an arc-shaped road) could then differ in a last bit
//! between two machines, and so would every run on it.
//!
//! An executable's own definition of a dynamic symbol takes precedence over
//! the shared library's (ELF symbol interposition), so defining them here
//! makes every caller in the process — ours and the dependencies' — use the
//! same portable code. glibc's internal calls use private aliases and are
//! unaffected. Each function has exactly the C signature of `<math.h>`.
//! `same_bits_on_older_cpu_code_paths` tests the effect. A shared object
//! (the Python module) gets the same precedence only when linked with
//! `-Bsymbolic-functions` (python/build.rs).

#![allow(unsafe_code)]

macro_rules! unary {
    ($($name:ident: $t:ty),* $(,)?) => {$(
        #[doc = concat!("`", stringify!($name), "` from the portable `libm` crate.")]
        #[unsafe(no_mangle)]
        pub extern "C" fn $name(x: $t) -> $t {
            libm::$name(x)
        }
    )*};
}

macro_rules! binary {
    ($($name:ident: $t:ty),* $(,)?) => {$(
        #[doc = concat!("`", stringify!($name), "` from the portable `libm` crate.")]
        #[unsafe(no_mangle)]
        pub extern "C" fn $name(x: $t, y: $t) -> $t {
            libm::$name(x, y)
        }
    )*};
}

unary!(
    sin: f64, cos: f64, tan: f64, asin: f64, acos: f64, atan: f64,
    exp: f64, exp2: f64, log: f64, log2: f64, log10: f64, cbrt: f64,
    sinh: f64, cosh: f64, tanh: f64,
    sinf: f32, cosf: f32, tanf: f32, asinf: f32, acosf: f32, atanf: f32,
    expf: f32, exp2f: f32, logf: f32, log2f: f32, log10f: f32, cbrtf: f32,
);
binary!(atan2: f64, pow: f64, hypot: f64, atan2f: f32, powf: f32, hypotf: f32);

/// `sincos` from the portable `libm` crate.
///
/// # Safety
/// `s` and `c` must be valid for writes, as `<math.h>` requires of callers.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sincos(x: f64, s: *mut f64, c: *mut f64) {
    let (sin, cos) = libm::sincos(x);
    // SAFETY: the C contract of sincos: both pointers are valid for writes.
    unsafe {
        s.write(sin);
        c.write(cos);
    }
}

/// `sincosf` from the portable `libm` crate.
///
/// # Safety
/// `s` and `c` must be valid for writes, as `<math.h>` requires of callers.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sincosf(x: f32, s: *mut f32, c: *mut f32) {
    let (sin, cos) = libm::sincosf(x);
    // SAFETY: the C contract of sincosf: both pointers are valid for writes.
    unsafe {
        s.write(sin);
        c.write(cos);
    }
}

/// Puts every definition here into the program that calls it: an executable
/// takes an object of a library crate only when something refers to it, and
/// the SVG stack's calls alone would reach the platform's libm instead.
// The Python module includes this file in its own crate (every object linked).
#[allow(dead_code)]
pub fn link() {
    macro_rules! refer {
        ($($name:ident),* $(,)?) => {$(std::hint::black_box($name as *const ());)*};
    }
    refer!(
        sin, cos, tan, asin, acos, atan, exp, exp2, log, log2, log10, cbrt, sinh, cosh, tanh, sinf,
        cosf, tanf, asinf, acosf, atanf, expf, exp2f, logf, log2f, log10f, cbrtf, atan2, pow,
        hypot, atan2f, powf, hypotf, sincos, sincosf,
    );
}

/// Whether std's math (what the SVG stack calls) gives the portable `libm`
/// crate's bits in this binary, over a sweep of arguments.
// The program calls it only from its tests; the Python module exports it.
#[allow(dead_code)]
pub fn std_math_is_portable() -> bool {
    // std's f64::sin compiles to a call of the C symbol `sin`, which this
    // binary defines; the two must agree to the bit.
    let mut x = -20.0f64;
    while x < 20.0 {
        let y = std::hint::black_box(x);
        let same = y.sin().to_bits() == libm::sin(y).to_bits()
            && y.atan2(0.3).to_bits() == libm::atan2(y, 0.3).to_bits()
            && y.exp().to_bits() == libm::exp(y).to_bits()
            && (y as f32).cos().to_bits() == libm::cosf(y as f32).to_bits();
        if !same {
            return false;
        }
        x += 0.173;
    }
    true
}

#[cfg(test)]
mod tests {
    #[test]
    fn std_math_resolves_to_the_portable_functions() {
        assert!(super::std_math_is_portable());
    }
}
