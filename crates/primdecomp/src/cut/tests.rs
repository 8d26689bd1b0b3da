//! The cut's tests: tolerances, chains, byte targets and enclosure on small meshes.

use super::*;
use crate::decompose::decompose;
use crate::params::{Goal, Params, Tolerance};

/// A closed cube within 1% of its diagonal is one box, whatever the cap; an
/// icosphere one round primitive; a tolerance tighter than the cube's faces allow
/// still gives the box (nothing is worth splitting), and the level records what
/// was asked and reached.
#[test]
fn a_tolerance_needs_no_count() {
    let cube = error::tests::cube_mesh(1.0);
    for t in [Tolerance::Diagonal(0.01), Tolerance::Units(1e-6)] {
        let p = Params {
            goal: Goal::Within {
                caps: vec![64],
                tolerance: vec![t],
                max_bytes: vec![],
            },
            ..Params::default()
        };
        let d = decompose(&cube, &p).expect("decomposes");
        let level = &d.levels[0];
        assert_eq!(level.primitives.len(), 1, "{t:?}");
        assert_eq!(level.primitives[0].kind(), crate::primitive::Kind::Box);
        assert_eq!(level.tolerance, Some(t.in_units(cube.diagonal())));
        assert!(level.distance.expect("measured") < 1e-9);
    }
}

/// A chain of tolerances from one pass: each level within its tolerance on the
/// demo scene (or at the least the tree reaches, which the distance says), a
/// tighter tolerance never fewer primitives, and a byte target kept.
#[test]
fn tolerance_chains_and_byte_targets() {
    let mesh = crate::input::demo::demo_scene();
    let p = Params {
        goal: Goal::Within {
            caps: vec![400, 400, 400],
            tolerance: vec![
                Tolerance::Diagonal(0.05),
                Tolerance::Diagonal(0.02),
                Tolerance::Diagonal(0.01),
            ],
            max_bytes: vec![],
        },
        ..Params::default()
    };
    let d = decompose(&mesh, &p).expect("decomposes");
    let counts: Vec<usize> = d.levels.iter().map(|l| l.primitives.len()).collect();
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert!(counts[0] < counts[2], "{counts:?}");
    for l in &d.levels[..2] {
        let (t, got) = (l.tolerance.expect("asked"), l.distance.expect("measured"));
        assert!(got <= t, "distance {got} over the tolerance {t}");
        // Each primitive's own bound, refined alone, is no tighter than 2% plus
        // the refinement's floor below the level's.
        let alone = worst_error(&mesh, &l.primitives);
        assert!(
            got >= alone / 1.02 - 2e-4 * mesh.diagonal(),
            "{got} {alone}"
        );
    }
    let small = Params {
        goal: Goal::Within {
            caps: vec![400],
            tolerance: vec![],
            max_bytes: vec![600],
        },
        ..Params::default()
    };
    let d = decompose(&mesh, &small).expect("decomposes");
    let l = &d.levels[0];
    assert!(l.bytes() <= 600 && l.bytes() > 300, "{} bytes", l.bytes());
    assert_eq!(l.max_bytes, Some(600));
    assert_eq!(l.shortfall, None, "no tolerance asked");
    // With a tolerance the 600 bytes cannot reach, the level says the bytes stopped it.
    let tight = Params {
        goal: Goal::Within {
            caps: vec![400],
            tolerance: vec![Tolerance::Diagonal(0.01)],
            max_bytes: vec![600],
        },
        ..small
    };
    let l = &decompose(&mesh, &tight).expect("decomposes").levels[0];
    assert!(l.distance.expect("measured") > l.tolerance.expect("asked"));
    assert_eq!(l.shortfall, Some(crate::output::result::Shortfall::Bytes));
}

/// Two triangles folded along a shared edge (the corpus's tiny_2triangles): the
/// right triangle of legs 1 and √2 (the other is equilateral) stands 0.82 off its
/// own box, the fit the k·V
/// with the rim term chooses, and the pair's prism 0.80 off, so the cut kept the
/// pair at 33% of the diagonal when asked for 1%. An isosceles prism on the
/// hypotenuse stands a third off (the mirror of the right angle); the skewed prism
/// (docs/decisions/0045) holds each triangle exactly, a plate as thick as the
/// output floor: the cut must split the pair and be within 1%, every vertex
/// enclosed. Asked for less than that floor, faces stop it and it says so.
#[test]
fn a_face_the_cut_cannot_split_gets_its_nearest_fit() {
    let mut b = crate::input::mesh::MeshBuilder::new();
    b.positions.extend([
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        [2.0, 1.0, 0.0],
    ]);
    b.push_face(&[0, 1, 2]);
    b.push_face(&[1, 3, 2]);
    let mesh = crate::input::mesh::Mesh::from_builder(b);
    let levels = |tol: f64| {
        let p = Params {
            goal: Goal::Within {
                caps: vec![],
                tolerance: vec![Tolerance::Diagonal(tol)],
                max_bytes: vec![],
            },
            ..Params::default()
        };
        decompose(&mesh, &p).expect("decomposes").levels.remove(0)
    };
    let level = levels(0.01);
    assert_eq!(level.primitives.len(), 2, "{:?}", level.primitives);
    let skewed = |q: &Primitive| matches!(q, Primitive::Prism(p) if p.is_skewed());
    // The right triangle's prism is skewed; the other triangle is equilateral.
    assert!(
        level.primitives.iter().any(skewed),
        "{:?}",
        level.primitives
    );
    let got = level.distance.expect("measured");
    assert!(got <= level.tolerance.expect("asked"), "farthest {got}");
    assert_eq!(level.shortfall, None);
    for v in 0..mesh.vertex_count() as u32 {
        let w = crate::math::add(mesh.pos(v), mesh.offset);
        let inside = level.primitives.iter().any(|q| q.contains(w, 1e-9));
        assert!(inside, "vertex {v}");
    }
    let floor = levels(0.0001);
    assert_eq!(floor.primitives.len(), 2, "{:?}", floor.primitives);
    assert!(floor.distance.expect("measured") <= 1.01 * got);
    assert_eq!(
        floor.shortfall,
        Some(crate::output::result::Shortfall::Faces)
    );
}

/// Mismatched lists and fill with a cut are refused with a message naming them.
#[test]
fn limits_are_validated() {
    let two = Params {
        goal: Goal::Within {
            caps: vec![10, 20, 30],
            tolerance: vec![Tolerance::Diagonal(0.01); 2],
            max_bytes: vec![],
        },
        ..Params::default()
    };
    let e = two.validate().unwrap_err().to_string();
    assert!(e.contains("tolerance has 2 values for 3 targets"), "{e}");
    let zero = Params {
        goal: Goal::Within {
            caps: vec![],
            tolerance: vec![Tolerance::Units(0.0)],
            max_bytes: vec![],
        },
        ..Params::default()
    };
    assert!(zero.validate().is_err());
    let fill = Params::from_json(r#"{"max_bytes": [100], "fill": true}"#);
    assert!(fill.unwrap_err().to_string().contains("fill"));
}

/// The largest of a level's primitives' bounds, each alone, in the input's frame.
fn worst_error(mesh: &crate::input::mesh::Mesh, prims: &[Primitive]) -> f64 {
    let surface = Triangles::new(mesh);
    let back = mesh.offset.map(|x| -x);
    prims
        .iter()
        .map(|p| error_of(&p.translated(back), &surface))
        .fold(0.0, f64::max)
}

/// On the demo scene (several separate objects) cut at 4, 16 and 64 from one pass:
/// at most N primitives each, every input vertex inside one of them (any cut
/// encloses the mesh), and a larger N never stands farther from the input than a
/// smaller one (up to the post-processing's plate joins, within the floor).
#[test]
fn cuts_enclose_and_improve_with_n() {
    let mesh = crate::input::demo::demo_scene();
    let p = Params {
        goal: Goal::Cut {
            counts: vec![4, 16, 64],
        },
        ..Params::default()
    };
    let d = decompose(&mesh, &p).expect("decomposes");
    let tol = 1e-9 * mesh.diagonal();
    let mut errors = Vec::new();
    for level in &d.levels {
        assert!(
            level.primitives.len() <= level.target,
            "{}",
            level.primitives.len()
        );
        for v in 0..mesh.vertex_count() as u32 {
            let w = crate::math::add(mesh.pos(v), mesh.offset);
            assert!(
                level.primitives.iter().any(|q| q.contains(w, tol)),
                "vertex {v}"
            );
        }
        errors.push(worst_error(&mesh, &level.primitives));
    }
    let floor = FLOOR_HALVES * p.fit.min_extent * mesh.diagonal();
    assert!(errors[0] > errors[2], "{errors:?}: the cut never helped");
    assert!(
        errors.windows(2).all(|w| w[1] <= w[0] + floor),
        "{errors:?}"
    );
}

/// The greedy snapshot and the cut agree at one primitive per tree root: with a
/// target of one, both are the whole scene's single primitive.
#[test]
fn one_target_is_the_root() {
    let mesh = crate::input::demo::demo_scene();
    let greedy = Params {
        goal: Goal::counts([1]),
        ..Params::default()
    };
    let cut = Params {
        goal: Goal::Cut { counts: vec![1] },
        ..greedy.clone()
    };
    let a = decompose(&mesh, &greedy).expect("greedy");
    let b = decompose(&mesh, &cut).expect("cut");
    assert_eq!(a.levels[0].primitives, b.levels[0].primitives);
}

/// Fitting ahead of the worst-first splits ([`Cutter::ahead`], and the next splits'
/// children, `Cutter::fit_next`) changes no cut: the same levels with it and without
/// it, on one thread, two and three, where every node over the tolerance is split
/// (2% at 400 nodes) and where the count runs out first (0.2% at 40: the rounds stop
/// short, and the splits go on from what they fitted).
#[test]
fn fitting_ahead_changes_no_cut() {
    for (targets, tolerance) in [(400, 0.02), (40, 0.002)] {
        same_cuts_fitting_ahead(targets, tolerance);
    }
}

fn same_cuts_fitting_ahead(count: usize, tolerance: f64) {
    let mesh = crate::input::demo::demo_scene();
    let p = Params {
        goal: Goal::Within {
            caps: vec![count; 3],
            tolerance: vec![
                Tolerance::Diagonal(0.05),
                Tolerance::Diagonal(tolerance * 2.0),
                Tolerance::Diagonal(tolerance),
            ],
            max_bytes: vec![],
        },
        ..Params::default()
    };
    let run = |threads: usize, off: bool| levels_with(&mesh, &p, threads, (&AHEAD_OFF, off));
    let serial = run(1, true);
    let capped = (count < 400).then_some(crate::output::result::Shortfall::Count);
    assert_eq!(serial[2].shortfall, capped, "{count}");
    for (threads, off) in [(1, false), (2, false), (2, true), (3, false)] {
        let levels = run(threads, off);
        for (a, b) in serial.iter().zip(&levels) {
            assert_eq!(a.primitives, b.primitives, "{threads} threads, off {off}");
            assert_eq!(a.distance, b.distance, "{threads} threads, off {off}");
        }
    }
}

/// A count or byte cap is spent on what post-processing keeps: nested primitives it
/// removes free their share, which the cut spends again (docs/decisions/0044; the
/// cut counted them, and a level of 1000 bytes came back with 664). On the demo
/// scene, byte targets come within two primitives' bytes of the target, and a cut
/// of 40 keeps at least 36 primitives (it kept 28); none over its cap.
#[test]
fn caps_are_spent_on_what_post_processing_keeps() {
    let mesh = crate::input::demo::demo_scene();
    let most = crate::primitive::Kind::ALL
        .iter()
        .map(|k| k.bytes())
        .max()
        .unwrap_or(0);
    for bytes in [600, 1000, 2000] {
        let p = Params {
            goal: Goal::Within {
                caps: vec![1024],
                tolerance: vec![],
                max_bytes: vec![bytes],
            },
            ..Params::default()
        };
        let l = &decompose(&mesh, &p).expect("decomposes").levels[0];
        let got = l.bytes();
        assert!(got <= bytes && got + 2 * most > bytes, "{bytes}: {got}");
        assert_eq!((l.target, l.max_bytes), (1024, Some(bytes)));
    }
    let p = Params {
        goal: Goal::Cut { counts: vec![40] },
        ..Params::default()
    };
    let l = &decompose(&mesh, &p).expect("decomposes").levels[0];
    let n = l.primitives.len();
    assert!((36..=40).contains(&n), "{n}");
    assert_eq!(l.target, 40);
}

/// A group's fit kept from an earlier exploration ([`Cutter::group_fits`]) is the fit
/// that would be made again: on a city block of 400 separate parts at 20 primitives,
/// whose cuts halve the same groups of parts in each exploration, the levels are the
/// same with nothing kept, on one thread and two, and kept fits were given back.
#[test]
fn groups_fits_kept_change_no_cut() {
    use std::sync::atomic::Ordering::Relaxed;
    let dir = std::env::temp_dir().join(format!("primdecomp-group-fits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    let path = dir.join("city.ply");
    primdecomp_testkit::ladder::city_block_ply(400, 1, &path).expect("writes the block");
    let mesh = crate::input::mesh::Mesh::load(&path).expect("loads the block");
    std::fs::remove_dir_all(&dir).expect("removes the folder");
    let p = Params {
        goal: Goal::Counts { counts: vec![20] },
        ..Params::default()
    };
    let run = |threads: usize, off: bool| levels_with(&mesh, &p, threads, (&GROUP_FITS_OFF, off));
    let fresh = run(2, true);
    let before = GROUP_FITS_REUSED.load(Relaxed);
    for threads in [1, 2] {
        let levels = run(threads, false);
        assert_eq!(
            fresh[0].primitives, levels[0].primitives,
            "{threads} threads"
        );
        assert_eq!(fresh[0].distance, levels[0].distance, "{threads} threads");
    }
    assert!(
        GROUP_FITS_REUSED.load(Relaxed) > before,
        "no group's fit was kept"
    );
}

/// The levels of `mesh` with `p` on `threads` threads, with a test switch of the
/// cutter's set to `off` during the run.
fn levels_with(
    mesh: &crate::input::mesh::Mesh,
    p: &Params,
    threads: usize,
    (switch, off): (&std::sync::atomic::AtomicBool, bool),
) -> Vec<crate::output::result::Level> {
    use std::sync::atomic::Ordering::Relaxed;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool");
    switch.store(off, Relaxed);
    let d = pool.install(|| decompose(mesh, p)).expect("decomposes");
    switch.store(false, Relaxed);
    d.levels
}
