//! The demo scene as merge-stage input, for the allocation tests.

use primdecomp::decompose::{evaluator, seed_volumes};
use primdecomp::merge::{Clusters, Evaluator};
use primdecomp::mesh::{adjacency, dedup};
use primdecomp::{demo, quadric, Mesh, Params};

/// Runs `f` on the demo scene's evaluator, its single-face clusters and adjacent pairs.
pub fn with_demo<R>(f: impl FnOnce(&Evaluator, Clusters, Vec<(u32, u32)>) -> R) -> R {
    let mesh = Mesh::from_builder(demo::demo_scene());
    let p = Params::default();
    let (welded, _) = dedup::weld(&mesh, p.dedup);
    let pairs = adjacency::face_pairs(&mesh.face_offsets, &welded);
    let mut q = Vec::new();
    quadric::face_quadrics(&mesh, p.tangent_eps, &mut q);
    let ev = evaluator(&mesh, &welded, &p, mesh.aabb());
    let vols = seed_volumes(&ev, &q);
    let cl = Clusters::new(q, vols, &pairs);
    f(&ev, cl, pairs)
}

/// Merges the clusters of the first `n` adjacent pairs, so that candidates span
/// multi-face point lists too.
pub fn grow(ev: &Evaluator, cl: &mut Clusters, pairs: &[(u32, u32)], n: usize) {
    for &(a, b) in pairs.iter().take(n) {
        let (ra, rb) = (cl.find(a), cl.find(b));
        if ra != rb {
            let mut verts = ev.all_verts(cl, ra);
            verts.extend(ev.all_verts(cl, rb));
            verts.sort_unstable();
            verts.dedup();
            cl.merge(ra, rb, verts, 1.0);
        }
    }
}
