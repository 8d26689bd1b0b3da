//! The pairs the merge loop's queue holds, put in and taken out in bulk: every adjacent
//! pair priced in parallel blocks when the loop starts (Alg. 1, line 3), components
//! bridged by each cluster's nearest clusters when adjacency runs out (§3.4 "Pairwise
//! Component Merging", `bridge.rs`), and stale entries purged as the queue grows.

use crate::merge::bridge::{nearest_pairs, BRIDGE_K};
use crate::merge::cluster::Clusters;
use crate::merge::cost::{Fitter, Workspace};
use crate::merge::heap::{Candidate, Queue};
use crate::merge::lazy::{valid, Lazy};
use crate::progress::Checkpoint;
use rayon::prelude::*;

/// Pairs priced per parallel task.
const CHUNK: usize = 1024;
/// Pairs priced per block when seeding the queue.
const PRICE_BLOCK: usize = 1 << 16;

/// Prices pairs in parallel chunks, in place; the output order equals the input order.
pub(super) fn price(fitter: &Fitter, cl: &Clusters, pairs: &[(u32, u32)]) -> Vec<Candidate> {
    let none = Candidate {
        cost: f64::NAN,
        volume: 0.0,
        a: 0,
        b: 0,
        t: 0,
        flat: false,
    };
    let mut out = vec![none; pairs.len()];
    out.par_chunks_mut(CHUNK)
        .zip(pairs.par_chunks(CHUNK))
        .for_each_init(Workspace::default, |ws, (slots, chunk)| {
            for (slot, &(a, b)) in slots.iter_mut().zip(chunk) {
                if let Some((c, _)) = fitter.candidate(cl, a, b, ws) {
                    *slot = c;
                }
            }
        });
    // Merges over the excess-volume cap were left as NaN placeholders.
    out.retain(|c| !c.cost.is_nan());
    out
}

/// Prices the input's adjacent pairs into `heap` in blocks, so that only one block of
/// pairs and candidates exists outside the queue; returns how many were priced.
/// `None` when `go_on` (asked between blocks, reporting no progress yet) says stop.
pub(super) fn seed_queue<Q: Queue>(
    fitter: &Fitter,
    cl: &Clusters,
    heap: &mut Q,
    go_on: Checkpoint,
) -> Option<usize> {
    let (n, mut priced) = (cl.len() as u32, 0);
    let mut block = Vec::with_capacity(PRICE_BLOCK);
    for a in 0..n {
        // Roots' neighbour lists: the input's adjacency, or (phase 2 of
        // `Params::partitions`) the resolved adjacency between groups of faces, or
        // (after `merge::components`) whole components' lists as their loops left them,
        // whose merged-away ids name the component itself.
        let nbrs = if cl.is_root(a) { cl.neighbors(a) } else { &[] };
        let pair = |&b: &u32| b > a && cl.is_root(b);
        block.extend(nbrs.iter().copied().filter(|b| pair(b)).map(|b| (a, b)));
        if block.len() >= PRICE_BLOCK || a + 1 == n {
            priced += block.len();
            price(fitter, cl, &block)
                .into_iter()
                .for_each(|c| heap.push(c));
            block.clear();
            if !go_on(0.0) {
                return None;
            }
        }
    }
    Some(priced)
}

/// Drops stale entries: lazy deletion's would otherwise outnumber the live pairs many
/// times over (memory); dropping them keeps the order unchanged. Deferred pairs'
/// entries are kept: they are the pairs' only keys.
pub(super) fn purge<Q: Queue>(fitter: &Fitter, cl: &Clusters, lazy: &mut Lazy, heap: &mut Q) {
    if fitter.pricing.defer_degree == u32::MAX {
        heap.retain(|c| valid(cl, c));
    } else {
        heap.retain(|c| lazy.keep(cl, c));
        lazy.prune(cl);
    }
}

/// Links every live cluster to its nearest clusters by centroid (`bridge.rs`).
pub(super) fn bridge(fitter: &Fitter, cl: &mut Clusters) -> Vec<(u32, u32)> {
    let roots = cl.roots();
    let centroids: Vec<[f64; 3]> = roots.iter().map(|&r| centroid(fitter, cl, r)).collect();
    let pairs: Vec<(u32, u32)> = nearest_pairs(&centroids, BRIDGE_K)
        .into_iter()
        .map(|(i, j)| (roots[i as usize], roots[j as usize]))
        .collect();
    // Roots increase with their index, so the pairs stay sorted and distinct.
    debug_assert!(pairs.windows(2).all(|w| w[0] < w[1]));
    for &(a, b) in &pairs {
        cl.link(a, b);
    }
    pairs
}

fn centroid(fitter: &Fitter, cl: &Clusters, c: u32) -> [f64; 3] {
    let vs = fitter.verts(cl, c);
    let mut s = [0.0; 3];
    for v in vs.iter() {
        let p = fitter.input.mesh.pos(v);
        (0..3).for_each(|k| s[k] += p[k]);
    }
    s.map(|x| x / vs.len().max(1) as f64)
}
