//! No stage grows faster than the input: two made-up inputs, one four times the
//! other's faces, each decomposed to a count and by default, and every stage's CPU
//! time per face compared between them. A stage quadratic in the faces takes four
//! times as long per face on the larger; a linear one about as long. Ratios of sizes
//! within one run, not times: CPU seconds of this process (what other jobs on the
//! machine cannot add to), one thread, the least of three runs per input, and
//! stages too short on the larger input to stand above fixed costs left out.
//! The benchmark that measures the whole ladder, to 56M faces, is
//! `cargo bench -p primdecomp-cli --bench ladder`.

use primdecomp::{decompose_with, Goal, Mesh, Params, Partitions, Progress, Stage};
use std::sync::Mutex;

/// A stage's CPU time per face on the larger input over the smaller's above this
/// fails (linear: about 1; n log n: about 1.15; quadratic: 4).
const STAGE_BOUND: f64 = 2.0;
/// The same for the whole run.
const RUN_BOUND: f64 = 1.6;
/// Stages under this many CPU seconds on the larger input are not compared.
const SHORTEST: f64 = 0.04;

/// A bumpy closed sphere of about `2 × rings × 2 rings` triangles with holes cut in
/// it (open patches, whose outer side rays decide), and a few separate bumpy
/// boxes beside it (components).
fn input(rings: u32) -> Mesh {
    let segments = 2 * rings;
    let mut pos = Vec::new();
    for i in 0..=rings {
        let t = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let p = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            let r = 1.0 + 0.05 * (7.0 * t).sin() * (5.0 * p).cos();
            pos.push([r * t.sin() * p.cos(), r * t.sin() * p.sin(), r * t.cos()]);
        }
    }
    let at = |i: u32, j: u32| i * segments + j % segments;
    let mut tris = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            // Square holes on a coarse lattice of the sphere.
            if (i * 16 / rings) % 4 == 1 && (j * 16 / segments) % 4 == 1 {
                continue;
            }
            tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    Mesh::from_triangles(&pos, &tris).expect("a valid input")
}

/// CPU seconds of this process (every thread) so far.
fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid timespec for the call to fill.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

/// The stage running, the CPU seconds when it started, and each stage's before it.
type Marks = (Option<Stage>, f64, Vec<(Stage, f64)>);

/// CPU seconds per stage, read as each stage starts.
struct StageClock(Mutex<Marks>);

impl Progress for StageClock {
    fn update(&self, stage: Stage, _: f64) {
        let mut s = self.0.lock().unwrap();
        if s.0 != Some(stage) {
            let now = cpu_seconds();
            if let Some(before) = s.0 {
                let spent = now - s.1;
                s.2.push((before, spent));
            }
            (s.0, s.1) = (Some(stage), now);
        }
    }
}

/// Per stage, the least CPU seconds of `runs` runs, and the least of the whole runs.
fn stage_seconds(mesh: &Mesh, params: &Params, runs: usize) -> (Vec<(Stage, f64)>, f64) {
    let mut best: Vec<(Stage, f64)> = Vec::new();
    let mut whole = f64::INFINITY;
    for _ in 0..runs {
        let clock = StageClock(Mutex::new((None, 0.0, Vec::new())));
        let start = cpu_seconds();
        primdecomp_testkit::on_threads(1, || decompose_with(mesh, params, &clock)).expect("runs");
        let end = cpu_seconds();
        let mut s = clock.0.into_inner().unwrap();
        if let Some(last) = s.0 {
            s.2.push((last, end - s.1));
        }
        whole = whole.min(end - start);
        for (stage, t) in s.2 {
            match best.iter_mut().find(|b| b.0 == stage) {
                Some(b) => b.1 = b.1.min(t),
                None => best.push((stage, t)),
            }
        }
    }
    (best, whole)
}

/// Parts of equal size on both inputs (as `Partitions::Auto` gives large inputs),
/// the count and the default (a tolerance) run.
fn settings(faces: usize) -> Vec<(&'static str, Params)> {
    let parts = Partitions::Fixed((faces / 16_384).max(1));
    vec![
        (
            "-n 200",
            Params {
                goal: Goal::counts([200]),
                partitions: parts,
                ..Params::default()
            },
        ),
        (
            "default",
            Params {
                partitions: parts,
                ..Params::default()
            },
        ),
    ]
}

#[test]
fn no_stage_grows_faster_than_the_faces() {
    let (small, large) = (input(120), input(240));
    let (fs, fl) = (small.face_count() as f64, large.face_count() as f64);
    assert!(fl / fs > 3.8 && fl / fs < 4.2, "{fs} and {fl} faces");
    let mut failures = Vec::new();
    for ((name, ps), (_, pl)) in settings(small.face_count())
        .into_iter()
        .zip(settings(large.face_count()))
    {
        let (s, ws) = stage_seconds(&small, &ps, 3);
        let (l, wl) = stage_seconds(&large, &pl, 3);
        let run = (wl / fl) / (ws / fs);
        eprintln!("{name}: whole run {ws:.3} s → {wl:.3} s, per face ×{run:.2}");
        if run > RUN_BOUND {
            failures.push(format!("{name}: the whole run's time per face ×{run:.2}"));
        }
        for (stage, tl) in &l {
            let ts = s.iter().find(|x| x.0 == *stage).map_or(0.0, |x| x.1);
            let ratio = (tl / fl) / (ts.max(1e-6) / fs);
            eprintln!(
                "  {}: {ts:.3} s → {tl:.3} s, per face ×{ratio:.2}",
                stage.name()
            );
            if *tl >= SHORTEST && ratio > STAGE_BOUND {
                failures.push(format!("{name}: {} per face ×{ratio:.2}", stage.name()));
            }
        }
    }
    assert!(failures.is_empty(), "superlinear: {failures:?}");
}
