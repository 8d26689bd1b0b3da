//! Narrow-phase cost of one ball–static pair by the static shape's kind, as `primdecomp
//! sim` hands shapes to Rapier (src/sim/shapes.rs): parry's contact-manifold update for
//! a ball of radius 0.1 resting on the top of a unit-sized shape (touching) and one in
//! its AABB but 0.05 clear of it (a broad-phase pair with no contact). Kinds: our
//! native cuboid, capsule and cylinder; a prism as the hull of its 8 corners and as
//! `PrismShape` (the same hull, analytic point projection: src/sim/prism_shape.rs); a frustum
//! as its 16-gon hull (32 vertices) and as `FrustumShape` (the same hull, analytic point
//! projection: src/sim/frustum_shape.rs); and convex hulls of 8, 16 and 64 points on a
//! sphere, the range of V-HACD's hulls on the corpus. `primdecomp sim --profile` counts
//! the pairs per frame by kind; this gives the cost per pair.
//! Run: `cargo bench --bench sim_pairs` (figures in docs/results/sim.md).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

use primdecomp::{Frustum, Primitive, Prism};
use primdecomp_sim::shapes::{self, Frame, Placed};
use rapier3d::geometry::SharedShape;
use rapier3d::math::{Pose, Vector};
use rapier3d::parry::query::{ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher};
use rapier3d::parry::shape::Ball;
use std::f64::consts::PI;
use std::time::Duration;

const R: f32 = 0.1;

/// `n` points spread over the unit sphere (Fibonacci lattice).
fn sphere_points(n: usize) -> Vec<Vector> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            let t = golden * i as f64;
            Vector::new((r * t.cos()) as f32, y as f32, (r * t.sin()) as f32)
        })
        .collect()
}

fn cases() -> Vec<(&'static str, Placed)> {
    let frame = Frame {
        offset: [0.0; 3],
        scale: 1.0,
    };
    let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let prism = Primitive::Prism(Prism {
        center: [0.0; 3],
        axes: [axes[0], axes[2], axes[1]],
        hx: 1.0,
        hy: 1.0,
        hz_top: 0.6,
        hz_bottom: 1.0,
        shift: 0.0,
    });
    let frustum = Primitive::Frustum(Frustum {
        p0: [0.0, -1.0, 0.0],
        p1: [0.0, 1.0, 0.0],
        r0: 1.0,
        r1: 0.7,
    });
    let Primitive::Prism(q) = prism else {
        unreachable!()
    };
    let corners = q.corners();
    let hull = |n| {
        (
            SharedShape::convex_hull(&sphere_points(n)).unwrap(),
            Pose::IDENTITY,
        )
    };
    vec![
        (
            "cuboid",
            (SharedShape::cuboid(1.0, 1.0, 1.0), Pose::IDENTITY),
        ),
        (
            "capsule",
            (SharedShape::capsule_y(0.5, 0.5), Pose::IDENTITY),
        ),
        (
            "cylinder",
            (SharedShape::cylinder(1.0, 1.0), Pose::IDENTITY),
        ),
        ("prism_hull_8", shapes::hull(&corners).unwrap()),
        ("prism_native", shapes::primitive(&prism, &frame).unwrap()),
        (
            "frustum_hull_32",
            shapes::hull(
                &frustum
                    .tessellate(primdecomp_sim::frustum_shape::FRUSTUM_SEGMENTS)
                    .vertices
                    .into_iter()
                    .map(|q| frame.point(q))
                    .collect::<Vec<_>>(),
            )
            .unwrap(),
        ),
        (
            "frustum_native",
            shapes::primitive(&frustum, &frame).unwrap(),
        ),
        ("hull_8", hull(8)),
        ("hull_16", hull(16)),
        ("hull_64", hull(64)),
    ]
}

fn pairs(c: &mut Criterion) {
    let d = DefaultQueryDispatcher;
    let ball = Ball::new(R);
    let mut g = c.benchmark_group("ball_pair");
    g.warm_up_time(Duration::from_millis(300));
    g.measurement_time(Duration::from_secs(1));
    for (name, (shape, pose)) in cases() {
        let aabb = shape.compute_aabb(&pose);
        // Straight above the shape's AABB centre, touching (0.01 deep) or 0.05 clear.
        for (state, gap) in [("touching", -0.01f32), ("near", 0.05)] {
            let top = aabb.maxs.y;
            let centre = Vector::new(0.0, top + R + gap, 0.0);
            let pos12 = pose.inverse() * Pose::from_translation(centre);
            let mut manifolds: Vec<ContactManifold<(), ()>> = Vec::new();
            let mut ws = None;
            g.bench_function(BenchmarkId::new(name, state), |b| {
                b.iter(|| {
                    PersistentQueryDispatcher::<(), ()>::contact_manifolds(
                        &d,
                        std::hint::black_box(&pos12),
                        &*shape,
                        &ball,
                        0.002,
                        &mut manifolds,
                        &mut ws,
                    )
                    .unwrap();
                    manifolds.len()
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, pairs);
criterion_main!(benches);
