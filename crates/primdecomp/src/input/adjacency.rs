//! Face adjacency (§3.3: merges follow the input's topology): two faces are adjacent
//! when they share an edge after deduplication. Built by sorting (edge, face) records
//! in parallel, so the result is the same for any thread count.

use rayon::prelude::*;
use std::sync::atomic::{AtomicU16, AtomicU32, AtomicU64, Ordering::Relaxed};

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
    face_pairs_checked(offsets, indices, &unwelded, &|_| true).map_or_else(Vec::new, |(p, _)| p)
}

/// Faces per block of the passes over the neighbour lists' pairs (a check of `go_on`
/// after each: a few milliseconds apart).
const FACE_BLOCK: usize = 1 << 20;
/// Faces per chunk of the partition of the faces' sides: each chunk counts and
/// places its own sides, so the records' order is the same for any thread count.
const CHUNK: usize = 1 << 18;
/// A side's bucket is its lower vertex's id without these low bits: 2^13 vertices,
/// about 49k sides of 10 bytes, which sort within a core's L2 cache; and the
/// placing pass writes to few enough buckets at once (3,400 at 56M faces) that
/// their cursors stay cached too.
const VERTEX_BITS: u32 = 13;
/// A pair's bucket is its first face's id without these low bits (2^14 faces, about
/// 25k pairs of 8 bytes).
const FACE_BITS: u32 = 14;

/// [`face_pairs`] of `indices` read through `weld`, with the number of edges only
/// one face holds (0: the input is closed), that reports the fraction done to `go_on`
/// between chunks of faces and buckets of vertices, and stops (`None`) when it says
/// so.
///
/// Two radix passes, each partitioning by a coarse key first and finishing each
/// bucket on its own (in cache, buckets in parallel): the sides by their lower
/// vertex (one 10-byte record per side: the other vertex and the face, and the low
/// bits of the lower vertex), each vertex's few records then sorted on their own,
/// which is the order of one sort of (edge, face) records; then the pairs by their
/// first face. The partitions' counts are kept per chunk of input, so no write is
/// shared between threads and the result is the same for any thread count. Scattered
/// writes to one slot per vertex or per face would leave the caches from a few
/// million faces on (docs/results/ladder.md, "Adjacency in cache-sized buckets").
pub fn face_pairs_checked(
    offsets: &[u32],
    indices: &[u32],
    weld: &super::dedup::Weld,
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<(u32, u32)>, u64)> {
    let faces = offsets.len().saturating_sub(1);
    debug_assert!(
        offsets.first().is_none_or(|&o| o == 0),
        "CSR offsets start at 0"
    );
    let verts = (indices.par_iter().map(|&v| weld.of(v)).max()).map_or(0, |m| m as usize + 1);
    // Each face's sides (lo, hi), lo < hi, its corners read through the weld.
    let sides = |f: usize, visit: &mut dyn FnMut(u32, u32)| {
        let idx = weld.corners(&indices[offsets[f] as usize..offsets[f + 1] as usize]);
        for i in 0..idx.len() {
            let (a, b) = (idx.get(i), idx.get((i + 1) % idx.len()));
            if a != b {
                visit(a.min(b), a.max(b));
            }
        }
    };
    let (keys, lows, start) = bucketed_sides(&sides, faces, verts, go_on)?;
    let (lists, open) = edge_pairs(&keys, &lows, &start, go_on)?;
    drop((keys, lows));
    Some((sorted_pairs(lists, faces, go_on)?, open))
}

/// The first radix pass of [`face_pairs_checked`]: each of the `faces` faces'
/// `sides` (lo, hi) as a record in its lower vertex's bucket (of `verts` vertices),
/// each chunk of faces counted and placed in its own stretch, in parallel: the
/// records (`keys`: other vertex `<< 32 |` face; `lows`: the lower vertex's low bits)
/// and each bucket's start (the last entry the end). `None` when `go_on` said stop.
fn bucketed_sides(
    sides: &(impl Fn(usize, &mut dyn FnMut(u32, u32)) + Sync),
    faces: usize,
    verts: usize,
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<u64>, Vec<u16>, Vec<usize>)> {
    let chunks: Vec<std::ops::Range<usize>> = (0..faces)
        .step_by(CHUNK)
        .map(|f0| f0..(f0 + CHUNK).min(faces))
        .collect();
    let buckets = (verts >> VERTEX_BITS) + 1;
    let bucket = |lo: u32| (lo >> VERTEX_BITS) as usize;
    let counts = |done: f64| {
        let each = |r: &std::ops::Range<usize>| {
            let mut count = vec![0u32; buckets];
            for f in r.clone() {
                sides(f, &mut |lo, _| count[bucket(lo)] += 1);
            }
            go_on(done + 0.25 * r.end as f64 / faces as f64).then_some(count)
        };
        chunks.par_iter().map(each).collect::<Option<Vec<_>>>()
    };
    let (start, cursors) = chunk_starts(counts(0.0)?, buckets);
    // The records in their vertex's bucket, each chunk's in its own stretch.
    let keys: Vec<AtomicU64> = zeroed(start[buckets]);
    let lows: Vec<AtomicU16> = zeroed(start[buckets]);
    let placed = chunks.par_iter().zip(cursors).all(|(r, mut at)| {
        for f in r.clone() {
            sides(f, &mut |lo, hi| {
                let i = &mut at[bucket(lo)];
                keys[*i].store((u64::from(hi) << 32) | f as u64, Relaxed);
                lows[*i].store((lo & ((1 << VERTEX_BITS) - 1)) as u16, Relaxed);
                *i += 1;
            });
        }
        go_on(0.25 + 0.25 * r.end as f64 / faces as f64)
    });
    if !placed {
        return None;
    }
    let keys: Vec<u64> = keys.into_iter().map(AtomicU64::into_inner).collect();
    let lows: Vec<u16> = lows.into_iter().map(AtomicU16::into_inner).collect();
    Some((keys, lows, start))
}

/// Each vertex bucket's pairs of faces around its edges, from its sides (`keys`:
/// other vertex `<< 32 |` face, `lows`: the lower vertex's low bits) at
/// `start[b]..start[b + 1]`: each vertex's records sorted, each edge's faces paired
/// ([`push_edge_pairs`]); buckets in parallel, each asking `go_on`. Also the number
/// of edges one face alone holds.
fn edge_pairs(
    keys: &[u64],
    lows: &[u16],
    start: &[usize],
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<Pairs>, u64)> {
    let buckets = start.len() - 1;
    let done = AtomicU32::new(0);
    let lists: Vec<Option<(Pairs, u64)>> = (0..buckets)
        .into_par_iter()
        .map_init(Finish::default, |scratch, b| {
            let (keys, lows) = (&keys[start[b]..start[b + 1]], &lows[start[b]..start[b + 1]]);
            let (mut pairs, mut open) = (Vec::new(), 0u64);
            for run in scratch.runs(keys, lows, 1 << VERTEX_BITS) {
                run.sort_unstable();
                for edge in run.chunk_by(|x, y| x >> 32 == y >> 32) {
                    open += u64::from(edge.len() == 1);
                    push_edge_pairs(edge, &mut pairs);
                }
            }
            let k = done.fetch_add(1, Relaxed) + 1;
            go_on(0.5 + 0.4 * f64::from(k) / buckets as f64).then_some((pairs, open))
        })
        .collect();
    let lists: Vec<(Pairs, u64)> = lists.into_iter().collect::<Option<_>>()?;
    let open = lists.iter().map(|l| l.1).sum();
    Some((lists.into_iter().map(|l| l.0).collect(), open))
}

/// One bucket's pairs of faces sharing an edge.
type Pairs = Vec<(u32, u32)>;

/// From each chunk's count of items per bucket: each bucket's start (one more entry
/// than buckets), and each chunk's cursor per bucket: the chunks' items in a bucket
/// follow each other in the chunks' order.
fn chunk_starts(counts: Vec<Vec<u32>>, buckets: usize) -> (Vec<usize>, Vec<Vec<usize>>) {
    let mut start = vec![0usize; buckets + 1];
    let mut cursors: Vec<Vec<usize>> = counts.iter().map(|_| Vec::with_capacity(buckets)).collect();
    let mut at = 0usize;
    for b in 0..buckets {
        start[b] = at;
        for (count, cursor) in counts.iter().zip(&mut cursors) {
            cursor.push(at);
            at += count[b] as usize;
        }
    }
    start[buckets] = at;
    (start, cursors)
}

/// A bucket's items grouped by their low bits (a counting sort in scratch kept
/// between buckets).
#[derive(Default)]
struct Finish {
    count: Vec<u32>,
    items: Vec<u64>,
}

impl Finish {
    /// `keys` in runs of equal `lows` (of `width` values), in increasing low bits,
    /// each run in its items' order; empty runs left out.
    fn runs<'s>(
        &'s mut self,
        keys: &[u64],
        lows: &[u16],
        width: usize,
    ) -> impl Iterator<Item = &'s mut [u64]> {
        self.count.clear();
        self.count.resize(width + 1, 0);
        for &l in lows {
            self.count[usize::from(l) + 1] += 1;
        }
        for i in 0..width {
            self.count[i + 1] += self.count[i];
        }
        self.items.clear();
        self.items.resize(keys.len(), 0);
        for (&k, &l) in keys.iter().zip(lows) {
            let at = &mut self.count[usize::from(l)];
            self.items[*at as usize] = k;
            *at += 1;
        }
        // `count[i]` is now run i's end.
        let ends = &self.count[..width];
        let mut rest = &mut self.items[..];
        let mut from = 0;
        ends.iter().filter_map(move |&end| {
            let (run, tail) = std::mem::take(&mut rest).split_at_mut((end - from) as usize);
            (rest, from) = (tail, end);
            (!run.is_empty()).then_some(run)
        })
    }
}

/// The pairs of `lists` sorted and each once, as one sort of all of them gives: a
/// partition by the first face's bucket (counted and placed per list, in parallel),
/// then each bucket sorted on its own in cache (by the first face's low bits, then
/// each face's few pairs), buckets in parallel, each asking `go_on` (one sort of
/// every pair is seconds without a check at 14M faces); `None` when it said stop.
/// The same pairs for any thread count.
fn sorted_pairs(
    lists: Vec<Vec<(u32, u32)>>,
    faces: usize,
    go_on: crate::progress::Checkpoint,
) -> Option<Vec<(u32, u32)>> {
    let (mut keys, start) = bucketed_keys(lists, faces, go_on)?;
    sort_buckets(&mut keys, &start, go_on)?;
    let mut pairs: Vec<(u32, u32)> = keys
        .into_iter()
        .map(|k| ((k >> 32) as u32, k as u32))
        .collect();
    pairs.dedup();
    pairs.shrink_to_fit();
    Some(pairs)
}

/// The pairs of `lists` as keys `a << 32 | b` (ordered as the pairs are), partitioned
/// by the first face's bucket, and each bucket's start (the last entry the end):
/// counted and placed per list, in parallel. `None` when `go_on` said stop.
fn bucketed_keys(
    lists: Vec<Vec<(u32, u32)>>,
    faces: usize,
    go_on: crate::progress::Checkpoint,
) -> Option<(Vec<u64>, Vec<usize>)> {
    let buckets = (faces >> FACE_BITS) + 1;
    let bucket = |a: u32| (a >> FACE_BITS) as usize;
    let counts: Vec<Vec<u32>> = lists
        .par_iter()
        .map(|list| {
            let mut count = vec![0u32; buckets];
            list.iter().for_each(|&(a, _)| count[bucket(a)] += 1);
            count
        })
        .collect();
    go_on(0.9).then_some(())?;
    let (start, cursors) = chunk_starts(counts, buckets);
    let slots: Vec<AtomicU64> = zeroed(start[buckets]);
    lists.par_iter().zip(cursors).for_each(|(list, mut at)| {
        for &(a, b) in list {
            let i = &mut at[bucket(a)];
            slots[*i].store((u64::from(a) << 32) | u64::from(b), Relaxed);
            *i += 1;
        }
    });
    drop(lists);
    go_on(0.9).then_some(())?;
    let keys: Vec<u64> = slots.into_iter().map(AtomicU64::into_inner).collect();
    Some((keys, start))
}

/// Sorts each bucket of `keys` (from `start[b]` to `start[b + 1]`) on its own in
/// cache, by the first face's low bits, then each face's few pairs; buckets in
/// parallel, each asking `go_on`. `None` when it said stop.
fn sort_buckets(
    keys: &mut [u64],
    start: &[usize],
    go_on: crate::progress::Checkpoint,
) -> Option<()> {
    let buckets = start.len() - 1;
    // Buckets own disjoint stretches of the keys.
    let mut stretches = Vec::with_capacity(buckets);
    let mut rest = keys;
    for b in 0..buckets {
        let (head, tail) = rest.split_at_mut(start[b + 1] - start[b]);
        stretches.push(head);
        rest = tail;
    }
    let lows: u64 = (1 << FACE_BITS) - 1;
    let sorted = stretches
        .into_par_iter()
        .map_init(
            || (Finish::default(), Vec::new()),
            |(scratch, low), keys| {
                low.clear();
                low.extend(keys.iter().map(|&k| ((k >> 32) & lows) as u16));
                let mut at = 0;
                for run in scratch.runs(keys, low, 1 << FACE_BITS) {
                    run.sort_unstable();
                    keys[at..at + run.len()].copy_from_slice(run);
                    at += run.len();
                }
                go_on(0.9)
            },
        )
        .all(|going| going);
    sorted.then_some(())
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

    /// Over several chunks of faces and buckets of vertices and faces, on several
    /// thread counts: the pairs of one sort of every (edge, face) record.
    #[test]
    fn buckets_give_one_sort_of_all_records() {
        // A 500 × 600 grid of quads as triangles, vertex ids scrambled so sides
        // fall in every bucket, with a quad, a fan of six faces around one edge and a
        // repeated face appended.
        let (w, h) = (500u32, 600u32);
        let id = |x: u32, y: u32| ((y * (w + 1) + x).wrapping_mul(2_654_435_761)) % 400_009;
        let mut indices = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let (a, b) = (id(x, y), id(x + 1, y));
                let (c, d) = (id(x + 1, y + 1), id(x, y + 1));
                indices.extend([a, b, c, a, c, d]);
            }
        }
        let mut offsets: Vec<u32> = (0..=indices.len() as u32 / 3).map(|i| 3 * i).collect();
        let mut push = |face: &[u32]| {
            indices.extend_from_slice(face);
            offsets.push(indices.len() as u32);
        };
        push(&[id(0, 0), id(1, 0), id(1, 1), id(0, 1)]);
        for k in 0..6 {
            push(&[id(7, 7), id(8, 7), 400_010 + k]);
        }
        push(&[id(3, 3), id(4, 3), id(4, 4)]);
        assert!(offsets.len() - 1 > 2 * CHUNK && 400_016 >> VERTEX_BITS > 8);
        // One sort of every (lo, hi, face) record, each edge's faces paired.
        let mut records = Vec::new();
        for f in 0..offsets.len() - 1 {
            let idx = &indices[offsets[f] as usize..offsets[f + 1] as usize];
            for i in 0..idx.len() {
                let (a, b) = (idx[i], idx[(i + 1) % idx.len()]);
                if a != b {
                    records.push((a.min(b), (u64::from(a.max(b)) << 32) | f as u64));
                }
            }
        }
        records.sort_unstable();
        let mut expected = Vec::new();
        for edge in records.chunk_by(|x, y| x.0 == y.0 && x.1 >> 32 == y.1 >> 32) {
            let run: Vec<u64> = edge.iter().map(|r| r.1).collect();
            push_edge_pairs(&run, &mut expected);
        }
        expected.sort_unstable();
        expected.dedup();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let got = pool.install(|| face_pairs(&offsets, &indices));
            assert!(got == expected, "{threads} threads");
        }
        let unwelded = crate::input::dedup::Weld::none();
        assert!(face_pairs_checked(&offsets, &indices, &unwelded, &|_| false).is_none());
    }

    /// Edges one face alone holds, counted by the same pass: none on a closed box of
    /// quads, the lid's four once the lid is left out, every edge where the quads
    /// share no vertex.
    #[test]
    fn open_edges_are_those_one_face_holds() {
        let quads = crate::input::demo::BOX_FACES.map(|q| q.map(|c| c as u32));
        let open = |quads: &[[u32; 4]]| {
            let indices: Vec<u32> = quads.iter().flatten().copied().collect();
            let offsets: Vec<u32> = (0..=quads.len() as u32).map(|i| 4 * i).collect();
            let unwelded = crate::input::dedup::Weld::none();
            face_pairs_checked(&offsets, &indices, &unwelded, &|_| true).map(|(_, open)| open)
        };
        assert_eq!(open(&quads), Some(0));
        assert_eq!(open(&quads[..5]), Some(4)); // without the top, +z
        let apart: Vec<[u32; 4]> = (0..6u32).map(|f| [0, 1, 2, 3].map(|c| 4 * f + c)).collect();
        assert_eq!(open(&apart), Some(24));
    }

    #[test]
    fn degenerate_edges_are_ignored() {
        let offsets = [0, 3, 6];
        assert!(face_pairs(&offsets, &[0, 0, 1, 2, 2, 3]).is_empty());
    }
}
