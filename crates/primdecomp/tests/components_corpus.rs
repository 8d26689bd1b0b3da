//! Connected components merged apart (`merge/components.rs`) on real multi-part meshes
//! from the corpus: the same primitives as the global loop, at targets above, at and
//! below the component count — above it the output is replayed from the components'
//! own merges, below it the global loop goes on from every component whole.
//!
//! The global loop alone is what a run does under an excess-volume cap (a cap turns the
//! components phase off, and re-pricing exact); the cap here is too large to refuse any
//! merge, so the two runs differ only in the path, and both re-price exactly
//! (`--reprice exact`; under deferred re-pricing queue purges at other queue sizes can
//! change round-off, see the module's doc). Needs `../shared/datasets/corpus`; says so
//! loudly and returns when it is absent.

use primdecomp::{decompose, Fit, Goal, Params, Reprice};

/// Meshes of 4,096 faces or more whose largest component holds at most 60% of the
/// faces (so the components phase applies): 26, 59 and 3 components.
const MESHES: [&str; 3] = ["cgal_bones.off", "truck_shrec.obj", "chair_model.obj"];

fn params(targets: &[usize], cap: Option<f64>) -> Params {
    Params {
        goal: Goal::counts(targets.to_vec()),
        fit: Fit {
            max_excess_volume: cap,
            ..Default::default()
        },
        reprice: Reprice::Exact,
        ..Default::default()
    }
}

#[test]
fn components_apart_equal_the_global_loop_on_corpus_meshes() {
    for name in MESHES {
        let Some(m) = primdecomp_testkit::corpus_mesh(name) else {
            return;
        };
        let f = m.face_count();
        // Every face (where free merges into plates run before the snapshot,
        // docs/decisions/0025-free-merges-into-plates.md: replayed from the traced merges marked
        // free), a tenth and 1% of the faces,
        // 32 and 8: at or above the component count for the chair (3) everywhere, below
        // it for the bones (26) at 8 and the truck (59) at 1%, 32 and 8.
        let targets = [f, f / 10, f / 100, 32, 8];
        let apart = decompose(&m, &params(&targets, None)).unwrap();
        let stages: Vec<&str> = apart.timings.iter().map(|s| s.0.as_str()).collect();
        assert!(stages.contains(&"components"), "{name}: {stages:?}");
        let global = decompose(&m, &params(&targets, Some(1e12))).unwrap();
        let global_stages: Vec<&str> = global.timings.iter().map(|s| s.0.as_str()).collect();
        assert!(
            !global_stages.contains(&"components"),
            "{name}: {global_stages:?}"
        );
        for (a, g) in apart.levels.iter().zip(&global.levels) {
            assert_eq!(a.target, g.target);
            assert_eq!(
                format!("{:?}", a.primitives),
                format!("{:?}", g.primitives),
                "{name} at N = {}",
                a.target
            );
            assert_eq!(a.faces, g.faces, "{name} at N = {}", a.target);
        }
    }
}
