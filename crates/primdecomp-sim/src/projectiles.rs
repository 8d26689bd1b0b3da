//! `primdecomp sim --scenario projectiles`: balls fired at the object from every
//! side at game speeds, with discrete fixed steps and (by default) no continuous
//! collision detection; counts the balls that tunnel — end
//! inside the input's closed volume or beyond the object along their path. The
//! paper's §4.1 measures frame time with slow balls; this measures what a thin
//! collider (a plate, a triangle mesh) does to a fast body (docs/results/projectiles.md).
//!
//! # Scene
//! - **Frame, ball.** As the drop scenario ([`super::scene`]): the input scaled to an
//!   AABB diagonal D = 10 m, ball radius r = 0.01·D, fixed step 1/60 s, Rapier's
//!   defaults otherwise (no restitution). No gravity: every path is a straight line
//!   until it meets a collider. Balls collide with the collider only, never with one
//!   another, so every shot is independent of the others.
//! - **Shots.** Shot i flies along direction dᵢ, the i-th point of a Fibonacci sphere
//!   of `shots` points (every side alike), on the line through aᵢ, a point of the
//!   input's surface (triangle chosen by area, barycentric point, both from the
//!   seeded SplitMix64 stream). It starts where the line enters the sphere of radius
//!   D/2 + 3r around the AABB centre (outside every collider) at speed v along dᵢ.
//!   A shot counts only when its line meets the input's triangles (always, unless
//!   aᵢ's triangle is degenerate); t_out is the last such meeting along dᵢ.
//! - **Speeds** ([`SPEEDS`]), in ball diameters per frame: slow 0.1, walking 0.5,
//!   thrown 2, bullet 10; in the 10 m scene with 0.2 m balls at 60 Hz these are
//!   1.2, 6, 24 and 120 m/s. A body crosses a plate of thickness t between two
//!   frames, never touching it, once it moves more than 2r + t per frame.
//! - **Frames.** Until the slowest shot, unobstructed, would be 4r past its t_out,
//!   plus [`SETTLE_FRAMES`] for contacts to resolve.
//!
//! # Collision detection
//! Off (default): plain discrete steps. Rapier 0.36 sweeps fast dynamic bodies
//! against fixed colliders on its own (`IntegrationParameters::max_ccd_substeps`
//! = 1); that is turned off (0), as most engines' default discrete mode.
//! [`Settings::ccd`]: Rapier's default sweep and CCD on every ball.
//!
//! # Measures (per collider and speed, over the counted shots)
//! After every frame each ball's move since the last is ray cast against the input's
//! triangles: `crossed` once its centre has crossed the input's surface.
//! - `inside`: crossed, and the centre ends inside the input's volume (generalized
//!   winding number of the input's triangles > 1/2: parity for a closed mesh,
//!   robust to small holes).
//! - `beyond`: crossed, outside at the end, and past t_out + r along dᵢ from the
//!   start. A ball a collider stops never crosses; one that sinks into a solid part
//!   in a long step and is pushed out through another face (near an edge) counts.
//! - `passed` = inside or beyond: the pass-through count.

use super::scene::{frame_of, SplitMix, BALL_RADIUS_REL, DT};
use super::shapes::{Frame, Placed};
use super::{placed, Entry, Geometry};
use primdecomp::{Error, Mesh};
use primdecomp_math::{add, cross, dot, norm, norm2, scale, sub, V3};
use rapier3d::dynamics::{RigidBodyBuilder, RigidBodyHandle};
use rapier3d::geometry::{ColliderBuilder, Group, InteractionGroups, InteractionTestMode};
use rapier3d::math::Vector;
use rapier3d::parry::query::Ray;
use rapier3d::pipeline::PhysicsWorld;

/// Results with the library's one error type.
type Result<T> = std::result::Result<T, Error>;

/// Named speeds in ball diameters per frame (see the module documentation).
pub const SPEEDS: [(&str, f64); 4] = [
    ("slow", 0.1),
    ("walking", 0.5),
    ("thrown", 2.0),
    ("bullet", 10.0),
];
/// Frames added after the last shot would have passed, for contacts to resolve.
pub const SETTLE_FRAMES: usize = 10;
/// Start sphere radius beyond D/2, in ball radii.
const START_MARGIN_RADII: f64 = 3.0;
/// Mixed into the seed for the aim points' stream.
const AIM_SEED: u64 = 0x5851_F42D_4C95_7F2D;

/// Projectile run settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Shots per collider and speed.
    pub shots: usize,
    pub seed: u64,
    /// Continuous collision detection on the balls (off in engines by default).
    pub ccd: bool,
    /// Threads for Rapier's parallel parts (≥ 1).
    pub threads: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            shots: 256,
            seed: 0,
            ccd: false,
            threads: 1,
        }
    }
}

/// One shot's line in the simulation frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    pub start: V3,
    pub dir: V3,
    /// Distance along `dir` from `start` to the input's last triangle on the line.
    pub t_out: f64,
}

/// Pass-through counts of one collider at one speed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Tally {
    pub inside: usize,
    pub beyond: usize,
    pub passed: usize,
}

/// One collider's tallies, one per entry of [`SPEEDS`].
#[derive(Clone, Debug)]
pub struct Outcome {
    pub label: String,
    pub kind: &'static str,
    pub shapes: usize,
    pub tallies: Vec<Tally>,
}

/// A whole projectile run: the shots and one outcome per collider, the input mesh
/// (as a triangle mesh) first.
#[derive(Clone, Debug)]
pub struct Run {
    pub settings: Settings,
    pub radius: f64,
    pub shots: Vec<Shot>,
    /// Frames simulated per speed.
    pub frames: Vec<usize>,
    pub outcomes: Vec<Outcome>,
}

/// The input's triangles in the simulation frame (fan-triangulated polygons).
fn triangles(mesh: &Mesh, s: f64) -> Vec<[V3; 3]> {
    let mut out = Vec::with_capacity(mesh.face_count());
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        let p = |k: usize| scale(mesh.pos(face[k]), s);
        for k in 1..face.len().saturating_sub(1) {
            out.push([p(0), p(k), p(k + 1)]);
        }
    }
    out
}

/// Every t where the line `o + t·d` meets triangle `t` (Möller–Trumbore), if any.
fn line_hit(o: V3, d: V3, t: &[V3; 3]) -> Option<f64> {
    let (e1, e2) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-14 {
        return None;
    }
    let s = sub(o, t[0]);
    let u = dot(s, p) / det;
    let q = cross(s, e1);
    let v = dot(d, q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0).then(|| dot(e2, q) / det)
}

/// Generalized winding number of the triangles around `p` (Jacobson et al. 2013):
/// 1 inside a closed outward mesh, 0 outside, fractional near holes.
pub fn winding(tris: &[[V3; 3]], p: V3) -> f64 {
    let mut sum = 0.0;
    for t in tris {
        let (a, b, c) = (sub(t[0], p), sub(t[1], p), sub(t[2], p));
        let (la, lb, lc) = (norm(a), norm(b), norm(c));
        let num = dot(a, cross(b, c));
        let den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
        sum += 2.0 * num.atan2(den);
    }
    (sum / (4.0 * std::f64::consts::PI)).abs()
}

/// The i-th of n points of a Fibonacci sphere (unit vectors, evenly spread).
fn fibonacci(i: usize, n: usize) -> V3 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
    let r = (1.0 - y * y).max(0.0).sqrt();
    let a = golden * i as f64;
    [r * a.cos(), y, r * a.sin()]
}

/// A surface point chosen by area from the stream (`cum`: cumulative areas).
fn aim(tris: &[[V3; 3]], cum: &[f64], rng: &mut SplitMix) -> V3 {
    let total = *cum.last().unwrap_or(&0.0);
    let x = 0.5 * (rng.symmetric() + 1.0) * total;
    let k = cum.partition_point(|&c| c <= x).min(tris.len() - 1);
    let (mut u, mut v) = (0.5 * (rng.symmetric() + 1.0), 0.5 * (rng.symmetric() + 1.0));
    if u + v > 1.0 {
        (u, v) = (1.0 - u, 1.0 - v);
    }
    let t = &tris[k];
    add(
        t[0],
        add(scale(sub(t[1], t[0]), u), scale(sub(t[2], t[0]), v)),
    )
}

/// The shots (see the module documentation); lines that meet no triangle are left out.
pub fn shots(tris: &[[V3; 3]], radius: f64, n: usize, seed: u64) -> Vec<Shot> {
    let mut cum = Vec::with_capacity(tris.len());
    let mut acc = 0.0;
    for t in tris {
        acc += 0.5 * norm2(cross(sub(t[1], t[0]), sub(t[2], t[0]))).sqrt();
        cum.push(acc);
    }
    if tris.is_empty() || acc <= 0.0 {
        return Vec::new();
    }
    let big = 0.5 * super::scene::SCENE_DIAGONAL + START_MARGIN_RADII * radius;
    let mut rng = SplitMix(seed ^ AIM_SEED);
    (0..n)
        .filter_map(|i| {
            let dir = fibonacci(i, n);
            let a = aim(tris, &cum, &mut rng);
            // Entry into the sphere |x| = big (the frame is centred on the AABB).
            let b = dot(a, dir);
            let start = sub(a, scale(dir, b + (b * b - norm2(a) + big * big).sqrt()));
            let t_out = tris
                .iter()
                .filter_map(|t| line_hit(start, dir, t))
                .fold(f64::NEG_INFINITY, f64::max);
            (t_out > 0.0).then_some(Shot { start, dir, t_out })
        })
        .collect()
}

/// Shapes of every entry, the input mesh first.
fn collider_shapes(mesh: &Mesh, frame: &Frame, colliders: &[Entry]) -> Result<Vec<Vec<Placed>>> {
    let reference = Geometry::Reference;
    std::iter::once(&reference)
        .chain(colliders.iter().map(|e| &e.geometry))
        .zip(std::iter::once("input").chain(colliders.iter().map(|e| e.label.as_str())))
        .map(|(g, label)| {
            placed(g, mesh, frame)
                .map(|(s, _)| s)
                .map_err(|err| match err {
                    Error::InvalidParams(m) => Error::InvalidParams(format!("{label}: {m}")),
                    other => other,
                })
        })
        .collect()
}

/// Where the balls of one world ended and which of them crossed the input's surface.
struct Flight {
    ends: Vec<V3>,
    crossed: Vec<bool>,
}

/// Fires every shot at `speed` (m per frame) at the static `shapes` for `frames`
/// frames; after every frame, tests each ball's move since the last frame against
/// the input's triangles (`input`, a triangle mesh: a segment ray cast).
fn fire(
    shapes: &[Placed],
    input: &Placed,
    shots: &[Shot],
    radius: f64,
    speed: f64,
    frames: usize,
    ccd: bool,
) -> Flight {
    let mut world = PhysicsWorld::new();
    world.gravity = Frame::vector([0.0; 3]);
    world.integration_parameters.dt = DT as f32;
    if !ccd {
        // Rapier 0.36 sweeps fast bodies against fixed colliders by default (its
        // automatic CCD); 0 substeps turns that off: plain discrete steps.
        world.integration_parameters.max_ccd_substeps = 0;
    }
    for (shape, pose) in shapes {
        world.insert_collider(ColliderBuilder::new(shape.clone()).position(*pose), None);
    }
    let groups = InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And);
    let ball = ColliderBuilder::ball(radius as f32).collision_groups(groups);
    let v = speed / DT;
    let balls: Vec<RigidBodyHandle> = shots
        .iter()
        .map(|s| {
            let body = RigidBodyBuilder::dynamic()
                .translation(Frame::vector(s.start))
                .linvel(Frame::vector(scale(s.dir, v)))
                .ccd_enabled(ccd);
            world.insert(body, ball.clone()).0
        })
        .collect();
    let mut prev: Vec<Vector> = shots.iter().map(|s| Frame::vector(s.start)).collect();
    let mut crossed = vec![false; shots.len()];
    for _ in 0..frames {
        world.step();
        for ((h, p), c) in balls.iter().zip(prev.iter_mut()).zip(crossed.iter_mut()) {
            let q = world.bodies[*h].translation();
            if !*c && q != *p {
                let ray = Ray::new(*p, q - *p);
                *c = input.0.cast_ray(&input.1, &ray, 1.0, false).is_some();
            }
            *p = q;
        }
    }
    let ends = prev
        .iter()
        .map(|p| [p.x as f64, p.y as f64, p.z as f64])
        .collect();
    Flight { ends, crossed }
}

/// Counts the shots whose balls ended inside the input's volume, or crossed its
/// surface and ended past its last triangle on their line (`t_out` + r).
fn tally(tris: &[[V3; 3]], shots: &[Shot], flight: &Flight, radius: f64) -> Tally {
    let mut t = Tally {
        inside: 0,
        beyond: 0,
        passed: 0,
    };
    for ((s, &e), &c) in shots.iter().zip(&flight.ends).zip(&flight.crossed) {
        let inside = c && winding(tris, e) > 0.5;
        let beyond = c && !inside && dot(sub(e, s.start), s.dir) > s.t_out + radius;
        t.inside += inside as usize;
        t.beyond += beyond as usize;
        t.passed += (inside || beyond) as usize;
    }
    t
}

/// Fires the shots at the input mesh (as a triangle mesh, the first outcome) and
/// every collider at every speed of [`SPEEDS`].
pub fn run(mesh: &Mesh, input: &str, colliders: &[Entry], settings: &Settings) -> Result<Run> {
    if settings.shots == 0 || settings.threads == 0 {
        return Err(Error::InvalidParams(format!(
            "projectiles need at least one shot and one thread (got {settings:?})"
        )));
    }
    let (frame, _) = frame_of(mesh);
    let radius = BALL_RADIUS_REL * super::scene::SCENE_DIAGONAL;
    let tris = triangles(mesh, frame.scale);
    let shots = shots(&tris, radius, settings.shots, settings.seed);
    if shots.is_empty() {
        return Err(Error::InvalidParams(format!(
            "{input}: no surface to aim at"
        )));
    }
    let shapes = collider_shapes(mesh, &frame, colliders)?;
    let input_shape = &shapes[0][0];
    let (steps, frames) = steps_and_frames(&shots, radius);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .map_err(|e| {
            Error::InvalidParams(format!("cannot start {} threads: {e}", settings.threads))
        })?;
    let tallies: Vec<Vec<Tally>> = pool.install(|| {
        shapes
            .iter()
            .map(|s| {
                steps
                    .iter()
                    .zip(&frames)
                    .map(|(&st, &f)| {
                        let flight = fire(s, input_shape, &shots, radius, st, f, settings.ccd);
                        tally(&tris, &shots, &flight, radius)
                    })
                    .collect()
            })
            .collect()
    });
    let outcomes = outcomes_of(input, colliders, tallies, &shapes);
    Ok(Run {
        settings: settings.clone(),
        radius,
        shots,
        frames,
        outcomes,
    })
}

/// Each speed of [`SPEEDS`] as the distance a ball moves in a frame, and the frames
/// a shot is followed at it: until the farthest exit (plus two diameters) is passed,
/// then [`SETTLE_FRAMES`] more.
fn steps_and_frames(shots: &[Shot], radius: f64) -> (Vec<f64>, Vec<usize>) {
    let reach = shots.iter().fold(0.0f64, |m, s| m.max(s.t_out)) + 4.0 * radius;
    let steps: Vec<f64> = SPEEDS.iter().map(|(_, k)| k * 2.0 * radius).collect();
    let frames: Vec<usize> = steps
        .iter()
        .map(|st| (reach / st).ceil() as usize + SETTLE_FRAMES)
        .collect();
    (steps, frames)
}

/// Each collider's outcome (the input's first, as a triangle mesh): its label, kind,
/// shape count and tallies per speed.
fn outcomes_of(
    input: &str,
    colliders: &[Entry],
    tallies: Vec<Vec<Tally>>,
    shapes: &[Vec<Placed>],
) -> Vec<Outcome> {
    let names = std::iter::once((input.to_string(), Geometry::Reference.kind())).chain(
        colliders
            .iter()
            .map(|e| (e.label.clone(), e.geometry.kind())),
    );
    names
        .zip(tallies)
        .zip(shapes)
        .map(|(((label, kind), tallies), s)| Outcome {
            label,
            kind,
            shapes: s.len(),
            tallies,
        })
        .collect()
}

#[derive(serde::Serialize)]
struct SpeedJson {
    name: &'static str,
    diameters_per_frame: f64,
    metres_per_second: f64,
    frames: usize,
}

#[derive(serde::Serialize)]
struct ColliderJson<'a> {
    collider: &'a str,
    kind: &'a str,
    shapes: usize,
    /// One per speed, in the order of `speeds`.
    tallies: &'a [Tally],
}

#[derive(serde::Serialize)]
struct RunJson<'a> {
    input: &'a str,
    scenario: &'static str,
    shots: usize,
    shots_requested: usize,
    seed: u64,
    ccd: bool,
    ball_radius_m: f64,
    scene_diagonal_m: f64,
    dt: f64,
    speeds: Vec<SpeedJson>,
    colliders: Vec<ColliderJson<'a>>,
}

impl Run {
    /// The JSON report (pretty, deterministic: no timings).
    pub fn to_json(&self, input: &str) -> String {
        let speeds = SPEEDS
            .iter()
            .zip(&self.frames)
            .map(|(&(name, k), &frames)| SpeedJson {
                name,
                diameters_per_frame: k,
                metres_per_second: k * 2.0 * self.radius / DT,
                frames,
            })
            .collect();
        let colliders = self
            .outcomes
            .iter()
            .map(|o| ColliderJson {
                collider: &o.label,
                kind: o.kind,
                shapes: o.shapes,
                tallies: &o.tallies,
            })
            .collect();
        let doc = RunJson {
            input,
            scenario: "projectiles",
            shots: self.shots.len(),
            shots_requested: self.settings.shots,
            seed: self.settings.seed,
            ccd: self.settings.ccd,
            ball_radius_m: self.radius,
            scene_diagonal_m: super::scene::SCENE_DIAGONAL,
            dt: DT,
            speeds,
            colliders,
        };
        serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
    }

    /// A Markdown table: one row per collider, the pass-through fraction per speed.
    pub fn table(&self) -> String {
        let mut s = String::from("| collider | kind | shapes |");
        for (name, k) in SPEEDS {
            s += &format!(" {name} ({k} d/frame) |");
        }
        s += "\n|---|---|---:|";
        s += &"---:|".repeat(SPEEDS.len());
        s.push('\n');
        let n = self.shots.len().max(1) as f64;
        for o in &self.outcomes {
            s += &format!("| {} | {} | {} |", o.label, o.kind, o.shapes);
            for t in &o.tallies {
                s += &format!(" {:.3} |", t.passed as f64 / n);
            }
            s.push('\n');
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::{Obb, Primitive};
    use primdecomp_eval::collider::Collider;

    const AXES: [V3; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

    /// Six boxes 0.001·D thick lining the inside of the box lo–hi (the shell of plates
    /// the default decomposition makes of a closed part).
    fn plate_shell(lo: V3, hi: V3, thick: f64) -> Vec<Primitive> {
        let c = scale(add(lo, hi), 0.5);
        let h = scale(sub(hi, lo), 0.5);
        let mut out = Vec::new();
        for k in 0..3 {
            for side in [-1.0, 1.0] {
                let mut center = c;
                center[k] += side * (h[k] - 0.5 * thick);
                let mut half = h;
                half[k] = 0.5 * thick;
                out.push(Primitive::Box(Obb {
                    center,
                    axes: AXES,
                    half,
                }));
            }
        }
        out
    }

    /// Balls fired head-on at the centres of the six faces of the box mesh at
    /// `step` m per frame, from 16 start distances 1/16 of a step apart (so some
    /// frames land just short of a face and the next ones past it), at `parts`:
    /// how many end inside the box or beyond it.
    fn head_on(mesh: &Mesh, parts: Vec<Primitive>, step: f64, ccd: bool) -> usize {
        let (frame, aabb) = frame_of(mesh);
        let radius = BALL_RADIUS_REL * crate::scene::SCENE_DIAGONAL;
        let geometry = Geometry::Collider(Collider::Primitives(parts));
        let (shapes, _) = placed(&geometry, mesh, &frame).unwrap();
        let input = crate::shapes::trimesh(mesh, &frame).unwrap();
        let mut shots = Vec::new();
        for k in 0..3 {
            for side in [-1.0, 1.0] {
                for j in 0..16 {
                    let mut dir = [0.0; 3];
                    dir[k] = -side;
                    let face = if side > 0.0 { aabb.1[k] } else { aabb.0[k] };
                    let mut start = [0.0; 3];
                    start[k] = face + side * (3.0 * radius + step * j as f64 / 16.0);
                    let t_out = (start[k] - side * face).abs() + (aabb.1[k] - aabb.0[k]);
                    shots.push(Shot { start, dir, t_out });
                }
            }
        }
        let frames = 20.0_f64.max((aabb.1[0] - aabb.0[0] + 1.0) / step) as usize;
        let tris = triangles(mesh, frame.scale);
        let flight = fire(&shapes, &input, &shots, radius, step, frames, ccd);
        tally(&tris, &shots, &flight, radius).passed
    }

    /// The check: a closed box's collider stops a ball fired at 1.5 ball
    /// diameters per frame (CCD off), which crosses a 0.001·D plate between two
    /// frames without touching it. A shell of such plates (hand-made, and the
    /// default decomposition at N = 12 and 64, which is one) lets balls through; the
    /// option the README gives for closed parts hit by fast bodies,
    /// `--min-thickness 0.3` (plates thickened inward, docs/decisions/0033), stops
    /// every one at N = 12 and 64, as does a solid box (the `--solid` decomposition
    /// at N = 3). `--solid` does not fill this box at N ≥ 6: its six faces are six
    /// plates before any merge (docs/decisions/sim-projectiles.md). Rapier's own sweep
    /// of fixed colliders (`ccd`) stops them at the shell too.
    #[test]
    fn solid_box_stops_balls_that_tunnel_through_plates() {
        let (lo, hi) = ([0.0; 3], [3.0, 1.0, 2.0]);
        let mesh = crate::cuboid_mesh(lo, hi);
        let thick = 0.001 * norm(sub(hi, lo));
        let r = BALL_RADIUS_REL * crate::scene::SCENE_DIAGONAL;
        let step = 1.5 * 2.0 * r;
        // Plates are 0.01 m thick in the 10 m scene: a step this long can skip one.
        assert!(step > 2.0 * r + 0.001 * crate::scene::SCENE_DIAGONAL);
        let level = |n, solid, min_thickness| {
            let p = primdecomp::Params {
                goal: primdecomp::Goal::counts([n]),
                plates: primdecomp::Plates {
                    solid,
                    min_thickness,
                    ..Default::default()
                },
                ..Default::default()
            };
            primdecomp::decompose(&mesh, &p)
                .unwrap()
                .levels
                .remove(0)
                .primitives
        };
        let shell = head_on(&mesh, plate_shell(lo, hi, thick), step, false);
        assert!(shell > 0, "hand-made shell");
        for n in [12, 64] {
            let default = level(n, false, 0.0);
            assert!(default.len() >= 6, "default: {default:?}");
            assert!(
                head_on(&mesh, default, step, false) > 0,
                "default shell, N = {n}"
            );
            let thick = level(n, false, 0.3);
            assert_eq!(head_on(&mesh, thick, step, false), 0, "N = {n}");
        }
        let solid = level(3, true, 0.0);
        assert_eq!(solid.len(), 1, "{solid:?}");
        assert_eq!(head_on(&mesh, solid, step, false), 0);
        assert_eq!(head_on(&mesh, plate_shell(lo, hi, thick), step, true), 0);
    }

    /// A unit cube's winding number: 1 inside, 0 outside.
    #[test]
    fn winding_number_tells_inside_from_outside() {
        let mesh = crate::cuboid_mesh([0.0; 3], [1.0; 3]);
        let tris = triangles(&mesh, 1.0);
        // Mesh positions are re-centred on the AABB centre.
        assert!((winding(&tris, [0.1, -0.2, 0.3]) - 1.0).abs() < 1e-9);
        assert!(winding(&tris, [0.1, 0.7, 0.3]).abs() < 1e-9);
    }
}
