//! Self-tests of the independent containment oracle in `tests/common/contain.rs`.
//!
//! Boundary points are generated in each primitive's local frame and mapped to
//! world space with Rodrigues' rotation formula (not quaternions), so a
//! convention error in the oracle's quaternion handling (scalar order,
//! conjugation, direction) shows up as a failure.  Every boundary probe checks
//! a point `D` inside and `D` outside along the outward normal, and the
//! tolerance behaviour at `D/2` and `2D`.

use primdecomp_testkit::contain::{
    faces_enclosed, faces_enclosed_with_work, parse_primitive, shape_contains, Shape,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::f64::consts::PI;

type P3 = [f64; 3];

/// Probe offset; shapes in these tests have sizes 0.05–3.
const D: f64 = 1e-6;

fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: P3, s: f64) -> P3 {
    a.map(|x| x * s)
}
fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: P3) -> P3 {
    mul(a, 1.0 / dot(a, a).sqrt())
}

fn random_unit(rng: &mut ChaCha8Rng) -> P3 {
    loop {
        let v = [0.0; 3].map(|_: f64| rng.gen_range(-1.0..1.0));
        let n2 = dot(v, v);
        if n2 > 1e-4 && n2 <= 1.0 {
            return unit(v);
        }
    }
}

/// A random unit vector perpendicular to the unit vector `k`.
fn random_perp(rng: &mut ChaCha8Rng, k: P3) -> P3 {
    loop {
        let c = cross(k, random_unit(rng));
        if dot(c, c) > 1e-4 {
            return unit(c);
        }
    }
}

/// Rigid frame `world = R·local + c`, `R` = rotation by `angle` about unit `axis`.
struct Frame {
    axis: P3,
    angle: f64,
    c: P3,
}

impl Frame {
    fn random(rng: &mut ChaCha8Rng) -> Frame {
        Frame {
            axis: random_unit(rng),
            angle: rng.gen_range(-PI..PI),
            c: [0.0; 3].map(|_: f64| rng.gen_range(-5.0..5.0)),
        }
    }

    /// Scalar-last unit quaternion of the rotation.
    fn quat(&self) -> [f64; 4] {
        let (s, c) = (0.5 * self.angle).sin_cos();
        [self.axis[0] * s, self.axis[1] * s, self.axis[2] * s, c]
    }

    /// Rodrigues: `v cosθ + (k×v) sinθ + k (k·v)(1 − cosθ)`.
    fn dir(&self, v: P3) -> P3 {
        let (s, c) = self.angle.sin_cos();
        let k = self.axis;
        add(
            add(mul(v, c), mul(cross(k, v), s)),
            mul(k, dot(k, v) * (1.0 - c)),
        )
    }

    fn point(&self, v: P3) -> P3 {
        add(self.dir(v), self.c)
    }
}

/// The identity frame at the origin plus `n` random frames.
fn frames(rng: &mut ChaCha8Rng, n: usize) -> Vec<Frame> {
    let id = Frame {
        axis: [0.0, 0.0, 1.0],
        angle: 0.0,
        c: [0.0; 3],
    };
    std::iter::once(id)
        .chain((0..n).map(|_| Frame::random(rng)))
        .collect()
}

/// Boundary point `s` with outward unit normal `n` (world space): checks
/// inside/outside at distance `D`, and the tolerance at `D/2` and `2D`.
fn probe(shape: &Shape, s: P3, n: P3, what: &str) {
    let inner = add(s, mul(n, -D));
    let outer = add(s, mul(n, D));
    assert!(
        shape_contains(shape, inner, 0.0),
        "{what}: inner {inner:?} {shape:?}"
    );
    assert!(
        !shape_contains(shape, outer, 0.0),
        "{what}: outer {outer:?} {shape:?}"
    );
    assert!(
        !shape_contains(shape, outer, 0.5 * D),
        "{what}: tol D/2 {shape:?}"
    );
    assert!(
        shape_contains(shape, outer, 2.0 * D),
        "{what}: tol 2D {shape:?}"
    );
}

fn sym(rng: &mut ChaCha8Rng, h: f64) -> f64 {
    rng.gen_range(-h..h)
}

#[test]
fn box_faces_and_corners() {
    let mut rng = ChaCha8Rng::seed_from_u64(10);
    for f in frames(&mut rng, 300) {
        let h = [0.0; 3].map(|_: f64| rng.gen_range(0.2..2.0));
        let v = json!({"kind": "box", "center": f.c, "rotation": f.quat(), "half_extents": h});
        let shape = parse_primitive(&v);
        assert!(shape_contains(&shape, f.c, 0.0));
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let mut l = h.map(|x| sym(&mut rng, 0.95 * x));
                l[axis] = sign * h[axis];
                let mut n = [0.0; 3];
                n[axis] = sign;
                probe(&shape, f.point(l), f.dir(n), "box face");
            }
        }
        // Beyond a corner by D along each axis: Euclidean distance D·√3.
        let s = [0.0; 3].map(|_: f64| if rng.gen_bool(0.5) { 1.0 } else { -1.0 });
        let p = f.point([0, 1, 2].map(|i| s[i] * (h[i] + D)));
        assert!(!shape_contains(&shape, p, 1.6 * D), "corner tol 1.6D");
        assert!(shape_contains(&shape, p, 1.8 * D), "corner tol 1.8D");
    }
}

#[test]
fn sphere_surface() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for f in frames(&mut rng, 100) {
        let r = rng.gen_range(0.05..3.0);
        let shape = parse_primitive(&json!({"kind": "sphere", "center": f.c, "radius": r}));
        for _ in 0..20 {
            let u = random_unit(&mut rng);
            probe(&shape, add(f.c, mul(u, r)), u, "sphere");
        }
    }
    // A zero-radius sphere is a point: tolerance makes it a ball of radius tol.
    let dot_shape = parse_primitive(&json!({"kind": "sphere", "center": [1, 2, 3], "radius": 0}));
    assert!(shape_contains(&dot_shape, [1.0, 2.0, 3.0], 0.0));
    assert!(shape_contains(&dot_shape, [1.0, 2.0, 3.0 + 0.5e-3], 1e-3));
    assert!(!shape_contains(&dot_shape, [1.0, 2.0, 3.0 + 2e-3], 1e-3));
}

/// Axis end points `p0`, `p1` along the frame's local x, and the world axis.
fn axis_of(f: &Frame, len: f64) -> (P3, P3, P3) {
    (
        f.point([-0.5 * len, 0.0, 0.0]),
        f.point([0.5 * len, 0.0, 0.0]),
        f.dir([1.0, 0.0, 0.0]),
    )
}

#[test]
fn capsule_sides_and_rounded_ends() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for f in frames(&mut rng, 200) {
        let (len, r) = (rng.gen_range(0.5..3.0), rng.gen_range(0.2..1.0));
        let (p0, p1, k) = axis_of(&f, len);
        let shape = parse_primitive(&json!({"kind": "capsule", "p0": p0, "p1": p1, "radius": r}));
        for _ in 0..10 {
            let u = random_perp(&mut rng, k);
            let t = rng.gen_range(0.05..0.95) * len;
            probe(
                &shape,
                add(add(p0, mul(k, t)), mul(u, r)),
                u,
                "capsule side",
            );
            for (end, out) in [(p1, k), (p0, mul(k, -1.0))] {
                let phi: f64 = rng.gen_range(0.0..1.5);
                let d = add(mul(out, phi.cos()), mul(u, phi.sin()));
                probe(&shape, add(end, mul(d, r)), d, "capsule end");
            }
            // Rounded, not flat: (0.5r, 0.95r) beyond the end is outside
            // (|·| = 1.07r), (0.5r, 0.85r) inside (|·| = 0.99r).
            let beyond = add(p1, mul(k, 0.5 * r));
            assert!(!shape_contains(&shape, add(beyond, mul(u, 0.95 * r)), 0.0));
            assert!(shape_contains(&shape, add(beyond, mul(u, 0.85 * r)), 0.0));
        }
    }
    // p0 == p1: a sphere.
    let ball = parse_primitive(
        &json!({"kind": "capsule", "p0": [1, 1, 1], "p1": [1, 1, 1], "radius": 0.5}),
    );
    assert!(shape_contains(&ball, [1.0, 1.0, 1.49], 0.0));
    assert!(!shape_contains(&ball, [1.0, 1.0, 1.51], 0.0));
}

/// Side, cap and rim probes for a cylinder or frustum along `p0 → p1`.
fn check_revolved(rng: &mut ChaCha8Rng, shape: &Shape, ends: (P3, P3, P3, f64), r0: f64, r1: f64) {
    let (p0, p1, k, len) = ends;
    let slope = (r1 - r0) / len;
    for _ in 0..10 {
        let u = random_perp(rng, k);
        let t = rng.gen_range(0.05..0.95) * len;
        let rt = r0 + slope * t;
        let side = add(add(p0, mul(k, t)), mul(u, rt));
        probe(shape, side, unit(add(u, mul(k, -slope))), "revolved side");
        for (c, r, out) in [(p0, r0, mul(k, -1.0)), (p1, r1, k)] {
            // Cap interior point (the apex itself when r = 0).
            let rho = rng.gen_range(0.0..0.9) * r;
            probe(shape, add(c, mul(u, rho)), out, "revolved cap");
        }
    }
}

#[test]
fn cylinder_sides_caps_and_rims() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    for f in frames(&mut rng, 200) {
        let (len, r) = (rng.gen_range(0.3..3.0), rng.gen_range(0.1..1.5));
        let (p0, p1, k) = axis_of(&f, len);
        let shape = parse_primitive(&json!({"kind": "cylinder", "p0": p0, "p1": p1, "radius": r}));
        check_revolved(&mut rng, &shape, (p0, p1, k, len), r, r);
        // Beyond the rim by D axially and radially: distance D·√2.
        let u = random_perp(&mut rng, k);
        let rim = add(add(p1, mul(k, D)), mul(u, r + D));
        assert!(!shape_contains(&shape, rim, 1.3 * D), "rim tol 1.3D");
        assert!(shape_contains(&shape, rim, 1.5 * D), "rim tol 1.5D");
        // Flat cap, not rounded: just past the cap near the rim is outside.
        let past = add(add(p1, mul(k, 1e-3)), mul(u, 0.99 * r));
        assert!(!shape_contains(&shape, past, 0.0));
    }
    // p0 == p1: no axis; treated as the single point p0.
    let flat = parse_primitive(
        &json!({"kind": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 0], "radius": 1}),
    );
    assert!(shape_contains(&flat, [0.0; 3], 0.0));
    assert!(!shape_contains(&flat, [0.1, 0.0, 0.0], 0.0));
}

#[test]
fn frustum_sides_caps_and_apex() {
    let mut rng = ChaCha8Rng::seed_from_u64(14);
    let radii = [(1.0, 0.5), (0.3, 1.2), (0.8, 0.0), (0.0, 0.7), (0.6, 0.6)];
    for f in frames(&mut rng, 100) {
        for (a, b) in radii {
            let s = rng.gen_range(0.3..2.0);
            let (r0, r1, len) = (a * s, b * s, rng.gen_range(0.3..3.0));
            let (p0, p1, k) = axis_of(&f, len);
            let v = json!({"kind": "frustum", "p0": p0, "p1": p1, "radius0": r0, "radius1": r1});
            let shape = parse_primitive(&v);
            check_revolved(&mut rng, &shape, (p0, p1, k, len), r0, r1);
            // Linear radius: at mid-height the radius is the mean of the caps.
            let u = random_perp(&mut rng, k);
            let mid = add(p0, mul(k, 0.5 * len));
            let rm = 0.5 * (r0 + r1);
            assert!(shape_contains(&shape, add(mid, mul(u, rm - D)), 0.0));
            assert!(!shape_contains(&shape, add(mid, mul(u, rm + 2.0 * D)), 0.0));
        }
    }
}

/// Half-width along z of the trapezoid at height `y`.
fn trapezoid_width(y: f64, hy: f64, a: f64, b: f64) -> f64 {
    b + (a - b) * (y + hy) / (2.0 * hy)
}

/// Probes of one prism: ±x faces, top/bottom (when not degenerate), slanted sides.
fn check_prism(rng: &mut ChaCha8Rng, shape: &Shape, f: &Frame, h: (f64, f64, f64, f64)) {
    let (hx, hy, a, b) = h;
    let m = (a - b) / (2.0 * hy);
    for _ in 0..8 {
        let x = sym(rng, 0.9 * hx);
        let y = sym(rng, 0.9 * hy);
        let w = trapezoid_width(y, hy, a, b);
        for sx in [-1.0, 1.0] {
            let l = [sx * hx, y, sym(rng, 0.9 * w)];
            probe(shape, f.point(l), f.dir([sx, 0.0, 0.0]), "prism x face");
        }
        for (yy, half, sy) in [(hy, a, 1.0), (-hy, b, -1.0)] {
            // Top/bottom face, or the apex edge when its half-width is 0.
            let l = [x, yy, sym(rng, 0.9 * half.max(1e-300))];
            probe(shape, f.point(l), f.dir([0.0, sy, 0.0]), "prism top/bottom");
        }
        for sz in [-1.0, 1.0] {
            let l = [x, y, sz * w];
            let n = unit([0.0, -m, sz]);
            probe(shape, f.point(l), f.dir(n), "prism slanted side");
        }
    }
}

#[test]
fn prism_faces_slants_and_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    let tops = [(0.5, 1.0), (1.0, 0.5), (0.7, 0.7), (0.0, 0.8), (0.8, 0.0)];
    for f in frames(&mut rng, 100) {
        for (ta, tb) in tops {
            let s = rng.gen_range(0.3..2.0);
            let (hx, hy) = (rng.gen_range(0.1..2.0), rng.gen_range(0.1..2.0));
            let (a, b) = (ta * s, tb * s);
            let v = json!({"kind": "prism", "center": f.c, "rotation": f.quat(),
                "half_x": hx, "half_y": hy, "half_z_top": a, "half_z_bottom": b, "faces": 8});
            let shape = parse_primitive(&v);
            check_prism(&mut rng, &shape, &f, (hx, hy, a, b));
            // Inside the bounding box but outside the trapezoid.
            if a != b {
                let y = if a < b { 0.9 * hy } else { -0.9 * hy };
                let p = f.point([0.0, y, 0.5 * (a + b)]);
                assert!(!shape_contains(&shape, p, 0.0), "trapezoid, not box");
            }
        }
    }
}

#[test]
fn rotation_convention_by_hand() {
    let s = 0.5f64.sqrt();
    // +90° about z: local x → world y.
    let long = json!({"kind": "box", "center": [0, 0, 0], "rotation": [0, 0, s, s],
        "half_extents": [2.0, 0.1, 0.1]});
    let long = parse_primitive(&long);
    assert!(shape_contains(&long, [0.0, 1.9, 0.0], 0.0));
    assert!(!shape_contains(&long, [1.9, 0.0, 0.0], 0.0));
    // +90° about x: local y → world z, local z → world −y.  Triangle apex at +z.
    let tri = json!({"kind": "prism", "center": [0, 0, 0], "rotation": [s, 0, 0, s],
        "half_x": 1.0, "half_y": 1.0, "half_z_top": 0.0, "half_z_bottom": 1.0});
    let tri = parse_primitive(&tri);
    assert!(shape_contains(&tri, [0.0, 0.0, 0.95], 0.0));
    assert!(shape_contains(&tri, [0.0, 0.9, -0.95], 0.0));
    assert!(!shape_contains(&tri, [0.0, 0.5, 0.9], 0.0));
    assert!(!shape_contains(&tri, [0.0, 0.0, 1.01], 0.0));
}

#[test]
fn near_unit_quaternion_accepted_and_extra_fields_ignored() {
    let v = json!({"kind": "box", "center": [0, 0, 0], "rotation": [0, 0, 0, 1.000001],
        "half_extents": [1, 1, 1], "faces": 12});
    assert!(shape_contains(&parse_primitive(&v), [0.999, 0.0, 0.0], 0.0));
}

#[test]
#[should_panic(expected = "unknown primitive kind")]
fn malformed_kind_panics() {
    parse_primitive(&json!({"kind": "torus", "center": [0, 0, 0], "radius": 1}));
}

#[test]
#[should_panic(expected = "lacks field \"radius\"")]
fn malformed_missing_field_panics() {
    parse_primitive(&json!({"kind": "sphere", "center": [0, 0, 0]}));
}

#[test]
#[should_panic(expected = "is negative")]
fn malformed_negative_radius_panics() {
    parse_primitive(&json!({"kind": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 1], "radius": -1}));
}

#[test]
#[should_panic(expected = "not a unit quaternion")]
fn malformed_rotation_panics() {
    parse_primitive(
        &json!({"kind": "box", "center": [0, 0, 0], "rotation": [0, 0, 0, 2],
        "half_extents": [1, 1, 1]}),
    );
}

#[test]
#[should_panic(expected = "not an array of 3 numbers")]
fn malformed_center_panics() {
    parse_primitive(&json!({"kind": "sphere", "center": [0, 0], "radius": 1}));
}

#[test]
#[should_panic(expected = "not a number")]
fn malformed_number_panics() {
    parse_primitive(&json!({"kind": "sphere", "center": [0, 0, 0], "radius": "big"}));
}

/// A random primitive of any kind around `c` with size ~`s`.
fn random_shape(rng: &mut ChaCha8Rng, c: P3, s: f64) -> Value {
    let f = Frame {
        c,
        ..Frame::random(rng)
    };
    let kind = rng.gen_range(0..6);
    let g: [f64; 7] = [
        (0.2, 1.5),
        (0.05, 0.8),
        (0.0, 0.8),
        (0.0, 0.8),
        (0.05, 1.0),
        (0.05, 1.0),
        (0.05, 1.0),
    ]
    .map(|(lo, hi)| rng.gen_range(lo..hi) * s);
    let (len, r, r2) = (g[0], g[1], g[2]);
    let (p0, p1, _) = axis_of(&f, len);
    match kind {
        0 => json!({"kind": "box", "center": c, "rotation": f.quat(),
            "half_extents": [g[4], g[5], g[6]]}),
        1 => json!({"kind": "sphere", "center": c, "radius": r}),
        2 => json!({"kind": "capsule", "p0": p0, "p1": p1, "radius": r}),
        3 => json!({"kind": "cylinder", "p0": p0, "p1": p1, "radius": r}),
        4 => json!({"kind": "frustum", "p0": p0, "p1": p1, "radius0": r, "radius1": r2}),
        _ => json!({"kind": "prism", "center": c, "rotation": f.quat(), "half_x": len,
            "half_y": r, "half_z_top": r2, "half_z_bottom": g[3], "faces": 8}),
    }
}

/// A face of 1–5 vertices scattered by up to `spread` around `c`.
fn random_face(rng: &mut ChaCha8Rng, c: P3, spread: f64) -> Vec<P3> {
    let n = rng.gen_range(1..=5);
    (0..n)
        .map(|_| add(c, [0.0; 3].map(|_: f64| rng.gen_range(-spread..spread))))
        .collect()
}

fn brute_force(shapes: &[Shape], faces: &[Vec<P3>], tol: f64) -> Vec<bool> {
    faces
        .iter()
        .map(|f| {
            shapes
                .iter()
                .any(|s| f.iter().all(|&v| shape_contains(s, v, tol)))
        })
        .collect()
}

/// Random scene: shapes in `[0, extent]³` and faces, half near shape centres.
fn random_scene(seed: u64, n_shapes: usize, n_faces: usize) -> (Vec<Shape>, Vec<Vec<P3>>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let extent = 2.0 * (n_shapes as f64).cbrt();
    let centres: Vec<P3> = (0..n_shapes)
        .map(|_| [0.0; 3].map(|_: f64| rng.gen_range(0.0..extent)))
        .collect();
    let shapes: Vec<Shape> = centres
        .iter()
        .map(|&c| parse_primitive(&random_shape(&mut rng, c, 1.0)))
        .collect();
    let faces = (0..n_faces)
        .map(|i| {
            let spread = [0.02, 0.2, 1.0][i % 3];
            let c = if i % 2 == 0 {
                centres[rng.gen_range(0..n_shapes)]
            } else {
                [0.0; 3].map(|_: f64| rng.gen_range(-1.0..extent + 1.0))
            };
            random_face(&mut rng, c, spread)
        })
        .collect();
    (shapes, faces)
}

#[test]
fn faces_enclosed_matches_brute_force() {
    let (shapes, faces) = random_scene(16, 300, 30_000);
    for tol in [0.0, 1e-3, 0.3] {
        let fast = faces_enclosed(&shapes, &faces, tol);
        assert_eq!(fast, brute_force(&shapes, &faces, tol), "tol {tol}");
        let inside = fast.iter().filter(|&&b| b).count();
        assert!(
            inside > 3_000 && inside < 27_000,
            "tol {tol}: {inside} enclosed"
        );
    }
}

#[test]
fn faces_enclosed_edge_cases() {
    let unit_box = parse_primitive(&json!({"kind": "box", "center": [0, 0, 0],
        "rotation": [0, 0, 0, 1], "half_extents": [1, 1, 1]}));
    let faces = vec![
        vec![],
        vec![[0.0; 3], [1.0 + 0.5e-3, 0.0, 0.0], [0.0, 1.0, 1.0]],
        vec![[0.0; 3], [1.0 + 2e-3, 0.0, 0.0]],
        vec![[5.0, 5.0, 5.0]],
        vec![[-1.0 - 0.5e-3, 0.0, 0.0]],
        vec![[f64::NAN, 0.0, 0.0]],
    ];
    let shapes = [unit_box];
    let got = faces_enclosed(&shapes, &faces, 1e-3);
    assert_eq!(got, vec![true, true, false, false, true, false]);
    assert_eq!(got, brute_force(&shapes, &faces, 1e-3));
    assert_eq!(faces_enclosed(&[], &faces, 1e-3), vec![false; faces.len()]);
    assert!(faces_enclosed(&shapes, &[], 0.0).is_empty());
    // All shapes with a degenerate (point) AABB: a one-cell grid.
    let dot_shape = parse_primitive(&json!({"kind": "sphere", "center": [1, 1, 1], "radius": 0}));
    let pts = vec![vec![[1.0, 1.0, 1.0]], vec![[1.0, 1.0, 1.1]]];
    assert_eq!(faces_enclosed(&[dot_shape], &pts, 0.0), vec![true, false]);
}

fn num(v: &Value, k: &str) -> f64 {
    v[k].as_f64().unwrap()
}
fn vec3(v: &Value, k: &str) -> P3 {
    [0, 1, 2].map(|i| v[k][i].as_f64().unwrap())
}

/// Rotation matrix of a scalar-last unit quaternion (textbook formula).
fn quat_matrix(v: &Value) -> [[f64; 3]; 3] {
    let [x, y, z, w] = [0, 1, 2, 3].map(|i| v["rotation"][i].as_f64().unwrap());
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// Exact AABB from the JSON, via support functions: `Σ_j |R_ij| h_j` for a
/// box, disc extents `r·√(1 − k_i²)`, corner hull for the prism.
fn exact_aabb(v: &Value) -> (P3, P3) {
    let grow = |pts: &[(P3, P3)]| {
        let lo = [0, 1, 2].map(|i| {
            pts.iter()
                .map(|(p, e)| p[i] - e[i])
                .fold(f64::INFINITY, f64::min)
        });
        let hi = [0, 1, 2].map(|i| {
            pts.iter()
                .map(|(p, e)| p[i] + e[i])
                .fold(f64::NEG_INFINITY, f64::max)
        });
        (lo, hi)
    };
    match v["kind"].as_str().unwrap() {
        "sphere" => grow(&[(vec3(v, "center"), [num(v, "radius"); 3])]),
        "capsule" => grow(&[
            (vec3(v, "p0"), [num(v, "radius"); 3]),
            (vec3(v, "p1"), [num(v, "radius"); 3]),
        ]),
        "box" => {
            let (r, h) = (quat_matrix(v), vec3(v, "half_extents"));
            let e = [0, 1, 2].map(|i| (0..3).map(|j| r[i][j].abs() * h[j]).sum::<f64>());
            grow(&[(vec3(v, "center"), e)])
        }
        "prism" => {
            let (r, c) = (quat_matrix(v), vec3(v, "center"));
            let (hx, hy) = (num(v, "half_x"), num(v, "half_y"));
            let (a, b) = (num(v, "half_z_top"), num(v, "half_z_bottom"));
            let mut pts = Vec::new();
            for l in [[hx, hy, a], [hx, hy, -a], [hx, -hy, b], [hx, -hy, -b]] {
                for l in [l, [-l[0], l[1], l[2]]] {
                    let w = [0, 1, 2].map(|i| c[i] + (0..3).map(|j| r[i][j] * l[j]).sum::<f64>());
                    pts.push((w, [0.0; 3]));
                }
            }
            grow(&pts)
        }
        _ => {
            let (p0, p1) = (vec3(v, "p0"), vec3(v, "p1"));
            let k = unit(add(p1, mul(p0, -1.0)));
            let (r0, r1) = match v.get("radius") {
                Some(r) => (r.as_f64().unwrap(), r.as_f64().unwrap()),
                None => (num(v, "radius0"), num(v, "radius1")),
            };
            let disc = |r: f64| k.map(|ki| r * (1.0 - ki * ki).max(0.0).sqrt());
            grow(&[(p0, disc(r0)), (p1, disc(r1))])
        }
    }
}

#[test]
fn aabb_is_conservative_and_tight() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    for _ in 0..2_000 {
        let v = random_shape(&mut rng, [1.0, -2.0, 3.0], 1.0);
        let shape = parse_primitive(&v);
        let (lo, hi) = shape.aabb();
        let (elo, ehi) = exact_aabb(&v);
        for i in 0..3 {
            assert!(lo[i] <= elo[i] && ehi[i] <= hi[i], "not conservative: {v}");
            assert!(elo[i] - lo[i] < 1e-6 && hi[i] - ehi[i] < 1e-6, "loose: {v}");
        }
        for _ in 0..200 {
            let p = [1.0, -2.0, 3.0].map(|c: f64| c + rng.gen_range(-3.0..3.0));
            if shape_contains(&shape, p, 0.0) {
                assert!((0..3).all(|i| lo[i] <= p[i] && p[i] <= hi[i]), "{p:?} {v}");
            }
        }
    }
}

/// The grid keeps the work linear: eight times the shapes and the faces at the
/// same density cost about eight times the work (all pairs would cost 64), and a
/// face tries a few shapes, not all 2,000. Counted, not timed.
#[test]
fn scale_200k_faces_2000_shapes() {
    let (small_shapes, small_faces) = random_scene(19, 250, 25_000);
    let (_, small) = faces_enclosed_with_work(&small_shapes, &small_faces, 1e-6);
    let (shapes, faces) = random_scene(18, 2_000, 200_000);
    let (fast, large) = faces_enclosed_with_work(&shapes, &faces, 1e-6);
    let ratio = large.total() as f64 / small.total() as f64;
    let per_face = large.candidates as f64 / faces.len() as f64;
    println!("work: {small:?} → {large:?}, ratio {ratio:.2}, {per_face:.2} candidates a face");
    assert!(ratio < 12.0, "8× the input costs {ratio:.1}× the work");
    assert!(per_face < 20.0, "{per_face:.1} candidate shapes a face");
    let sample: Vec<usize> = (0..faces.len()).step_by(40).collect();
    let subset: Vec<Vec<P3>> = sample.iter().map(|&i| faces[i].clone()).collect();
    let want = brute_force(&shapes, &subset, 1e-6);
    let got: Vec<bool> = sample.iter().map(|&i| fast[i]).collect();
    assert_eq!(got, want);
}
