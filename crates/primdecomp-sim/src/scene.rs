//! The simulated scene (paper §4.1 "Simulation details"): the frame the input is
//! scaled into, the balls' size and release positions, and one Rapier world per
//! collider with identical balls. The rules are documented in [`super`].

use super::profile::{Profile, Tally};
use super::shapes::{Frame, Placed};
use super::Settings;
use primdecomp::Mesh;
use primdecomp_math::{norm, sub, V3};
use rapier3d::dynamics::{RigidBodyBuilder, RigidBodyHandle};
use rapier3d::geometry::{ColliderBuilder, SharedShape};
use rapier3d::math::Vector;
use rapier3d::pipeline::PhysicsWorld;
use std::time::Instant;

/// The input's AABB diagonal in the simulation, in metres.
pub const SCENE_DIAGONAL: f64 = 10.0;
/// Ball radius as a fraction of the input's AABB diagonal.
pub const BALL_RADIUS_REL: f64 = 0.01;
/// Release grid spacing in ball radii (columns and layers).
pub const SPACING_RADII: f64 = 3.0;
/// Gravity, m/s².
pub const GRAVITY: f64 = 9.81;
/// Fixed time step, s.
pub const DT: f64 = 1.0 / 60.0;
/// Largest per-axis start offset of the perturbed reference run, in ball radii
/// (1e-4 r = 10 µm in the scene: ~20 f32 ulps at 5 m from the origin, so Rapier sees
/// it, and 5000 times smaller than the release jitter).
pub const PERTURBATION_RADII: f64 = 1e-4;
/// Mixed into the seed for the perturbation's stream, so it differs from the jitter's.
const PERTURBATION_SEED: u64 = 0xD1B5_4A32_D192_ED03;

/// Scene geometry shared by every collider's world, in the simulation frame.
#[derive(Clone, Debug)]
pub struct Scene {
    pub frame: Frame,
    /// Ball radius, simulation units (m).
    pub radius: f64,
    /// Index of the up axis (gravity points along −up).
    pub up: usize,
    /// The input's AABB in the simulation frame.
    pub aabb: (V3, V3),
    /// Initial ball centres, simulation frame.
    pub release: Vec<V3>,
}

/// SplitMix64: a tiny, well-mixed, seedable stream for the release jitter.
pub(crate) struct SplitMix(pub(crate) u64);

impl SplitMix {
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [−1, 1).
    pub(crate) fn symmetric(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

impl Scene {
    /// Scales the input so its AABB diagonal is [`SCENE_DIAGONAL`] and lays out the
    /// release grid over its footprint.
    pub fn new(mesh: &Mesh, settings: &Settings) -> Scene {
        let (frame, aabb) = frame_of(mesh);
        let radius = BALL_RADIUS_REL * SCENE_DIAGONAL;
        let release = release_grid(aabb, radius, settings);
        Scene {
            frame,
            radius,
            up: settings.up,
            aabb,
            release,
        }
    }

    /// Ball radius in the input's units.
    pub fn radius_world(&self) -> f64 {
        self.radius / self.frame.scale
    }

    /// The release positions, each moved by up to [`PERTURBATION_RADII`] · r per axis
    /// (uniform, from a stream seeded by `seed`): the perturbed reference run, whose
    /// distance from the reference run is the behaviour measures' noise floor.
    pub fn perturbed_release(&self, seed: u64) -> Vec<V3> {
        let mut rng = SplitMix(seed ^ PERTURBATION_SEED);
        let d = PERTURBATION_RADII * self.radius;
        self.release
            .iter()
            .map(|p| p.map(|x| x + d * rng.symmetric()))
            .collect()
    }
}

/// The simulation frame of `mesh` (re-centred on its AABB centre, scaled to an AABB
/// diagonal of [`SCENE_DIAGONAL`]) and its AABB in that frame.
pub fn frame_of(mesh: &Mesh) -> (Frame, (V3, V3)) {
    let (lo, hi) = mesh.aabb();
    let diag = norm(sub(hi, lo));
    let scale = if diag > 0.0 && diag.is_finite() {
        SCENE_DIAGONAL / diag
    } else {
        1.0
    };
    let frame = Frame {
        offset: mesh.centre(),
        scale,
    };
    (frame, (lo.map(|x| x * scale), hi.map(|x| x * scale)))
}

/// Columns `SPACING_RADII · r` apart over the AABB's footprint (cells centred, at
/// least one per axis), layers as far apart upwards from `r · SPACING_RADII` above
/// the top, filled layer by layer in row order; each centre jittered uniformly by up
/// to r/2 per axis from the seeded stream, so neighbours never overlap.
fn release_grid(aabb: (V3, V3), r: f64, settings: &Settings) -> Vec<V3> {
    let up = settings.up;
    let (a, b) = ((up + 1) % 3, (up + 2) % 3);
    let s = SPACING_RADII * r;
    let cells = |k: usize| (((aabb.1[k] - aabb.0[k]) / s).floor() as usize).max(1);
    let (na, nb) = (cells(a), cells(b));
    let step = |k: usize, n: usize| (aabb.1[k] - aabb.0[k]) / n as f64;
    let (sa, sb) = (step(a, na), step(b, nb));
    let mut rng = SplitMix(settings.seed);
    (0..settings.balls)
        .map(|i| {
            let (layer, cell) = (i / (na * nb), i % (na * nb));
            let (ia, ib) = (cell / nb, cell % nb);
            let mut p = [0.0; 3];
            p[a] = aabb.0[a] + (ia as f64 + 0.5) * sa;
            p[b] = aabb.0[b] + (ib as f64 + 0.5) * sb;
            p[up] = aabb.1[up] + s * (layer as f64 + 1.0);
            for x in p.iter_mut() {
                *x += 0.5 * r * rng.symmetric();
            }
            p
        })
        .collect()
}

/// CPU time of the whole process, ms (all threads): unlike wall time it does not
/// count the time the machine gave to other processes. NaN where unsupported.
#[cfg(unix)]
pub fn process_cpu_ms() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    if rc != 0 {
        return f64::NAN;
    }
    ts.tv_sec as f64 * 1e3 + ts.tv_nsec as f64 * 1e-6
}

/// CPU time of the whole process, ms: not available here.
#[cfg(not(unix))]
pub fn process_cpu_ms() -> f64 {
    f64::NAN
}

/// One collider's Rapier world: the static shapes and the scene's balls.
pub struct World {
    world: PhysicsWorld,
    balls: Vec<RigidBodyHandle>,
    /// Step-time attribution, when profiling.
    tally: Option<Tally>,
}

impl World {
    /// Static `shapes` plus one dynamic ball per `release` position (the scene's, or
    /// their perturbed copy), with CCD (fast balls would otherwise tunnel through the
    /// reference's zero-thickness triangles). Rapier's parallel parts run on the rayon
    /// pool the caller is in. `settings.profile`: tally every step
    /// ([`super::profile`]); `settings.compound`: two or more shapes go in as one
    /// compound collider.
    pub fn new(scene: &Scene, shapes: Vec<Placed>, release: &[V3], settings: &Settings) -> World {
        let mut world = PhysicsWorld::new();
        let mut g = [0.0f32; 3];
        g[scene.up] = -GRAVITY as f32;
        world.gravity = Vector::from_array(g);
        world.integration_parameters.dt = DT as f32;
        if settings.compound && shapes.len() > 1 {
            let parts = shapes.into_iter().map(|(s, p)| (p, s)).collect();
            world.insert_collider(ColliderBuilder::new(SharedShape::compound(parts)), None);
        } else {
            for (shape, pose) in shapes {
                world.insert_collider(ColliderBuilder::new(shape).position(pose), None);
            }
        }
        let ball = ColliderBuilder::ball(scene.radius as f32);
        let balls = release
            .iter()
            .map(|&p| {
                let body = RigidBodyBuilder::dynamic()
                    .translation(Frame::vector(p))
                    .ccd_enabled(true);
                world.insert(body, ball.clone()).0
            })
            .collect();
        let tally = settings
            .profile
            .then(|| Tally::new(&world, scene.aabb, scene.radius));
        World {
            world,
            balls,
            tally,
        }
    }

    /// Advances one fixed step; returns the wall time and the process CPU time of
    /// the step alone, in ms. The profile's tally, if any, runs after the timing.
    pub fn step_timed(&mut self) -> (f64, f64) {
        let (t, c) = (Instant::now(), process_cpu_ms());
        self.world.step();
        let times = (t.elapsed().as_secs_f64() * 1e3, process_cpu_ms() - c);
        if let Some(tally) = &mut self.tally {
            tally.add(&self.world);
        }
        times
    }

    /// The step-time attribution so far, when profiling.
    pub fn profile(&self) -> Option<Profile> {
        self.tally.as_ref().map(Tally::profile)
    }

    /// Ball centres (simulation frame) and speeds (m/s), in release order.
    pub fn balls(&self) -> (Vec<V3>, Vec<f64>) {
        self.balls
            .iter()
            .map(|&h| {
                let b = &self.world.bodies[h];
                let (p, v) = (b.translation(), b.linvel());
                ([p.x as f64, p.y as f64, p.z as f64], v.length() as f64)
            })
            .unzip()
    }
}
