//! `[f64; 3]` helpers. Plain functions keep the kernels readable and inlinable.

/// A point or direction in 3D.
pub type V3 = [f64; 3];

/// `a + b`.
#[inline(always)]
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
/// `a − b`.
#[inline(always)]
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
/// `s·a`.
#[inline(always)]
pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
/// `a · b`.
#[inline(always)]
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// `a × b`.
#[inline(always)]
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// Squared length.
#[inline(always)]
pub fn norm2(a: V3) -> f64 {
    dot(a, a)
}
/// Length.
#[inline(always)]
pub fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
/// `a + s·b`.
#[inline(always)]
pub fn madd(a: V3, b: V3, s: f64) -> V3 {
    [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s]
}
/// Unit vector along `a`, or `None` when `a` has no usable length.
#[inline]
pub fn normalize(a: V3) -> Option<V3> {
    let n = norm(a);
    if n > 0.0 && n.is_finite() {
        Some(scale(a, 1.0 / n))
    } else {
        None
    }
}

/// `max` for hot loops over finite values: one `maxsd`, where `f64::max` also
/// handles NaN with extra compares and blends. With a NaN argument it returns `a`.
#[inline(always)]
pub fn fmax(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// `min` counterpart of [`fmax`].
#[inline(always)]
pub fn fmin(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// Min/max corners of a point stream; `([0;3],[0;3])` for an empty stream.
pub fn aabb_of(points: impl Iterator<Item = V3>) -> (V3, V3) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if lo[0] > hi[0] {
        return ([0.0; 3], [0.0; 3]);
    }
    (lo, hi)
}

/// Two unit vectors `u`, `v` with `u × v = a` (for unit `a`), chosen deterministically:
/// primdecomp's tessellation puts vertex j of a circle around `a` at `u cos t + v sin t`,
/// t = 2πj/k, and the exporters place their circles the same way.
pub fn circle_frame(a: V3) -> (V3, V3) {
    let k = (0..3)
        .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let u = normalize(cross(e, a)).unwrap_or([1.0, 0.0, 0.0]);
    (u, cross(a, u))
}
