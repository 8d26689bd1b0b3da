//! What a user reads off a simulation run: frame-time statistics and behaviour
//! against the reference (the input mesh). Definitions are in [`super`]'s docs.

use super::scene::Scene;
use primdecomp_math::{norm, sub, V3};
use serde::Serialize;
use std::collections::HashMap;

/// Frame-time statistics, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct FrameStats {
    pub mean: f64,
    pub median: f64,
    pub p95: f64,
    pub total: f64,
}

impl FrameStats {
    /// Mean, median (mean of the two middle values for an even count), p95 (the
    /// nearest-rank 95th percentile) and sum of `ms`; zeros for no frames.
    pub fn of(ms: &[f64]) -> FrameStats {
        if ms.is_empty() {
            return FrameStats::default();
        }
        let mut s = ms.to_vec();
        s.sort_by(f64::total_cmp);
        let n = s.len();
        let total: f64 = s.iter().sum();
        let median = if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        };
        let rank = ((0.95 * n as f64).ceil() as usize).clamp(1, n);
        FrameStats {
            mean: total / n as f64,
            median,
            p95: s[rank - 1],
            total,
        }
    }
}

/// Behaviour of one run, compared with the reference run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Behaviour {
    /// Fraction of balls ending within one ball diameter of their end on the mesh.
    pub similarity: f64,
    /// Chaos-robust variant: fraction of end points within one diameter of some end
    /// point of the other run, averaged over both directions.
    pub similarity_set: f64,
    /// Fraction of balls ending on the object (not fallen off or through).
    pub on_object: f64,
    /// Fraction of balls on the object and at rest.
    pub resting: f64,
    /// Fraction of balls whose on-object state matches the reference run's.
    pub on_object_agreement: f64,
    /// Mean distance between a ball's end and its end on the mesh, input units.
    pub mean_displacement: f64,
    /// `mean_displacement` over the input's AABB diagonal.
    pub mean_displacement_rel: f64,
}

/// Whether a ball centre is on the object: inside the AABB grown by one ball
/// diameter on every side, with no upper bound (piles may stand above the top).
pub fn on_object(scene: &Scene, p: V3) -> bool {
    let d = 2.0 * scene.radius;
    (0..3).all(|k| p[k] >= scene.aabb.0[k] - d && (k == scene.up || p[k] <= scene.aabb.1[k] + d))
}

/// At rest: slower than one ball radius per second.
pub fn at_rest(scene: &Scene, speed: f64) -> bool {
    speed < scene.radius
}

impl Behaviour {
    /// Compares final ball centres and speeds (simulation frame) with the reference
    /// run's centres.
    pub fn of(scene: &Scene, pos: &[V3], speed: &[f64], reference: &[V3]) -> Behaviour {
        let n = pos.len().max(1) as f64;
        let frac = |f: &dyn Fn(usize) -> bool| (0..pos.len()).filter(|&i| f(i)).count() as f64 / n;
        let dist = |i: usize| norm(sub(pos[i], reference[i]));
        let mean = (0..pos.len()).map(dist).sum::<f64>() / n;
        let diameter = 2.0 * scene.radius;
        Behaviour {
            similarity: frac(&|i| dist(i) <= diameter),
            similarity_set: 0.5
                * (near_fraction(pos, reference, diameter)
                    + near_fraction(reference, pos, diameter)),
            on_object: frac(&|i| on_object(scene, pos[i])),
            resting: frac(&|i| on_object(scene, pos[i]) && at_rest(scene, speed[i])),
            on_object_agreement: frac(&|i| {
                on_object(scene, pos[i]) == on_object(scene, reference[i])
            }),
            mean_displacement: mean / scene.frame.scale,
            mean_displacement_rel: mean / super::scene::SCENE_DIAGONAL,
        }
    }
}

/// Fraction of points of `a` within `d` of some point of `b`, through a hash grid
/// of cell `d` over `b` (each query looks at its 27 neighbour cells).
pub fn near_fraction(a: &[V3], b: &[V3], d: f64) -> f64 {
    if a.is_empty() {
        return 0.0;
    }
    let cell = |p: V3| p.map(|x| (x / d).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, &p) in b.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(i);
    }
    let near = |p: V3| {
        let c = cell(p);
        (0..27).any(|k| {
            let key = [c[0] + k % 3 - 1, c[1] + k / 3 % 3 - 1, c[2] + k / 9 - 1];
            grid.get(&key)
                .is_some_and(|v| v.iter().any(|&j| norm(sub(p, b[j])) <= d))
        })
    };
    a.iter().filter(|&&p| near(p)).count() as f64 / a.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Odd and even counts, the nearest-rank p95, and order independence.
    #[test]
    fn frame_stats() {
        let s = FrameStats::of(&[3.0, 1.0, 2.0]);
        assert_eq!((s.mean, s.median, s.p95, s.total), (2.0, 2.0, 3.0, 6.0));
        let v: Vec<f64> = (1..=100).rev().map(f64::from).collect();
        let s = FrameStats::of(&v);
        assert_eq!((s.median, s.p95, s.total), (50.5, 95.0, 5050.0));
        assert_eq!(FrameStats::of(&[]), FrameStats::default());
    }

    /// Set similarity ignores which ball is where: a shuffled copy matches fully,
    /// points just inside / outside the distance count / do not, also across cells.
    #[test]
    fn near_fraction_matches_brute_force() {
        let a: Vec<V3> = (0..50)
            .map(|i| [i as f64 * 0.37, (i % 7) as f64 * 0.5, -1.3])
            .collect();
        let mut b = a.clone();
        b.reverse();
        assert_eq!(near_fraction(&a, &b, 0.2), 1.0);
        let b: Vec<V3> = a.iter().map(|p| [p[0] + 0.199, p[1], p[2]]).collect();
        assert_eq!(near_fraction(&a, &b, 0.2), 1.0);
        let c: Vec<V3> = a.iter().map(|p| [p[0], p[1] - 0.201, p[2] + 0.0]).collect();
        let brute = a
            .iter()
            .filter(|p| c.iter().any(|q| norm(sub(**p, *q)) <= 0.2))
            .count() as f64
            / a.len() as f64;
        assert_eq!(near_fraction(&a, &c, 0.2), brute);
        assert_eq!(near_fraction(&[], &c, 0.2), 0.0);
    }
}
