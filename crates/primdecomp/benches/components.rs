//! Many disjoint components (docs/decisions/hostile-input-limits.md, "Many components"): C small tetrahedra on a jittered
//! 3D grid (4 faces each, no shared vertices), decomposed to N = C/10 and to N = 1, for
//! C = 1,000, 3,000 and 10,000. Adjacency runs out at N = C, so every further merge
//! goes through the bridging step (docs/decisions/0006-component-bridging-nearest-12.md); a
//! quadratic step
//! would show as a 10k/1k time ratio near 100 instead of near 10.
//! Run: `cargo bench --bench components` (figures in docs/decisions/hostile-input-limits.md,
//! "Many components").

use criterion::{criterion_group, criterion_main, Criterion};
use primdecomp::{decompose, Goal, Mesh, Params};
use std::time::Duration;

/// `c` tetrahedra of edge ~0.3 at integer grid points, deterministically jittered.
fn tetrahedra(c: usize) -> Mesh {
    let side = (c as f64).cbrt().ceil() as usize;
    let mut v = Vec::with_capacity(4 * c);
    let mut f = Vec::with_capacity(4 * c);
    let mut x: u64 = 12345;
    let mut jitter = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 0.2
    };
    for i in 0..c {
        let o = [i % side, i / side % side, i / (side * side)].map(|k| k as f64);
        let b = v.len() as u32;
        for d in [
            [0.0, 0.0, 0.0],
            [0.3, 0.0, 0.0],
            [0.0, 0.3, 0.0],
            [0.0, 0.0, 0.3],
        ] {
            v.push([0, 1, 2].map(|k| o[k] + d[k] + jitter()));
        }
        for t in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
            f.push(t.iter().map(|&k| b + k).collect::<Vec<u32>>());
        }
    }
    Mesh::from_polygons(&v, &f).unwrap()
}

fn components(c: &mut Criterion) {
    let mut g = c.benchmark_group("components");
    g.sample_size(10).warm_up_time(Duration::from_secs(1));
    for n in [1_000, 3_000, 10_000] {
        let mesh = tetrahedra(n);
        let params = Params {
            goal: Goal::counts([n / 10, 1]),
            ..Default::default()
        };
        g.bench_function(format!("{n}"), |b| {
            b.iter(|| decompose(&mesh, &params).expect("decomposes"))
        });
    }
    g.finish();
}

criterion_group!(benches, components);
criterion_main!(benches);
