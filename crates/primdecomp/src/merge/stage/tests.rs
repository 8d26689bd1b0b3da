use super::*;
use crate::input::adjacency::neighbour_lists;
use crate::merge::cost::InputView;
use crate::merge::driver::tests::{in_pool, with_input};
use crate::merge::rim::FaceAdjacency;

/// The demo scene with every fifth face turned over: the faces' outer sides are not
/// all their windings' (the orientation walk has work to do).
fn turned_scene() -> Mesh {
    let mut mesh = crate::input::demo::demo_scene();
    for f in (0..mesh.face_count()).step_by(5) {
        let (a, b) = (mesh.face_offsets[f], mesh.face_offsets[f + 1]);
        mesh.face_indices[a as usize..b as usize].reverse();
    }
    mesh
}

/// After spatial parts, the faces' outer sides left to the merge stage (found on
/// the first thread out of parts) are the orientation walk's own, and the stage's
/// snapshots — fitted with rims, which read them — are those of a stage given the
/// sides up front, on one thread, two and three.
#[test]
fn sides_found_beside_the_parts_are_the_surface_sides_on_any_thread_count() {
    let mesh = turned_scene();
    let p = Params::default();
    with_input(&mesh, &p, |priced, q, _, pairs| {
        let (offsets, adj) = neighbour_lists(q.len(), pairs);
        let weld = priced.input.weld;
        let sides = orient::face_signs_checked(&mesh, weld, &offsets, &adj, &|_| true).unwrap();
        assert!(
            sides.contains(&1) && sides.contains(&-1),
            "some faces turned"
        );
        let around = FaceAdjacency {
            offsets: &offsets,
            adj: &adj,
        };
        // Rims priced in output fits, the sides not known yet (as `Seeds::build`
        // leaves them after parts), or known.
        let late = Fitter {
            input: InputView {
                face_adj: around,
                ..priced.input
            },
            pricing: priced.pricing,
        };
        assert!(late.prices_rims());
        let known = with_signs(&late, &sides);
        let lists: partition::Lists = (offsets.clone().into(), adj.clone().into());
        let run = |fitter: &Fitter, late_signs: bool| {
            let input = MergeInput {
                q: Vec::new(),
                volumes: Vec::new(),
                pairs: Vec::new(),
                lists: lists.clone(),
                tangent_eps: p.fit.tangent_eps,
                late_signs,
            };
            let first = FirstPhase::Parts {
                parts: 5,
                target: 30,
            };
            let (mut stats, mut laps) = (Stats::default(), PhaseTimes::default());
            let go_on = &|_: f64| true;
            merge(
                fitter,
                input,
                first,
                &[30, 8],
                AtTargets,
                &mut stats,
                go_on,
                &mut laps,
            )
        };
        let (want, (), none) = in_pool(1, || run(&known, false));
        assert!(none.is_none());
        assert_eq!(want.snapshots.len(), 2);
        for threads in [1, 2, 3] {
            let (got, (), found) = in_pool(threads, || run(&late, true));
            assert_eq!(found.as_ref(), Some(&sides), "{threads} threads");
            for (a, b) in got.snapshots.iter().zip(&want.snapshots) {
                assert_eq!(a.prims, b.prims, "{threads} threads, target {}", a.target);
                assert_eq!(a.members, b.members);
            }
        }
    });
}

/// A stage told to stop during the parts returns no sides and a stopped output.
#[test]
fn a_stopped_stage_finds_no_sides() {
    let mesh = turned_scene();
    let p = Params::default();
    with_input(&mesh, &p, |fitter, q, _, pairs| {
        let (offsets, adj) = neighbour_lists(q.len(), pairs);
        let input = MergeInput {
            q: Vec::new(),
            volumes: Vec::new(),
            pairs: Vec::new(),
            lists: (offsets.into(), adj.into()),
            tangent_eps: p.fit.tangent_eps,
            late_signs: true,
        };
        let first = FirstPhase::Parts {
            parts: 5,
            target: 30,
        };
        let (mut stats, mut laps) = (Stats::default(), PhaseTimes::default());
        let stop = &|_: f64| false;
        let (out, (), found) = in_pool(2, || {
            merge(
                fitter,
                input,
                first,
                &[30],
                AtTargets,
                &mut stats,
                stop,
                &mut laps,
            )
        });
        assert!(out.stopped);
        assert!(found.is_none());
    });
}
