//! Frames for degenerate quadrics (a fix to §3.2): the paper takes a cluster's axes
//! from the eigenvectors of its quadric Q. Where two eigenvalues of Q tie — every
//! planar cluster (Q has rank 1), a square tube, a box with two equal face pairs —
//! the eigenvectors in the tied plane are arbitrary: round-off picks them, so the fit
//! depends on the mesh's orientation and a single right triangle gets a box twice its
//! area. There the fit also tries the frames aligned with the longest edges of the
//! points' convex hull projected onto the tied plane (a minimum-area rectangle and an
//! isosceles trapezoid with a base on the polygon both have a side on a hull edge) and
//! keeps the cheapest. The measurements are in
//! docs/decisions/0013-frames-for-degenerate-quadrics.md.

use crate::math::{dot, madd, scale, V3};

/// Two eigenvalues closer than this fraction of the largest count as tied.
pub const TIE: f64 = 1e-6;

/// Another frame replaces the eigen-frame's fit only when it costs less by more than
/// this fraction: equal costs keep the paper's frame instead of round-off's choice.
pub const MARGIN: f64 = 1e-6;

/// At most this many edge directions are tried (the longest hull edges first).
pub const MAX_DIRS: usize = 6;

/// Reusable buffers for the projected points and their 2D hull.
#[derive(Clone, Debug, Default)]
pub struct PlaneScratch {
    p: Vec<[f64; 2]>,
    hull: Vec<[f64; 2]>,
    /// Candidate directions as (cos, sin) in the tied plane, with edge length.
    dirs: Vec<([f64; 2], f64)>,
}

/// The indices `(i, j)` of two tied eigenvalues (sorted by magnitude, largest first),
/// or `None` when the eigen-frame is well defined. A three-way tie returns the lower
/// pair (the top axis stays as the solver gave it).
pub fn tied_plane(values: &[f64; 3]) -> Option<(usize, usize)> {
    let top = values[0].abs();
    if top.is_nan() || top <= 0.0 {
        // Zero (or non-finite) Q: nothing to go on but the points; treat every
        // in-plane direction of the first two axes' complement as free.
        return Some((1, 2));
    }
    let tie = |a: f64, b: f64| (a.abs() - b.abs()).abs() <= TIE * top;
    if tie(values[1], values[2]) {
        Some((1, 2))
    } else if tie(values[0], values[1]) {
        Some((0, 1))
    } else {
        None
    }
}

/// True when the points, whose extents along the eigen-frame's axes are `span`, lie in
/// the plane of axes 1 and 2 up to round-off (a coplanar cluster): the tangent term of §3.4 then
/// makes Q's in-plane eigenvalues differ, but it aligns the frame with one edge of one
/// face, which may not be the cheapest (a lone right triangle gets a box twice its area
/// where the frame along its hypotenuse fits a prism exactly).
pub fn flat(span: [f64; 3]) -> bool {
    span[0] <= TIE * span[1].max(span[2])
}

/// Fills `s` with up to [`MAX_DIRS`] distinct directions (modulo quarter turns, since
/// the fits try every axis ordering) of the longest edges of the 2D convex hull of the
/// points projected on `(e0, e1)`, other than `e0`'s own (the frame already fitted);
/// returns how many. Zero when the projection has no edge (all points coincide).
pub fn edge_directions(
    x: &[f64],
    y: &[f64],
    z: &[f64],
    e0: V3,
    e1: V3,
    s: &mut PlaneScratch,
) -> usize {
    s.p.clear();
    s.p.extend((0..x.len()).map(|i| {
        let q = [x[i], y[i], z[i]];
        [dot(e0, q), dot(e1, q)]
    }));
    convex_hull_2d(&mut s.p, &mut s.hull);
    s.dirs.clear();
    let n = s.hull.len();
    if n < 2 {
        return 0;
    }
    for k in 0..n {
        let (a, b) = (s.hull[k], s.hull[(k + 1) % n]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = d[0].hypot(d[1]);
        if len > 0.0 && len.is_finite() {
            s.dirs
                .push((quarter_canonical([d[0] / len, d[1] / len]), len));
        }
    }
    // Longest first; equal lengths keep hull order (stable sort: deterministic).
    s.dirs.sort_by(|a, b| b.1.total_cmp(&a.1));
    // Slot 0 stands for the eigen-frame itself (already fitted): edges along it or
    // across it are dropped as duplicates.
    s.dirs.insert(0, ([1.0, 0.0], f64::INFINITY));
    let mut kept = 1;
    for k in 1..s.dirs.len() {
        let d = s.dirs[k].0;
        let dup = s.dirs[..kept].iter().any(|e| close(e.0, d));
        if !dup {
            s.dirs[kept] = s.dirs[k];
            kept += 1;
            if kept == MAX_DIRS + 1 {
                break;
            }
        }
    }
    s.dirs.truncate(kept);
    s.dirs.remove(0);
    kept - 1
}

/// Direction `k` found by the last [`edge_directions`] call, as (cos, sin).
pub fn direction(s: &PlaneScratch, k: usize) -> [f64; 2] {
    s.dirs[k].0
}

/// `axes` with axes `i` and `j` turned in their plane so that axis `i` points along
/// `(c, s)` of the old pair; the third axis and the handedness are unchanged.
pub fn turn(axes: [V3; 3], (i, j): (usize, usize), [c, s]: [f64; 2]) -> [V3; 3] {
    let mut out = axes;
    out[i] = madd(scale(axes[i], c), axes[j], s);
    out[j] = madd(scale(axes[j], c), axes[i], -s);
    out
}

/// The representative of `d` under quarter turns with `d.0 > 0, d.1 ≥ 0`.
fn quarter_canonical(mut d: [f64; 2]) -> [f64; 2] {
    for _ in 0..4 {
        if d[0] > 0.0 && d[1] >= 0.0 {
            break;
        }
        d = [d[1], -d[0]];
    }
    d
}

/// Directions equal up to round-off (they also match across the wrap at a quarter turn).
fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    let cross = (a[0] * b[1] - a[1] * b[0]).abs();
    let dot = a[0] * b[0] + a[1] * b[1];
    cross <= 1e-9 || dot.abs() <= 1e-9
}

/// Andrew's monotone chain: the counter-clockwise hull of `p` (sorted in place) into
/// `out`, collinear points dropped.
pub(crate) fn convex_hull_2d(p: &mut [[f64; 2]], out: &mut Vec<[f64; 2]>) {
    out.clear();
    p.sort_unstable_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let n = p.len();
    for pass in 0..2 {
        let start = out.len();
        for k in 0..n {
            let q = if pass == 0 { p[k] } else { p[n - 1 - k] };
            while out.len() >= start + 2 && cross(out[out.len() - 2], out[out.len() - 1], q) <= 0.0
            {
                out.pop();
            }
            out.push(q);
        }
        out.pop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties() {
        assert_eq!(tied_plane(&[1.0, 0.0, 0.0]), Some((1, 2)));
        assert_eq!(tied_plane(&[1.0, 1.0, 0.5]), Some((0, 1)));
        assert_eq!(tied_plane(&[1.0, 0.5, 0.25]), None);
        assert_eq!(tied_plane(&[0.0, 0.0, 0.0]), Some((1, 2)));
    }

    #[test]
    fn hull_of_a_square_with_inner_points() {
        let mut p = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [0.5, 0.5],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.5, 0.0],
        ];
        let mut h = Vec::new();
        convex_hull_2d(&mut p, &mut h);
        assert_eq!(h, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    }

    #[test]
    fn right_triangle_adds_the_direction_the_frame_lacks() {
        // Legs along x and y collapse to one direction modulo quarter turns; the
        // hypotenuse gives the 45° one, and it is the longest.
        let (x, y, z) = (vec![0.0, 2.0, 0.0], vec![0.0, 0.0, 2.0], vec![0.0; 3]);
        let mut s = PlaneScratch::default();
        let n = edge_directions(&x, &y, &z, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], &mut s);
        // The legs are along the given frame (already fitted): only the hypotenuse.
        assert_eq!(n, 1);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let d0 = direction(&s, 0);
        assert!(
            (d0[0] - h).abs() < 1e-12 && (d0[1] - h).abs() < 1e-12,
            "{d0:?}"
        );
        // In a frame along the hypotenuse, the legs are the one other direction.
        let n = edge_directions(&x, &y, &z, [h, h, 0.0], [-h, h, 0.0], &mut s);
        assert_eq!(n, 1);
        let d0 = direction(&s, 0);
        assert!(
            (d0[0] - h).abs() < 1e-12 && (d0[1] - h).abs() < 1e-12,
            "{d0:?}"
        );
    }

    #[test]
    fn turn_keeps_an_orthonormal_right_handed_frame() {
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let (c, s) = (0.6, 0.8);
        let t = turn(axes, (1, 2), [c, s]);
        assert_eq!(t[0], axes[0]);
        assert_eq!(t[1], [0.0, 0.6, 0.8]);
        assert_eq!(t[2], [0.0, -0.8, 0.6]);
        // y × z = x: still right-handed.
        let cr = [
            t[1][1] * t[2][2] - t[1][2] * t[2][1],
            t[1][2] * t[2][0] - t[1][0] * t[2][2],
            t[1][0] * t[2][1] - t[1][1] * t[2][0],
        ];
        assert!((cr[0] - 1.0).abs() < 1e-15 && cr[1].abs() < 1e-15 && cr[2].abs() < 1e-15);
    }
}
