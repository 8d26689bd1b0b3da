//! How soon a run answers a cancel, stage by stage, on large inputs: for each input
//! and mode, one run that never cancels but times every call of
//! [`primdecomp::Progress::cancelled`] (the library's only way to learn of a cancel),
//! and prints each timed step's longest stretch between two calls (`--timings`'
//! steps, by when the stretch opened); then one run cancelled
//! inside the longest stretch of all (10 ms after the call that opened it, found by
//! its number among the calls) and the time from that cancel to the run's return,
//! the answer wanted within 1 s.
//!
//! The stretches are between calls from any thread: where threads check in turn,
//! a cancel waits for the slowest of them, which the cancelled run measures.
//!
//! Run: `cargo bench -p primdecomp-cli --bench cancel`. Settings, by environment:
//! - `CANCEL_INPUTS` (default the corpus's dragon): mesh files, comma-separated (the
//!   ladder's rungs: `primdecomp-testkit ladder DRAGON LEVELS OUT.ply`);
//! - `CANCEL_MODES` (default `n2000,default`): `-n 2000` and the default run;
//! - `CANCEL_TRACE` (seconds, unset: off): where the stretches longer than this open
//!   and close, the core's frames of the two calls' stacks (a stack captured at every
//!   call: slower, for finding a stretch's code, not for its length).

use primdecomp::Progress;
use std::backtrace::Backtrace;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering::Relaxed};
use std::sync::Mutex;
use std::time::Instant;

/// Every call of `cancelled()` timed; the stretches between two calls kept when
/// longer than [`KEPT`].
struct Probe {
    start: Instant,
    /// Nanoseconds since `start` at the last call.
    last: AtomicU64,
    calls: AtomicU64,
    /// Each kept stretch: its seconds, the number of the call that opened it and
    /// when that was (s since the start).
    stretches: Mutex<Vec<(f64, u64, f64)>>,
    /// `CANCEL_TRACE`: the threshold, the last call's stack, and each longer
    /// stretch's seconds, opening time and the stacks that opened and closed it.
    trace: Option<f64>,
    last_stack: Mutex<Option<Backtrace>>,
    traced: Mutex<Vec<(f64, f64, Backtrace, Backtrace)>>,
}

/// Stretches shorter than this are not kept (s).
const KEPT: f64 = 0.01;

impl Progress for Probe {
    fn cancelled(&self) -> bool {
        let now = self.start.elapsed().as_nanos() as u64;
        let before = self.last.swap(now, Relaxed);
        let call = self.calls.fetch_add(1, Relaxed);
        let gap = now.saturating_sub(before) as f64 * 1e-9;
        if gap > KEPT {
            let at = (gap, call.saturating_sub(1), before as f64 * 1e-9);
            self.stretches.lock().expect("no panic").push(at);
        }
        if let Some(over) = self.trace {
            let here = Backtrace::force_capture();
            let mut last = self.last_stack.lock().expect("no panic");
            if gap > over {
                let opened = last.take().unwrap_or_else(Backtrace::disabled);
                let closed = Backtrace::force_capture();
                let at = (gap, before as f64 * 1e-9, opened, closed);
                self.traced.lock().expect("no panic").push(at);
            }
            *last = Some(here);
        }
        false
    }
}

/// Cancels 10 ms after call number `at` of `cancelled()`; when it did.
struct Trap {
    at: u64,
    calls: AtomicU64,
    flag: AtomicBool,
    armed: Mutex<Option<Instant>>,
}

impl Progress for Trap {
    fn cancelled(&self) -> bool {
        if self.calls.fetch_add(1, Relaxed) == self.at {
            *self.armed.lock().expect("no panic") = Some(Instant::now());
        }
        self.flag.load(Relaxed)
    }
}

fn main() {
    let corpus = primdecomp_testkit::corpus_dir();
    let inputs = std::env::var("CANCEL_INPUTS").map_or_else(
        |_| vec![corpus.join("dragon_vrip_full.ply")],
        |s| s.split(',').map(Into::into).collect(),
    );
    let modes = std::env::var("CANCEL_MODES").unwrap_or_else(|_| "n2000,default".into());
    println!("| input | faces | mode | run s | longest stretch without a check, by step, of those ≥ 0.05 s (s) | cancelled in the longest: answered after (s) |");
    println!("|---|---:|---|---:|---|---:|");
    for path in inputs {
        let mesh = match primdecomp::Mesh::load(&path) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{}: {e}", path.display());
                continue;
            }
        };
        for mode in modes.split(',') {
            let params = primdecomp::Params {
                goal: match mode {
                    "n2000" => primdecomp::Goal::counts([2000]),
                    _ => primdecomp::Goal::default(),
                },
                ..primdecomp::Params::default()
            };
            let probe = Probe {
                start: Instant::now(),
                last: AtomicU64::new(0),
                calls: AtomicU64::new(0),
                stretches: Mutex::new(Vec::new()),
                trace: std::env::var("CANCEL_TRACE")
                    .ok()
                    .and_then(|s| s.parse().ok()),
                last_stack: Mutex::new(None),
                traced: Mutex::new(Vec::new()),
            };
            let dec = primdecomp::decompose_with(&mesh, &params, &probe).expect("the run");
            let secs = probe.start.elapsed().as_secs_f64();
            let stretches = probe.stretches.into_inner().expect("no panic");
            print_traced(probe.traced.into_inner().expect("no panic"));
            // Each timed step's longest stretch, by where it opened (the steps'
            // seconds added up give when each started).
            let mut by_step: Vec<String> = Vec::new();
            let mut from = 0.0;
            for (name, t) in &dec.timings {
                let longest = stretches
                    .iter()
                    .filter(|s| (from..from + t).contains(&s.2))
                    .map(|s| s.0)
                    .fold(0.0, f64::max);
                if longest >= 0.05 {
                    by_step.push(format!("{name} {longest:.3}"));
                }
                from += t;
            }
            let worst = stretches
                .iter()
                .max_by(|a, b| a.0.total_cmp(&b.0))
                .copied()
                .unwrap_or_default();
            let answer = cancelled_at(&mesh, &params, worst.1);
            println!(
                "| {} | {} | {mode} | {secs:.1} | {} | {} |",
                path.file_name().unwrap_or_default().to_string_lossy(),
                mesh.face_count(),
                by_step.join(", "),
                answer.map_or("finished first".into(), |a| format!("{a:.3}")),
            );
        }
    }
}

/// The core's frames of each traced stretch's two stacks, longest first.
fn print_traced(mut traced: Vec<(f64, f64, Backtrace, Backtrace)>) {
    traced.sort_by(|a, b| b.0.total_cmp(&a.0));
    let core = |bt: &Backtrace| {
        let text = bt.to_string();
        let names: Vec<String> = text
            .lines()
            .filter_map(|l| l.trim().split_once(": ").map(|(_, name)| name.to_string()))
            .filter(|n| {
                let skip = [
                    "std::", "core::", "alloc::", "<alloc", "<core", "cancel::", "rayon",
                ];
                !skip.iter().any(|s| n.starts_with(s)) && !n.contains("Progress")
            })
            .take(6)
            .collect();
        names.join(" < ")
    };
    for (gap, at, opened, closed) in traced.iter().take(12) {
        eprintln!(
            "stretch {gap:.3} s from {at:.2} s\n  opened: {}\n  closed: {}",
            core(opened),
            core(closed)
        );
    }
}

/// Runs `mesh` cancelled 10 ms after call `at` of `cancelled()`: the seconds from
/// the cancel to the return, or `None` when the run finished first.
fn cancelled_at(mesh: &primdecomp::Mesh, params: &primdecomp::Params, at: u64) -> Option<f64> {
    let trap = Trap {
        at,
        calls: AtomicU64::new(0),
        flag: AtomicBool::new(false),
        armed: Mutex::new(None),
    };
    let (result, set, returned) = std::thread::scope(|s| {
        let run = s.spawn(|| {
            let r = primdecomp::decompose_with(mesh, params, &trap);
            (r, Instant::now())
        });
        let mut set = None;
        while !run.is_finished() {
            let armed = *trap.armed.lock().expect("no panic");
            if let (Some(t), None) = (armed, set) {
                if t.elapsed().as_secs_f64() >= 0.01 {
                    trap.flag.store(true, Relaxed);
                    set = Some(Instant::now());
                }
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        let (r, returned) = run.join().expect("no panic");
        (r, set, returned)
    });
    match (result, set) {
        (Err(primdecomp::Error::Cancelled), Some(at)) => {
            Some(returned.duration_since(at).as_secs_f64())
        }
        (Ok(_), _) => None,
        (Err(e), _) => panic!("{e}"),
    }
}
