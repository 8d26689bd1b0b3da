//! Timing and reporting a run's stages: [`Clock`] times each stage, reports it to the
//! caller's [`Progress`] and stops the run when it is cancelled.

use crate::error::{Error, Result};
use crate::progress::wallclock::Instant;
use crate::progress::{Checkpoint, Progress, Stage};

/// Times each stage, reports it to the caller, and turns a cancellation into
/// [`Error::Cancelled`] between stages (and within them through the callback).
pub(crate) struct Clock<'p> {
    progress: &'p dyn Progress,
    pub(crate) timings: Vec<(String, f64)>,
    /// The stage reported last: a stage run in several steps starts (0) once.
    current: Option<Stage>,
}

impl<'p> Clock<'p> {
    pub(crate) fn new(progress: &'p dyn Progress) -> Self {
        Clock {
            progress,
            timings: Vec::new(),
            current: None,
        }
    }

    /// Runs `work`, a step of `stage` before the one [`Clock::stage`] runs, timed as
    /// `name`: it reports the stage's start, not its end.
    pub(crate) fn step<T>(
        &mut self,
        stage: Stage,
        name: &str,
        work: impl FnOnce() -> T,
    ) -> Result<T> {
        self.start(stage)?;
        let now = Instant::now();
        let out = work();
        self.timings
            .push((name.to_string(), now.elapsed().as_secs_f64()));
        match self.progress.cancelled() {
            true => Err(Error::Cancelled),
            false => Ok(out),
        }
    }

    /// [`Clock::step`] whose `work` gets a callback that says whether to go on (it
    /// reports no fraction: the step is part of a stage that reports its own).
    pub(crate) fn step_checked<T>(
        &mut self,
        stage: Stage,
        name: &str,
        work: impl FnOnce(Checkpoint) -> T,
    ) -> Result<T> {
        let p = self.progress;
        self.step(stage, name, || work(&|_| !p.cancelled()))
    }

    /// Reports `stage`'s start unless it has started already; `Cancelled` first if so.
    pub(crate) fn start(&mut self, stage: Stage) -> Result<()> {
        if self.progress.cancelled() {
            return Err(Error::Cancelled);
        }
        if self.current != Some(stage) {
            self.progress.update(stage, 0.0);
            self.current = Some(stage);
        }
        Ok(())
    }

    /// Runs `work` as (the last step of) `stage`, timed as `name`. `work` gets a callback for
    /// the fraction of the stage done that says whether to go on, and [`PhaseTimes`] to time
    /// phases of its own (recorded before `name`, which keeps the rest).
    pub(crate) fn stage<T>(
        &mut self,
        stage: Stage,
        name: &str,
        work: impl FnOnce(Checkpoint, &mut PhaseTimes) -> T,
    ) -> Result<T> {
        self.start(stage)?;
        let p = self.progress;
        let go_on = |fraction: f64| {
            p.update(stage, fraction.clamp(0.0, 1.0));
            !p.cancelled()
        };
        let now = Instant::now();
        let mut laps = PhaseTimes::default();
        let out = work(&go_on, &mut laps);
        let mut rest = now.elapsed().as_secs_f64();
        for (lap, secs) in laps.0 {
            self.timings.push((lap.to_string(), secs));
            rest -= secs;
        }
        self.timings.push((name.to_string(), rest.max(0.0)));
        if p.cancelled() {
            return Err(Error::Cancelled);
        }
        p.update(stage, 1.0);
        Ok(out)
    }
}

/// Phases a stage times on its own (`partitions`, `regroup`, `components`).
#[derive(Default)]
pub(crate) struct PhaseTimes(Vec<(&'static str, f64)>);

impl PhaseTimes {
    pub(crate) fn time<T>(&mut self, name: &'static str, work: impl FnOnce() -> T) -> T {
        let now = Instant::now();
        let out = work();
        self.0.push((name, now.elapsed().as_secs_f64()));
        out
    }
}
