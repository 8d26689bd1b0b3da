//! `decompose`'s progress: a bar on a terminal, `--progress` lines elsewhere, with
//! the time left from the library's estimate ([`Stage::seconds_left`]).

use crate::args::DecomposeArgs;
use crate::exit::eprintln;
use primdecomp::{Params, Stage};
use std::time::Instant;

/// A run's progress as the user sees it: a bar on a terminal (stage, percent of the
/// run, time left), lines on stderr every few seconds with `--progress` elsewhere,
/// or nothing (quiet, several inputs at once, a small input, or stderr not a terminal
/// without `--progress`).
pub(super) struct Shown {
    /// The run's settings (which stages' shares the estimate takes) and its start.
    params: Params,
    start: Instant,
    bar: Option<indicatif::ProgressBar>,
    /// `--progress` off a terminal: when the last line was printed, and its stage.
    lines: Option<std::sync::Mutex<(Instant, Option<Stage>)>>,
}

impl Shown {
    /// What to show for a run of `faces` faces (nothing when unwanted, see [`Shown`]).
    pub(super) fn new(
        params: &Params,
        faces: usize,
        a: &DecomposeArgs,
        beside_others: bool,
    ) -> Shown {
        use std::io::IsTerminal;
        let wanted = !a.quiet && !beside_others && (a.progress || faces >= 100_000);
        let terminal = std::io::stderr().is_terminal();
        let bar = (wanted && terminal).then(|| {
            let b = indicatif::ProgressBar::new(1000);
            b.set_style(
                indicatif::ProgressStyle::with_template(
                    "{msg:<24} {bar:30} {percent:>3}% {prefix}",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            b
        });
        let lines = (wanted && !terminal && a.progress)
            .then(|| std::sync::Mutex::new((Instant::now(), None)));
        Shown {
            params: params.clone(),
            start: Instant::now(),
            bar,
            lines,
        }
    }

    /// `stage` is `fraction` done: moves the bar, or prints a line when one is due.
    pub(super) fn update(&self, stage: Stage, fraction: f64) {
        if self.bar.is_none() && self.lines.is_none() {
            return;
        }
        let fraction = fraction.clamp(0.0, 1.0);
        let overall = stage.overall(fraction, &self.params);
        let spent = self.start.elapsed().as_secs_f64();
        let left = (stage.seconds_left(fraction, &self.params, spent))
            .map_or(String::new(), |s| format!("about {} left", duration(s)));
        if let Some(b) = &self.bar {
            b.set_message(format!("{} {:.0}%", stage.name(), 100.0 * fraction));
            b.set_prefix(left.clone());
            b.set_position((overall * 1000.0) as u64);
        }
        if let Some(last) = &self.lines {
            // A line as each stage starts, and every few seconds within one.
            let mut last = last.lock().unwrap_or_else(|e| e.into_inner());
            if last.1 != Some(stage) || last.0.elapsed().as_secs_f64() >= PROGRESS_EVERY {
                *last = (Instant::now(), Some(stage));
                eprintln!(
                    "progress  {} {:.0}%, run {:.0}%{}",
                    stage.name(),
                    100.0 * fraction,
                    100.0 * overall,
                    if left.is_empty() {
                        left
                    } else {
                        format!(", {left}")
                    }
                );
            }
        }
    }

    /// Clears the bar.
    pub(super) fn finish(self) {
        if let Some(b) = self.bar {
            b.finish_and_clear();
        }
    }
}

/// Seconds between `--progress` lines off a terminal.
const PROGRESS_EVERY: f64 = 5.0;

/// `s` seconds as `1h02m`, `3m05s` or `42s`.
fn duration(s: f64) -> String {
    let s = s.round() as u64;
    match s {
        0..=59 => format!("{s}s"),
        60..=3599 => format!("{}m{:02}s", s / 60, s % 60),
        _ => format!("{}h{:02}m", s / 3600, s % 3600 / 60),
    }
}
