//! Errors measured once per primitive and threshold (`cut::error`): a run's
//! explorations, their retries with exact errors and the recut's raised counts fit
//! the same nodes to the same primitives, and their bounds, the cut's main cost, are
//! the same each time.
//!
//! [`error_until`](super::error::error_until) refines one primitive's bound in an
//! order that does not depend on its `above`; `above` only stops it, once a point
//! beyond it is found. So an answer `r` measured with `above = a` is the answer for
//! another `a'` whenever that run would stop at the same step:
//! - `r ≤ a` (stopped by its bound): every point found is within `r`, so for any
//!   `a' ≥ r` the run never stops on a point and ends where this one did;
//! - `r > a` (stopped at the first point beyond `a`, at distance `r`): the points
//!   before it are within `a`, so for `a ≤ a' < r` the run stops at that same point.

use std::collections::HashMap;
use std::sync::Mutex;

use crate::primitive::Primitive;

/// One measure: the primitive, the `above` it was measured with, and the answer.
type Measure = (Primitive, f64, f64);

/// The measures of a run, shared by its threads (the answers do not depend on which
/// thread measured first: a measure kept is the one a new run would make).
#[derive(Default)]
pub(super) struct Measures {
    by_box: Mutex<HashMap<[u64; 6], Vec<Measure>>>,
}

impl Measures {
    /// The answer of `measure()`, a measure of `prim` with `above`: a kept one where
    /// it tells, else measured and kept.
    pub(super) fn of(&self, prim: &Primitive, above: f64, measure: impl FnOnce() -> f64) -> f64 {
        if let Some(r) = self.get(prim, above) {
            return r;
        }
        let r = measure();
        let mut map = self.by_box.lock().unwrap_or_else(|e| e.into_inner());
        map.entry(super::limits::key(prim))
            .or_default()
            .push((*prim, above, r));
        r
    }

    /// The answer a measure of `prim` with `above` would give, if one kept tells.
    fn get(&self, prim: &Primitive, above: f64) -> Option<f64> {
        let map = self.by_box.lock().unwrap_or_else(|e| e.into_inner());
        let kept = map.get(&super::limits::key(prim))?;
        kept.iter()
            .filter(|(p, _, _)| p == prim)
            .find(|&&(_, a, r)| answers(a, r, above))
            .map(|m| m.2)
    }
}

/// Whether the answer `r` measured with `above = a` is the answer with `above`.
fn answers(a: f64, r: f64, above: f64) -> bool {
    match r <= a {
        true => r <= above,
        false => a <= above && above < r,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::error::tests::random_primitive;
    use crate::cut::error::{error_until, Ask};
    use crate::input::triangles::Triangles;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Every answer the rule reuses is the answer a new measure gives: primitives of
    /// every kind about the demo scene, each measured with thresholds from well below
    /// its error to above it, and each kept answer checked against every other
    /// threshold. Both of the rule's cases must be met, with thresholds other than
    /// the one measured with.
    #[test]
    fn a_kept_answer_is_the_measure_it_stands_for() {
        let mesh = crate::input::demo::demo_scene();
        let surface = Triangles::new(&mesh);
        let d = mesh.diagonal();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let measure = |p: &Primitive, above: f64| {
            let ask = Ask {
                level: 0.01 * d,
                above,
                coarse: true,
            };
            error_until(p, &surface, ask)
        };
        let mut reused = [0; 2];
        for i in 0..12 {
            let mut v = || std::array::from_fn(|_| rng.gen_range(-0.3..0.3) * d);
            let (p0, p1) = (v(), v());
            let prim = random_primitive(i % 6, p0, p1, [0.05 * d, 0.1 * d][i % 2]);
            let e = measure(&prim, f64::INFINITY);
            let aboves = [0.0, 0.2, 0.5, 0.8, 0.95, 1.0, 1.5].map(|f| f * e);
            for a in aboves.into_iter().chain([f64::INFINITY]) {
                let kept = Measures::default();
                let r = kept.of(&prim, a, || measure(&prim, a));
                for above in aboves.into_iter().chain([f64::INFINITY]) {
                    let Some(got) = kept.get(&prim, above) else {
                        continue;
                    };
                    let at = format!("{prim:?}: measured with {a}, asked {above}");
                    assert_eq!(got.to_bits(), measure(&prim, above).to_bits(), "{at}");
                    reused[usize::from(r > a)] += usize::from(above != a);
                }
            }
        }
        assert!(reused.iter().all(|&n| n > 0), "{reused:?}");
    }
}
