//! meshoptimizer's simplifier as the benches' yardstick: the mesh in the form it
//! reads, and one timed run down to a triangle count.

use std::time::Instant;

/// The mesh's positions in f32 and its faces' corners (fan-triangulated).
pub fn flat(m: &primdecomp::Mesh) -> (Vec<[f32; 3]>, Vec<u32>) {
    let pos = (0..m.vertex_count() as u32)
        .map(|v| m.pos(v).map(|c| c as f32))
        .collect();
    let mut idx = Vec::with_capacity(3 * m.face_count());
    for f in 0..m.face_count() {
        let v = m.face(f);
        for k in 2..v.len() {
            idx.extend([v[0], v[k - 1], v[k]]);
        }
    }
    (pos, idx)
}

/// Seconds meshoptimizer's simplifier takes to bring `idx` over `pos` down to
/// `triangles` triangles (one run; no error limit, so the count decides).
pub fn simplify_seconds(idx: &[u32], pos: &[[f32; 3]], triangles: usize) -> f64 {
    let start = Instant::now();
    let out = meshopt::simplify_decoder(
        idx,
        pos,
        3 * triangles,
        1.0,
        meshopt::SimplifyOptions::None,
        None,
    );
    std::hint::black_box(out);
    start.elapsed().as_secs_f64()
}
