//! The `vivae` command-line program.
fn main() {}
