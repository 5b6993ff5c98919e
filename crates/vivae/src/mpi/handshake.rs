//! The start-up handshake: every rank's fingerprint (version, executable,
//! evaluation config, scenario, threads), checked by rank 0 before any work.

use mpi::point_to_point::{Destination, Source};
use mpi::topology::{Communicator, SimpleCommunicator};
use serde::{Deserialize, Serialize};

use vivae_lab::config::{Config, RunConfig};

use super::worker::{serve, wait_from_root};
use super::{MpiError, TAG_GO, TAG_HELLO, TAG_STOP, Work, WorkerRank, decode, encode, state};

/// What one rank tells rank 0 at start-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Hello {
    /// `vivae`'s version.
    version: String,
    /// Hash of the running executable's bytes.
    executable: u64,
    /// Hash of the evaluation-relevant config.
    config: u64,
    /// Hash of the scenario's text.
    scenario: u64,
    /// Evaluation threads of the rank.
    threads: usize,
    /// The rank's own set-up failed with this message.
    error: Option<String>,
}

/// What a rank brings to the start-up handshake.
pub struct Setup<'a> {
    /// The resolved config.
    pub config: &'a Config,
    /// The scenario's text.
    pub scenario_text: &'a str,
    /// What this rank does as a worker: evaluate genomes of the task built
    /// from both ([`super::Genomes`]), or a task on its own driver's kind
    /// ([`super::OwnDriverWork`]).
    pub work: &'a dyn Work,
    /// Evaluation threads for this rank (0 = one per core).
    pub threads: usize,
}

/// How [`start`] left this rank.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Started {
    /// Not under MPI, a job of one rank, or rank 0 of a job whose workers all
    /// checked in: go on as the run's only writer.
    Lead,
    /// A worker rank whose work is done (rank 0 stopped it): exit quietly.
    WorkerDone,
}

/// The start-up handshake; every rank of a job calls it once with its set-up.
///
/// Rank 0 gathers every worker's fingerprint and refuses the job if one
/// differs from its own or a worker's set-up failed. A worker sends its
/// fingerprint, then does work items until rank 0 stops it. Without MPI, or
/// in a job of one rank, this does nothing. When rank 0's own set-up failed it
/// returns [`Started::Lead`] so the caller reports that failure; its workers
/// are stopped when the [`Launch`] is dropped.
pub fn start(setup: Result<Setup<'_>, String>, quiet: bool) -> Result<Started, MpiError> {
    let Some((rank, size)) = state(|s| {
        s.as_mut().map(|s| {
            s.quiet = quiet;
            (s.rank, s.size)
        })
    }) else {
        return Ok(Started::Lead);
    };
    if size == 1 {
        return Ok(Started::Lead);
    }
    let world = SimpleCommunicator::world();
    let hello = hello(setup.as_ref());
    if rank != 0 {
        let bytes = encode(&hello)?;
        world
            .process_at_rank(0)
            .send_with_tag(&bytes[..], TAG_HELLO);
        let (_, tag) = wait_from_root(&world);
        return match (tag, setup) {
            (TAG_GO, Ok(setup)) => {
                serve(&world, setup.work, setup.threads)?;
                Ok(Started::WorkerDone)
            }
            (TAG_STOP, _) => Ok(Started::WorkerDone),
            (tag, _) => Err(MpiError::Mpi(format!(
                "rank {rank}: unexpected message (tag {tag}) from rank 0 at start-up"
            ))),
        };
    }
    if setup.is_err() {
        return Ok(Started::Lead);
    }
    let mut workers = Vec::with_capacity(size as usize - 1);
    for r in 1..size {
        let (bytes, _) = world
            .process_at_rank(r)
            .receive_vec_with_tag::<u8>(TAG_HELLO);
        let theirs: Hello = decode(&bytes).map_err(|e| {
            MpiError::Refused(format!(
                "rank {r} sent an unreadable start-up message ({e})"
            ))
        })?;
        if let Some(why) = refusal(&hello, &theirs) {
            return Err(MpiError::Refused(format!("rank {r} {why}")));
        }
        workers.push(WorkerRank {
            rank: r,
            depth: theirs.threads + 1,
        });
    }
    for w in &workers {
        world
            .process_at_rank(w.rank)
            .send_with_tag(&[0u8][..], TAG_GO);
    }
    state(|s| {
        if let Some(s) = s.as_mut() {
            s.workers = workers;
        }
    });
    Ok(Started::Lead)
}

/// This rank's fingerprint (version, executable, config, scenario, threads).
fn hello(setup: Result<&Setup<'_>, &String>) -> Hello {
    let executable = std::env::current_exe()
        .and_then(std::fs::read)
        .map_or(0, |bytes| hash(&bytes));
    match setup {
        Ok(s) => Hello {
            version: env!("CARGO_PKG_VERSION").into(),
            executable,
            config: hash(evaluation_config(s.config).as_bytes()),
            scenario: hash(s.scenario_text.as_bytes()),
            threads: resolved_threads(s.threads),
            error: None,
        },
        Err(e) => Hello {
            version: env!("CARGO_PKG_VERSION").into(),
            executable,
            config: 0,
            scenario: 0,
            threads: 0,
            error: Some(e.clone()),
        },
    }
}

/// Why rank 0 (`ours`) refuses a worker (`theirs`), if it does.
fn refusal(ours: &Hello, theirs: &Hello) -> Option<String> {
    if let Some(e) = &theirs.error {
        return Some(format!("could not start: {e}"));
    }
    if theirs.version != ours.version {
        return Some(format!(
            "runs vivae {} but rank 0 runs vivae {}: every rank must run the same binary",
            theirs.version, ours.version
        ));
    }
    if theirs.executable != ours.executable {
        return Some(
            "runs a different vivae executable than rank 0: every rank must run the same binary"
                .into(),
        );
    }
    if theirs.config != ours.config {
        return Some(
            "was started with a different config than rank 0: every rank must get the same command line and files"
                .into(),
        );
    }
    if theirs.scenario != ours.scenario {
        return Some(
            "was started with a different scenario than rank 0: every rank must get the same command line and files"
                .into(),
        );
    }
    None
}

/// The config as far as it decides evaluations: without the generation count,
/// file names (the scenario's text is compared separately, the starting
/// population only concerns rank 0) and how the run is executed.
fn evaluation_config(config: &Config) -> String {
    let mut c = config.clone();
    c.experiment.generations = 0;
    c.experiment.scenario.clear();
    c.experiment.scenarios.clear();
    c.experiment.init_population.clear();
    c.run = RunConfig::default();
    c.to_toml()
}

fn resolved_threads(threads: usize) -> usize {
    if threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        threads
    }
}

/// FNV-1a over 64-bit words: a fingerprint, not a defence against tampering.
fn hash(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ bytes.len() as u64;
    let mut chunks = bytes.chunks_exact(8);
    for c in &mut chunks {
        let w = u64::from_le_bytes(c.try_into().expect("8 bytes"));
        h = (h ^ w).wrapping_mul(0x0100_0000_01b3).rotate_left(29);
    }
    for &b in chunks.remainder() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use vivae_neat::EvalContext;
    use vivae_neat::driver::Evaluation;

    fn hello() -> Hello {
        Hello {
            version: "0.1.0".into(),
            executable: 1,
            config: 2,
            scenario: 3,
            threads: 2,
            error: None,
        }
    }

    #[test]
    fn same_fingerprint_is_accepted_whatever_the_threads() {
        let ours = hello();
        let theirs = Hello {
            threads: 7,
            ..hello()
        };
        assert_eq!(refusal(&ours, &theirs), None);
    }

    #[test]
    fn each_difference_is_named() {
        let ours = hello();
        let cases = [
            (
                Hello {
                    version: "0.2.0".into(),
                    ..hello()
                },
                "vivae 0.2.0",
            ),
            (
                Hello {
                    executable: 9,
                    ..hello()
                },
                "different vivae executable",
            ),
            (
                Hello {
                    config: 9,
                    ..hello()
                },
                "different config",
            ),
            (
                Hello {
                    scenario: 9,
                    ..hello()
                },
                "different scenario",
            ),
            (
                Hello {
                    error: Some("c.toml: no such file".into()),
                    ..hello()
                },
                "could not start: c.toml: no such file",
            ),
        ];
        for (theirs, expected) in cases {
            let why = refusal(&ours, &theirs).expect("refused");
            assert!(why.contains(expected), "{why}");
        }
    }

    #[test]
    fn evaluation_config_ignores_what_does_not_change_evaluations() {
        let a = Config::default();
        let mut b = a.clone();
        b.experiment.generations += 5;
        b.experiment.scenario = "elsewhere/roads.svg".into();
        b.run.threads = 3;
        b.run.checkpoint_keep = 9;
        assert_eq!(evaluation_config(&a), evaluation_config(&b));
        b.experiment.steps += 1;
        assert_ne!(evaluation_config(&a), evaluation_config(&b));
    }

    #[test]
    fn messages_round_trip_exactly() {
        let ctx = EvalContext {
            generation: 3,
            index: 17,
            seed: u64::MAX - 5,
        };
        let e = Evaluation {
            fitness: 0.1 + 0.2,
            metrics: vec![f64::MIN_POSITIVE, -0.0, 1e300],
            behaviour: vec![],
        };
        let bytes = encode(&(&ctx, 42u64, &e)).unwrap();
        let (ctx2, i, e2): (EvalContext, u64, Evaluation) = decode(&bytes).unwrap();
        assert_eq!(
            (ctx, 42, e.fitness.to_bits()),
            (ctx2, i, e2.fitness.to_bits())
        );
        assert_eq!(e, e2);
    }

    #[test]
    fn hash_sees_every_byte() {
        let a = vec![7u8; 1001];
        let mut b = a.clone();
        b[1000] = 8;
        let mut c = a.clone();
        c[3] = 8;
        assert_ne!(hash(&a), hash(&b));
        assert_ne!(hash(&a), hash(&c));
        assert_ne!(hash(&a), hash(&a[..1000]));
    }
}
