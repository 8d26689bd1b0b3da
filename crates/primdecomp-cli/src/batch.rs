//! Several inputs at once (`primdecomp decompose A B C … --jobs J`): J inputs are
//! decomposed side by side, each on its own share of the threads. An asset library is
//! mostly small meshes, whose runs are too short for the merge loop's two threads to
//! pay (docs/decisions/perf-batch-jobs.md), so running one per core is what uses the
//! machine. Each input's output is the same bytes on any thread count, so only the
//! order of the messages changes.
//!
//! Order: the largest files are started first (longest processing time first), so
//! that a big scan does not start last and run alone while the other jobs idle.
//!
//! Memory: before loading an input a job reserves the input's estimated peak
//! (`primdecomp::Mesh::memory_needed`; the whole budget where it cannot be known) from the
//! `--max-memory` budget, and waits while the others' reservations leave too little;
//! an input runs alone when nothing else is reserved, where the per-input limit of
//! `LoadOptions::max_memory` applies as in a sequential run.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};

/// Bytes reserved by the running jobs, against a budget.
struct Budget {
    limit: Option<u64>,
    used: Mutex<u64>,
    freed: Condvar,
}

impl Budget {
    /// Waits until `need` fits beside the other reservations (or nothing else is
    /// reserved), then reserves it; returns what was reserved.
    fn reserve(&self, need: Option<u64>) -> u64 {
        let Some(limit) = self.limit else { return 0 };
        let need = need.unwrap_or(limit).min(limit);
        let mut used = self.used.lock().unwrap_or_else(|e| e.into_inner());
        while *used > 0 && *used + need > limit {
            used = self.freed.wait(used).unwrap_or_else(|e| e.into_inner());
        }
        *used += need;
        need
    }

    fn release(&self, n: u64) {
        let mut used = self.used.lock().unwrap_or_else(|e| e.into_inner());
        *used -= n;
        self.freed.notify_all();
    }
}

/// Runs `run(i)` for every input, `jobs` at a time, each inside a rayon pool of
/// `threads / jobs` threads (at least one); results in input order. One job runs the
/// inputs in order on the caller's own pool. `memory` is the
/// budget (`None`: unlimited).
pub fn run_all<T: Send>(
    inputs: &[PathBuf],
    jobs: usize,
    threads: usize,
    memory: Option<u64>,
    run: impl Fn(usize) -> anyhow::Result<T> + Sync,
) -> Vec<anyhow::Result<T>> {
    let jobs = jobs.clamp(1, inputs.len().max(1));
    if jobs == 1 {
        // One after another in input order on the caller's pool: no pool of our own,
        // and nothing else runs beside an input, so no reservation is needed.
        return (0..inputs.len()).map(run).collect();
    }
    let per_job = (threads / jobs).max(1);
    let budget = Budget {
        limit: memory,
        used: Mutex::new(0),
        freed: Condvar::new(),
    };
    // Largest files first (one `stat` per file); ties (and unreadable sizes, as 0) in
    // input order.
    let mut order: Vec<usize> = (0..inputs.len()).collect();
    let size = |i: usize| std::fs::metadata(&inputs[i]).map_or(0, |m| m.len());
    order.sort_by_cached_key(|&i| std::cmp::Reverse(size(i)));
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<anyhow::Result<T>>>> =
        inputs.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(per_job).build();
                while let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
                    let held = budget.reserve(primdecomp::Mesh::memory_needed(&inputs[i]));
                    let r = match &pool {
                        Ok(p) => p.install(|| run(i)),
                        Err(e) => Err(anyhow::anyhow!("cannot start {per_job} threads: {e}")),
                    };
                    budget.release(held);
                    *slots[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
                }
            });
        }
    });
    slots
        .into_iter()
        .map(|m| {
            m.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .unwrap_or_else(|| Err(anyhow::anyhow!("input not run (a job thread failed)")))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;
    use std::time::Duration;

    fn paths(n: usize) -> Vec<PathBuf> {
        (0..n)
            .map(|i| PathBuf::from(format!("in{i}.obj")))
            .collect()
    }

    /// Results come back in input order whatever order the jobs finish in, errors in
    /// their places, and every input runs once.
    #[test]
    fn results_keep_input_order() {
        let runs = AtomicUsize::new(0);
        let out = run_all(&paths(9), 3, 3, None, |i| {
            runs.fetch_add(1, Ordering::Relaxed);
            std::thread::sleep(Duration::from_millis(((9 - i) * 3) as u64));
            if i == 4 {
                anyhow::bail!("input {i} failed");
            }
            Ok(i * 10)
        });
        assert_eq!(runs.load(Ordering::Relaxed), 9);
        for (i, r) in out.iter().enumerate() {
            match r {
                Ok(v) => assert_eq!(*v, i * 10),
                Err(e) => assert_eq!((i, e.to_string()), (4, "input 4 failed".into())),
            }
        }
    }

    /// Each job's rayon pool has its share of the threads.
    #[test]
    fn each_job_gets_its_share_of_threads() {
        let out = run_all(&paths(4), 2, 4, None, |_| Ok(rayon::current_num_threads()));
        assert!(out.iter().all(|r| *r.as_ref().unwrap() == 2));
        let out = run_all(&paths(4), 4, 2, None, |_| Ok(rayon::current_num_threads()));
        assert!(out.iter().all(|r| *r.as_ref().unwrap() == 1));
    }

    /// With a budget, reservations never exceed it while two or more jobs run (inputs
    /// of unknown size reserve the whole budget: they run alone).
    #[test]
    fn reservations_stay_within_the_budget() {
        let budget = Budget {
            limit: Some(100),
            used: Mutex::new(0),
            freed: Condvar::new(),
        };
        let (live, worst) = (AtomicU64::new(0), AtomicU64::new(0));
        let sizes = [
            Some(60),
            Some(30),
            None,
            Some(50),
            Some(10),
            Some(200),
            Some(40),
        ];
        let next = AtomicUsize::new(0);
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&need) = sizes.get(i) else { break };
                    let held = budget.reserve(need);
                    let now = live.fetch_add(held, Ordering::SeqCst) + held;
                    worst.fetch_max(now, Ordering::SeqCst);
                    std::thread::sleep(Duration::from_millis(5));
                    live.fetch_sub(held, Ordering::SeqCst);
                    budget.release(held);
                });
            }
        });
        assert!(worst.load(Ordering::SeqCst) <= 100, "{worst:?}");
        assert_eq!(*budget.used.lock().unwrap(), 0);
    }
}
