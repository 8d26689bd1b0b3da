//! Area-uniform sampling of a surface made of pieces (triangles of a mesh or a hull,
//! the analytic pieces of primitives), each tagged with the part that owns it.
//!
//! Samples come in fixed chunks; chunk `k` of stream `s` draws from a ChaCha8
//! generator seeded by (seed, s, k) alone, so the samples — and everything computed
//! from them in order — are the same for any thread count.

use super::shape::Piece;
use primdecomp_math::V3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Samples per chunk (one generator each).
pub const CHUNK: usize = 4096;

/// A surface: pieces, the part each belongs to, and their cumulative areas.
#[derive(Clone, Debug, Default)]
pub struct Surface {
    pub pieces: Vec<Piece>,
    pub owner: Vec<u32>,
    cumulative: Vec<f64>,
}

/// One sample: the point and the part it lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub p: V3,
    pub part: u32,
}

impl Surface {
    pub fn new(pieces: Vec<Piece>, owner: Vec<u32>) -> Surface {
        debug_assert_eq!(pieces.len(), owner.len());
        let mut acc = 0.0;
        let cumulative = pieces
            .iter()
            .map(|p| {
                acc += p.area().max(0.0);
                acc
            })
            .collect();
        Surface {
            pieces,
            owner,
            cumulative,
        }
    }

    /// Total area.
    pub fn area(&self) -> f64 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// `n` area-uniform samples (none when the area is zero).
    pub fn sample(&self, n: usize, seed: u64, stream: u64) -> Vec<Sample> {
        let total = self.area();
        if !(total > 0.0 && total.is_finite()) {
            return Vec::new();
        }
        let chunks = n.div_ceil(CHUNK);
        (0..chunks)
            .into_par_iter()
            .flat_map_iter(|k| {
                let mut rng = ChaCha8Rng::seed_from_u64(chunk_seed(seed, stream, k as u64));
                let len = CHUNK.min(n - k * CHUNK);
                (0..len)
                    .map(|_| self.one(&mut rng, total))
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    fn one(&self, rng: &mut ChaCha8Rng, total: f64) -> Sample {
        let target = rng.gen::<f64>() * total;
        let i = self
            .cumulative
            .partition_point(|&c| c <= target)
            .min(self.pieces.len() - 1);
        let w = [rng.gen(), rng.gen(), rng.gen()];
        Sample {
            p: self.pieces[i].point(w),
            part: self.owner[i],
        }
    }
}

/// SplitMix64 finaliser over (seed, stream, chunk).
fn chunk_seed(seed: u64, stream: u64, chunk: u64) -> u64 {
    let mut z = seed
        ^ stream.wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ chunk.wrapping_mul(0xD1B5_4A32_D192_ED03);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_triangles() -> Surface {
        // Areas 0.5 and 1.5: a quarter of the samples on part 0.
        let t0 = Piece::Tri([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        let t1 = Piece::Tri([[0.0, 0.0, 1.0], [3.0, 0.0, 1.0], [0.0, 1.0, 1.0]]);
        Surface::new(vec![t0, t1], vec![0, 1])
    }

    #[test]
    fn split_by_area_and_reproducible() {
        let s = two_triangles();
        assert_eq!(s.area(), 2.0);
        let a = s.sample(100_000, 5, 0);
        assert_eq!(a.len(), 100_000);
        let on0 = a.iter().filter(|x| x.part == 0).count() as f64 / a.len() as f64;
        assert!((on0 - 0.25).abs() < 0.01, "{on0}");
        assert!(a.iter().all(|x| (x.p[2] == 0.0) == (x.part == 0)));
        assert_eq!(a, s.sample(100_000, 5, 0));
        assert_ne!(a[..10], s.sample(10, 6, 0)[..]);
        assert_ne!(a[..10], s.sample(10, 5, 1)[..]);
        assert_eq!(a[..10], s.sample(10, 5, 0)[..], "a prefix is the same");
    }

    #[test]
    fn same_samples_on_any_thread_count() {
        let s = two_triangles();
        let run = |t| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
                .install(|| s.sample(3 * CHUNK + 17, 9, 2))
        };
        assert_eq!(run(1), run(3));
    }

    #[test]
    fn empty_surface_has_no_samples() {
        assert!(Surface::default().sample(10, 0, 0).is_empty());
        let flat = Piece::Tri([[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
        assert!(Surface::new(vec![flat], vec![0])
            .sample(10, 0, 0)
            .is_empty());
    }
}
