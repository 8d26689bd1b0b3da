//! Progress and cancellation through the public API (`decompose_with`): every stage
//! is reported in run order with fractions that only grow, and a cancelled run
//! stops at its next check — whether the single loop or spatial parts are merging —
//! and returns `Error::Cancelled`. Counts, not clocks: how soon a run stops is
//! measured by the reports that follow the cancel, never by time.

use primdecomp::{decompose_with, Error, Goal, Mesh, Params, Partitions, Progress, Stage};
use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
use std::sync::Mutex;

/// A UV sphere of `rings × segments` quads split into triangles (2 × r × s faces).
fn sphere(rings: u32, segments: u32) -> Mesh {
    let mut pos = Vec::new();
    for i in 0..=rings {
        let t = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segments {
            let p = std::f64::consts::TAU * j as f64 / segments as f64;
            pos.push([t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]);
        }
    }
    let at = |i: u32, j: u32| i * segments + j % segments;
    let mut tris = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    Mesh::from_triangles(&pos, &tris).expect("a valid sphere")
}

/// Records every report; cancels once `cancel_at` says so.
struct Recorder<F: Fn(Stage, f64) -> bool + Sync> {
    seen: Mutex<Vec<(Stage, f64, bool)>>,
    cancel: AtomicBool,
    cancel_at: F,
}

impl<F: Fn(Stage, f64) -> bool + Sync> Progress for Recorder<F> {
    fn update(&self, stage: Stage, fraction: f64) {
        let was = self.cancel.load(Relaxed);
        self.seen.lock().unwrap().push((stage, fraction, was));
        if (self.cancel_at)(stage, fraction) {
            self.cancel.store(true, Relaxed);
        }
    }
    fn cancelled(&self) -> bool {
        self.cancel.load(Relaxed)
    }
}

fn recorder<F: Fn(Stage, f64) -> bool + Sync>(cancel_at: F) -> Recorder<F> {
    Recorder {
        seen: Mutex::new(Vec::new()),
        cancel: AtomicBool::new(false),
        cancel_at,
    }
}

fn params(partitions: Partitions) -> Params {
    Params {
        goal: Goal::counts([40]),
        partitions,
        ..Params::default()
    }
}

#[test]
fn every_stage_is_reported_in_order_and_fractions_only_grow() {
    let mesh = sphere(40, 60);
    for parts in [Partitions::Fixed(1), Partitions::Fixed(4)] {
        let r = recorder(|_, _| false);
        let dec = decompose_with(&mesh, &params(parts), &r).expect("runs");
        assert!(!dec.levels[0].primitives.is_empty());
        let seen = r.seen.into_inner().unwrap();
        let order: Vec<Stage> = seen.iter().map(|s| s.0).fold(Vec::new(), |mut v, s| {
            if v.last() != Some(&s) {
                v.push(s);
            }
            v
        });
        assert_eq!(order, Stage::ALL, "{parts:?}: stages out of order");
        for stage in Stage::ALL {
            let f: Vec<f64> = seen.iter().filter(|s| s.0 == stage).map(|s| s.1).collect();
            assert!(
                f.iter().all(|x| (0.0..=1.0).contains(x)),
                "{stage:?}: {f:?}"
            );
            assert_eq!(f.last(), Some(&1.0), "{stage:?} does not end at 1");
            // Parts report from several threads, so only the single loop's merge
            // reports are ordered.
            if stage != Stage::Merge || parts == Partitions::Fixed(1) {
                assert!(f.windows(2).all(|w| w[0] <= w[1]), "{stage:?}: {f:?}");
            }
        }
        let merge_reports = seen.iter().filter(|s| s.0 == Stage::Merge).count();
        assert!(
            merge_reports >= 2,
            "{parts:?}: the merge reports only its ends"
        );
    }
}

/// Cancelling as each stage starts, and in the middle of the merge loop (one global
/// loop, and spatial parts merged in parallel): the run returns `Cancelled`, and after
/// the cancel at most a few reports follow (each part's loop, or the stage, stops at
/// its next check instead of running on).
#[test]
fn a_cancelled_run_stops_at_its_next_check() {
    let mesh = sphere(60, 100); // 12,000 faces: three checks of the merge loop
    for parts in [Partitions::Fixed(1), Partitions::Fixed(4)] {
        for stage in Stage::ALL {
            let r = recorder(move |s, f| s == stage && (stage != Stage::Merge || f > 0.0));
            let run = decompose_with(&mesh, &params(parts), &r);
            assert!(
                matches!(run, Err(Error::Cancelled)),
                "{parts:?}, cancelled at {stage:?}: {:?}",
                run.map(|d| d.levels.len())
            );
            let seen = r.seen.into_inner().unwrap();
            let after = seen.iter().filter(|s| s.2).count();
            assert!(
                after <= 5,
                "{parts:?}, {stage:?}: {after} reports after the cancel: {seen:?}"
            );
            assert!(
                seen.iter().filter(|s| s.2).all(|s| s.0 == stage),
                "{parts:?}: a later stage ran after cancelling {stage:?}"
            );
        }
    }
}

/// The merge tree's cut (the default goal, a tolerance) asks whether to go on as
/// it splits: cancelled at its first question (the post-processing stage's second
/// report, the first being the stage's start), the run returns `Cancelled` after a
/// few more reports, not at the end of the cut.
#[test]
fn a_cut_stops_at_its_next_split() {
    let mesh = sphere(60, 100);
    let params = Params::default();
    let asked = std::sync::atomic::AtomicUsize::new(0);
    let r = recorder(|s, _| s == Stage::Postprocess && asked.fetch_add(1, Relaxed) == 1);
    let run = decompose_with(&mesh, &params, &r);
    assert!(
        matches!(run, Err(Error::Cancelled)),
        "the cut ran to its end: {:?}",
        run.map(|d| d.levels.len())
    );
    let seen = r.seen.into_inner().unwrap();
    let after = seen.iter().filter(|s| s.2).count();
    assert!(after <= 5, "{after} reports after the cancel: {seen:?}");
    // Cancelled inside the cut: the stage never ends.
    let ends = seen
        .iter()
        .filter(|s| s.0 == Stage::Postprocess && s.1 == 1.0);
    assert_eq!(ends.count(), 0, "{seen:?}");
}

/// Post-processing asks as it goes, before each primitive's hosts are found (a
/// level's primitives hold every face: one step over them all was seconds long at
/// tens of millions of faces): after the cut has ended (at 1), the stage reports 1
/// at each ask, more often than the level has primitives; cancelled at its first
/// ask, the run returns `Cancelled` after a few more reports.
#[test]
fn post_processing_asks_before_each_primitive() {
    let mesh = sphere(60, 100);
    let params = Params::default();
    let r = recorder(|_, _| false);
    let dec = decompose_with(&mesh, &params, &r).expect("runs");
    let prims: usize = dec.levels.iter().map(|l| l.primitives.len()).sum();
    let seen = r.seen.into_inner().unwrap();
    let ends = |s: &&(Stage, f64, bool)| s.0 == Stage::Postprocess && s.1 == 1.0;
    // The cut's end, post-processing's and the distances' are three of them.
    let ones = seen.iter().filter(ends).count();
    assert!(
        ones >= 3 + prims,
        "{ones} reports at 1 for {prims} primitives"
    );
    let at = std::sync::atomic::AtomicUsize::new(0);
    let r = recorder(|s, f| s == Stage::Postprocess && f == 1.0 && at.fetch_add(1, Relaxed) == 1);
    let run = decompose_with(&mesh, &params, &r);
    assert!(
        matches!(run, Err(Error::Cancelled)),
        "post-processing ran to its end"
    );
    let seen = r.seen.into_inner().unwrap();
    let after = seen.iter().filter(|s| s.2).count();
    assert!(after <= 5, "{after} reports after the cancel: {seen:?}");
}
