//! `primdecomp sim`: the paper's rigid-body benchmark (§4.1 "Efficiency of Collision
//! Objects"): drop balls on each collider in Rapier, time every frame's physics step,
//! and compare where the balls end with where they end on the input mesh itself.
//!
//! # Scene
//! - **Frame.** Coordinates are re-centred on the input's AABB centre and scaled so
//!   the AABB diagonal D is [`scene::SCENE_DIAGONAL`] = 10 m, whatever the file's
//!   units; gravity 9.81 m/s² along −up (`up` = y by default, z for Z-up files); fixed
//!   step 1/60 s; Rapier's defaults otherwise (friction 0.5, no restitution).
//! - **Balls.** Radius r = 0.01·D (0.1 m in the scene). Release grid over the AABB's
//!   footprint (its two horizontal axes): columns 3r apart (⌊W/3r⌋ per axis, at least
//!   one, cells centred), layers 3r apart starting 3r above the AABB's top, filled
//!   layer by layer. Each centre is jittered uniformly by up to r/2 per axis from a
//!   SplitMix64 stream seeded with `seed`, so no two balls overlap; they start at
//!   rest, with CCD on. Every collider sees exactly the same balls.
//! - **Colliders.** The input mesh as one triangle mesh (the reference, always the
//!   first entry), our primitives ([`shapes::primitive`]) and convex hulls, all fixed:
//!   one Rapier collider per part, or with [`Settings::compound`] each collider's
//!   parts as one compound shape (every collider alike).
//! - **Noise floor.** Unless [`Settings::perturbed`] is off, the second entry is the
//!   reference again with every ball's start moved by up to
//!   [`scene::PERTURBATION_RADII`] = 1e-4 r per axis (uniform, its own seeded stream):
//!   kind `mesh_perturbed`, label `<input> (perturbed)`. Its behaviour measures are the
//!   mesh against itself, so a collider's similarity differences smaller than
//!   1 − the perturbed run's are chaos, not geometry. Its world is stepped in the
//!   frame rotation like every other, so it adds the same load to all colliders'
//!   frames; its frame times (the same mesh twice) show the timing noise floor too.
//!
//! # Timing
//! All colliders' worlds live in one process and advance frame by frame, each frame
//! stepping every world once in an order rotated by the frame number, so machine
//! noise hits all colliders alike and their ratios hold. Only the `step` call is
//! timed, by wall clock (`frame_ms_*`) and by the process's CPU clock (`cpu_ms_*`:
//! on a loaded machine wall times are stretched by preemption, in multiples of the
//! scheduler's tick, while CPU time counts only this process's work). `threads` sizes the rayon pool that runs Rapier's parallel parts (default
//! 1: one core, the most repeatable).
//!
//! # Behaviour (after the last frame, against the reference run)
//! - `similarity`: fraction of balls whose centre ends within one ball diameter (2r)
//!   of where the same ball ends on the input mesh. Piles are chaotic, so even a
//!   faithful collider scores below 1 on a busy scene; compare colliders, not 1.
//! - `similarity_set`: the same test without ball identity, robust to that chaos:
//!   the fraction of end points lying within 2r of *some* end point of the other
//!   run, averaged over both directions (collider → reference, reference → collider).
//! - `on_object`: fraction of balls whose centre ends inside the input's AABB grown
//!   by 2r on every side (no upper bound, piles may stand above it), i.e. that did
//!   not fall off or through; `resting`: of all balls, the fraction on the object and
//!   slower than r per second; `on_object_agreement`: fraction whose on-object state
//!   matches the reference's.
//! - `mean_displacement`: mean distance between a ball's end and its end on the
//!   mesh, in the input's units (`mean_displacement_rel`: over D).

pub mod frustum_shape;
mod hull_backed;
pub mod metrics;
pub mod plot;
pub mod prism_shape;
pub mod profile;
pub mod projectiles;
pub mod report;
pub mod scene;
pub mod shapes;

use metrics::{Behaviour, FrameStats};
use primdecomp::Error;
use primdecomp::Mesh;
use primdecomp_eval::collider::Collider;
use primdecomp_math::V3;
use scene::{Scene, World};
use shapes::Placed;

/// Results with the library's one error type.
type Result<T> = std::result::Result<T, Error>;

/// Run settings. `Default` is the paper's 5,000 balls and 1,000 frames.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    pub balls: usize,
    pub frames: usize,
    pub seed: u64,
    /// Threads for Rapier's parallel parts (≥ 1).
    pub threads: usize,
    /// Up axis: 0 = x, 1 = y, 2 = z.
    pub up: usize,
    /// Also simulate the perturbed reference (the behaviour's noise floor).
    pub perturbed: bool,
    /// Attribute each collider's step time ([`profile`]): Rapier's stage timers and
    /// the contact pairs by shape kind, counted after every (timed) step.
    pub profile: bool,
    /// Give Rapier each collider's parts as one compound shape (one collider with its
    /// own BVH, as `ColliderBuilder::convex_decomposition` builds) instead of one
    /// collider per part. Applies to every collider alike; the reference mesh is one
    /// shape either way.
    pub compound: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            balls: 5000,
            frames: 1000,
            seed: 0,
            threads: 1,
            up: 1,
            perturbed: true,
            profile: false,
            compound: false,
        }
    }
}

/// What a simulated collider is made of (world coordinates).
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// The input mesh as a triangle mesh: the reference.
    Reference,
    /// The reference with the balls' starts perturbed (the noise floor).
    Perturbed,
    /// Primitives or convex hulls ([`primdecomp_eval::collider::load`]).
    Collider(Collider),
}

impl Geometry {
    /// Name of the kind in the report.
    pub fn kind(&self) -> &'static str {
        match self {
            Geometry::Reference => "mesh",
            Geometry::Perturbed => "mesh_perturbed",
            Geometry::Collider(Collider::Primitives(_)) => "primitives",
            Geometry::Collider(Collider::Hulls(_)) => "hulls",
        }
    }
}

/// A collider to simulate and its label (the file it came from).
#[derive(Clone, Debug)]
pub struct Entry {
    pub label: String,
    pub geometry: Geometry,
}

/// One collider's run.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub label: String,
    pub kind: &'static str,
    /// Shapes given to Rapier.
    pub shapes: usize,
    /// Parts dropped because they span no volume (flat hulls).
    pub skipped: usize,
    /// Physics-step wall time per frame, ms.
    pub frame_ms: Vec<f64>,
    pub stats: FrameStats,
    /// Physics-step process CPU time per frame, ms (NaN where unsupported).
    pub cpu_ms: Vec<f64>,
    pub cpu_stats: FrameStats,
    pub behaviour: Behaviour,
    /// Final ball centres (simulation frame) and speeds.
    pub end: Vec<V3>,
    pub speed: Vec<f64>,
    /// Where the step time went, with [`Settings::profile`].
    pub profile: Option<profile::Profile>,
}

/// A whole run: the scene and one outcome per collider, the reference first.
#[derive(Clone, Debug)]
pub struct Run {
    pub scene: Scene,
    pub settings: Settings,
    pub outcomes: Vec<Outcome>,
}

/// Rapier shapes of one collider; the count of parts that had no volume.
pub(crate) fn placed(
    geometry: &Geometry,
    mesh: &Mesh,
    f: &shapes::Frame,
) -> Result<(Vec<Placed>, usize)> {
    let all: Vec<Option<Placed>> = match geometry {
        Geometry::Reference | Geometry::Perturbed => vec![shapes::trimesh(mesh, f)],
        Geometry::Collider(Collider::Primitives(p)) => {
            // Rapier's f32 holds what reaches no farther than MAX_LENGTH.
            for (i, p) in p.iter().enumerate() {
                let far = shapes::reach(p, f);
                if far.is_nan() || far > shapes::MAX_LENGTH {
                    return Err(Error::InvalidParams(format!(
                        "primitive {i} ({}) reaches {:.3e} input diagonals from the input's \
                         centre; the simulation's 32-bit floats hold {:e}",
                        p.kind().name(),
                        far / scene::SCENE_DIAGONAL,
                        shapes::MAX_LENGTH / scene::SCENE_DIAGONAL
                    )));
                }
            }
            p.iter().map(|p| shapes::primitive(p, f)).collect()
        }
        Geometry::Collider(Collider::Hulls(h)) => {
            let far = h
                .iter()
                .flat_map(|h| &h.positions)
                .flat_map(|&p| f.point(p));
            if !far.clone().all(|x| x.abs() <= shapes::MAX_LENGTH) {
                return Err(Error::InvalidParams(format!(
                    "a hull vertex lies more than {:e} input diagonals from the input's \
                     centre, beyond what the simulation's 32-bit floats hold",
                    shapes::MAX_LENGTH / scene::SCENE_DIAGONAL
                )));
            }
            h.iter()
                .map(|h| shapes::hull(&h.positions.iter().map(|&p| f.point(p)).collect::<Vec<_>>()))
                .collect()
        }
    };
    let n = all.len();
    let kept: Vec<Placed> = all.into_iter().flatten().collect();
    if kept.is_empty() && n > 0 {
        return Err(Error::InvalidParams(format!(
            "{} collider has no part with volume",
            geometry.kind()
        )));
    }
    let skipped = n - kept.len();
    Ok((kept, skipped))
}

/// Simulates the reference (`mesh` as a triangle mesh, labelled `input`), its
/// perturbed copy (when `settings.perturbed`) and every collider, interleaved frame by
/// frame; the reference is the run's first outcome, the perturbed copy the second.
/// Calls `progress` with the number of frames done after each frame.
pub fn run(
    mesh: &Mesh,
    input: &str,
    colliders: &[Entry],
    settings: &Settings,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Run> {
    if settings.balls == 0 || settings.frames == 0 || settings.threads == 0 || settings.up > 2 {
        return Err(Error::InvalidParams(format!(
            "sim needs at least one ball, frame and thread and an up axis of x, y or z (got {settings:?})"
        )));
    }
    let scene = Scene::new(mesh, settings);
    let reference = [
        Entry {
            label: input.to_string(),
            geometry: Geometry::Reference,
        },
        Entry {
            label: format!("{input} (perturbed)"),
            geometry: Geometry::Perturbed,
        },
    ];
    let own = if settings.perturbed { 2 } else { 1 };
    let entries: Vec<&Entry> = reference[..own].iter().chain(colliders).collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .thread_name(|i| format!("sim-{i}"))
        .build()
        .map_err(|e| {
            Error::InvalidParams(format!("cannot start {} threads: {e}", settings.threads))
        })?;
    let (mut worlds, parts) = worlds_of(&entries, mesh, &scene, settings)?;
    // The whole loop runs on one of the pool's workers, so no step hands work over
    // to another thread first, and Rapier's parallel parts use this pool.
    let times = pool.install(|| step_all(&mut worlds, settings.frames, progress));
    let outcomes = outcomes_of(&scene, &entries, &worlds, times, parts);
    Ok(Run {
        scene,
        settings: settings.clone(),
        outcomes,
    })
}

/// One world per entry, each with its collider's shapes and its release (the
/// perturbed one for the perturbed copy); and each collider's count of shapes and of
/// parts skipped for having no volume. An error names the entry.
fn worlds_of(
    entries: &[&Entry],
    mesh: &Mesh,
    scene: &Scene,
    settings: &Settings,
) -> Result<(Vec<World>, Vec<ShapeCounts>)> {
    let perturbed = scene.perturbed_release(settings.seed);
    let mut worlds = Vec::with_capacity(entries.len());
    let mut parts = Vec::with_capacity(entries.len());
    for e in entries {
        let (shapes, skipped) =
            placed(&e.geometry, mesh, &scene.frame).map_err(|err| match err {
                Error::InvalidParams(m) => Error::InvalidParams(format!("{}: {m}", e.label)),
                other => other,
            })?;
        parts.push((shapes.len(), skipped));
        let release = match e.geometry {
            Geometry::Perturbed => &perturbed,
            _ => &scene.release,
        };
        worlds.push(World::new(scene, shapes, release, settings));
    }
    Ok((worlds, parts))
}

/// A collider's count of shapes and of parts skipped for having no volume.
type ShapeCounts = (usize, usize);

/// Each world's wall and CPU milliseconds per frame.
type FrameTimes = (Vec<Vec<f64>>, Vec<Vec<f64>>);

/// Steps the worlds `frames` times, interleaved frame by frame (each frame starting
/// one world further on), calling `progress` with the frames done after each.
fn step_all(worlds: &mut [World], frames: usize, progress: &(dyn Fn(usize) + Sync)) -> FrameTimes {
    let mut frame_ms = vec![Vec::with_capacity(frames); worlds.len()];
    let mut cpu_ms = frame_ms.clone();
    for frame in 0..frames {
        for k in 0..worlds.len() {
            let w = (frame + k) % worlds.len();
            let (wall, cpu) = worlds[w].step_timed();
            frame_ms[w].push(wall);
            cpu_ms[w].push(cpu);
        }
        progress(frame + 1);
    }
    (frame_ms, cpu_ms)
}

/// Each entry's outcome: its shapes, frame times, and where its balls ended measured
/// against the reference's (the first world's).
fn outcomes_of(
    scene: &Scene,
    entries: &[&Entry],
    worlds: &[World],
    (frame_ms, cpu_ms): FrameTimes,
    parts: Vec<ShapeCounts>,
) -> Vec<Outcome> {
    let ends: Vec<(Vec<V3>, Vec<f64>)> = worlds.iter().map(World::balls).collect();
    let profiles: Vec<Option<profile::Profile>> = worlds.iter().map(World::profile).collect();
    let reference = &ends[0].0;
    entries
        .iter()
        .zip(frame_ms.into_iter().zip(cpu_ms))
        .zip(ends.iter().zip(parts))
        .zip(profiles)
        .map(
            |(((e, (ms, cpu)), ((end, speed), (shapes, skipped))), profile)| Outcome {
                label: e.label.clone(),
                kind: e.geometry.kind(),
                shapes,
                skipped,
                stats: FrameStats::of(&ms),
                frame_ms: ms,
                cpu_stats: FrameStats::of(&cpu),
                cpu_ms: cpu,
                behaviour: Behaviour::of(scene, end, speed, reference),
                end: end.clone(),
                speed: speed.clone(),
                profile,
            },
        )
        .collect()
}

/// The closed axis-aligned box `lo`–`hi` as six outward quads (tests).
#[cfg(test)]
pub(crate) fn cuboid_mesh(lo: V3, hi: V3) -> Mesh {
    primdecomp_testkit::shapes::mesh(&primdecomp_testkit::shapes::cuboid(lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::{Obb, Primitive};
    use primdecomp_eval::collider::{parse_hulls_obj, parse_json};
    use std::path::Path;

    /// A 2 × 1 × 2 box (world units) from (10, 0, 10): mesh and matching primitive.
    fn box_mesh() -> (Mesh, Primitive) {
        let prim = Primitive::Box(Obb {
            center: [11.0, 0.5, 11.0],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            half: [1.0, 0.5, 1.0],
        });
        (cuboid_mesh([10.0, 0.0, 10.0], [12.0, 1.0, 12.0]), prim)
    }

    /// The box mesh and its primitive as the one collider.
    fn box_scene() -> (Mesh, [Entry; 1]) {
        let (mesh, prim) = box_mesh();
        let e = Entry {
            label: "box".into(),
            geometry: Geometry::Collider(Collider::Primitives(vec![prim])),
        };
        (mesh, [e])
    }

    fn settings(balls: usize, frames: usize) -> Settings {
        Settings {
            balls,
            frames,
            ..Default::default()
        }
    }

    /// Ball centres' heights (simulation frame) at the end of `outcome`.
    fn heights(o: &Outcome) -> Vec<f64> {
        o.end.iter().map(|p| p[1]).collect()
    }

    /// A ball dropped on a box comes to rest on its top face: centre height = top +
    /// radius (within Rapier's contact tolerance, 1% of the radius here), speed 0,
    /// and the behaviour measures call it resting on the object.
    #[test]
    fn ball_rests_on_top_of_a_box() {
        let (mesh, e) = box_scene();
        let run = run(&mesh, "mesh", &e, &settings(4, 150), &|_| {}).unwrap();
        let top = run.scene.aabb.1[1] + run.scene.radius;
        for o in &run.outcomes {
            for (h, v) in heights(o).iter().zip(&o.speed) {
                assert!(
                    (h - top).abs() < 0.01 * run.scene.radius,
                    "{}: height {h}, expected {top}",
                    o.label
                );
                assert!(*v < 1e-3, "{}: still moving at {v} m/s", o.label);
            }
            assert_eq!((o.behaviour.on_object, o.behaviour.resting), (1.0, 1.0));
        }
        // The perturbed mesh run and the box's run match the mesh's ball for ball.
        assert_eq!(run.outcomes[1].kind, "mesh_perturbed");
        assert_eq!(run.outcomes[1].behaviour.similarity, 1.0);
        assert_eq!(run.outcomes[2].behaviour.similarity, 1.0);
    }

    /// The noise-floor entry: second, labelled, its balls started at most
    /// `PERTURBATION_RADII` · r per axis away (but not all at the same place); on one
    /// ball on a box it ends where the reference's does; `perturbed: false` drops it.
    #[test]
    fn perturbed_reference_is_the_second_entry() {
        let (mesh, e) = box_scene();
        let run = run(&mesh, "in.obj", &e, &settings(1, 150), &|_| {}).unwrap();
        let kinds: Vec<&str> = run.outcomes.iter().map(|o| o.kind).collect();
        assert_eq!(kinds, ["mesh", "mesh_perturbed", "primitives"]);
        assert_eq!(run.outcomes[1].label, "in.obj (perturbed)");
        assert_eq!(run.outcomes[1].behaviour.similarity, 1.0);
        assert_eq!(run.outcomes[1].behaviour.similarity_set, 1.0);
        let moved = run.scene.perturbed_release(0);
        let d = scene::PERTURBATION_RADII * run.scene.radius;
        for (p, q) in run.scene.release.iter().zip(&moved) {
            assert!((0..3).all(|k| (p[k] - q[k]).abs() <= d), "{p:?} vs {q:?}");
            assert_ne!(p, q);
        }
        let off = Settings {
            perturbed: false,
            ..settings(1, 10)
        };
        let run = super::run(&mesh, "in.obj", &e, &off, &|_| {}).unwrap();
        assert_eq!(run.outcomes.len(), 2);
        assert_eq!(run.outcomes[1].kind, "primitives");
    }

    /// The same box read from a primdecomp JSON document and from an OBJ file of
    /// convex hulls (the two collider paths of `primdecomp sim`) gives the same resting
    /// heights, to f32 round-off of the two shapes.
    #[test]
    fn json_box_and_obj_hull_box_rest_alike() {
        let (mesh, _) = box_mesh();
        let json = br#"{"format":"primdecomp","version":1,"primitives":[{"kind":"box","center":[11,0.5,11],
            "rotation":[0,0,0,1],"half_extents":[1,0.5,1]}]}"#;
        let obj = b"o hull_0\nv 10 0 10\nv 12 0 10\nv 10 1 10\nv 12 1 10\nv 10 0 12\n\
            v 12 0 12\nv 10 1 12\nv 12 1 12\nf 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\n\
            f 1 3 4 2\nf 5 6 8 7\n";
        let e = [
            Entry {
                label: "json".into(),
                geometry: Geometry::Collider(parse_json(json, Path::new("box.json")).unwrap()),
            },
            Entry {
                label: "obj".into(),
                geometry: Geometry::Collider(Collider::Hulls(
                    parse_hulls_obj(obj, Path::new("box.obj")).unwrap(),
                )),
            },
        ];
        let run = run(&mesh, "mesh", &e, &settings(9, 150), &|_| {}).unwrap();
        let top = run.scene.aabb.1[1] + run.scene.radius;
        let (a, b) = (heights(&run.outcomes[2]), heights(&run.outcomes[3]));
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - y).abs() < 1e-3 * run.scene.radius,
                "json {x} vs obj {y}"
            );
            assert!(
                (x - top).abs() < 0.01 * run.scene.radius,
                "json {x} vs top {top}"
            );
        }
    }

    /// Same seed, same result to the bit (positions, speeds, measures); another seed
    /// moves the release points.
    #[test]
    fn fixed_seed_is_repeatable() {
        let (mesh, e) = box_scene();
        let go = |seed| {
            let s = Settings {
                seed,
                ..settings(40, 60)
            };
            run(&mesh, "mesh", &e, &s, &|_| {}).unwrap()
        };
        let (a, b, c) = (go(7), go(7), go(8));
        for (x, y) in a.outcomes.iter().zip(&b.outcomes) {
            assert_eq!(
                (&x.end, &x.speed, x.behaviour),
                (&y.end, &y.speed, y.behaviour)
            );
        }
        assert_eq!(a.scene.release, b.scene.release);
        assert_ne!(a.scene.release, c.scene.release);
    }

    /// `profile` attributes every collider's steps: 4 balls resting on a box give
    /// ball–cuboid pairs (the primitive) and ball–trimesh pairs (the mesh), touching
    /// for most of the 150 frames, never two static shapes at once (there is one);
    /// Rapier's stage times are filled in. Without it there is no profile.
    #[test]
    fn profile_counts_pairs_by_kind() {
        let (mesh, e) = box_scene();
        let s = Settings {
            profile: true,
            ..settings(4, 150)
        };
        let run = run(&mesh, "mesh", &e, &s, &|_| {}).unwrap();
        for (o, key) in run
            .outcomes
            .iter()
            .zip(["ball-tri_mesh", "ball-tri_mesh", "ball-cuboid"])
        {
            let p = o.profile.as_ref().expect("profiled");
            let c = p.pairs[key];
            assert!(c.touching > 2.0 && c.touching <= 4.0, "{}: {c:?}", o.label);
            assert!(c.pairs >= c.touching, "{}: {c:?}", o.label);
            assert_eq!(p.balls_on_several_shapes, 0.0);
            assert_eq!(p.contacts_of_balls_on_several, 0.0);
            // The mesh and the box primitive each fill the input's AABB exactly.
            assert!((p.shape_aabb_reach - 1.0).abs() < 1e-5, "{p:?}");
            assert!(p.step_ms > 0.0 && p.narrow_phase_ms > 0.0, "{p:?}");
        }
        let plain = super::run(&mesh, "mesh", &e, &settings(4, 5), &|_| {}).unwrap();
        assert!(plain.outcomes.iter().all(|o| o.profile.is_none()));
    }

    /// Balls resting on a top face that two overlapping boxes share (the box and a
    /// slab of its upper half) touch both: the profile counts each such ball once and
    /// its two contacts, while the mesh (one shape) has none; the two boxes reach over
    /// the box's volume plus the slab's (each grown by the ball radius).
    #[test]
    fn profile_counts_balls_on_two_overlapping_boxes() {
        let (mesh, _) = box_mesh();
        let part = |cy: f64, hy: f64| {
            Primitive::Box(Obb {
                center: [11.0, cy, 11.0],
                axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                half: [1.0, hy, 1.0],
            })
        };
        let e = [Entry {
            label: "two boxes".into(),
            geometry: Geometry::Collider(Collider::Primitives(vec![
                part(0.5, 0.5),
                part(0.75, 0.25),
            ])),
        }];
        // The same with the two boxes as one compound collider: a ball on both is one
        // pair with a manifold per box, counted as two shapes all the same.
        for compound in [false, true] {
            let s = Settings {
                profile: true,
                compound,
                ..settings(4, 150)
            };
            let run = run(&mesh, "mesh", &e, &s, &|_| {}).unwrap();
            let mesh_p = run.outcomes[0].profile.as_ref().expect("profiled");
            assert_eq!(mesh_p.balls_on_several_shapes, 0.0);
            let p = run.outcomes[2].profile.as_ref().expect("profiled");
            let key = if compound {
                "ball-compound"
            } else {
                "ball-cuboid"
            };
            assert!(p.pairs.contains_key(key), "{compound}: {p:?}");
            assert!(p.balls_on_several_shapes > 2.0, "{compound}: {p:?}");
            assert_eq!(
                p.contacts_of_balls_on_several,
                2.0 * p.balls_on_several_shapes
            );
        }
    }

    /// A collider of several parts given to Rapier as one compound shape holds the
    /// balls where the same parts as separate colliders do: 16 balls on a box cut
    /// into four quarter boxes rest on its top either way, ball for ball within
    /// Rapier's contact tolerance, and the run reports one shape list per collider.
    #[test]
    fn compound_parts_hold_balls_like_separate_parts() {
        let (mesh, _) = box_mesh();
        let quarter = |x: f64, z: f64| {
            Primitive::Box(Obb {
                center: [x, 0.5, z],
                axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                half: [0.5, 0.5, 0.5],
            })
        };
        let parts = vec![
            quarter(10.5, 10.5),
            quarter(11.5, 10.5),
            quarter(10.5, 11.5),
            quarter(11.5, 11.5),
        ];
        let e = [Entry {
            label: "quarters".into(),
            geometry: Geometry::Collider(Collider::Primitives(parts)),
        }];
        let go = |compound| {
            let s = Settings {
                compound,
                ..settings(16, 150)
            };
            run(&mesh, "mesh", &e, &s, &|_| {}).unwrap()
        };
        let (apart, joined) = (go(false), go(true));
        let top = apart.scene.aabb.1[1] + apart.scene.radius;
        let (a, b) = (heights(&apart.outcomes[2]), heights(&joined.outcomes[2]));
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x - top).abs() < 0.01 * apart.scene.radius,
                "apart {x} vs {top}"
            );
            assert!(
                (y - top).abs() < 0.01 * apart.scene.radius,
                "compound {y} vs {top}"
            );
        }
        assert_eq!(joined.outcomes[2].shapes, 4);
        assert_eq!(joined.outcomes[2].behaviour.on_object, 1.0);
    }

    /// Bad settings are refused with a message, not a panic or a hang.
    #[test]
    fn bad_settings_are_refused() {
        let (mesh, _) = box_mesh();
        for s in [
            settings(0, 10),
            settings(10, 0),
            Settings {
                up: 3,
                ..settings(1, 1)
            },
        ] {
            assert!(matches!(
                run(&mesh, "m", &[], &s, &|_| {}),
                Err(Error::InvalidParams(_))
            ));
        }
    }
}
