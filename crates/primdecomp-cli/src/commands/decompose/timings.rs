//! `decompose --timings` and `-v`: seconds per stage, peak resident memory (per stage
//! for a run alone in the process) and CPU seconds per stage, read from Linux's
//! `/proc` and `clock_gettime`.

use crate::exit::println;
use primdecomp::Decomposition;

/// The stage breakdown (load through write) and the process's peak resident memory
/// (with `by_stage`, each stage's own peak, MiB, and the largest of them); with
/// `verbose` also the merge loop's counters.
pub(super) fn print_timings(
    dec: &Decomposition,
    write_s: f64,
    several: bool,
    verbose: bool,
    by_stage: Option<&[(String, f64, f64)]>,
) {
    let stages: Vec<String> = dec
        .timings
        .iter()
        .map(|(s, t)| format!("{s} {t:.3}"))
        .collect();
    println!(
        "seconds   {}, write {write_s:.3} | total {:.3}",
        stages.join(", "),
        dec.seconds() + write_s
    );
    let st = &dec.stats;
    if verbose {
        println!(
        "fits      {} merges{}; {} seeding, {} re-priced at once, {} when popped ({:.2} per merge); {} merges' points reduced ahead",
        st.merges,
        match st.merges_past {
            0 => String::new(),
            n => format!(" (and {n} past the target by components' loops)"),
        },
        st.fits_seeded,
        st.fits_at_once,
        st.fits_when_popped,
        (st.fits_at_once + st.fits_when_popped) as f64 / st.merges.max(1) as f64,
        st.merges_ahead
    );
    }
    if let Some(stages) = by_stage.filter(|s| !s.is_empty()) {
        let peak = stages.iter().map(|s| s.1).fold(0.0, f64::max);
        let each: Vec<String> = stages
            .iter()
            .map(|(n, m, _)| format!("{n} {m:.1}"))
            .collect();
        let cpu: Vec<String> = stages
            .iter()
            .map(|(n, _, c)| format!("{n} {c:.3}"))
            .collect();
        println!("memory    peak resident {peak:.1} MiB");
        println!("memory    by stage (MiB): {}", each.join(", "));
        println!("cpu       by stage (s): {}", cpu.join(", "));
    } else if let Some(kib) = peak_rss_kib() {
        // The process's peak so far: with several inputs, of all of them up to now.
        let whose = if several {
            " (the process's, all inputs so far)"
        } else {
            ""
        };
        println!(
            "memory    peak resident {:.1} MiB{whose}",
            kib as f64 / 1024.0
        );
    }
}

/// Each stage's peak resident memory (`--timings` on a run alone): as a stage
/// starts, the kernel's high-water mark is read for the stage before and reset
/// (Linux `/proc/self/clear_refs`; where that cannot be written, each figure is the
/// peak so far).
/// Each stage's CPU seconds (every thread of the process) are read at the same
/// moments: what other jobs on the machine cannot add to, for comparing stages
/// between input sizes on a busy machine.
pub(super) struct StageMemory(std::sync::Mutex<StageMarks>);

impl StageMemory {
    pub(super) fn new(first: &'static str) -> StageMemory {
        reset_peak_rss();
        StageMemory(std::sync::Mutex::new((first, cpu_seconds(), Vec::new())))
    }

    /// `stage` runs now (called often, from any thread).
    pub(super) fn enter(&self, stage: &'static str) {
        let mut s = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if s.0 != stage {
            let mib = peak_rss_kib().unwrap_or(0) as f64 / 1024.0;
            reset_peak_rss();
            let cpu = cpu_seconds();
            let before = std::mem::replace(&mut s.0, stage);
            let spent = cpu - std::mem::replace(&mut s.1, cpu);
            s.2.push((before.to_string(), mib, spent));
        }
    }

    /// The stages' peaks and CPU seconds in order, the last one's (through writing)
    /// included.
    pub(super) fn finish(self) -> Vec<(String, f64, f64)> {
        self.enter("");
        let s = self.0.into_inner().unwrap_or_else(|e| e.into_inner());
        s.2
    }
}

/// The stage running, the process's CPU seconds when it started, and per stage
/// before it: (name, peak MiB, CPU seconds).
type StageMarks = (&'static str, f64, Vec<(String, f64, f64)>);

/// CPU seconds of this process (every thread) so far; 0 where unknown.
fn cpu_seconds() -> f64 {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid timespec for the call to fill.
        if unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) } == 0 {
            return ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64;
        }
    }
    0.0
}

/// Resets the process's peak resident set size to its current one (Linux 4.0+).
fn reset_peak_rss() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// Peak resident set size of this process so far (Linux `VmHWM`), if known.
fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
