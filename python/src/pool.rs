//! Worker thread pools that survive `fork`: a forked child has none of its
//! parent's threads, so a pool used before the fork would wait forever on
//! workers that do not exist (`multiprocessing.Pool` on Linux forks). Each
//! pool remembers the process that built it and is rebuilt in any other.

use std::sync::{Arc, Mutex};

use pyo3::PyResult;

use crate::errors;

/// A rayon pool of a fixed thread count, rebuilt after a fork.
pub struct ForkSafePool {
    threads: usize,
    built: Mutex<(u32, Arc<rayon::ThreadPool>)>,
}

impl ForkSafePool {
    /// A pool of `threads` workers (0 = one per core).
    pub fn new(threads: usize) -> PyResult<ForkSafePool> {
        Ok(ForkSafePool {
            threads,
            built: Mutex::new((std::process::id(), Arc::new(build(threads)?))),
        })
    }

    /// The pool of this process: the one built here, or a new one in a forked child.
    pub fn get(&self) -> PyResult<Arc<rayon::ThreadPool>> {
        // Held only for this check by the parent's own calls, which the GIL
        // serialises: no thread holds it at the moment Python forks.
        let mut built = self.built.lock().unwrap_or_else(|e| e.into_inner());
        let pid = std::process::id();
        if built.0 != pid {
            let stale = std::mem::replace(&mut built.1, Arc::new(build(self.threads)?));
            // Dropping it would signal workers that only exist in the parent,
            // through locks they may have held at the fork: it is leaked.
            std::mem::forget(stale);
            built.0 = pid;
        }
        Ok(Arc::clone(&built.1))
    }

    /// Worker threads of the pool.
    pub fn threads(&self) -> PyResult<usize> {
        Ok(self.get()?.current_num_threads())
    }
}

fn build(threads: usize) -> PyResult<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| errors::value(format!("starting worker threads: {e}")))
}
