//! Per-face linear operator Q = area·(nnᵀ + ε·ttᵀ) (§3.1 "Linear Operator",
//! "Face Normal Computation"; §3.4 "Coplanar Vertices"), computed in parallel chunks.
//!
//! - Triangles: n from the edge cross product; t along the middle-length edge. The paper
//!   writes t₀ = ½(e₀ − e₁ + e₂) for counter-clockwise edges sorted by length; since the
//!   edges of a triangle sum to zero this is exactly −e₁, the middle edge (the quad side
//!   of a triangulated quad that is not the diagonal). The paper's sign flip of t does
//!   not change ttᵀ, so it is omitted.
//! - Quads: n from the cross product of the diagonals, area ½|d₀ × d₁| (exact when
//!   planar), t = v₀ − v₂ + v₁ − v₃.
//! - Larger polygons: a triangle fan from vertex 0, each triangle with its own normal.

use crate::input::mesh::Mesh;
use crate::math::{add, cross, norm, normalize, sub, Sym3, V3};
use rayon::prelude::*;

/// Faces per parallel chunk.
const CHUNK: usize = 4096;

/// Q of every face of `mesh` (with its own, un-welded indices), into `out`.
#[cfg(any(test, feature = "test-internals"))]
pub fn face_quadrics(mesh: &Mesh, tangent_eps: f64, out: &mut Vec<Sym3>) {
    face_quadrics_checked(mesh, tangent_eps, out, &|_| true);
}

/// Faces per block between reports to `go_on` (a few milliseconds of work).
const BLOCK: usize = 1 << 20;

/// [`face_quadrics`] a block at a time, reporting the fraction done to `go_on` and
/// stopping (the rest left zero; the caller then returns cancelled) when it says so.
pub fn face_quadrics_checked(
    mesh: &Mesh,
    tangent_eps: f64,
    out: &mut Vec<Sym3>,
    go_on: crate::progress::Checkpoint,
) {
    out.clear();
    out.resize(mesh.face_count(), Sym3::ZERO);
    let n = out.len().max(1);
    for (b, block) in out.chunks_mut(BLOCK).enumerate() {
        block
            .par_chunks_mut(CHUNK)
            .enumerate()
            .for_each(|(c, chunk)| {
                for (j, q) in chunk.iter_mut().enumerate() {
                    let f = b * BLOCK + c * CHUNK + j;
                    *q = face_quadric(mesh.face(f), |v| mesh.pos(v), tangent_eps);
                }
            });
        if !go_on(((b + 1) * BLOCK).min(n) as f64 / n as f64) {
            return;
        }
    }
}

/// Q of one polygon given its vertex indices and a position lookup.
pub fn face_quadric(idx: &[u32], pos: impl Fn(u32) -> V3, eps: f64) -> Sym3 {
    match idx.len() {
        0..=2 => Sym3::ZERO,
        3 => triangle_quadric(pos(idx[0]), pos(idx[1]), pos(idx[2]), eps),
        4 => quad_quadric([pos(idx[0]), pos(idx[1]), pos(idx[2]), pos(idx[3])], eps),
        _ => {
            let p0 = pos(idx[0]);
            let mut q = Sym3::ZERO;
            for w in idx[1..].windows(2) {
                q = q.add(&triangle_quadric(p0, pos(w[0]), pos(w[1]), eps));
            }
            q
        }
    }
}

/// area·(nnᵀ + ε·ttᵀ) with unit n and t; zero for a degenerate face.
fn weighted(area: f64, n: Option<V3>, t: Option<V3>, eps: f64) -> Sym3 {
    let Some(n) = n else {
        return Sym3::ZERO;
    };
    let q = Sym3::outer(n, area);
    match t {
        Some(t) if eps > 0.0 => q.add(&Sym3::outer(t, area * eps)),
        _ => q,
    }
}

fn triangle_quadric(a: V3, b: V3, c: V3, eps: f64) -> Sym3 {
    let e = [sub(b, a), sub(c, b), sub(a, c)];
    let n = cross(e[0], sub(c, a));
    let area = 0.5 * norm(n);
    let len = e.map(norm);
    // Index of the middle-length edge (ties broken by edge order, for determinism).
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| len[i].total_cmp(&len[j]));
    let t = normalize(e[order[1]]);
    weighted(area, normalize(n), t, eps)
}

fn quad_quadric(v: [V3; 4], eps: f64) -> Sym3 {
    let d0 = sub(v[0], v[2]);
    let d1 = sub(v[1], v[3]);
    let n = cross(d0, d1);
    weighted(0.5 * norm(n), normalize(n), normalize(add(d0, d1)), eps)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Sym3, b: &Sym3) -> bool {
        let d = [
            a.xx - b.xx,
            a.xy - b.xy,
            a.xz - b.xz,
            a.yy - b.yy,
            a.yz - b.yz,
            a.zz - b.zz,
        ];
        d.iter().all(|x| x.abs() < 1e-12)
    }

    #[test]
    fn unit_square_quad_and_its_triangles() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let q = face_quadric(&[0, 1, 2, 3], |i| p[i as usize], 0.0);
        assert!(close(&q, &Sym3::outer([0.0, 0.0, 1.0], 1.0)));
        // Tangent of the quad: v0 − v2 + v1 − v3 = (0, −2, 0) → along y.
        let qt = face_quadric(&[0, 1, 2, 3], |i| p[i as usize], 0.5);
        let want = Sym3::outer([0.0, 0.0, 1.0], 1.0).add(&Sym3::outer([0.0, 1.0, 0.0], 0.5));
        assert!(close(&qt, &want));
        // Half of the quad: tangent along one of its sides, area 1/2.
        let t = face_quadric(&[0, 1, 2], |i| p[i as usize], 1.0);
        assert!((t.zz - 0.5).abs() < 1e-12);
        assert!((t.xx + t.yy - 0.5).abs() < 1e-12 && t.xy.abs() < 1e-12);
    }

    #[test]
    fn fan_of_a_planar_hexagon_sums_areas() {
        let p: Vec<V3> = (0..6)
            .map(|i| {
                let a = i as f64 * std::f64::consts::PI / 3.0;
                [a.cos(), a.sin(), 0.0]
            })
            .collect();
        let idx: Vec<u32> = (0..6).collect();
        let q = face_quadric(&idx, |i| p[i as usize], 0.0);
        let area = 1.5 * 3f64.sqrt();
        assert!((q.zz - area).abs() < 1e-12 && q.xx.abs() < 1e-12);
    }

    #[test]
    fn degenerate_faces_give_zero() {
        let p = [[1.0, 2.0, 3.0]; 3];
        assert_eq!(
            face_quadric(&[0, 1, 2], |i| p[i as usize], 0.01),
            Sym3::ZERO
        );
        let line = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert_eq!(
            face_quadric(&[0, 1, 2], |i| line[i as usize], 0.01),
            Sym3::ZERO
        );
    }
}
