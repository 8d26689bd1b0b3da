//! The distinct corners of a cut's node, as its snapshot keeps them (§3.4 reads them
//! as the primitive's vertices), found in steps of bounded work: one sort of the
//! corners of a node of millions of faces is seconds long, which would keep a
//! cancel waiting (docs/results/throughput.md, "Cancellation").

use crate::input::mesh::Mesh;
use crate::math::marks::distinct_increasing;

/// Faces of a node, at least, whose corners are marked in a bitset instead of
/// sorted (a sort of fewer corners is milliseconds long).
const MARKED_FROM: usize = 1 << 18;

/// Faces marked between two asks of `go_on`.
const BLOCK: usize = 1 << 16;

/// The distinct vertices of `faces`' corners, increasing: sorted for a node of
/// fewer than [`MARKED_FROM`] faces, else marked in a bitset over the mesh's
/// vertices and read back in order (the same list), asking `go_on` first and
/// every [`BLOCK`] faces ([`distinct_increasing`]); `None` when it said stop.
pub(super) fn distinct_corners(
    mesh: &Mesh,
    faces: &[u32],
    go_on: impl Fn() -> bool,
) -> Option<Vec<u32>> {
    let corners = |fs: &[u32]| {
        (fs.iter())
            .flat_map(|&f| mesh.face(f as usize).iter().copied())
            .collect::<Vec<u32>>()
    };
    if !go_on() {
        return None;
    }
    if faces.len() < MARKED_FROM {
        let mut v = corners(faces);
        v.sort_unstable();
        v.dedup();
        return Some(v);
    }
    let blocks = faces.chunks(BLOCK).map(corners);
    distinct_increasing(mesh.vertex_count(), blocks, go_on)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Marked or sorted, the same list; told to stop, `None`.
    #[test]
    fn marks_give_the_sorted_list_and_stop_when_told() {
        let n = 600usize;
        let mut p = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                p.push([i as f64, j as f64, ((i * 7 + j * 3) % 5) as f64]);
            }
        }
        let at = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                tris.push(vec![at(i, j), at(i + 1, j), at(i, j + 1)]);
                tris.push(vec![at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let mesh = Mesh::from_polygons(&p, &tris).unwrap();
        // Every other face, from the back: more than MARKED_FROM, not in order.
        let faces: Vec<u32> = (0..mesh.face_count() as u32).rev().step_by(2).collect();
        assert!(faces.len() >= MARKED_FROM);
        let mut sorted: Vec<u32> = (faces.iter())
            .flat_map(|&f| mesh.face(f as usize).iter().copied())
            .collect();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(distinct_corners(&mesh, &faces, || true), Some(sorted));
        let asked = std::cell::Cell::new(0);
        let once = || {
            asked.set(asked.get() + 1);
            asked.get() < 3
        };
        assert_eq!(distinct_corners(&mesh, &faces, once), None);
        assert_eq!(asked.get(), 3);
        assert_eq!(distinct_corners(&mesh, &faces[..9], || false), None);
    }
}
