//! Helpers for the tests that launch `vivae` under Open MPI's `mpirun`.
#![allow(dead_code)]

use std::path::Path;
use std::process::Command;

/// `mpirun` running `n` ranks of the `vivae` under test, allowed to run as root
/// and to put more ranks than cores on this machine.
pub fn mpirun(n: usize) -> Command {
    let mut cmd = mpirun_bare();
    cmd.args(["-n", &n.to_string(), env!("CARGO_BIN_EXE_vivae")]);
    cmd
}

/// `mpirun` with its options but no program yet (for MPMD command lines, `A : B`).
pub fn mpirun_bare() -> Command {
    let mut cmd = Command::new("mpirun");
    cmd.args(["--oversubscribe", "--bind-to", "none"])
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        // Containers often forbid the cross-process memory copy Open MPI tries first.
        .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none");
    cmd
}

/// `mpirun -n n vivae evolve -q --threads 1 [extra…] --config CONFIG --out OUT`, which must succeed.
pub fn mpi_evolve(n: usize, config: &Path, out: &Path, extra: &[&str]) -> String {
    crate::common::ok(
        mpirun(n)
            .args(["evolve", "-q", "--threads", "1"])
            .args(extra)
            .arg("--config")
            .arg(config)
            .arg("--out")
            .arg(out),
    )
}
