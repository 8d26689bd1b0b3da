//! Convex polygons in a plane, as lists of 2D points: their area and their clipping
//! (Sutherland–Hodgman), for plates' footprints (`postprocess::plates`) and the cut's
//! cell shadows (`cut::cell_shadow`).

/// The shoelace area of a polygon, positive when counter-clockwise.
pub fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
}

/// The part of the convex polygon `p` where `side ≥ 0` (`side` affine), into `out`.
pub fn clip_by(p: &[[f64; 2]], side: impl Fn([f64; 2]) -> f64, out: &mut Vec<[f64; 2]>) {
    out.clear();
    for k in 0..p.len() {
        let (a, b) = (p[k], p[(k + 1) % p.len()]);
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            let t = sa / (sa - sb);
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
}

/// The intersection of two convex counter-clockwise polygons.
pub fn clip(subject: &[[f64; 2]], by: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = subject.to_vec();
    let mut input = Vec::with_capacity(out.len() + by.len());
    for i in 0..by.len() {
        let (a, b) = (by[i], by[(i + 1) % by.len()]);
        let side = |p: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        std::mem::swap(&mut input, &mut out);
        clip_by(&input, side, &mut out);
        if out.is_empty() {
            break;
        }
    }
    out
}
