//! Where a collider's physics-step time goes (`primdecomp sim --profile`): Rapier's
//! own per-stage timers (its `profiler` feature) and, after every step, the contact
//! pairs of the world counted by the kinds of shape they join. A pair is what the
//! broad phase hands the narrow phase (AABBs, grown by the prediction distance,
//! overlap); a *touching* pair has a contact the solver sees. Ball–static pairs cost
//! one narrow-phase test each (analytic for a cuboid, ball or capsule; a support-map
//! projection for a cylinder or a convex polyhedron; a BVH walk for the triangle
//! mesh); ball–ball pairs depend only on where the balls are, i.e. on behaviour.
//! Figures are means per frame.

use primdecomp_math::V3;
use rapier3d::geometry::{
    Collider, ColliderHandle, ColliderSet, ContactPair, NarrowPhase, ShapeType,
};
use rapier3d::pipeline::PhysicsWorld;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};

/// Pairs of one kind, mean per frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PairCount {
    /// Pairs in the narrow phase (their AABBs overlap).
    pub pairs: f64,
    /// Of those, pairs with a contact the solver sees.
    pub touching: f64,
}

/// Per-frame means of one collider's run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Profile {
    /// Rapier's whole step, ms (its own timer).
    pub step_ms: f64,
    /// Broad phase, including the end-of-step AABB refresh, ms.
    pub broad_phase_ms: f64,
    /// Narrow phase (contact manifolds of every pair), ms.
    pub narrow_phase_ms: f64,
    /// Island building and constraint collection, ms.
    pub islands_ms: f64,
    /// Constraint solver, ms.
    pub solver_ms: f64,
    /// CCD time-of-impact search, ms.
    pub ccd_ms: f64,
    /// Position integration and its bookkeeping, ms.
    pub update_ms: f64,
    /// Balls awake (not asleep) after the step.
    pub awake_balls: f64,
    /// Balls touching two or more static shapes at once. Each part of a compound
    /// counts as one shape, touching when one of its contact points is within Rapier's
    /// prediction distance: stricter than the test for a separate shape (a contact the
    /// solver keeps, which also looks ahead by the approach speed), so counts of the
    /// two modes compare only roughly.
    pub balls_on_several_shapes: f64,
    /// The static shapes' reach for the broad phase: the sum over shapes of the volume
    /// where a ball's centre brings the ball's AABB over the shape's (its AABB grown by
    /// the ball radius on every side), over the same volume for the input's AABB. 1
    /// for one shape as large as the input; above 1 where shapes' boxes overlap or
    /// stand out of their shapes (long tilted plates), below where they leave space
    /// uncovered. Balls there cost a pair each frame, touching or not. A compound
    /// collider is one box here (its parts' boxes are its own BVH's, walked in the
    /// narrow phase).
    pub shape_aabb_reach: f64,
    /// Touching ball–static pairs of those balls: contacts the solver sees only
    /// because the shapes under one ball are several (one each under a single shape).
    pub contacts_of_balls_on_several: f64,
    /// Pairs by kind: `"ball-ball"`, `"ball-cuboid"`, `"ball-cylinder"`,
    /// `"ball-convex_polyhedron"`, `"ball-tri_mesh"`, …
    pub pairs: BTreeMap<String, PairCount>,
}

/// Running sums behind a [`Profile`].
#[derive(Clone, Debug, Default)]
pub struct Tally {
    frames: usize,
    sums: Profile,
    /// Static shapes each ball touches this frame (scratch; only the counts are read).
    touches: HashMap<ColliderHandle, u32>,
    /// A compound's parts under one ball (scratch for [`parts_touched`]).
    parts: Vec<u32>,
}

/// Snake-case name of a shape kind.
fn kind_name(t: ShapeType) -> String {
    let debug = format!("{t:?}");
    let mut out = String::with_capacity(debug.len() + 4);
    for (i, c) in debug.chars().enumerate() {
        if c.is_ascii_uppercase() && i > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// Pair key: the two kinds, the ball first, otherwise alphabetical.
fn pair_key(a: ShapeType, b: ShapeType) -> String {
    let (a, b) = (kind_name(a), kind_name(b));
    if a == "ball" || (b != "ball" && a <= b) {
        format!("{a}-{b}")
    } else {
        format!("{b}-{a}")
    }
}

/// Static shapes a touching ball–static pair `p` stands for: the parts of a compound
/// with a contact point within the `prediction` distance (one manifold each; Rapier
/// clusters a pair's manifolds for the solver and then clears their own solver
/// contacts, so the points are read, without the solver's look-ahead by the
/// approach speed that decides whether a pair touches at all), at least 1; any other
/// shape is 1 (a triangle mesh is one shape, however many of its triangles the ball
/// touches). `parts`: scratch.
fn parts_touched(
    p: &ContactPair,
    fixed: &Collider,
    static_first: bool,
    prediction: f32,
    parts: &mut Vec<u32>,
) -> u32 {
    if fixed.shape().shape_type() != ShapeType::Compound {
        return 1;
    }
    parts.clear();
    let near = p
        .manifolds()
        .iter()
        .filter(|m| m.points.iter().any(|c| c.dist < prediction));
    parts.extend(near.map(|m| {
        if static_first {
            m.subshape1
        } else {
            m.subshape2
        }
    }));
    parts.sort_unstable();
    parts.dedup();
    parts.len().max(1) as u32
}

impl Tally {
    /// A tally for `world`'s static shapes ([`Profile::shape_aabb_reach`]) against
    /// the input's AABB `input` (both in the simulation frame) and balls of `radius`.
    pub fn new(world: &PhysicsWorld, input: (V3, V3), radius: f64) -> Tally {
        let grown = |lo: [f64; 3], hi: [f64; 3]| {
            (0..3)
                .map(|k| hi[k] - lo[k] + 2.0 * radius)
                .product::<f64>()
        };
        let shapes: f64 = world
            .colliders
            .iter()
            .filter(|(_, c)| c.parent().is_none())
            .map(|(_, c)| {
                let b = c.compute_aabb();
                let (lo, hi) = (b.mins, b.maxs);
                grown(
                    [lo.x, lo.y, lo.z].map(f64::from),
                    [hi.x, hi.y, hi.z].map(f64::from),
                )
            })
            .sum();
        let mut t = Tally::default();
        t.sums.shape_aabb_reach = shapes / grown(input.0, input.1);
        t
    }

    /// Adds one step of `world` (call right after the step).
    pub fn add(&mut self, world: &PhysicsWorld) {
        let c = &world.physics_pipeline.counters;
        let s = &mut self.sums;
        s.step_ms += c.step_time_ms();
        s.broad_phase_ms += c.cd.broad_phase_time.time_ms() + c.cd.final_broad_phase_time.time_ms();
        s.narrow_phase_ms += c.cd.narrow_phase_time.time_ms();
        s.islands_ms += c.stages.island_construction_time.time_ms()
            + c.stages.island_constraints_collection_time.time_ms();
        s.solver_ms += c.stages.solver_time.time_ms();
        s.ccd_ms += c.ccd.toi_computation_time.time_ms();
        s.update_ms += c.stages.update_time.time_ms();
        s.awake_balls += world.islands.active_bodies().count() as f64;
        let prediction = world.integration_parameters.prediction_distance();
        self.count_pairs(&world.narrow_phase, &world.colliders, prediction);
        self.frames += 1;
    }

    fn count_pairs(&mut self, narrow: &NarrowPhase, colliders: &ColliderSet, prediction: f32) {
        self.touches.clear();
        for p in narrow.contact_pairs() {
            let (Some(c1), Some(c2)) = (colliders.get(p.collider1), colliders.get(p.collider2))
            else {
                continue;
            };
            let touching = p.has_any_active_contact();
            let entry = self
                .sums
                .pairs
                .entry(pair_key(c1.shape().shape_type(), c2.shape().shape_type()))
                .or_default();
            entry.pairs += 1.0;
            if !touching {
                continue;
            }
            entry.touching += 1.0;
            // A static shape has no parent body; count the ball's touches of them.
            let (ball, fixed, static_first) = match (c1.parent(), c2.parent()) {
                (Some(_), None) => (p.collider1, c2, false),
                (None, Some(_)) => (p.collider2, c1, true),
                _ => continue,
            };
            let n = parts_touched(p, fixed, static_first, prediction, &mut self.parts);
            *self.touches.entry(ball).or_default() += n;
        }
        let several = self.touches.values().filter(|&&n| n >= 2);
        self.sums.balls_on_several_shapes += several.clone().count() as f64;
        self.sums.contacts_of_balls_on_several += several.map(|&n| n as f64).sum::<f64>();
    }

    /// Means per frame of everything added.
    pub fn profile(&self) -> Profile {
        let n = self.frames.max(1) as f64;
        let s = &self.sums;
        Profile {
            step_ms: s.step_ms / n,
            broad_phase_ms: s.broad_phase_ms / n,
            narrow_phase_ms: s.narrow_phase_ms / n,
            islands_ms: s.islands_ms / n,
            solver_ms: s.solver_ms / n,
            ccd_ms: s.ccd_ms / n,
            update_ms: s.update_ms / n,
            awake_balls: s.awake_balls / n,
            balls_on_several_shapes: s.balls_on_several_shapes / n,
            contacts_of_balls_on_several: s.contacts_of_balls_on_several / n,
            shape_aabb_reach: s.shape_aabb_reach,
            pairs: s
                .pairs
                .iter()
                .map(|(k, c)| {
                    let m = PairCount {
                        pairs: c.pairs / n,
                        touching: c.touching / n,
                    };
                    (k.clone(), m)
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pair_keys_put_the_ball_first() {
        assert_eq!(pair_key(ShapeType::Cuboid, ShapeType::Ball), "ball-cuboid");
        assert_eq!(pair_key(ShapeType::Ball, ShapeType::Ball), "ball-ball");
        assert_eq!(
            pair_key(ShapeType::Ball, ShapeType::ConvexPolyhedron),
            "ball-convex_polyhedron"
        );
        assert_eq!(
            pair_key(ShapeType::TriMesh, ShapeType::Ball),
            "ball-tri_mesh"
        );
    }
}
