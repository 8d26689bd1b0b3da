//! The merge-tree cut of a count against the greedy level of the same count (issue
//! 26's target: a lower Hausdorff, a Chamfer within 5%; docs/decisions/0051). The
//! worst-first cut spent the whole count on the worst nodes: at 1% of the faces,
//! bathtub's Chamfer was 75% over the greedy level's and chair_model's 14%. The
//! count the least worst error leaves now goes to the latest merges, within 1.25
//! times that error.

use primdecomp::{decompose, Goal, Mesh, Params};
use primdecomp_eval::collider::Collider;
use primdecomp_eval::{evaluate, Input, Metrics};

/// The first level of `counts` (the cut's or the greedy pass's, from one pass),
/// measured with 30,000 samples per surface, seed 0 (the same numbers on any thread
/// count).
fn measured(m: &Mesh, counts: &[usize], cut: bool) -> Metrics {
    let p = Params {
        // Without a cut, the greedy pass's level to compare with (docs/decisions/0054).
        goal: match cut {
            true => Goal::Cut {
                counts: counts.to_vec(),
            },
            false => Goal::Greedy {
                counts: counts.to_vec(),
            },
        },
        ..Params::default()
    };
    let d = decompose(m, &p).expect("decomposes");
    let prims = d.levels[0].primitives.clone();
    evaluate(&Input::new(m), &Collider::Primitives(prims), 30_000, 0)
}

/// The cut's target for one cut level against the greedy level of the same count.
fn nearer_with_the_greedy_mean(name: &str, cut: &Metrics, greedy: &Metrics) {
    assert!(
        cut.hausdorff < greedy.hausdorff,
        "{name}: Hausdorff {} (cut) vs {} (greedy)",
        cut.hausdorff,
        greedy.hausdorff
    );
    assert!(
        cut.chamfer <= 1.05 * greedy.chamfer,
        "{name}: Chamfer {} (cut) vs {} (greedy)",
        cut.chamfer,
        greedy.chamfer
    );
    assert_eq!(cut.enclosure, 1.0, "{name}");
}

#[test]
fn a_cut_of_a_count_stands_nearer_and_keeps_the_greedy_mean() {
    for name in ["bathtub.obj", "chair_model.obj"] {
        let Some(m) = primdecomp_testkit::corpus_mesh(name) else {
            continue;
        };
        let count = m.face_count() / 100;
        let (greedy, cut) = (measured(&m, &[count], false), measured(&m, &[count], true));
        nearer_with_the_greedy_mean(name, &cut, &greedy);
    }
}

/// Regression: in a chain only the largest count was loosened, so bathtub cut at 64
/// and 256 from one pass gave its 64 level the worst-first cut, a Chamfer 27% over
/// the greedy `-n 64`'s (3.29e-3 against 2.59e-3). Each count of a chain is now
/// loosened on its own, as that count alone is (2.21e-3, the level `-n 64` alone
/// gives).
#[test]
fn a_chains_smaller_count_keeps_the_greedy_mean_too() {
    let Some(m) = primdecomp_testkit::corpus_mesh("bathtub.obj") else {
        return;
    };
    let (greedy, cut) = (measured(&m, &[64], false), measured(&m, &[64, 256], true));
    nearer_with_the_greedy_mean("bathtub at 64 of 64 and 256", &cut, &greedy);
}
