//! The compound in its real consumer, Rapier: every input face lies inside one part of
//! the compound (in parry's f32), and balls dropped on it in a Rapier world come to
//! rest on it without any ball's centre ever entering or crossing it.

use primdecomp::{decompose, demo_scene, Goal, Mesh, Params, Primitive};
use primdecomp_parry::{compound, shapes, Colliders};
use primdecomp_testkit::shapes::{cuboid, cylinder, icosphere, join, mesh};
use rapier3d::dynamics::RigidBodyBuilder;
use rapier3d::geometry::ColliderBuilder;
use rapier3d::math::Vector;
use rapier3d::parry::query::Ray;
use rapier3d::pipeline::PhysicsWorld;

/// A table-like scene on a slab: a ball, a standing cylinder and a box.
fn made_up() -> Mesh {
    let mut ball = icosphere(0.8, 2);
    ball.0
        .iter_mut()
        .for_each(|v| *v = [v[0] - 2.5, v[1] + 0.8, v[2]]);
    let mut drum = cylinder(0.6, 1.2, 24);
    // Stand it up (+z to +y) at x = 1.
    drum.0
        .iter_mut()
        .for_each(|v| *v = [v[0] + 1.0, v[2], -v[1]]);
    let slab = cuboid([-4.0, -0.3, -2.0], [4.0, 0.0, 2.0]);
    let block = cuboid([2.2, 0.0, -1.0], [3.6, 0.9, 0.5]);
    mesh(&join(&[slab, ball, drum, block]))
}

fn vector(p: [f64; 3]) -> Vector {
    Vector::new(p[0] as f32, p[1] as f32, p[2] as f32)
}

/// The faces no single part of the compound holds (every corner inside it), the
/// corners taken relative to the compound's origin (in f64, then f32: where the
/// collider sits, the engine computes relative to it too).
fn faces_outside(mesh: &Mesh, c: &Colliders) -> usize {
    let parts = c.shape.as_compound().expect("a compound").shapes();
    (0..mesh.face_count())
        .filter(|&f| {
            let corners: Vec<Vector> = mesh
                .face(f)
                .iter()
                .map(|&v| {
                    let w = mesh.world_pos(v);
                    vector([0, 1, 2].map(|k| w[k] - c.origin[k]))
                })
                .collect();
            !parts
                .iter()
                .any(|(p, s)| corners.iter().all(|&q| s.contains_point(p, q)))
        })
        .count()
}

struct Drop {
    balls: usize,
    resting_on_it: usize,
    through: usize,
}

/// Balls on a grid over the compound, where it lies below; steps until they rest.
fn drop_balls(mesh: &Mesh, c: &Colliders) -> Drop {
    let (lo, hi) = mesh.aabb();
    let (lo, hi) = (
        [0, 1, 2].map(|k| lo[k] + mesh.centre()[k]),
        [0, 1, 2].map(|k| hi[k] + mesh.centre()[k]),
    );
    let size = [0, 1, 2].map(|k| hi[k] - lo[k]);
    let diag = size.iter().map(|x| x * x).sum::<f64>().sqrt();
    let radius = 0.01 * diag;
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, -9.81, 0.0);
    world.insert(
        RigidBodyBuilder::fixed().translation(vector(c.origin)),
        ColliderBuilder::new(c.shape.clone()),
    );
    let ground = lo[1] - 0.02 * diag;
    world.insert(
        RigidBodyBuilder::fixed().translation(vector([
            0.5 * (lo[0] + hi[0]),
            ground - 0.05 * diag,
            0.5 * (lo[2] + hi[2]),
        ])),
        ColliderBuilder::cuboid(
            (size[0] + diag) as f32,
            (0.05 * diag) as f32,
            (size[2] + diag) as f32,
        ),
    );
    let pose = c.pose();
    let n = [0, 2].map(|k| ((size[k] / (3.0 * radius)) as usize).max(2));
    let mut balls = Vec::new();
    for i in 0..n[0] {
        for j in 0..n[1] {
            let x = lo[0] + (i as f64 + 0.5) / n[0] as f64 * size[0];
            let z = lo[2] + (j as f64 + 0.5) / n[1] as f64 * size[2];
            let y = hi[1] + radius * (2.0 + 3.0 * ((i + j) % 4) as f64);
            let below = Ray::new(vector([x, y, z]), Vector::new(0.0, -1.0, 0.0));
            if c.shape
                .cast_ray(&pose, &below, (2.0 * diag) as f32, true)
                .is_none()
            {
                continue;
            }
            let body = RigidBodyBuilder::dynamic()
                .translation(vector([x, y, z]))
                .linear_damping(0.2)
                .angular_damping(1.5);
            let ball = ColliderBuilder::ball(radius as f32)
                .friction(0.8)
                .restitution(0.0);
            balls.push(world.insert(body, ball).0);
        }
    }
    let mut through = 0;
    let mut prev: Vec<Vector> = balls
        .iter()
        .map(|&b| world.bodies[b].translation())
        .collect();
    for frame in 0..1200 {
        world.step();
        let now: Vec<Vector> = balls
            .iter()
            .map(|&b| world.bodies[b].translation())
            .collect();
        for (a, b) in prev.iter().zip(&now) {
            let d = *b - *a;
            let len = d.length();
            let dir = if len > 0.0 {
                d / len
            } else {
                Vector::new(0.0, -1.0, 0.0)
            };
            // The centre's path this step, solid: a centre inside counts at 0.
            if c.shape
                .cast_ray(&pose, &Ray::new(*a, dir), len, true)
                .is_some()
            {
                through += 1;
            }
        }
        prev = now;
        if frame > 60 && balls.iter().all(|&b| world.bodies[b].is_sleeping()) {
            break;
        }
    }
    let resting_on_it = balls
        .iter()
        .filter(|&&b| (world.bodies[b].translation().y as f64) > ground + 1.5 * radius)
        .count();
    Drop {
        balls: balls.len(),
        resting_on_it,
        through,
    }
}

fn check(name: &str, mesh: &Mesh, params: &Params, resting: f64) {
    let result = decompose(mesh, params).unwrap();
    let prims: &[Primitive] = &result.levels[0].primitives;
    let c = compound(prims).unwrap();
    assert_eq!(c.shape.as_compound().unwrap().shapes().len(), prims.len());
    assert_eq!(
        faces_outside(mesh, &c),
        0,
        "{name}: faces outside every part of the compound"
    );
    let d = drop_balls(mesh, &c);
    eprintln!(
        "{name}: {} primitives in one compound; {} balls, {} resting on it, {} passed into or through it",
        prims.len(),
        d.balls,
        d.resting_on_it,
        d.through
    );
    assert!(d.balls >= 20, "{name}: {} balls", d.balls);
    assert_eq!(
        d.through, 0,
        "{name}: ball centres that entered or crossed the compound"
    );
    assert!(
        d.resting_on_it as f64 >= resting * d.balls as f64,
        "{name}: only {} of {} balls rest on the compound",
        d.resting_on_it,
        d.balls
    );
}

/// The made-up scene's slab, ball, drum and block hold nearly every ball.
#[test]
fn balls_rest_on_the_made_up_scene() {
    check("made-up scene", &made_up(), &Params::default(), 0.9);
}

/// Most of the demo scene is pipes, stairs and a roof that balls roll off; a fifth of
/// them stay on its table, washer and steps.
#[test]
fn balls_rest_on_the_demo_scene() {
    let p = Params {
        goal: Goal::counts([150]),
        ..Params::default()
    };
    check("demo scene, 150 primitives", &demo_scene(), &p, 0.2);
}

/// Far from the origin the shapes are placed relative to the primitives' centre, so
/// f32 keeps the detail and the faces stay inside.
#[test]
fn a_scene_far_from_the_origin_stays_enclosed() {
    let (mut v, f) = join(&[cuboid([0.0; 3], [1.0, 0.2, 0.6]), {
        let mut d = cylinder(0.2, 0.5, 16);
        d.0.iter_mut().for_each(|p| p[0] += 2.0);
        d
    }]);
    v.iter_mut()
        .for_each(|p| *p = [p[0] + 1.0e5, p[1] - 3.0e4, p[2] + 7.0e4]);
    let far = Mesh::from_polygons(&v, &f).unwrap();
    let result = decompose(&far, &Params::default()).unwrap();
    let c = compound(&result.levels[0].primitives).unwrap();
    assert_eq!(faces_outside(&far, &c), 0);
    // Each shape alone, as for one collider per primitive, relative to any origin.
    let one = shapes(&result.levels[0].primitives, c.origin).unwrap();
    assert_eq!(one.len(), result.levels[0].primitives.len());
}
