//! Face adjacency (§3.3: merges follow the input's topology): two faces are adjacent
//! when they share an edge after deduplication. Built by sorting (edge, face) records
//! in parallel, so the result is the same for any thread count.

use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering::Relaxed};

/// Faces around one edge beyond which we chain them instead of pairing all of them,
/// so a non-manifold "fan" edge cannot create a quadratic number of pairs.
const ALL_PAIRS_UP_TO: usize = 4;

/// The pairs as neighbour lists of `n` faces, CSR: face `f`'s neighbours are
/// `adj[offsets[f]..offsets[f + 1]]`, in the pairs' order.
pub fn neighbour_lists(n: usize, pairs: &[(u32, u32)]) -> (Vec<u32>, Vec<u32>) {
    neighbour_lists_checked(n, pairs, &|_| true).expect("never told to stop")
}

/// [`neighbour_lists`] asking `go_on` after each [`FACE_BLOCK`] pairs of its two
/// passes; `None` when it said stop.
pub fn neighbour_lists_checked(
    n: usize,
    pairs: &[(u32, u32)],
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<u32>, Vec<u32>)> {
    if pairs.len() >= PARALLEL_FROM && sorted_apart(pairs) {
        return sorted_neighbour_lists(n, pairs, go_on);
    }
    lists_in_order(n, pairs, go_on)
}

/// [`neighbour_lists_checked`] of any pairs, on this thread: each face's neighbours in
/// the pairs' order.
fn lists_in_order(
    n: usize,
    pairs: &[(u32, u32)],
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<u32>, Vec<u32>)> {
    let mut offsets = vec![0u32; n + 1];
    for block in pairs.chunks(FACE_BLOCK) {
        for &(a, b) in block {
            offsets[a as usize + 1] += 1;
            offsets[b as usize + 1] += 1;
        }
        go_on(0.0).then_some(())?;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut adj = vec![0u32; 2 * pairs.len()];
    for block in pairs.chunks(FACE_BLOCK) {
        for &(a, b) in block {
            adj[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
            adj[fill[b as usize] as usize] = a;
            fill[b as usize] += 1;
        }
        go_on(0.0).then_some(())?;
    }
    Some((offsets, adj))
}

/// Pairs from which [`neighbour_lists_checked`] runs in parallel (when sorted).
const PARALLEL_FROM: usize = 1 << 16;

/// Whether `pairs` are sorted, each once, each `(a, b)` with `a < b` (the input's
/// face pairs, [`face_pairs`]). Then face `f`'s list in the pairs' order is its
/// neighbours ascending: its pairs `(a, f)` come before its pairs `(f, b)`, and each
/// run is sorted.
fn sorted_apart(pairs: &[(u32, u32)]) -> bool {
    pairs.par_iter().all(|&(a, b)| a < b) && pairs.par_windows(2).all(|w| w[0] < w[1])
}

/// [`neighbour_lists_checked`] of pairs [`sorted_apart`], in parallel: counted and
/// placed a block of [`FACE_BLOCK`] pairs at a time (asking `go_on` after each), then
/// each face's list sorted, which is the order the serial pass gives such pairs. The
/// same lists for any thread count.
fn sorted_neighbour_lists(
    n: usize,
    pairs: &[(u32, u32)],
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<u32>, Vec<u32>)> {
    let blocks = |visit: &(dyn Fn(u32, u32) + Sync)| {
        pairs.chunks(FACE_BLOCK).all(|block| {
            let each = |&(a, b): &(u32, u32)| visit(a, b);
            block.par_iter().with_min_len(4096).for_each(each);
            go_on(0.0)
        })
    };
    let count: Vec<AtomicU32> = zeroed(n + 1);
    let counted = blocks(&|a, b| {
        count[a as usize + 1].fetch_add(1, Relaxed);
        count[b as usize + 1].fetch_add(1, Relaxed);
    });
    if !counted {
        return None;
    }
    let (offsets, next) = starts_of(count);
    let slots: Vec<AtomicU32> = zeroed(2 * pairs.len());
    let place = |f: u32, g: u32| {
        let at = next[f as usize].fetch_add(1, Relaxed);
        slots[at as usize].store(g, Relaxed);
    };
    if !blocks(&|a, b| {
        place(a, b);
        place(b, a);
    }) {
        return None;
    }
    drop(next);
    let mut adj: Vec<u32> = slots.into_iter().map(AtomicU32::into_inner).collect();
    sort_runs(&mut adj, &offsets, 0.0, go_on)?;
    Some((offsets, adj))
}

/// From `count[i + 1]` items in bucket `i` (`count[0]` zero): each bucket's start
/// (a prefix sum, one more entry than buckets) and a cursor per bucket at its start,
/// for placing items in parallel.
fn starts_of(count: Vec<AtomicU32>) -> (Vec<u32>, Vec<AtomicU32>) {
    let mut start: Vec<u32> = count.into_iter().map(AtomicU32::into_inner).collect();
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let buckets = start.len().saturating_sub(1);
    let next = start[..buckets]
        .iter()
        .map(|&s| AtomicU32::new(s))
        .collect();
    (start, next)
}

/// `n` counters or slots at zero, made in parallel (a pass over memory at 14M faces).
fn zeroed<T: Default + Send>(n: usize) -> Vec<T> {
    (0..n).into_par_iter().map(|_| T::default()).collect()
}

/// Sorts each run `items[start[i]..start[i + 1]]`, blocks of runs in parallel (each
/// asking `go_on`, reporting the fraction `done`, when done); `None` when it said stop.
fn sort_runs<T: Ord + Send>(
    items: &mut [T],
    start: &[u32],
    done: f64,
    go_on: crate::progress::Checkpoint,
) -> Option<()> {
    let runs = start.len().saturating_sub(1);
    let per = (FACE_BLOCK / 16).max(1);
    // Blocks of runs own disjoint stretches of the items.
    let mut blocks = Vec::new();
    let mut rest = items;
    for r0 in (0..runs).step_by(per) {
        let r1 = (r0 + per).min(runs);
        let (head, tail) = rest.split_at_mut((start[r1] - start[r0]) as usize);
        blocks.push((r0, r1, head));
        rest = tail;
    }
    let sorted = |(r0, r1, block): (usize, usize, &mut [T])| {
        let base = start[r0] as usize;
        for r in r0..r1 {
            block[start[r] as usize - base..start[r + 1] as usize - base].sort_unstable();
        }
        go_on(done)
    };
    blocks.into_par_iter().all(sorted).then_some(())
}

/// Sorted, unique pairs `(a, b)` with `a < b` of faces sharing an edge. `offsets` and
/// `indices` are the CSR polygons (indices already welded).
#[cfg(test)]
pub fn face_pairs(offsets: &[u32], indices: &[u32]) -> Vec<(u32, u32)> {
    let unwelded = super::dedup::Weld::none();
    face_pairs_checked(offsets, indices, &unwelded, &|_| true).unwrap_or_default()
}

/// Vertices per block of the edge lists (a parallel task, and a check of `go_on`).
const BLOCK: usize = 1 << 14;
/// Faces per block of the passes over the faces' sides (a check of `go_on` after
/// each: a few milliseconds apart).
const FACE_BLOCK: usize = 1 << 20;

/// [`face_pairs`] of `indices` read through `weld`, that reports the fraction done
/// to `go_on` between blocks of vertices and stops (`None`) when it says so.
///
/// The sides are bucketed by their lower vertex (a counting sort: one 8-byte record
/// per side, the other vertex and the face, and a start per vertex), and each
/// vertex's few records sorted on their own: the same order as one sort of (edge,
/// face) records, in a third less memory and linear time, a block of vertices at a
/// time.
pub fn face_pairs_checked(
    offsets: &[u32],
    indices: &[u32],
    weld: &super::dedup::Weld,
    go_on: crate::progress::Checkpoint,
) -> Option<Vec<(u32, u32)>> {
    let faces = offsets.len().saturating_sub(1);
    debug_assert!(
        offsets.first().is_none_or(|&o| o == 0),
        "CSR offsets start at 0"
    );
    let verts = (indices.par_iter().map(|&v| weld.of(v)).max()).map_or(0, |m| m as usize + 1);
    // Each face's sides (a, b), a ≠ b, by chunks of faces, a block of faces at a
    // time with a check of `go_on` (from `done` to `done + 0.25`) after each; false
    // when it said stop.
    let sides = |visit: &(dyn Fn(u32, u32, u32) + Sync), done: f64| {
        (0..faces).step_by(FACE_BLOCK).all(|f0| {
            let f1 = (f0 + FACE_BLOCK).min(faces);
            (f0..f1).into_par_iter().with_min_len(4096).for_each(|f| {
                let idx = weld.corners(&indices[offsets[f] as usize..offsets[f + 1] as usize]);
                for i in 0..idx.len() {
                    let (a, b) = (idx.get(i), idx.get((i + 1) % idx.len()));
                    if a != b {
                        visit(a.min(b), a.max(b), f as u32);
                    }
                }
            });
            go_on(done + 0.25 * f1 as f64 / faces as f64)
        })
    };
    let count: Vec<AtomicU32> = zeroed(verts + 1);
    let counted = sides(
        &|lo, _, _| {
            count[lo as usize + 1].fetch_add(1, Relaxed);
        },
        0.0,
    );
    if !counted {
        return None;
    }
    // The records in their vertex's bucket, in any order (sorted below).
    let (start, next) = starts_of(count);
    let records: Vec<AtomicU64> = (0..start[verts]).map(|_| AtomicU64::new(0)).collect();
    let placed = sides(
        &|lo, hi, f| {
            let at = next[lo as usize].fetch_add(1, Relaxed);
            records[at as usize].store((u64::from(hi) << 32) | u64::from(f), Relaxed);
        },
        0.25,
    );
    if !placed {
        return None;
    }
    drop(next);
    let mut records: Vec<u64> = records.into_iter().map(AtomicU64::into_inner).collect();
    // Blocks of vertices own disjoint runs of records.
    let mut blocks = Vec::new();
    let mut rest = &mut records[..];
    for v0 in (0..verts).step_by(BLOCK) {
        let v1 = (v0 + BLOCK).min(verts);
        let (head, tail) = rest.split_at_mut((start[v1] - start[v0]) as usize);
        blocks.push((v0, v1, head));
        rest = tail;
    }
    let total = blocks.len().max(1);
    let done = AtomicU32::new(0);
    let lists: Vec<Option<Vec<(u32, u32)>>> = blocks
        .into_par_iter()
        .map(|(v0, v1, recs)| {
            let mut pairs = Vec::new();
            let base = start[v0] as usize;
            for v in v0..v1 {
                let run = &mut recs[start[v] as usize - base..start[v + 1] as usize - base];
                run.sort_unstable();
                for edge in run.chunk_by(|x, y| x >> 32 == y >> 32) {
                    push_edge_pairs(edge, &mut pairs);
                }
            }
            let k = done.fetch_add(1, Relaxed) + 1;
            go_on(0.5 + 0.4 * f64::from(k) / total as f64).then_some(pairs)
        })
        .collect();
    drop(records);
    let lists: Vec<Vec<(u32, u32)>> = lists.into_iter().collect::<Option<_>>()?;
    sorted_pairs(lists, faces, go_on)
}

/// The pairs of `lists` sorted and each once, as one sort of all of them gives: a
/// counting sort on the first face (counted and placed in parallel, asking `go_on`
/// after each pass), then each face's few pairs sorted on their own in parallel
/// blocks, each asking `go_on` (one sort of every pair is seconds without a check at
/// 14M faces); `None` when it said stop. The same pairs for any thread count.
fn sorted_pairs(
    lists: Vec<Vec<(u32, u32)>>,
    faces: usize,
    go_on: crate::progress::Checkpoint,
) -> Option<Vec<(u32, u32)>> {
    let count: Vec<AtomicU32> = zeroed(faces + 1);
    lists.par_iter().flatten().for_each(|&(a, _)| {
        count[a as usize + 1].fetch_add(1, Relaxed);
    });
    go_on(0.9).then_some(())?;
    let mut start: Vec<u32> = count.into_iter().map(AtomicU32::into_inner).collect();
    for f in 0..faces {
        start[f + 1] += start[f];
    }
    let next: Vec<AtomicU32> = start[..faces].iter().map(|&s| AtomicU32::new(s)).collect();
    // Each pair as `a << 32 | b`: ordered as the pairs are.
    let slots: Vec<AtomicU64> = zeroed(start[faces] as usize);
    lists.par_iter().flatten().for_each(|&(a, b)| {
        let at = next[a as usize].fetch_add(1, Relaxed);
        slots[at as usize].store((u64::from(a) << 32) | u64::from(b), Relaxed);
    });
    drop(next);
    drop(lists);
    go_on(0.9).then_some(())?;
    let mut keys: Vec<u64> = slots.into_iter().map(AtomicU64::into_inner).collect();
    sort_runs(&mut keys, &start, 0.9, go_on)?;
    let mut pairs: Vec<(u32, u32)> = keys
        .into_iter()
        .map(|k| ((k >> 32) as u32, k as u32))
        .collect();
    pairs.dedup();
    pairs.shrink_to_fit();
    Some(pairs)
}

/// Pairs of the distinct faces around one edge (records `other vertex << 32 | face`
/// of one edge, sorted by face): all of them for up to [`ALL_PAIRS_UP_TO`] faces, a
/// chain beyond. No allocation.
fn push_edge_pairs(run: &[u64], pairs: &mut Vec<(u32, u32)>) {
    let face = |r: u64| r as u32;
    let steps = || run.windows(2).filter(|w| face(w[0]) != face(w[1]));
    if 1 + steps().count() > ALL_PAIRS_UP_TO {
        pairs.extend(steps().map(|w| (face(w[0]), face(w[1]))));
        return;
    }
    let mut fs = [0u32; ALL_PAIRS_UP_TO];
    let mut n = 0;
    for f in run.iter().map(|&r| face(r)) {
        if n == 0 || fs[n - 1] != f {
            fs[n] = f;
            n += 1;
        }
    }
    for i in 0..n {
        for j in i + 1..n {
            pairs.push((fs[i], fs[j]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_strip_and_isolated_triangle() {
        // Two quads sharing edge 1–4, and a triangle touching only at vertex 0.
        let offsets = [0, 4, 8, 11];
        let indices = [0, 1, 4, 3, 1, 2, 5, 4, 0, 6, 7];
        assert_eq!(face_pairs(&offsets, &indices), vec![(0, 1)]);
    }

    #[test]
    fn duplicate_faces_pair_once_and_fans_chain() {
        let offsets = [0, 3, 6];
        assert_eq!(face_pairs(&offsets, &[0, 1, 2, 2, 1, 0]), vec![(0, 1)]);
        // Six triangles around edge 0–1: chained, 5 pairs, not 15.
        let offsets: Vec<u32> = (0..=6).map(|i| i * 3).collect();
        let indices: Vec<u32> = (0..6).flat_map(|i| [0, 1, 2 + i]).collect();
        let p = face_pairs(&offsets, &indices);
        assert_eq!(p, vec![(0, 1), (1, 2), (2, 3), (3, 4), (4, 5)]);
    }

    /// Pseudo-random sorted, distinct pairs `(a, b)`, `a < b`, of `n` faces.
    fn random_pairs(n: u32, count: usize) -> Vec<(u32, u32)> {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % u64::from(n)) as u32
        };
        let mut pairs: Vec<(u32, u32)> = (0..count)
            .map(|_| (next(), next()))
            .filter(|(a, b)| a != b)
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    /// Sorted pairs take the parallel path, which gives the serial pass's lists on any
    /// thread count; unsorted ones keep the pairs' order.
    #[test]
    fn parallel_lists_are_the_serial_ones() {
        let n = 50_000;
        let pairs = random_pairs(n, 3 * PARALLEL_FROM);
        assert!(pairs.len() >= PARALLEL_FROM && sorted_apart(&pairs));
        let serial = lists_in_order(n as usize, &pairs, &|_| true).unwrap();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let parallel = pool.install(|| neighbour_lists(n as usize, &pairs));
            assert_eq!(parallel, serial, "{threads} threads");
        }
        let mut unsorted = pairs.clone();
        unsorted.swap(0, pairs.len() - 1);
        assert!(!sorted_apart(&unsorted));
        let (offsets, adj) = neighbour_lists(n as usize, &unsorted);
        assert_eq!(
            (offsets, adj),
            lists_in_order(n as usize, &unsorted, &|_| true).unwrap()
        );
        // A stop is answered.
        assert!(neighbour_lists_checked(n as usize, &pairs, &|_| false).is_none());
    }

    /// The pairs of several lists come out as one sort and dedup of all of them.
    #[test]
    fn sorted_pairs_are_one_sort_of_all() {
        let n = 20_000;
        let all = random_pairs(n, 60_000);
        let mut lists: Vec<Vec<(u32, u32)>> = vec![Vec::new(); 7];
        for (i, &p) in all.iter().rev().enumerate() {
            lists[i % 7].push(p);
            if i % 5 == 0 {
                lists[(i + 3) % 7].push(p);
            }
        }
        let got = sorted_pairs(lists.clone(), n as usize, &|_| true).unwrap();
        assert_eq!(got, all);
        assert!(sorted_pairs(lists, n as usize, &|_| false).is_none());
    }

    #[test]
    fn degenerate_edges_are_ignored() {
        let offsets = [0, 3, 6];
        assert!(face_pairs(&offsets, &[0, 0, 1, 2, 2, 3]).is_empty());
    }
}
