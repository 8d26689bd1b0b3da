//! Tolerance and byte targets cut from the merge tree
//! (docs/decisions/0032): simple solids need no count, every level encloses the mesh
//! (checked by testkit's independent containment routine), a chain of tolerances
//! comes from one pass, and on a multi-part corpus mesh a larger count never stands
//! farther from the input.

use primdecomp::{decompose, Goal, Kind, Params, Tolerance};
use primdecomp_testkit::check::assert_valid;
use primdecomp_testkit::shapes::{cuboid, cylinder, join, mesh, uv_sphere};

fn within(t: f64, cap: usize) -> Params {
    Params {
        goal: Goal::Within {
            caps: vec![cap],
            tolerance: vec![Tolerance::Diagonal(t)],
            max_bytes: vec![],
        },
        ..Params::default()
    }
}

/// What a user asking for "a collider for this mesh" gets, at 1% of its size and with
/// no target at all (the default tolerance, docs/decisions/0037): one box for a box,
/// one sphere for a sphere, one cylinder for a closed cylinder — where a count of 64
/// gives plates and slices.
#[test]
fn simple_solids_are_one_primitive() {
    let cases = [
        (
            "box",
            mesh(&cuboid([-1.0, -2.0, -0.5], [1.0, 2.0, 0.5])),
            Kind::Box,
        ),
        ("sphere", mesh(&uv_sphere(1.0, 24, 48)), Kind::Sphere),
        ("cylinder", mesh(&cylinder(0.5, 2.0, 48)), Kind::Cylinder),
    ];
    for (name, m, kind) in cases {
        for p in [within(0.01, 1024), Params::default()] {
            let d = decompose(&m, &p).expect("decomposes");
            let l = &d.levels[0];
            let kinds: Vec<Kind> = l.primitives.iter().map(|p| p.kind()).collect();
            assert_eq!(kinds, vec![kind], "{name} {:?}", p.goal);
            assert!(l.distance.expect("measured") <= l.tolerance.expect("asked"));
            assert_valid(&m, &d, &p);
        }
        let counted = Params {
            goal: Goal::counts([64]),
            ..Params::default()
        };
        let plates = decompose(&m, &counted).expect("decomposes");
        assert!(plates.levels[0].primitives.len() > 1, "{name} at -n 64");
    }
}

/// Three separate solids side by side, with a tolerance chain and a byte target:
/// every level encloses every face, tighter tolerances never give fewer primitives,
/// each level is within its tolerance, and the byte target holds.
#[test]
fn chains_and_byte_targets_enclose() {
    let scene = mesh(&join(&[
        cuboid([0.0, 0.0, 0.0], [1.0, 0.2, 1.0]),
        cylinder(0.3, 1.5, 32),
        uv_sphere(0.4, 12, 24),
    ]));
    let p = Params {
        goal: Goal::Within {
            caps: vec![200, 200, 200],
            tolerance: vec![
                Tolerance::Diagonal(0.05),
                Tolerance::Diagonal(0.02),
                Tolerance::Diagonal(0.005),
            ],
            max_bytes: vec![4096],
        },
        ..Params::default()
    };
    let d = decompose(&scene, &p).expect("decomposes");
    assert_valid(&scene, &d, &p);
    let counts: Vec<usize> = d.levels.iter().map(|l| l.primitives.len()).collect();
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    for l in &d.levels {
        assert!(l.bytes() <= 4096, "{} bytes", l.bytes());
        let (got, t) = (l.distance.expect("measured"), l.tolerance.expect("asked"));
        assert!(
            got <= t,
            "{got} over {t} ({} primitives)",
            l.primitives.len()
        );
    }
}

/// engine_2cylinder (hundreds of separate parts) cut at 16, 64 and 256 from one
/// pass: every level encloses the mesh and a larger count never stands farther from
/// it (the recorded distance, the same estimate for every level).
#[test]
fn multi_part_mesh_improves_with_count() {
    let Some(m) = primdecomp_testkit::corpus_mesh("engine_2cylinder.glb") else {
        return;
    };
    let p = Params {
        goal: Goal::Cut {
            counts: vec![16, 64, 256],
        },
        ..Params::default()
    };
    let d = decompose(&m, &p).expect("decomposes");
    assert_valid(&m, &d, &p);
    let dist: Vec<f64> = d.levels.iter().map(|l| l.distance.expect("cut")).collect();
    assert!(dist.windows(2).all(|w| w[1] <= w[0]), "{dist:?}");
    assert!(dist[2] < dist[0], "{dist:?}");
}

/// Joining coplanar plates after the cut must keep the level's tolerance
/// (docs/decisions/0038): on these two corpus meshes the cut's nodes were all within
/// 2% but one or two plate joins made a plate covering an opening, and the level
/// stood 2.73% (kenney_building_garage) and 3.79% (cad_plate_holes) from the input.
/// The default run must report its distance within its tolerance, and enclose.
#[test]
fn plate_joins_keep_the_tolerance() {
    for name in ["kenney_building_garage.glb", "cad_plate_holes.STL"] {
        let Some(m) = primdecomp_testkit::corpus_mesh(name) else {
            return;
        };
        let p = Params::default();
        let d = decompose(&m, &p).expect("decomposes");
        let l = &d.levels[0];
        let (got, t) = (l.distance.expect("measured"), l.tolerance.expect("asked"));
        assert!(got <= t, "{name}: {got} over the tolerance {t}");
        assert_valid(&m, &d, &p);
    }
}

/// Regression (docs/decisions/0048): kitchenaid_mixer cut at 16 alone came back as 4
/// primitives (7 nodes before nested ones were removed), 9.49% of the diagonal from
/// it. The worst-first exploration spent its splits on the worst node's subtree, a
/// chain that splits no nearer, raising the count explored the same chain, and the
/// cut had no other split to fill the count with. The rest of the count must go to
/// the cut's other nodes: now 15 nodes, 12 primitives once 3 nested in others are
/// removed (that count is the pipeline's nested-removal, not the cut's), no farther
/// than 1.25 times 9.49%: a count's cut may stand that much farther than its least
/// worst error to spend the rest on the mean (docs/decisions/0051; here the loose
/// cut, 16 primitives at 10.09%, stood no nearer on the mean, so 16 at 9.08%).
#[test]
fn a_count_is_filled_where_the_worst_node_splits_no_nearer() {
    let Some(m) = primdecomp_testkit::corpus_mesh("kitchenaid_mixer.obj") else {
        return;
    };
    let got = cut_at(&m, &[16]);
    assert!(got[0].0 >= 12 && got[0].1 <= 1.25 * 0.0950, "{got:?}");
}

/// `m` cut at `counts` from one pass, checked valid: each level's primitives and
/// declared distance over the diagonal.
fn cut_at(m: &primdecomp::Mesh, counts: &[usize]) -> Vec<(usize, f64)> {
    let p = Params {
        goal: Goal::Cut {
            counts: counts.to_vec(),
        },
        ..Params::default()
    };
    let d = decompose(m, &p).expect("decomposes");
    assert_valid(m, &d, &p);
    let diagonal = m.diagonal();
    let level =
        |l: &primdecomp::Level| (l.primitives.len(), l.distance.expect("measured") / diagonal);
    d.levels.iter().map(level).collect()
}

/// A hall: a floor, four walls, no roof, and 49 crates on the floor.
fn hall() -> primdecomp::Mesh {
    let (l, h, t) = (10.0, 4.0, 0.2);
    let mut parts = vec![
        cuboid([0.0, 0.0, 0.0], [l, t, l]),
        cuboid([0.0, 0.0, 0.0], [t, h, l]),
        cuboid([l - t, 0.0, 0.0], [l, h, l]),
        cuboid([0.0, 0.0, 0.0], [l, h, t]),
        cuboid([0.0, 0.0, l - t], [l, h, l]),
    ];
    for i in 0..7 {
        for j in 0..7 {
            let (x, z) = (1.0 + 1.2 * i as f64, 1.0 + 1.2 * j as f64);
            let top = t + 0.3 + 0.1 * ((i * 3 + j) % 4) as f64;
            parts.push(cuboid([x, t, z], [x + 0.5, top, z + 0.5]));
        }
    }
    mesh(&join(&parts))
}

/// Regression (docs/decisions/0049): a hall of crates cut at 8 came back as one box,
/// 23.7% of the diagonal from the floor it spans. The pass merges each crate into
/// the hall's box at no cost, so the tree is a chain of crates; splitting it counted
/// a node per crate, and the crates one wall's split let out came out together, past
/// the count. Now crates inside a primitive are carried by it, a chain is walked
/// down at once, and the crates a split lets out come out as one group: the walls,
/// the floor and the crates, within 6%.
#[test]
fn a_hall_of_crates_cut_at_eight_stands_its_walls_apart() {
    let got = cut_at(&hall(), &[8]);
    assert!(got[0].0 >= 5 && got[0].1 <= 0.06, "{got:?}");
}

/// Regression (docs/decisions/0049): samurai_monastery cut at 64 and 256 came back
/// as 27 and 36 primitives, both 6.83% of the diagonal from it: its buildings'
/// boxes are chains of parts inside them, which post-processing removed as nested
/// after the cut had counted them. With carried parts and groups, the counts are
/// used and a larger one stands nearer.
#[test]
fn a_multi_part_scene_uses_its_counts() {
    let Some(m) = primdecomp_testkit::corpus_mesh("samurai_monastery.obj") else {
        return;
    };
    let got = cut_at(&m, &[64, 256]);
    assert!(got[0].0 >= 48 && got[0].1 <= 0.06, "{got:?}");
    assert!(got[1].0 >= 200 && got[1].1 <= 0.03, "{got:?}");
}

/// Regression: cad_cycloidal's first cut of 256 nodes has 107 inside one cylinder
/// node that is not their ancestor (post-processing removes them), and the raised
/// count's round gained 21 of its 108 primitives, under the quarter the raises once
/// stopped at: 169 primitives at 1.50% of the diagonal. At least 240 must be kept now
/// (the raises go on to 253 at 1.44%).
#[test]
fn nodes_nested_across_subtrees_give_their_count_back() {
    let Some(m) = primdecomp_testkit::corpus_mesh("cad_cycloidal.ply") else {
        return;
    };
    let got = cut_at(&m, &[256]);
    assert!(got[0].0 >= 240 && got[0].1 <= 0.015, "{got:?}");
}
