//! The demo scene as merge-stage input, for the allocation tests.

use primdecomp::internals::{
    face_pairs, face_quadrics, fitter, seed_volumes, weld, Clusters, Fitter,
};
use primdecomp::{demo_scene, Params};

/// Runs `f` on the demo scene's fitter, its single-face clusters and adjacent pairs.
pub fn with_demo<R>(f: impl FnOnce(&Fitter, Clusters, Vec<(u32, u32)>) -> R) -> R {
    let mesh = demo_scene();
    let p = Params::default();
    let (welded, _) = weld(&mesh, p.fit.dedup);
    let pairs = face_pairs(&mesh, &welded);
    let mut q = Vec::new();
    face_quadrics(&mesh, p.fit.tangent_eps, &mut q);
    let fitter = fitter(&mesh, &welded, &p, mesh.aabb());
    let vols = seed_volumes(&fitter, &q);
    let cl = Clusters::new(q, vols, &pairs);
    f(&fitter, cl, pairs)
}

/// Merges the clusters of the first `n` adjacent pairs, so that candidates span
/// multi-face point lists too.
pub fn grow(fitter: &Fitter, cl: &mut Clusters, pairs: &[(u32, u32)], n: usize) {
    for &(a, b) in pairs.iter().take(n) {
        let (ra, rb) = (cl.find(a), cl.find(b));
        if ra != rb {
            let mut verts = fitter.all_verts(cl, ra);
            verts.extend(fitter.all_verts(cl, rb));
            verts.sort_unstable();
            verts.dedup();
            cl.merge(ra, rb, verts, 1.0);
        }
    }
}
