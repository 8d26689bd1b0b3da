//! The distinct ids of a long list, increasing, in steps of bounded work: one sort of
//! millions of ids is a step of a second or more, which keeps a cancel waiting; ids
//! marked in a bitset over their range, a block at a time, and read back in order
//! give the same list with an ask between blocks.
//!
//! ```
//! use primdecomp_math::marks::distinct_increasing;
//!
//! let ids = [7u32, 3, 7, 0, 3];
//! let blocks = ids.chunks(2).map(|b| b.iter().copied());
//! assert_eq!(distinct_increasing(8, blocks, || true), Some(vec![0, 3, 7]));
//! assert_eq!(distinct_increasing(8, ids.chunks(2).map(|b| b.iter().copied()), || false), None);
//! ```

/// Bitset words read back between two asks of `go_on`.
const WORDS_PER_CHECK: usize = 1 << 16;

/// The distinct ids of `blocks` (each below `range`), increasing, marked in a bitset
/// over `0..range`: `go_on` asked before each block and every 2^16 words
/// read back (`WORDS_PER_CHECK`); `None` as soon as it said stop. The same list as a sort and
/// dedup of all the ids.
pub fn distinct_increasing<B: IntoIterator<Item = u32>>(
    range: usize,
    blocks: impl IntoIterator<Item = B>,
    go_on: impl Fn() -> bool,
) -> Option<Vec<u32>> {
    let mut marks = vec![0u64; range.div_ceil(64)];
    for block in blocks {
        if !go_on() {
            return None;
        }
        for v in block {
            marks[v as usize / 64] |= 1 << (v % 64);
        }
    }
    let mut out = Vec::new();
    for (b, words) in marks.chunks(WORDS_PER_CHECK).enumerate() {
        if !go_on() {
            return None;
        }
        for (w, &word) in words.iter().enumerate() {
            let base = ((b * WORDS_PER_CHECK + w) * 64) as u32;
            let mut bits = word;
            while bits != 0 {
                out.push(base + bits.trailing_zeros());
                bits &= bits - 1;
            }
        }
    }
    Some(out)
}
