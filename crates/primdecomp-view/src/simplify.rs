//! The input mesh as shown: its polygons as triangles, simplified with meshoptimizer
//! to a display budget when it has more, so a million-face scan opens quickly.

use crate::source::InputMesh;
use std::collections::HashMap;

/// Default display budget for the input mesh, in triangles.
pub const DISPLAY_TRIANGLES: usize = 200_000;

/// The triangles shown for an input mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Display {
    pub positions: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// Faces (polygons) of the file.
    pub source_faces: usize,
    /// Triangles of the file's polygons before simplification.
    pub source_triangles: usize,
    /// Whether the triangles are a simplification (more than the budget before).
    pub simplified: bool,
}

/// Fan-triangulates the input's polygons and, beyond `budget` triangles, welds
/// coincident vertices and simplifies to at most `budget` (meshoptimizer's
/// edge-collapse simplifier, then its sloppy one if borders keep it above).
pub fn display(mesh: &InputMesh, budget: usize) -> Display {
    let n = mesh.positions.len() as u32;
    let triangles: Vec<[u32; 3]> = mesh
        .polygons
        .iter()
        .filter(|f| f.iter().all(|&i| i < n))
        .flat_map(|f| (1..f.len().saturating_sub(1)).map(move |i| [f[0], f[i], f[i + 1]]))
        .collect();
    let source_triangles = triangles.len();
    if source_triangles <= budget {
        return Display {
            positions: mesh.positions.clone(),
            triangles,
            source_faces: mesh.polygons.len(),
            source_triangles,
            simplified: false,
        };
    }
    let (positions, triangles) = weld(&mesh.positions, &triangles);
    // meshoptimizer works in f32: coordinates relative to the first vertex keep a
    // scan far from the origin precise.
    let o = positions[0];
    let local: Vec<[f32; 3]> = positions
        .iter()
        .map(|p| [0, 1, 2].map(|d| (p[d] - o[d]) as f32))
        .collect();
    let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
    let target = 3 * budget.max(1);
    let mut out = meshopt::simplify_decoder(
        &flat,
        &local,
        target,
        f32::MAX,
        meshopt::SimplifyOptions::None,
        None,
    );
    if out.len() > target {
        out = meshopt::simplify_sloppy_decoder(&flat, &local, target, f32::MAX, None);
    }
    let (positions, triangles) = compact(&positions, &out);
    Display {
        positions,
        triangles,
        source_faces: mesh.polygons.len(),
        source_triangles,
        simplified: true,
    }
}

/// Merges vertices with bit-identical coordinates (STL repeats them per triangle),
/// first occurrence first, and drops triangles that collapse.
fn weld(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut out = Vec::new();
    let mut remap = vec![u32::MAX; positions.len()];
    let mut tris = Vec::with_capacity(triangles.len());
    for t in triangles {
        let t = t.map(|i| {
            let r = &mut remap[i as usize];
            if *r == u32::MAX {
                let p = positions[i as usize].map(|x| x + 0.0);
                *r = *index.entry(p.map(f64::to_bits)).or_insert_with(|| {
                    out.push(p);
                    out.len() as u32 - 1
                });
            }
            *r
        });
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            tris.push(t);
        }
    }
    (out, tris)
}

/// The vertices a flat index list uses, renumbered in order of first use.
fn compact(positions: &[[f64; 3]], flat: &[u32]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut remap = vec![u32::MAX; positions.len()];
    let mut out = Vec::new();
    let idx: Vec<u32> = flat
        .iter()
        .map(|&i| {
            let r = &mut remap[i as usize];
            if *r == u32::MAX {
                out.push(positions[i as usize]);
                *r = out.len() as u32 - 1;
            }
            *r
        })
        .collect();
    let tris = idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    (out, tris)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A w × w grid of quads as triangle soup (every triangle its own vertices, as an
    /// STL file has them), gently curved so the simplifier has something to keep.
    fn soup(w: u32) -> InputMesh {
        let mut positions = Vec::new();
        let mut polygons = Vec::new();
        let p = |i: u32, j: u32| {
            let (x, y) = (i as f64 / w as f64, j as f64 / w as f64);
            [x, y, 0.1 * (3.0 * x).sin() * (2.0 * y).cos() + 1.0e6]
        };
        for i in 0..w {
            for j in 0..w {
                for t in [
                    [(i, j), (i + 1, j), (i + 1, j + 1)],
                    [(i, j), (i + 1, j + 1), (i, j + 1)],
                ] {
                    let base = positions.len() as u32;
                    positions.extend(t.map(|(a, b)| p(a, b)));
                    polygons.push(vec![base, base + 1, base + 2]);
                }
            }
        }
        InputMesh {
            positions,
            polygons,
        }
    }

    #[test]
    fn small_inputs_are_shown_as_they_are() {
        let m = soup(4);
        let d = display(&m, 1000);
        assert!(!d.simplified);
        assert_eq!(d.triangles.len(), 32);
        assert_eq!(d.positions, m.positions);
    }

    #[test]
    fn large_soups_are_welded_and_simplified_to_the_budget() {
        let m = soup(100);
        let d = display(&m, 2000);
        assert!(d.simplified);
        assert_eq!(d.source_triangles, 20_000);
        assert!(d.triangles.len() <= 2000, "{}", d.triangles.len());
        assert!(d.triangles.len() >= 500, "{}", d.triangles.len());
        // Welded: far fewer vertices than three per triangle, all used.
        assert!(d.positions.len() < 2 * d.triangles.len());
        let (lo, hi) = crate::geometry::aabb(&d.positions, &d.triangles).unwrap();
        assert!(
            (lo[0] - 0.0).abs() < 1e-9 && (hi[0] - 1.0).abs() < 1e-9,
            "{lo:?} {hi:?}"
        );
        // The same input gives the same triangles.
        assert_eq!(display(&m, 2000), d);
    }
}
