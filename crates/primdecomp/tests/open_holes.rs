//! `Params::merge_min_extent_rel` (`--merge-min-extent`): merges priced as if every
//! primitive were at least that thick, output primitives as thin as `min_extent`;
//! `Plates::open_holes` (`--flat-merge-extent`): the same for merges of
//! coplanar clusters only.

use primdecomp::{decompose, demo_scene, Error, Goal, Mesh, Params, Plates};
use primdecomp_testkit::check::assert_valid;
use primdecomp_testkit::corpus_mesh;

/// Whether a primitive covers the point just under the AABB's top (a roof rim's top),
/// above its centre; the primitives are in the file's coordinates, like the AABB.
fn roof_centre_covered(mesh: &Mesh, p: &Params) -> bool {
    let d = decompose(mesh, p).expect("decomposes");
    let (lo, hi) = (d.input.aabb_min, d.input.aabb_max);
    let probe = [0.5 * (lo[0] + hi[0]), hi[1] - 5e-4, 0.5 * (lo[2] + hi[2])];
    d.levels[0]
        .primitives
        .iter()
        .any(|p| p.contains(probe, 0.0))
}

/// The greedy pass's level, whose coplanar pricing this measures (a count on several
/// parts is otherwise a cut of the merge tree: docs/decisions/0054).
fn with_flat(target: usize, flat: f64) -> Params {
    Params {
        goal: Goal::Greedy {
            counts: vec![target],
        },
        plates: Plates {
            open_holes: flat,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// The coplanar-only floor keeps both measured roof rims open
/// (docs/decisions/0018-coplanar-merges-priced-thicker.md): kenney_building_small_a.glb at N = 64
/// (V-HACD's hull
/// count) and kenney_building_garage.glb at N = 32 (CoACD's) close their rims into
/// lids without it, and balls roll off (similarity 0.007 and 0.008); priced at
/// 0.005 × diagonal or the default 0.01, the rims' holes cost more than the merges
/// left at those counts.
#[test]
fn flat_floor_keeps_roof_rims_open() {
    for (name, n) in [
        ("kenney_building_small_a.glb", 64),
        ("kenney_building_garage.glb", 32),
    ] {
        let Some(mesh) = corpus_mesh(name) else {
            return;
        };
        let covered = |flat| roof_centre_covered(&mesh, &with_flat(n, flat));
        assert!(covered(0.0), "{name}: the lid did not form");
        assert!(
            !covered(0.005),
            "{name}: the rim closed into a lid at 0.005"
        );
        assert!(
            !covered(0.01),
            "{name}: the rim closed into a lid by default"
        );
    }
}

/// Every face stays enclosed with the coplanar-only floor (independent containment
/// routine), on the demo scene at two targets; bad values are refused.
#[test]
fn flat_floor_keeps_enclosure_and_refuses_bad_values() {
    let mesh = demo_scene();
    let mut p = with_flat(120, 0.02);
    p.goal = Goal::counts([120, 30]);
    let d = decompose(&mesh, &p).expect("decomposes");
    assert_valid(&mesh, &d, &p);
    for bad in [-1e-3, 1.0, f64::NAN, f64::INFINITY] {
        let r = with_flat(4, bad).validate();
        assert!(matches!(r, Err(Error::InvalidParams(_))), "{bad}: {r:?}");
    }
}
