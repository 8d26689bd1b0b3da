//! An approximate point reduction (issue 5: "where an approximate reduction is faster
//! still, offer it as an explicit speed/accuracy setting"): the extreme points of a
//! cloud along the 13 axes of a 26-DOP (3 coordinate axes, 6 face diagonals, 4 body
//! diagonals), at most 26 points, in one pass over the points.
//!
//! Unlike [`super::hull::hull_vertices`] the result is not exact: its convex hull is an
//! inner approximation of the cloud's (a fit on it may come out smaller than on all
//! points along directions between the 13 axes). What it does keep is composition:
//! the extremes of the union of two clouds' extremes are the union's extremes (along
//! each axis, the union's maximum is one of the two clouds' maxima), so a cluster's
//! point list stays exactly the 26-DOP extremes of all its faces' vertices however
//! its merges were ordered.

/// The 13 axes: coordinate axes, face diagonals, body diagonals (not normalised: only
/// the order of the projections matters).
pub const AXES: [[f64; 3]; 13] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, 1.0, -1.0],
    [1.0, 1.0, 1.0],
    [1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Indices of the points of `x, y, z` (SoA, equal length) that are extreme along
/// each of [`AXES`], both ways, into `out`: sorted, without duplicates, at most 26.
/// On ties the lowest index wins, so the result depends on the points alone. Empty
/// input gives empty output.
pub fn extreme_points(x: &[f64], y: &[f64], z: &[f64], out: &mut Vec<u32>) {
    out.clear();
    let n = x.len().min(y.len()).min(z.len());
    if n == 0 {
        return;
    }
    let mut lo = [(f64::INFINITY, 0u32); 13];
    let mut hi = [(f64::NEG_INFINITY, 0u32); 13];
    for i in 0..n {
        let p = [x[i], y[i], z[i]];
        for (k, a) in AXES.iter().enumerate() {
            let v = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
            if v < lo[k].0 {
                lo[k] = (v, i as u32);
            }
            if v > hi[k].0 {
                hi[k] = (v, i as u32);
            }
        }
    }
    out.extend(lo.iter().chain(&hi).map(|e| e.1));
    out.sort_unstable();
    out.dedup();
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn extremes(p: &[[f64; 3]]) -> Vec<u32> {
        let (x, y, z): (Vec<f64>, Vec<f64>, Vec<f64>) = (
            p.iter().map(|q| q[0]).collect(),
            p.iter().map(|q| q[1]).collect(),
            p.iter().map(|q| q[2]).collect(),
        );
        let mut out = Vec::new();
        extreme_points(&x, &y, &z, &mut out);
        out
    }

    /// The greatest and least projection of `p` on each axis.
    fn support(p: &[[f64; 3]]) -> Vec<(f64, f64)> {
        AXES.iter()
            .map(|a| {
                let v = p.iter().map(|q| a[0] * q[0] + a[1] * q[1] + a[2] * q[2]);
                (
                    v.clone().fold(f64::INFINITY, f64::min),
                    v.fold(f64::NEG_INFINITY, f64::max),
                )
            })
            .collect()
    }

    #[test]
    fn a_cube_keeps_its_corners_and_drops_the_inside() {
        let mut p: Vec<[f64; 3]> = (0..8)
            .map(|c| [(c & 1) as f64, ((c >> 1) & 1) as f64, ((c >> 2) & 1) as f64])
            .collect();
        p.push([0.5, 0.5, 0.5]);
        p.push([0.5, 0.5, 0.0]);
        assert_eq!(extremes(&p), (0..8).collect::<Vec<u32>>());
        assert!(extremes(&[]).is_empty());
        assert_eq!(extremes(&[[1.0, 2.0, 3.0]]), vec![0]);
    }

    proptest! {
        /// The kept points have the cloud's support along every axis, there are at
        /// most 26, and reducing two clouds and then their union gives the same
        /// support as reducing the union at once (the merge loop's composition).
        #[test]
        fn support_is_kept_and_composes(
            a in prop::collection::vec(prop::array::uniform3(-1e3f64..1e3), 1..60),
            b in prop::collection::vec(prop::array::uniform3(-1e3f64..1e3), 1..60),
        ) {
            let ka = extremes(&a);
            prop_assert!(ka.len() <= 26);
            prop_assert!(ka.windows(2).all(|w| w[0] < w[1]));
            let kept: Vec<[f64; 3]> = ka.iter().map(|&i| a[i as usize]).collect();
            prop_assert_eq!(support(&kept), support(&a));
            let kb: Vec<[f64; 3]> = extremes(&b).iter().map(|&i| b[i as usize]).collect();
            let both: Vec<[f64; 3]> = kept.iter().chain(&kb).copied().collect();
            let all: Vec<[f64; 3]> = a.iter().chain(&b).copied().collect();
            let again: Vec<[f64; 3]> = extremes(&both).iter().map(|&i| both[i as usize]).collect();
            prop_assert_eq!(support(&again), support(&all));
        }
    }
}
