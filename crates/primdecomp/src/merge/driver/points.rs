//! The points the merge loop prices a merged cluster by: both clusters' points,
//! deduplicated and reduced to their convex hull's vertices (docs/decisions/0010), and
//! the look-ahead that reduces those of the likely next merge while the worker prices a
//! batch (docs/decisions/perf-repricing-worker-and-look-ahead.md).

use crate::math::hull::{hull_vertices, HullWorkspace};
use crate::merge::cluster::Clusters;
use crate::merge::cost::Fitter;
use crate::merge::heap::{Candidate, Queue};
use crate::merge::lazy::valid;

/// Point lists up to this size are not worth reducing to their hull: fitting a few
/// extra points costs less than the hull. The hull's vertices are a subset of the
/// points, so the fits agree up to the hull's tolerance (docs/decisions/perf-point-reduction.md).
const HULL_MIN: usize = 32;
/// Stale entries [`MergedPoints::look_ahead`] pops past to find a fresh one.
const LOOK_PAST: usize = 8;

/// Visited-marks for deduplicating vertex unions without clearing a whole array.
struct Stamps {
    mark: Vec<u32>,
    epoch: u32,
}

impl Stamps {
    fn next(&mut self) {
        if self.epoch == u32::MAX {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.epoch = 0;
        }
        self.epoch += 1;
    }
    /// True the first time `v` is seen in this epoch.
    fn first(&mut self, v: u32) -> bool {
        let m = &mut self.mark[v as usize];
        let fresh = *m != self.epoch;
        *m = self.epoch;
        fresh
    }
}

/// Buffers for reducing a merged cluster's points to its hull vertices.
#[derive(Default)]
struct Reducer {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    keep: Vec<u32>,
    hull: HullWorkspace,
}

/// A fresh queue entry and its merged point list, reduced before its turn.
struct Ahead {
    c: Candidate,
    verts: Vec<u32>,
}

/// What the loop reuses from merge to merge to find merged clusters' points, and the
/// points of a merge reduced ahead of its turn.
pub(super) struct MergedPoints {
    stamps: Stamps,
    reducer: Reducer,
    ahead: Option<Ahead>,
}

impl MergedPoints {
    /// For clusters over `vertex_count` welded vertices.
    pub(super) fn new(vertex_count: usize) -> Self {
        MergedPoints {
            stamps: Stamps {
                mark: vec![0; vertex_count],
                epoch: 0,
            },
            reducer: Reducer::default(),
            ahead: None,
        }
    }

    /// The points of `c`, a fresh entry (so neither cluster changed since it was
    /// priced): those [`Self::look_ahead`] reduced if it held `c` (then `true`), else
    /// reduced now.
    pub(super) fn of(&mut self, fitter: &Fitter, cl: &Clusters, c: &Candidate) -> (Vec<u32>, bool) {
        match self.ahead.take_if(|k| k.c == *c) {
            Some(k) => (k.verts, true),
            None => {
                let (st, r) = (&mut self.stamps, &mut self.reducer);
                (merged_points(fitter, cl, c.a, c.b, st, r), false)
            }
        }
    }

    /// Reduces the merged points of the queue's first fresh entry (kept if already
    /// held) while a re-pricing batch is out: the serial part of the next merge, done
    /// while the worker prices. Entries are only looked at: every one popped here goes
    /// back, so the queue, and with it the merge order, stays exactly as without the
    /// look-ahead. The entry is often the next merge; otherwise its points wait until
    /// it is popped still fresh (neither cluster changed since it was priced, so the
    /// same points) or another entry takes its place.
    pub(super) fn look_ahead<Q: Queue>(&mut self, fitter: &Fitter, cl: &Clusters, heap: &mut Q) {
        // Stale entries on top (often the merged cluster's old pairs) are passed over.
        let mut seen = [None; LOOK_PAST];
        let mut found = None;
        for slot in &mut seen {
            let Some(c) = heap.pop() else { break };
            *slot = Some(c);
            if valid(cl, &c) {
                found = Some(c);
                break;
            }
        }
        seen.into_iter().flatten().for_each(|c| heap.push(c));
        let Some(c) = found else { return };
        if self.ahead.as_ref().is_some_and(|k| k.c == c) {
            return;
        }
        let (st, r) = (&mut self.stamps, &mut self.reducer);
        let verts = merged_points(fitter, cl, c.a, c.b, st, r);
        self.ahead = Some(Ahead { c, verts });
    }
}

/// The points to price a merged cluster by: the distinct vertices of both clusters'
/// point lists, reduced to the vertices of their convex hull. Every fit maximises a
/// convex function (or minimises a concave one) over the points, so the hull vertices
/// give the same primitive as all points (docs/decisions/0010).
fn merged_points(
    fitter: &Fitter,
    cl: &Clusters,
    a: u32,
    b: u32,
    st: &mut Stamps,
    r: &mut Reducer,
) -> Vec<u32> {
    st.next();
    let (va, vb) = (fitter.verts(cl, a), fitter.verts(cl, b));
    let mut out = Vec::with_capacity(va.len() + vb.len());
    out.extend(va.iter().chain(vb.iter()).filter(|&v| st.first(v)));
    if out.len() <= HULL_MIN {
        return out;
    }
    r.x.clear();
    r.y.clear();
    r.z.clear();
    for &v in &out {
        let p = fitter.input.mesh.pos(v);
        r.x.push(p[0]);
        r.y.push(p[1]);
        r.z.push(p[2]);
    }
    hull_vertices(
        &r.x,
        &r.y,
        &r.z,
        fitter.pricing.hull_eps,
        &mut r.hull,
        &mut r.keep,
    );
    r.keep.iter().map(|&i| out[i as usize]).collect()
}
