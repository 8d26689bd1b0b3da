//! The built-in demo scene, built procedurally (no randomness): a staircase, a
//! table, three pipes (straight, perpendicular riser, and one bent by an elbow),
//! a gable-roof house, a torus and a washer, laid out along +x in meters with +y
//! up. Every `o` object is one closed, outward-wound shell; coincident corners of
//! touching objects share one vertex. Polygons are kept as quads and n-gons
//! (cylinder caps), which the engine treats specially.
//!
//! `datasets/demo_scene.obj` is the same scene as OBJ text, generated here and checked
//! by a test (the command line's `demo-scene` and the WebAssembly package embed that
//! file).

use crate::input::mesh::{Mesh, MeshBuilder};
use crate::math::{add, madd, scale, V3};
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Coordinates are rounded to 1 µm: short OBJ text, and no dependence on the
/// platform's last-ulp `sin`/`cos`.
const GRID: f64 = 1e6;
/// Segments around pipes and the washer; the torus uses this × (1, ½).
const ROUND: usize = 32;
const TORUS_MAJOR: usize = 48;
const TORUS_MINOR: usize = 24;

/// Box quads for corner `i` = (bit 0 → x, bit 1 → y, bit 2 → z; set = max side).
pub(crate) const BOX_FACES: [[usize; 4]; 6] = [
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

struct Object {
    name: String,
    /// Index of the first vertex this object added to the scene (where its `v` lines
    /// start in the OBJ text).
    #[cfg_attr(not(test), allow(dead_code))]
    first_vertex: usize,
    faces: Vec<Vec<u32>>,
}

/// Vertices shared by exact (rounded) position, and objects of polygons.
#[derive(Default)]
struct Scene {
    positions: Vec<V3>,
    lookup: HashMap<[u64; 3], u32>,
    objects: Vec<Object>,
}

impl Scene {
    fn begin(&mut self, name: impl Into<String>) {
        self.objects.push(Object {
            name: name.into(),
            first_vertex: self.positions.len(),
            faces: vec![],
        });
    }
    fn vertex(&mut self, p: V3) -> u32 {
        let p = p.map(|x| (x * GRID).round() / GRID + 0.0);
        let positions = &mut self.positions;
        *self.lookup.entry(p.map(f64::to_bits)).or_insert_with(|| {
            positions.push(p);
            (positions.len() - 1) as u32
        })
    }
    fn face(&mut self, idx: Vec<u32>) {
        self.objects
            .last_mut()
            .expect("begin() first")
            .faces
            .push(idx);
    }
}

/// Axis-aligned box between `lo` and `hi`.
fn add_box(s: &mut Scene, name: &str, lo: V3, hi: V3) {
    s.begin(name);
    let c: Vec<u32> = (0..8)
        .map(|i| std::array::from_fn(|k| if i >> k & 1 == 1 { hi[k] } else { lo[k] }))
        .map(|p| s.vertex(p))
        .collect();
    for f in BOX_FACES {
        s.face(f.iter().map(|&i| c[i]).collect());
    }
}

/// A capped tube through rings `(centre, u, v)` with `u × v` pointing forward along
/// the tube; caps are `k`-gons.
fn add_tube(s: &mut Scene, name: &str, rings: &[(V3, V3, V3)], r: f64, k: usize) {
    s.begin(name);
    let ids: Vec<Vec<u32>> = rings
        .iter()
        .map(|&(c, u, v)| {
            (0..k)
                .map(|j| {
                    let t = TAU * j as f64 / k as f64;
                    s.vertex(madd(madd(c, u, r * t.cos()), v, r * t.sin()))
                })
                .collect()
        })
        .collect();
    s.face(ids[0].iter().rev().copied().collect());
    for w in ids.windows(2) {
        for j in 0..k {
            let j1 = (j + 1) % k;
            s.face(vec![w[0][j], w[0][j1], w[1][j1], w[1][j]]);
        }
    }
    s.face(ids[ids.len() - 1].clone());
}

/// Straight capped cylinder from `p0` along `dir` (a unit coordinate axis) to `p1`.
fn add_pipe(s: &mut Scene, name: &str, p0: V3, p1: V3, dir: usize, r: f64) {
    let e = |k: usize| -> V3 { std::array::from_fn(|i| if i == k % 3 { 1.0 } else { 0.0 }) };
    let (u, v) = (e(dir + 1), e(dir + 2));
    add_tube(s, name, &[(p0, u, v), (p1, u, v)], r, ROUND);
}

/// Pipe running +x from `start` for `run`, bending up (+y) through a 90° elbow of
/// bend radius `bend` in `segments` steps, then rising by `rise`.
fn add_bent_pipe(s: &mut Scene, start: V3, run: f64, bend: f64, rise: f64, segments: usize) {
    let centre = add(start, [run, bend, 0.0]);
    // At bend angle α: tangent (cos α, sin α, 0); u points away from the bend
    // centre, v = −z, so u × v is the tangent.
    let ring = |a: f64, c: V3| (c, [a.sin(), -a.cos(), 0.0], [0.0, 0.0, -1.0]);
    let mut rings = vec![ring(0.0, start)];
    for i in 0..=segments {
        let a = FRAC_PI_2 * i as f64 / segments as f64;
        rings.push(ring(a, add(centre, scale([a.sin(), -a.cos(), 0.0], bend))));
    }
    rings.push(ring(FRAC_PI_2, add(centre, [bend, rise, 0.0])));
    add_tube(s, "pipe_bent", &rings, 0.1, ROUND);
}

/// Stepped staircase of `n` column boxes rising along +x.
fn add_staircase(s: &mut Scene, origin: V3, n: usize) {
    let (tread, rise, width) = (0.3, 0.18, 1.0);
    for i in 0..n {
        let lo = add(origin, [tread * i as f64, 0.0, 0.0]);
        let hi = add(
            origin,
            [tread * (i + 1) as f64, rise * (i + 1) as f64, width],
        );
        add_box(s, &format!("stairs_step_{i}"), lo, hi);
    }
}

/// Table: top slab and four inset legs.
fn add_table(s: &mut Scene, origin: V3) {
    let (len, depth, height, thick, leg, inset) = (1.6, 0.9, 0.76, 0.04, 0.06, 0.05);
    let below = height - thick;
    add_box(
        s,
        "table_top",
        add(origin, [0.0, below, 0.0]),
        add(origin, [len, height, depth]),
    );
    for (i, (fx, fz)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        let x = inset + fx * (len - 2.0 * inset - leg);
        let z = inset + fz * (depth - 2.0 * inset - leg);
        let lo = add(origin, [x, 0.0, z]);
        add_box(s, &format!("table_leg_{i}"), lo, add(lo, [leg, below, leg]));
    }
}

/// House: box walls and a gable roof (triangular prism, ridge along x) resting on
/// the walls' top face, sharing its corners.
fn add_house(s: &mut Scene, lo: V3, hi: V3, ridge: f64) {
    add_box(s, "house_walls", lo, hi);
    s.begin("house_roof");
    let y = hi[1];
    let zm = 0.5 * (lo[2] + hi[2]);
    let b00 = s.vertex([lo[0], y, lo[2]]);
    let b10 = s.vertex([hi[0], y, lo[2]]);
    let b01 = s.vertex([lo[0], y, hi[2]]);
    let b11 = s.vertex([hi[0], y, hi[2]]);
    let r0 = s.vertex([lo[0], y + ridge, zm]);
    let r1 = s.vertex([hi[0], y + ridge, zm]);
    s.face(vec![b00, b10, b11, b01]); // underside
    s.face(vec![b00, b01, r0]); // west gable
    s.face(vec![b10, r1, b11]); // east gable
    s.face(vec![b00, r0, r1, b10]); // south slope
    s.face(vec![b01, b11, r1, r0]); // north slope
}

/// Torus standing upright (axis +z) with quads.
fn add_torus(s: &mut Scene, c: V3, major: f64, minor: f64) {
    s.begin("torus");
    let (n, m) = (TORUS_MAJOR, TORUS_MINOR);
    let mut id = vec![vec![0u32; m]; n];
    for (i, row) in id.iter_mut().enumerate() {
        let t = TAU * i as f64 / n as f64;
        for (j, v) in row.iter_mut().enumerate() {
            let p = TAU * j as f64 / m as f64;
            let ring = major + minor * p.cos();
            *v = s.vertex(add(c, [ring * t.cos(), ring * t.sin(), minor * p.sin()]));
        }
    }
    for i in 0..n {
        for j in 0..m {
            let (i1, j1) = ((i + 1) % n, (j + 1) % m);
            s.face(vec![id[i][j], id[i1][j], id[i1][j1], id[i][j1]]);
        }
    }
}

/// Flat washer (annulus extruded along +y from `c`) with quads.
fn add_washer(s: &mut Scene, c: V3, r_in: f64, r_out: f64, thick: f64) {
    s.begin("washer");
    let k = ROUND + ROUND / 2;
    // Directions counter-clockwise about +y: z × x = y.
    let dir = |j: usize| {
        let t = TAU * j as f64 / k as f64;
        [t.sin(), 0.0, t.cos()]
    };
    let ring = |s: &mut Scene, r: f64, y: f64| -> Vec<u32> {
        (0..k)
            .map(|j| s.vertex(add(madd(c, dir(j), r), [0.0, y, 0.0])))
            .collect()
    };
    let (o0, o1) = (ring(s, r_out, 0.0), ring(s, r_out, thick));
    let (i0, i1) = (ring(s, r_in, 0.0), ring(s, r_in, thick));
    for j in 0..k {
        let j1 = (j + 1) % k;
        s.face(vec![i1[j], o1[j], o1[j1], i1[j1]]); // top
        s.face(vec![i0[j], i0[j1], o0[j1], o0[j]]); // bottom
        s.face(vec![o0[j], o0[j1], o1[j1], o1[j]]); // outer wall
        s.face(vec![i0[j], i1[j], i1[j1], i0[j1]]); // inner wall
    }
}

fn build() -> Scene {
    let mut s = Scene::default();
    add_staircase(&mut s, [-8.0, 0.0, 0.0], 9);
    add_table(&mut s, [-4.3, 0.0, 0.0]);
    add_pipe(
        &mut s,
        "pipe_straight",
        [-1.2, 0.2, 0.0],
        [1.2, 0.2, 0.0],
        0,
        0.1,
    );
    add_pipe(
        &mut s,
        "pipe_riser",
        [0.0, 0.0, 0.6],
        [0.0, 1.6, 0.6],
        1,
        0.1,
    );
    add_bent_pipe(&mut s, [-1.2, 0.15, 1.5], 1.4, 0.4, 1.05, 8);
    add_house(&mut s, [2.5, 0.0, 0.0], [5.5, 2.4, 2.5], 1.0);
    add_torus(&mut s, [7.2, 0.75, 0.5], 0.6, 0.15);
    add_washer(&mut s, [9.3, 0.0, 0.5], 0.25, 0.5, 0.1);
    s
}

/// The built-in demo scene, made in code: a staircase, a table, three pipes (one bent
/// by an elbow), a gable-roof house, a torus and a washer, laid out along +x in
/// meters with +y up; 1,829 polygons (quads and n-gon caps kept whole), each object
/// named ([`Mesh::objects`]). The same mesh as `datasets/demo_scene.obj`.
///
/// ```
/// let scene = primdecomp::demo_scene();
/// assert_eq!(scene.face_count(), 1829);
/// assert_eq!(scene.objects()[0].0, "stairs_step_0");
/// ```
pub fn demo_scene() -> Mesh {
    let s = build();
    let mut b = MeshBuilder::new();
    b.positions = s.positions;
    for o in &s.objects {
        b.start_object(o.name.clone());
        for f in &o.faces {
            b.push_face(f);
        }
    }
    Mesh::from_builder(b)
}

/// The demo scene ([`demo_scene`]) as OBJ text: each object's new vertices follow its
/// `o` line, then its faces (1-based, global indices). This is
/// `datasets/demo_scene.obj` (the tests check it and regenerate it).
#[cfg(test)]
fn demo_scene_obj() -> String {
    use std::fmt::Write;
    let s = build();
    let faces: usize = s.objects.iter().map(|o| o.faces.len()).sum();
    let mut out = String::new();
    out.push_str(
        "# primdecomp demo scene: staircase, table, pipes, gable-roof house, torus, washer.\n",
    );
    out.push_str(
        "# Generated by crates/primdecomp/src/input/demo.rs, whose test committed_file_is_current\n",
    );
    out.push_str("# checks it; do not edit by hand. Regenerate with\n");
    out.push_str(
        "#   cargo test -p primdecomp --lib input::demo::tests::regenerate_demo_scene_obj -- --ignored\n",
    );
    let _ = writeln!(
        out,
        "# Meters, +y up. {} vertices, {faces} faces, {} objects.",
        s.positions.len(),
        s.objects.len()
    );
    for (k, o) in s.objects.iter().enumerate() {
        let _ = writeln!(out, "o {}", o.name);
        let end = s
            .objects
            .get(k + 1)
            .map_or(s.positions.len(), |n| n.first_vertex);
        for p in &s.positions[o.first_vertex..end] {
            let _ = writeln!(out, "v {} {} {}", p[0], p[1], p[2]);
        }
        for f in &o.faces {
            out.push('f');
            for &i in f {
                let _ = write!(out, " {}", i + 1);
            }
            out.push('\n');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{cross, dot, norm, normalize, sub};

    const COMMITTED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");

    #[test]
    fn committed_file_is_current() {
        let committed = std::fs::read_to_string(COMMITTED).expect("datasets/demo_scene.obj");
        assert!(
            committed == demo_scene_obj(),
            "datasets/demo_scene.obj is stale; regenerate it (see its header)"
        );
    }

    /// Writes `datasets/demo_scene.obj` (run with `--ignored`).
    #[test]
    #[ignore]
    fn regenerate_demo_scene_obj() {
        std::fs::write(COMMITTED, demo_scene_obj()).unwrap();
    }

    #[test]
    fn every_object_is_closed_and_outward() {
        let s = build();
        assert!(s.objects.len() >= 6);
        for o in &s.objects {
            // Each directed edge once and its reverse once: every edge is shared by
            // exactly two faces of the object, wound consistently.
            let mut directed: Vec<(u32, u32)> = Vec::new();
            for f in &o.faces {
                let mut distinct = f.clone();
                distinct.sort_unstable();
                distinct.dedup();
                assert!(
                    f.len() >= 3 && distinct.len() == f.len(),
                    "{}: bad face {f:?}",
                    o.name
                );
                directed.extend((0..f.len()).map(|j| (f[j], f[(j + 1) % f.len()])));
            }
            directed.sort_unstable();
            assert!(
                directed.windows(2).all(|w| w[0] != w[1]),
                "{}: edge used twice",
                o.name
            );
            for &(a, b) in &directed {
                assert!(
                    directed.binary_search(&(b, a)).is_ok(),
                    "{}: open edge",
                    o.name
                );
            }
            let vol: f64 = o.faces.iter().map(|f| signed_volume(&s.positions, f)).sum();
            assert!(vol > 1e-4, "{}: volume {vol}", o.name);
        }
    }

    /// Signed volume of the cone from the origin over polygon `f`.
    fn signed_volume(pos: &[V3], f: &[u32]) -> f64 {
        let p0 = pos[f[0] as usize];
        (1..f.len() - 1)
            .map(|j| dot(p0, cross(pos[f[j] as usize], pos[f[j + 1] as usize])) / 6.0)
            .sum()
    }

    #[test]
    fn faces_are_planar() {
        let s = build();
        for o in &s.objects {
            for f in &o.faces {
                let p: Vec<V3> = f.iter().map(|&i| s.positions[i as usize]).collect();
                let n =
                    (0..p.len()).fold([0.0; 3], |n, j| add(n, cross(p[j], p[(j + 1) % p.len()])));
                let n = normalize(n).expect("face with area");
                for q in &p {
                    assert!(
                        dot(n, sub(*q, p[0])).abs() < 2e-6,
                        "{}: non-planar face",
                        o.name
                    );
                }
            }
        }
    }

    #[test]
    fn size_and_consistency() {
        let mesh = demo_scene();
        let faces = mesh.face_count();
        assert!((1000..=5000).contains(&faces), "{faces} faces");
        assert_eq!(mesh.skipped, Default::default());
        let s = build();
        let b = (
            s.positions,
            s.objects
                .iter()
                .flat_map(|o| o.faces.concat())
                .collect::<Vec<u32>>(),
        );
        let text = demo_scene_obj();
        assert!(text.len() < 200_000, "{} bytes", text.len());
        // The OBJ text describes exactly the builder's mesh.
        let mut pos: Vec<V3> = Vec::new();
        let mut idx: Vec<u32> = Vec::new();
        for line in text.lines() {
            let mut it = line.split_whitespace();
            match it.next() {
                Some("v") => pos.push(std::array::from_fn(|_| it.next().unwrap().parse().unwrap())),
                Some("f") => idx.extend(it.map(|t| t.parse::<u32>().unwrap() - 1)),
                _ => {}
            }
        }
        assert_eq!(pos, b.0);
        assert_eq!(idx, b.1);
        assert!(pos.iter().all(|p| p[1] >= 0.0 && norm(*p) < 20.0));
    }
}
