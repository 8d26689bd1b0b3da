//! `Params::partitions` (merge/partition.rs): with K > 1 parts the output must still
//! enclose every input face (checked by the independent oracle, `primdecomp_testkit::contain`),
//! hold at most N primitives, and be the same bytes on any thread count; K = 1 must be
//! the default run, and its JSON must not mention the setting (default output unchanged).

use primdecomp::{decompose, Goal, Mesh, Params, Partitions};
use primdecomp_testkit::check::{
    assert_counts, assert_same_on_threads, assert_valid, check_corpus_meshes,
};
use primdecomp_testkit::shapes::{cuboid, cylinder, flat_grid, join, mesh, uv_sphere, Polys};

fn moved((v, f): Polys, d: [f64; 3]) -> Polys {
    (
        v.iter().map(|p| [0, 1, 2].map(|k| p[k] + d[k])).collect(),
        f,
    )
}

/// ~6,100 faces in five components: a sphere, a flat grid (zero-cost merges that
/// straddle part boundaries), a cylinder and two boxes; phase 2 must bridge them.
fn scene() -> Mesh {
    mesh(&join(&[
        uv_sphere(3.0, 40, 60),
        moved(flat_grid(60), [-30.0, -30.0, -5.0]),
        moved(cylinder(1.0, 8.0, 64), [10.0, 0.0, -4.0]),
        cuboid([-20.0, 12.0, 0.0], [-14.0, 14.0, 9.0]),
        cuboid([15.0, 15.0, 1.0], [16.0, 25.0, 2.0]),
    ]))
}

fn params(targets: &[usize], k: usize) -> Params {
    Params {
        goal: Goal::counts(targets.to_vec()),
        partitions: Partitions::Fixed(k),
        ..Default::default()
    }
}

/// K = 2, 4, 8 on the generated scene: enclosing, at most N, phase 1 really ran, and
/// the two phases together merged down to the last target as K = 1 does.
#[test]
fn partitioned_output_encloses_the_generated_scene() {
    let m = scene();
    let one = decompose(&m, &params(&[60, 12], 1)).unwrap();
    for k in [2, 4, 8] {
        let p = params(&[60, 12], k);
        let dec = decompose(&m, &p).unwrap();
        assert_valid(&m, &dec, &p);
        assert_counts(&dec, &format!("scene, K={k}"));
        assert!(
            dec.timings.iter().any(|s| s.0 == "partitions"),
            "K={k}: phase 1 did not run"
        );
        assert_eq!(dec.stats.partitions, k);
        let stats = dec.to_json(0, &p);
        let stats = &stats[stats.find("\"stats\"").expect("stats")..];
        assert!(stats.contains(&format!("\"partitions\": {k}")), "{stats}");
        assert_eq!(
            dec.stats.merges, one.stats.merges,
            "K={k}: both run down to 12"
        );
    }
}

/// Same bytes (the JSON as written without `--timings`) on 1, 2 and 8 threads with K = 8 (parts are merged as parallel tasks
/// whose order of completion varies; phase 2's worker shares re-pricing).
#[test]
fn partitioned_output_is_identical_on_any_thread_count() {
    assert_same_on_threads(&scene(), &params(&[60, 12], 8));
}

/// Below `AUTO_MIN_FACES` faces the default (`Partitions::Auto`) is K = 1: the same
/// primitives as a fixed single part, each JSON recording the setting it was given and
/// one part used. A K > 1 run whose phase 1 would leave as many clusters as faces
/// (16 × N ≥ F) is K = 1's run with the setting recorded.
#[test]
fn one_partition_is_the_default_run_on_small_inputs() {
    assert!(scene().face_count() < primdecomp::internals::AUTO_MIN_FACES);
    let m = scene();
    let default = Params {
        goal: Goal::counts([60, 12]),
        ..Default::default()
    };
    let a = decompose(&m, &default).unwrap();
    let b = decompose(&m, &params(&[60, 12], 1)).unwrap();
    let text = b.to_json(0, &params(&[60, 12], 1));
    assert!(
        text.contains("\"partitions\": 1,"),
        "K=1 JSON records the setting"
    );
    assert!(a.to_json(0, &default).contains("\"partitions\": \"auto\","));
    assert_eq!(a.stats.partitions, 1, "auto split a small input");
    assert_eq!(a.levels, b.levels);
    let big = m.face_count() / 16 + 1;
    let c1 = decompose(&m, &params(&[big], 1)).unwrap();
    let c8 = decompose(&m, &params(&[big], 8)).unwrap();
    assert_eq!(
        format!("{:?}", c1.levels[0].primitives),
        format!("{:?}", c8.levels[0].primitives)
    );
    assert!(c8
        .to_json(0, &params(&[big], 8))
        .contains("\"partitions\": 8"));
}

/// 0 parts is refused, not run.
#[test]
fn zero_partitions_is_refused() {
    let m = scene();
    let err = decompose(&m, &params(&[10], 0)).unwrap_err();
    assert!(err.to_string().contains("partitions"), "{err}");
}

/// Corpus meshes (one closed scan, one model of many parts that phase 2 must bridge)
/// with K = 4 and 8 at about 1% of their faces and at 20: enclosing and at most N.
#[test]
fn partitioned_output_encloses_corpus_meshes() {
    check_corpus_meshes(|t| vec![params(t, 4), params(t, 8)]);
}

/// Progress covers both phases as one fraction of the merges: phase 1's parallel parts
/// report their merges so far (a bar no longer waits at 0% through phase 1), every
/// value within [0, 1].
#[test]
fn progress_is_reported_during_phase_one() {
    let m = mesh(&uv_sphere(3.0, 150, 200));
    let p = params(&[100], 2);
    let seen = std::sync::Mutex::new(Vec::new());
    let merge = |stage: primdecomp::Stage, f: f64| {
        if stage == primdecomp::Stage::Merge && f > 0.0 && f < 1.0 {
            seen.lock().unwrap().push(f)
        }
    };
    let dec = primdecomp::decompose_with(&m, &p, &merge).unwrap();
    assert!(dec.timings.iter().any(|s| s.0 == "partitions"));
    let seen = seen.into_inner().unwrap();
    assert!(seen.iter().all(|f| (0.0..=1.0).contains(f)), "{seen:?}");
    // 30,000 faces, two parts of ~14,200 merges each, reported every 4,096 merges.
    assert!(seen.len() >= 4, "{seen:?}");
    assert!(seen.iter().any(|&f| f < 0.5), "{seen:?}");
    assert!(seen.iter().any(|&f| f > 0.5), "{seen:?}");
}

/// Phase 1 re-prices lazily (every merge deferred:
/// docs/decisions/0019-large-inputs-merged-in-parts.md), so some pairs are
/// re-priced when popped; with `Reprice::Exact` nothing is, in either phase.
#[test]
fn parts_defer_unless_repricing_is_exact() {
    let m = scene();
    let lazy = decompose(&m, &params(&[12], 4)).unwrap();
    assert!(lazy.stats.fits_when_popped > 0, "{:?}", lazy.stats);
    let p = Params {
        reprice: primdecomp::Reprice::Exact,
        ..params(&[12], 4)
    };
    let exact = decompose(&m, &p).unwrap();
    assert_valid(&m, &exact, &p);
    assert_eq!(exact.stats.fits_when_popped, 0, "{:?}", exact.stats);
}

/// An open half cylinder (radius 10, length 10, `segs` strips of two triangles around
/// its half turn, two rows along its axis) and a block of 160 small separate cubes
/// beside it: more components than the merge tree's leaves after spatial parts held
/// (4 × the count's cap), so the greedy's snapshot at those leaves had the half
/// cylinder whole in one leaf.
fn sheet_and_cubes(segs: u32) -> Polys {
    let (r, l) = (10.0, 10.0);
    let mut v = Vec::new();
    for j in 0..=2 {
        for i in 0..=segs {
            let t = std::f64::consts::PI * i as f64 / segs as f64;
            v.push([r * t.cos(), r * t.sin(), l * j as f64 / 2.0]);
        }
    }
    let id = |i: u32, j: u32| j * (segs + 1) + i;
    let mut f = Vec::new();
    for j in 0..2 {
        for i in 0..segs {
            f.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            f.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mut parts = vec![(v, f)];
    for c in 0..160 {
        let (x, y, z) = ((c % 8) as f64, ((c / 8) % 5) as f64, (c / 40) as f64);
        let lo = [0.15 * x, -3.0 + 0.15 * y, 4.0 + 0.15 * z];
        parts.push(cuboid(lo, lo.map(|a| a + 0.1)));
    }
    join(&parts)
}

/// After spatial parts the merge tree's leaves larger than a primitive's mean are taken
/// apart down to their faces (the parts' merges are logged): the half cylinder, one
/// leaf of the greedy's, is cut into arcs within 2% of the diagonal (0.76% measured).
/// Before, the cut stopped at the whole half cylinder: 28.7% of the diagonal away, the
/// shortfall `faces`.
#[test]
fn parts_leave_no_leaf_the_cut_cannot_split() {
    within_two_percent_in_four_parts(&mesh(&sheet_and_cubes(32)));
}

/// A leaf too large for the faces the tree may take apart (an eighth of the input's)
/// is taken apart into pieces, the clusters its own merges made, instead of staying
/// whole: the half cylinder of 1,024 triangles beside the cubes, more than an eighth of
/// the faces, is cut into arcs within 2% of the diagonal (7.40 over 0.517, `faces`,
/// without the pieces).
#[test]
fn a_leaf_past_the_budget_is_taken_apart_into_pieces() {
    let m = mesh(&sheet_and_cubes(256));
    assert!(1024 > m.face_count() / 8, "{} faces", m.face_count());
    within_two_percent_in_four_parts(&m);
}

/// `m` in four spatial parts, 2% with at most 16 primitives: within the tolerance,
/// no shortfall, every face enclosed.
fn within_two_percent_in_four_parts(m: &Mesh) {
    let p = Params {
        goal: Goal::Within {
            caps: vec![16],
            tolerance: vec![primdecomp::Tolerance::Diagonal(0.02)],
            max_bytes: vec![],
        },
        partitions: Partitions::Fixed(4),
        ..Default::default()
    };
    let dec = decompose(m, &p).unwrap();
    assert_eq!(dec.stats.partitions, 4, "spatial parts ran");
    assert_valid(m, &dec, &p);
    let level = &dec.levels[0];
    let (d, t) = (level.distance.unwrap(), level.tolerance.unwrap());
    assert!(d <= t, "{d} over {t}: {:?}", level.shortfall);
    assert!(level.shortfall.is_none(), "{:?}", level.shortfall);
}
