//! Basins of a top surface: the cells of a height field where a ball resting on it
//! cannot roll off (the water a priority flood would hold over the ball's centre
//! height). A collider with basins the mesh lacks holds balls in a simulation that the
//! mesh sheds (tests/rim.rs). Independent of the fitting code: it reads triangles.

use primdecomp_math::V3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A regular grid over x (i) and z (j), up = +y, cell centres at `x0 + i·step`.
pub struct Grid {
    pub x0: f64,
    pub z0: f64,
    pub step: f64,
    pub nx: usize,
    pub nz: usize,
}

impl Grid {
    fn at(&self, i: usize, j: usize) -> usize {
        i * self.nz + j
    }
}

/// The highest point of `tris` over each cell centre, −∞ where none lies above it.
pub fn heights(tris: &[[V3; 3]], g: &Grid) -> Vec<f64> {
    let mut h = vec![f64::NEG_INFINITY; g.nx * g.nz];
    for [a, b, c] in tris {
        let (u, v) = ([b[0] - a[0], b[2] - a[2]], [c[0] - a[0], c[2] - a[2]]);
        let den = u[0] * v[1] - v[0] * u[1];
        if den.abs() < 1e-14 {
            continue; // vertical in x–z: seen by the faces beside it
        }
        let lo = |k: usize| a[k].min(b[k]).min(c[k]);
        let hi = |k: usize| a[k].max(b[k]).max(c[k]);
        let cells = |lo: f64, hi: f64, o: f64, n: usize| {
            let first = ((lo - o) / g.step).ceil().max(0.0) as usize;
            let last = (((hi - o) / g.step).floor() as isize).min(n as isize - 1);
            first..(last + 1).max(0) as usize
        };
        for i in cells(lo(0), hi(0), g.x0, g.nx) {
            for j in cells(lo(2), hi(2), g.z0, g.nz) {
                let (px, pz) = (
                    g.x0 + i as f64 * g.step - a[0],
                    g.z0 + j as f64 * g.step - a[2],
                );
                let s = (px * v[1] - v[0] * pz) / den;
                let t = (u[0] * pz - px * u[1]) / den;
                if s >= -1e-9 && t >= -1e-9 && s + t <= 1.0 + 1e-9 {
                    let y = a[1] + s * (b[1] - a[1]) + t * (c[1] - a[1]);
                    let k = g.at(i, j);
                    h[k] = h[k].max(y);
                }
            }
        }
    }
    h
}

/// The height a ball of radius `r` centred over each cell rests at on the surface `h`
/// (the highest of h + √(r² − d²) over cells within r), −∞ where nothing is under it.
pub fn centre_heights(h: &[f64], g: &Grid, r: f64) -> Vec<f64> {
    let k = (r / g.step).round() as isize;
    let disc: Vec<(isize, isize, f64)> = (-k..=k)
        .flat_map(|di| (-k..=k).map(move |dj| (di, dj)))
        .filter_map(|(di, dj)| {
            let d2 = ((di * di + dj * dj) as f64) * g.step * g.step;
            (d2 <= r * r).then(|| (di, dj, (r * r - d2).sqrt()))
        })
        .collect();
    let mut c = vec![f64::NEG_INFINITY; h.len()];
    for i in 0..g.nx {
        for j in 0..g.nz {
            let mut best = f64::NEG_INFINITY;
            for &(di, dj, lift) in &disc {
                let (a, b) = (i as isize + di, j as isize + dj);
                if a >= 0 && b >= 0 && (a as usize) < g.nx && (b as usize) < g.nz {
                    best = best.max(h[g.at(a as usize, b as usize)] + lift);
                }
            }
            c[g.at(i, j)] = best;
        }
    }
    c
}

#[derive(PartialEq)]
struct Low(f64, usize);
impl Eq for Low {}
impl Ord for Low {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}
impl PartialOrd for Low {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// Cells where the ball's centre height `c` lies more than `depth` below the level a
/// flood from the grid's border and from the cells off the object (nothing under the
/// ball) would fill to: the ball cannot roll out of them.
pub fn basin_cells(c: &[f64], g: &Grid, depth: f64) -> usize {
    let mut fill = vec![f64::NAN; c.len()];
    let mut heap = BinaryHeap::new();
    for i in 0..g.nx {
        for j in 0..g.nz {
            let k = g.at(i, j);
            if i == 0 || j == 0 || i + 1 == g.nx || j + 1 == g.nz || c[k] == f64::NEG_INFINITY {
                fill[k] = c[k];
                heap.push(Low(c[k], k));
            }
        }
    }
    while let Some(Low(level, k)) = heap.pop() {
        let (i, j) = (k / g.nz, k % g.nz);
        let around = [
            (i + 1, j),
            (i.wrapping_sub(1), j),
            (i, j + 1),
            (i, j.wrapping_sub(1)),
        ];
        for (a, b) in around {
            if a < g.nx && b < g.nz && fill[g.at(a, b)].is_nan() {
                let n = g.at(a, b);
                fill[n] = c[n].max(level);
                heap.push(Low(fill[n], n));
            }
        }
    }
    (0..c.len()).filter(|&k| fill[k] - c[k] > depth).count()
}
