//! Links the extension so that its calls of the C math functions bind to
//! its own portable definitions (crates/vivae/src/portable_libm.rs), not the
//! interpreter's libm.

fn main() {
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        println!("cargo:rustc-link-arg-cdylib=-Wl,-Bsymbolic-functions");
    }
}
