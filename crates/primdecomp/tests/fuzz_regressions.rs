//! Inputs the fuzzers (`fuzz/`) found to break an invariant, each reduced to a test
//! that failed before its fix. The comment on each says what must happen and why.

use primdecomp::{decompose, Dedup, Error, Fit, Goal, Kind, Mesh, Params, Plates};
use primdecomp_testkit::check::assert_valid;

/// `fuzz/fuzz_targets/decompose.rs`, first run: one triangle at a 1e-30 scale welded
/// with a tolerance of 10 collapsed to one point, and the output sphere was fitted
/// around the welded point only, missing the face's other corner. Output primitives
/// must enclose the faces as given, whatever the weld did to the topology.
#[test]
fn tolerance_weld_does_not_shrink_the_output() {
    let v = [[1e-30, -1e-30, 0.0], [0.0, -1e-30, 2e-30]];
    let mesh = Mesh::from_polygons(&v, &[vec![0, 1, 1]]).unwrap();
    let params = Params {
        goal: Goal::counts([27]),
        fit: Fit {
            dedup: Dedup::Tolerance(10.0),
            ..Default::default()
        },
        ..Default::default()
    };
    assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
}

/// The same at ordinary scale: a strip of triangles 10 long whose vertices are 0.5
/// apart, welded with tolerance 0.6, merges transitively into one vertex group. Every
/// triangle must still lie inside an output primitive.
#[test]
fn transitive_tolerance_weld_keeps_every_face_enclosed() {
    let mut v = Vec::new();
    let mut f = Vec::new();
    for i in 0..=20 {
        v.push([0.5 * i as f64, 0.0, 0.0]);
        v.push([0.5 * i as f64, 0.5, 0.0]);
    }
    for i in 0..20u32 {
        f.push(vec![2 * i, 2 * i + 2, 2 * i + 1]);
        f.push(vec![2 * i + 1, 2 * i + 2, 2 * i + 3]);
    }
    let mesh = Mesh::from_polygons(&v, &f).unwrap();
    for n in [40, 4, 1] {
        let params = Params {
            goal: Goal::counts([n]),
            fit: Fit {
                dedup: Dedup::Tolerance(0.6),
                ..Default::default()
            },
            ..Default::default()
        };
        assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
        // The merge tree's cut too, whose nodes' points must be the faces' own, not
        // the welded ones the merge loop priced them by (docs/decisions/0052).
        let cut = Params {
            goal: Goal::Cut { counts: vec![n] },
            ..params
        };
        assert_valid(&mesh, &decompose(&mesh, &cut).unwrap(), &cut);
    }
}

/// `fuzz/fuzz_targets/decompose.rs`, second run (finding 3): one hexagon-shaped face
/// 5e-6 across at an offset of 8.5e6 (where f64 spacing is 1.9e-9) became one frustum
/// whose axis was about one ulp of the offset long. Moving it back to world
/// coordinates rounded each end point by up to half an ulp, tilting the axis so far
/// that the face's far corners fell outside the end caps. The world primitive must
/// still enclose the face.
#[test]
fn thin_frustum_far_from_the_origin_keeps_its_face() {
    // The fuzzer's grid: corner c × 1e-6 + 85 × 1e5 on every axis.
    let at = |c: [f64; 3]| c.map(|k| k * 1e-6 + 85.0 * 1e5);
    let v = [
        at([0.0, 2.0, 0.0]),
        at([5.0, 0.0, 0.0]),
        at([5.0, 0.0, 5.0]),
    ];
    let mesh = Mesh::from_polygons(&v, &[vec![0, 1, 2, 2, 2, 2]]).unwrap();
    let params = Params {
        goal: Goal::counts([18]),
        fit: Fit {
            weights: [1.0, 1.4, 2.1, 1.05, 1e-9, 1.0],
            tangent_eps: 1000.0,
            dedup: Dedup::Off,
            ..Default::default()
        },
        ..Default::default()
    };
    let dec = decompose(&mesh, &params).unwrap();
    assert_eq!(dec.levels[0].counts()[Kind::Frustum as usize], 1);
    assert_valid(&mesh, &dec, &params);
}

/// A regular 64-gon of radius 0.5, tilted off every axis, `n` of them side by side
/// `gap` apart, moved by `offset`.
fn tilted_discs(n: usize, gap: f64, offset: f64) -> Mesh {
    let (u, w) = ([0.6, 0.8, 0.0], [-0.48, 0.36, 0.8]);
    let mut v = Vec::new();
    let mut f: Vec<Vec<u32>> = Vec::new();
    for d in 0..n {
        let first = v.len() as u32;
        for i in 0..64 {
            let t = i as f64 / 64.0 * std::f64::consts::TAU;
            let (c, s) = (0.5 * t.cos(), 0.5 * t.sin());
            v.push([0, 1, 2].map(|k| offset + gap * d as f64 + c * u[k] + s * w[k]));
        }
        f.push((first..first + 64).collect());
    }
    Mesh::from_polygons(&v, &f).unwrap()
}

fn round_only(kind: Kind, targets: Vec<usize>, min_extent: f64) -> Params {
    let mut kinds = [false; 6];
    kinds[kind as usize] = true;
    Params {
        goal: Goal::counts(targets),
        fit: Fit {
            kinds,
            min_extent,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// The same loss of the axis at ordinary sizes: a flat disc 1 across at 8.5e6 with a
/// minimum extent of 1e-6 of the diagonal gets cylinders and frustums about 3e-6 long,
/// under 2,000 ulps of their position, and rounding tilts the axis by up to 1e-3: the
/// rim, 0.5 from the axis, would move 5e-4 along it, far beyond the 1.5e-6 tolerance.
/// The error grows with radius over length, so no minimum length alone removes it.
#[test]
fn flat_discs_far_from_the_origin_stay_enclosed() {
    cylinders_and_frustums_enclose(&tilted_discs(1, 0.0, 8.5e6), 1, 1e-6);
}

/// Without any offset the local frame rounds too: two discs 100 apart are re-centred
/// to ±50, and with a minimum extent of 1e-14 of the diagonal each disc's primitive is
/// about 2e-12 long against end points of magnitude 50 (ulp 7e-15). Both must stay
/// enclosed.
#[test]
fn near_zero_length_axes_stay_enclosed_at_the_origin() {
    cylinders_and_frustums_enclose(&tilted_discs(2, 100.0, 0.0), 2, 1e-14);
}

/// Decomposes `mesh` to `n` with only cylinders, then only frustums, and checks both.
fn cylinders_and_frustums_enclose(mesh: &Mesh, n: usize, min_extent: f64) {
    for kind in [Kind::Cylinder, Kind::Frustum] {
        let params = round_only(kind, vec![n], min_extent);
        assert_valid(mesh, &decompose(mesh, &params).unwrap(), &params);
    }
}

/// Decomposes `mesh` and checks that its first target is reached as one valid primitive.
fn merges_to_one(mesh: &Mesh, params: &Params) {
    let dec = decompose(mesh, params).unwrap();
    assert_eq!(dec.levels[0].primitives.len(), 1);
    assert_valid(mesh, &dec, params);
}

/// `fuzz/fuzz_targets/decompose.rs`, third run: two 8-corner faces on one vertex
/// (dedup off, so no shared edge) gave 2 primitives for a target of 1. With a zero
/// diagonal every volume and the cost grid (2^-40 of the diagonal cubed, with the
/// minimum half-extent of a point mesh then 1.5e-154) underflowed to 0, every merge
/// cost 0/0 = NaN, and NaN-priced merges are dropped like those over
/// the excess cap, so nothing could merge (post-processing hid it when it removed the
/// duplicate, so that is off here). Every target must be reached by merging.
#[test]
fn faces_on_one_point_still_merge() {
    let v = [[1e-30, -1e-30, -1e-30]];
    let mut f = vec![vec![0; 8], vec![0; 8]];
    f.extend(std::iter::repeat_n(vec![0], 14)); // skipped: fewer than 3 corners
    let mesh = Mesh::from_polygons(&v, &f).unwrap();
    let mut kinds = [false; 6];
    kinds[Kind::Box as usize] = true;
    kinds[Kind::Prism as usize] = true;
    let params = Params {
        goal: Goal::counts([1, 3]),
        fit: Fit {
            weights: [1e-9, 2.1, 1e-9, 1.0, 1.0, 1.0],
            kinds,
            dedup: Dedup::Off,
            ..Default::default()
        },
        plates: Plates {
            remove_nested: false,
            ..Default::default()
        },
        ..Default::default()
    };
    merges_to_one(&mesh, &params);
}

/// The same underflow with a positive diagonal: two triangles 1e-200 across (a cube
/// of 1e-600 is 0 in f64) in separate components must still merge down to one.
#[test]
fn meshes_1e_minus_200_across_still_merge() {
    let s = 1e-200;
    let v = [
        [0.0, 0.0, 0.0],
        [s, 0.0, 0.0],
        [0.0, s, 0.0],
        [3.0 * s, 0.0, s],
        [4.0 * s, 0.0, s],
        [3.0 * s, s, 2.0 * s],
    ];
    let mesh = Mesh::from_polygons(&v, &[vec![0, 1, 2], vec![3, 4, 5]]).unwrap();
    let params = Params {
        goal: Goal::counts([1]),
        plates: Plates {
            remove_nested: false,
            ..Default::default()
        },
        ..Default::default()
    };
    merges_to_one(&mesh, &params);
}

/// `fuzz/fuzz_targets/decompose.rs`, fourth run: one face on a single vertex at
/// z = -4.3e304 became a frustum whose padded ends (so that rounding cannot tilt its
/// axis, `primitive::world`) were computed with a square that overflowed: the JSON got
/// an infinite coordinate. Pads of ~1e-13 × coordinates that large are themselves
/// lengths whose squares overflow, so such inputs are refused (`Error::Position`,
/// beyond ±1e70), and inputs just inside the limit give finite, enclosing output.
#[test]
fn coordinates_near_the_top_of_f64_are_refused() {
    let v = [[5.391989341715902e68, 0.0, -4.294604791590196e304]];
    let mesh = Mesh::from_polygons(&v, &[vec![0; 8]]).unwrap();
    let params = Params {
        goal: Goal::counts([37]),
        fit: Fit {
            weights: [1.0, 1.0, 1.0, 1.0, 1e-9, 1e9],
            kinds: [false, true, true, false, true, true],
            tangent_eps: 0.0,
            ..Default::default()
        },
        ..Default::default()
    };
    match decompose(&mesh, &params) {
        Err(Error::Position {
            vertex,
            coordinate,
            limit,
            ..
        }) => assert_eq!(
            (vertex, coordinate, limit),
            (1, -4.294604791590196e304, 1e70)
        ),
        other => panic!("expected Error::Position, got {other:?}"),
    }
    for z in [1e70, -1e70, 9.9e69] {
        let v = [[0.0, 0.0, z], [0.0, 1e55, z], [0.0, 0.0, z]];
        let mesh = Mesh::from_polygons(&v, &[vec![0, 1, 2], vec![0, 0, 0]]).unwrap();
        for kind in [Kind::Frustum, Kind::Cylinder] {
            let params = round_only(kind, vec![1], 5e-4);
            assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
        }
    }
}

/// `fuzz/fuzz_targets/decompose.rs`, fifth run: two vertices 6e-22 apart with a minimum
/// extent of 6.8e-304 of the diagonal: the minimum half-extent underflowed to 0, a
/// degenerate axis got half-length 0, and the frustum fit computed 0/0 and panicked in
/// `clamp`. Every fit needs a positive minimum half-extent, however small the mesh and
/// the setting.
#[test]
fn minimum_extent_that_underflows_stays_positive() {
    let v = [[-1.2e9, 2e9, 0.0], [-1.2e9, 2e9, 6e-22]];
    let f = vec![vec![1, 1, 1, 0, 1, 1, 0, 1], vec![0; 5], vec![0; 8]];
    let mesh = Mesh::from_polygons(&v, &f).unwrap();
    let params = Params {
        goal: Goal::counts([15]),
        fit: Fit {
            weights: [1.0, 1e-9, 1.0, 1.0, 1.0, 1.0],
            dedup: Dedup::Off,
            min_extent: 6.833639853623446e-304,
            ..Default::default()
        },
        ..Default::default()
    };
    assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
    for kind in Kind::ALL {
        let params = round_only(kind, vec![1], 6.833639853623446e-304);
        assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
    }
}

/// `fuzz/fuzz_targets/decompose.rs`, sixth run: one zero-area face on a vertex at the
/// origin (diagonal 0, coordinates 0, so the enclosure tolerance is 0) became a box of
/// half-extent 2.2e-308 (the previous floor, the smallest normal number). The box was
/// right, but the oracle's grid took the reciprocal of a subnormal extent, got
/// infinity and found no candidate. The floor is now 1e-90, whose cube and reciprocal
/// square are normal, so downstream arithmetic on the primitives stays finite.
#[test]
fn a_face_on_the_origin_gets_a_normal_sized_primitive() {
    let mesh = Mesh::from_polygons(&[[0.0; 3]], &[vec![0, 0, 0]]).unwrap();
    let params = Params {
        goal: Goal::counts([39]),
        fit: Fit {
            max_excess_volume: Some(0.0),
            weights: [1.05, 1.0, 1.05, 1.4, 1e-9, 1.4],
            kinds: [true, true, true, true, false, true],
            dedup: Dedup::Off,
            min_extent: 0.5,
            ..Default::default()
        },
        // A cap re-prices every merge at once (the run it came from did so implicitly).
        reprice: primdecomp::Reprice::Exact,
        ..Default::default()
    };
    assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
}

/// `fuzz/fuzz_targets/decompose.rs`, seventh run: with `--remove-thin-boxes`, a thin
/// box was removed because each of its corners lay in some other primitive, but one
/// of its faces had corners in two different primitives and lay in neither: 3 faces,
/// 2 primitives, one face outside. A removed box's faces must each lie in one kept
/// primitive.
#[test]
fn thin_box_removal_keeps_every_face_in_one_primitive() {
    let v = [
        [6.000000000000001e17, 6.000000000000001e17, 70.0],
        [6.000000000000001e17, 70.0, 70.0],
        [70.0, 1.0000000000000006e17, 3.0000000000000006e17],
        [
            5.0000000000000006e17,
            6.000000000000001e17,
            4.0000000000000006e17,
        ],
        [5.0000000000000006e17, 6.000000000000001e17, 70.0],
        [70.0, 4.0000000000000006e17, 70.0],
        [
            3.0000000000000006e17,
            3.0000000000000006e17,
            3.0000000000000006e17,
        ],
    ];
    let f = vec![
        vec![3, 3, 3, 1, 1, 1, 2, 2],
        vec![3, 3, 3, 3, 3, 3, 2, 0],
        vec![0; 8],
    ];
    let mesh = Mesh::from_polygons(&v, &f).unwrap();
    let params = Params {
        goal: Goal::counts([27]),
        fit: Fit {
            weights: [1.0, 1e-9, 1e-9, 1.05, 1.05, 1.05],
            kinds: [true, false, true, false, true, false],
            dedup: Dedup::Off,
            min_extent: 1e-12,
            ..Default::default()
        },
        plates: Plates {
            remove_nested: false,
            remove_thin_boxes: Some(0.001),
            ..Default::default()
        },
        ..Default::default()
    };
    assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
}

/// `fuzz/fuzz_targets/decompose.rs`, run 13: a face collapsed to one point
/// (4e25, 4e25, -1e25) among 21 vertices at the 1e25 scale, with a subnormal minimum
/// extent and thin-box removal, was left outside every output primitive at target 23.
/// Every face, degenerate or not, must lie in one output primitive.
#[test]
fn point_face_at_1e25_stays_enclosed() {
    let v = [
        [4e25, 4e25, 4e25],
        [4e25, 4e25, 4e25],
        [4e25, 4e25, 4e25],
        [4e25, 4e25, -1e25],
        [
            -3.0000000000000005e25,
            3.0000000000000005e25,
            3.0000000000000005e25,
        ],
        [-1e25, 5e25, 4e25],
        [116000000.0, -1e25, 6.000000000000001e25],
        [-1e25, -1e25, -1e25],
        [-1e25, -7.000000000000001e25, 116000000.0],
        [1e25, 1e25, -1e25],
        [3.0000000000000005e25, 1e25, 4e25],
        [1e25, 6.000000000000001e25, 4e25],
        [5e25, -5e25, -5e25],
        [116000000.0, 5e25, 6.000000000000001e25],
        [-4e25, -6.000000000000001e25, -4e25],
        [116000000.0, -7.000000000000001e25, 2e25],
        [6.000000000000001e25, 6.000000000000001e25, 4e25],
        [4e25, 4e25, 4e25],
        [4e25, 4e25, 4e25],
        [116000000.0, 3.0000000000000005e25, 5e25],
        [
            6.000000000000001e25,
            6.000000000000001e25,
            6.000000000000001e25,
        ],
    ];
    let f = vec![
        vec![2, 2, 2, 2, 2, 11, 11],
        vec![11, 11, 11, 2, 2],
        vec![2; 8],
        vec![2; 8],
        vec![2, 16, 2, 2, 2, 2, 2, 2],
        vec![2; 8],
        vec![2, 2, 13, 2, 2, 2, 2, 2],
        vec![2; 8],
        vec![3; 8],
        vec![3, 3, 0, 20, 1, 2, 17, 16],
        vec![2],
        vec![13, 13, 13, 13, 4, 17, 0],
        vec![13, 15],
        vec![3, 0],
        vec![16, 17, 16, 16, 0, 9, 20],
    ];
    let mesh = Mesh::from_polygons(&v, &f).unwrap();
    let params = Params {
        goal: Goal::counts([23, 13, 17]),
        fit: Fit {
            weights: [1.0; 6],
            tangent_eps: 1.0,
            min_extent: 1.26e-321,
            ..Default::default()
        },
        plates: Plates {
            open_holes: 0.0,
            remove_thin_boxes: Some(0.1),
            ..Default::default()
        },
        reprice: primdecomp::Reprice::Deferred { min_degree: 0 },
        partitions: Default::default(),
    };
    assert_valid(&mesh, &decompose(&mesh, &params).unwrap(), &params);
}
