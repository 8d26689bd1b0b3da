//! The stages both variants of a pass share (the paper's Algorithm 1), chosen by
//! [`super::pass`]: the greedy ([`super::greedy_pass`], the clusters alive at each
//! count, §3.3) and the cut of the merge tree ([`super::cut_pass`], per level the cut a
//! tolerance, byte budget or count asks for, docs/decisions/0032). Both weld, find the
//! adjacency, seed and merge alike, one call per stage; a [`Clock`] times each stage,
//! reports it to the caller's `Progress` and stops the run when it is cancelled.

use crate::error::{Error, Result};
use crate::input::adjacency;
use crate::input::dedup::{self, Weld};
use crate::input::mesh::Mesh;
use crate::input::solid::{self, Solid};
use crate::input::triangles::Triangles;
use crate::math::{Sym3, V3};
use crate::merge::cost::InputView;
use crate::merge::setup::{pricing, seed_volumes};
use crate::merge::stage::{merge, FirstPhase, Keep, MergeInput, Merged, Surface};
use crate::merge::{components, Fitter};
use crate::output::result::{Decomposition, InputInfo, Level, Stats};
use crate::params::Params;
use crate::postprocess;
use crate::progress::clock::Clock;
use crate::progress::Stage;
use crate::seed::quadric;

/// The merge graph: each face's vertices welded, and the faces sharing an edge.
pub(crate) struct Graph {
    /// The bounds of the vertices the faces use (re-centred, [`Mesh::aabb`]).
    pub(crate) bounds: (V3, V3),
    /// Each vertex's weld target (§3.4), read per corner.
    pub(crate) weld: Weld,
    /// Distinct vertices after welding.
    pub(crate) distinct: usize,
    pub(crate) pairs: Vec<(u32, u32)>,
    /// Edges (between welded vertices) only one face holds: 0 where the input is
    /// closed.
    pub(crate) open_edges: u64,
}

impl Graph {
    pub(crate) fn build(clock: &mut Clock, mesh: &Mesh, params: &Params) -> Result<Self> {
        let bounds = mesh.aabb();
        // Weld overlapping vertices so seams between parts become adjacency (§3.4).
        let (weld, distinct) = clock
            .stage(Stage::Dedup, "dedup", |go_on, _| {
                dedup::weld_checked(mesh, params.fit.dedup, go_on)
            })?
            .ok_or(Error::Cancelled)?;
        // Faces sharing an edge form the merge graph (§3.3).
        let (pairs, open_edges) = clock
            .stage(Stage::Adjacency, "adjacency", |go_on, _| {
                let (offsets, indices) = (&mesh.face_offsets, &mesh.face_indices);
                adjacency::face_pairs_checked(offsets, indices, &weld, go_on)
            })?
            .ok_or(Error::Cancelled)?;
        Ok(Graph {
            bounds,
            weld,
            distinct,
            pairs,
            open_edges,
        })
    }

    /// Whether the faces form several separate parts (faces welded to a point join none);
    /// `None` when `go_on` said stop.
    pub(crate) fn several_parts(&self, mesh: &Mesh, go_on: &dyn Fn() -> bool) -> Option<bool> {
        let point = |f: usize| {
            let corners = self.weld.face(mesh, f);
            corners.iter().all(|v| v == corners.get(0))
        };
        components::several(mesh.face_count(), &self.pairs, point, go_on)
    }
}

/// What the merge loop starts from besides the graph: one operator per face (§3.1)
/// and the graph's pairs, also as neighbour lists, and the run's counters so far.
pub(crate) struct Seeds {
    q: Vec<Sym3>,
    /// Empty with spatial parts, which read the neighbour lists.
    pairs: Vec<(u32, u32)>,
    stats: Stats,
}

/// What output fits read of the input around a cluster: each face's neighbours and
/// outer side, and the input's interior (`--solid`).
pub(crate) struct Around {
    surface: Surface,
    solid: Option<Solid>,
}

impl Around {
    /// With the faces' outer sides the merge stage found, where they were left to it
    /// ([`merge_stage`]): a fitter of the input before then prices merges but must
    /// not fit output.
    pub(crate) fn with_signs(self, signs: Option<Vec<i8>>) -> Around {
        Around {
            surface: self.surface.with_signs(signs),
            ..self
        }
    }
}

impl Seeds {
    /// The stages from the quadrics to the interior, for a loop that starts at `first`.
    pub(crate) fn build(
        clock: &mut Clock,
        mesh: &Mesh,
        params: &Params,
        graph: &mut Graph,
        first: &FirstPhase,
    ) -> Result<(Seeds, Around)> {
        // Spatial parts compute their faces' operators and seed volumes themselves, and
        // read the pairs from the surface's neighbour lists: none is held for every face.
        let per_part = matches!(first, FirstPhase::Parts { .. });
        // One operator per face (§3.1).
        let q = clock.stage(Stage::Quadrics, "quadrics", |go_on, _| {
            let mut q = Vec::new();
            if !per_part {
                quadric::face_quadrics_checked(mesh, params.fit.tangent_eps, &mut q, go_on);
            }
            q
        })?;
        let stats = Stats {
            welded_vertices: graph.distinct,
            adjacency_edges: graph.pairs.len(),
            partitions: first.parts(),
            ..Stats::default()
        };
        // Each face's neighbours (the clusters' adjacency too) and outer side: output
        // fits keep off rims and lie flush.
        let mut pairs = Some(std::mem::take(&mut graph.pairs));
        let surface = clock
            .step_checked(Stage::Seed, "surface", |go_on| {
                let lists =
                    adjacency::neighbour_lists_checked(mesh.face_count(), pairs.as_ref()?, go_on)?;
                if per_part {
                    pairs = None;
                }
                // After spatial parts, which side of each face is outside is found
                // beside the parts' last ones (`MergeInput::late_signs`).
                Surface::build(mesh, &graph.weld, lists, params, per_part, go_on)
            })?
            .ok_or(Error::Cancelled)?;
        // The input's interior, where merges are priced by the air they add (--solid),
        // and whether it is closed: only then does the cut measure to its solid.
        let solid = clock.step(Stage::Seed, "solid", || {
            params.plates.solid.then(|| {
                let open = graph.open_edges > 0;
                Solid::build(mesh, solid::CELLS, solid::VOTES).with_open(open)
            })
        })?;
        let seeds = Seeds {
            q,
            pairs: pairs.unwrap_or_default(),
            stats,
        };
        Ok((seeds, Around { surface, solid }))
    }

    /// The faces' operators (the merge tree's leaves' when they are the faces).
    pub(crate) fn quadrics(&self) -> &[Sym3] {
        &self.q
    }

    /// What the merge loop consumes, with the faces' seed `volumes`; and the run's
    /// counters.
    pub(crate) fn merge_input(
        self,
        volumes: Vec<f64>,
        around: &Around,
        params: &Params,
    ) -> (MergeInput, Stats) {
        let input = MergeInput {
            q: self.q,
            volumes,
            pairs: self.pairs,
            lists: (around.surface.offsets.clone(), around.surface.adj.clone()),
            tangent_eps: params.fit.tangent_eps,
            late_signs: around.surface.signs_late(),
        };
        (input, self.stats)
    }
}

/// Fits and prices over the input's view — the mesh, its welded faces, the faces'
/// surface and the interior — with the settings made absolute for it ([`pricing`]).
pub(crate) fn fitter_of<'a>(
    mesh: &'a Mesh,
    graph: &'a Graph,
    params: &Params,
    around: &'a Around,
) -> Fitter<'a> {
    let input = InputView {
        mesh,
        weld: &graph.weld,
        face_sign: &around.surface.signs,
        face_adj: around.surface.adjacency(),
        solid: around.solid.as_ref(),
    };
    Fitter {
        input,
        pricing: pricing(params, graph.bounds),
    }
}

/// Each face's seed volume (Alg. 1, line 2), none with spatial parts (each part seeds
/// its own).
pub(crate) fn seed(
    clock: &mut Clock,
    fitter: &Fitter,
    q: &[Sym3],
    first: &FirstPhase,
) -> Result<Vec<f64>> {
    clock.stage(Stage::Seed, "seed", |go_on, _| match first {
        FirstPhase::Parts { .. } => Vec::new(),
        _ => seed_volumes(fitter, q, go_on),
    })
}

/// The merge stage: the loop from `first` through `targets` on `input`, keeping what
/// the pass asks besides the snapshots (`keep`: nothing, or the merge tree), its counts
/// added to `stats`; and the faces' outer sides if they were left to it (for
/// [`Around::with_signs`]).
pub(crate) fn merge_stage<K: Keep>(
    clock: &mut Clock,
    fitter: &Fitter,
    (input, first): (MergeInput, FirstPhase),
    (targets, keep): (&[usize], K),
    stats: &mut Stats,
) -> Result<Merged<K::Log>> {
    clock.stage(Stage::Merge, "merge", |go_on, laps| {
        merge(fitter, input, first, targets, keep, stats, go_on, laps)
    })
}

/// The input's triangles, once, where a later stage measures against them (`needed`).
pub(crate) fn triangles<'m>(
    clock: &mut Clock,
    mesh: &'m Mesh,
    needed: bool,
) -> Result<Option<Triangles<'m>>> {
    let tris = clock.step_checked(Stage::Postprocess, "triangles", |go_on| {
        needed.then(|| Triangles::new_checked(mesh, go_on))
    })?;
    // The hierarchy's build asks whether to go on; `None` inside is its stop.
    match tris {
        Some(None) => Err(Error::Cancelled),
        Some(Some(tris)) => Ok(Some(tris)),
        None => Ok(None),
    }
}

/// What post-processing reads of the input, once: with a minimum thickness, the
/// input's interior for plates thickened inward (--min-thickness).
pub(crate) fn interior<'a>(
    clock: &mut Clock,
    mesh: &Mesh,
    params: &Params,
    tris: Option<&'a Triangles>,
) -> Result<postprocess::Prepared<'a>> {
    clock.step(Stage::Postprocess, "interior", || {
        postprocess::Prepared::new(mesh, params, tris)
    })
}

/// The run's result: its levels, the input's description, the clock's timings.
pub(crate) fn decomposition(
    mesh: &Mesh,
    graph: &Graph,
    levels: Vec<Level>,
    clock: Clock,
    stats: Stats,
) -> Decomposition {
    Decomposition {
        input: input_info(mesh, graph.bounds),
        levels,
        timings: clock.timings,
        stats,
    }
}

/// Refuses an input the engine cannot decompose: no faces, or vertices so far apart
/// that volumes would overflow.
pub(crate) fn check_input(mesh: &Mesh) -> Result<()> {
    if mesh.face_count() == 0 {
        return Err(Error::EmptyMesh {
            path: "<mesh>".into(),
        });
    }
    mesh.check_extent("<mesh>".as_ref())
}

pub(crate) fn input_info(mesh: &Mesh, (lo, hi): (V3, V3)) -> InputInfo {
    InputInfo {
        path: None,
        faces: mesh.face_count(),
        vertices: mesh.vertex_count(),
        aabb_min: crate::math::add(lo, mesh.offset),
        aabb_max: crate::math::add(hi, mesh.offset),
        up: None,
        up_from: None,
    }
}
