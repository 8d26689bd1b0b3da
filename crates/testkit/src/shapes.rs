//! Small meshes built in code for the engine's tests: each is closed and outward-facing
//! unless its name says otherwise.

#![allow(dead_code)]

use primdecomp::Mesh;
use std::f64::consts::PI;

pub type Polys = (Vec<[f64; 3]>, Vec<Vec<u32>>);

/// `polys` as binary little-endian PLY: float positions, triangles fanned from each
/// polygon as `uchar int` lists (what the scale ladder writes).
pub fn ply_bytes((v, f): &Polys) -> Vec<u8> {
    let tris: Vec<[u32; 3]> = f
        .iter()
        .flat_map(|p| (1..p.len() - 1).map(move |i| [p[0], p[i], p[i + 1]]))
        .collect();
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        v.len(),
        tris.len()
    )
    .into_bytes();
    for p in v {
        for c in p {
            out.extend_from_slice(&(*c as f32).to_le_bytes());
        }
    }
    for t in &tris {
        out.push(3);
        for i in t {
            out.extend_from_slice(&(*i as i32).to_le_bytes());
        }
    }
    out
}

/// Axis-aligned box from `lo` to `hi` as 6 quads.
pub fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Polys {
    let v: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { lo[0] } else { hi[0] },
                if i & 2 == 0 { lo[1] } else { hi[1] },
                if i & 4 == 0 { lo[2] } else { hi[2] },
            ]
        })
        .collect();
    let f = vec![
        vec![0, 2, 3, 1],
        vec![4, 5, 7, 6],
        vec![0, 1, 5, 4],
        vec![2, 6, 7, 3],
        vec![0, 4, 6, 2],
        vec![1, 3, 7, 5],
    ];
    (v, f)
}

/// Concatenates meshes.
pub fn join(parts: &[Polys]) -> Polys {
    let mut v = Vec::new();
    let mut f = Vec::new();
    for (pv, pf) in parts {
        let base = v.len() as u32;
        v.extend_from_slice(pv);
        f.extend(
            pf.iter()
                .map(|face| face.iter().map(|i| i + base).collect::<Vec<u32>>()),
        );
    }
    (v, f)
}

pub fn mesh(p: &Polys) -> Mesh {
    Mesh::from_polygons(&p.0, &p.1).unwrap()
}

/// Closed cylinder along z: `n` side quads and two n-gon caps.
pub fn cylinder(radius: f64, height: f64, n: usize) -> Polys {
    let mut v = Vec::new();
    for z in [0.0, height] {
        for i in 0..n {
            let a = 2.0 * PI * i as f64 / n as f64;
            v.push([radius * a.cos(), radius * a.sin(), z]);
        }
    }
    let n32 = n as u32;
    let mut f: Vec<Vec<u32>> = (0..n32)
        .map(|i| vec![i, (i + 1) % n32, n32 + (i + 1) % n32, n32 + i])
        .collect();
    f.push((0..n32).rev().collect());
    f.push((n32..2 * n32).collect());
    (v, f)
}

/// The twelve corners of an icosahedron: the golden rectangles' corners.
fn icosahedron() -> Vec<[f64; 3]> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .to_vec()
}

/// The icosahedron's twenty faces, wound outward.
const ICOSAHEDRON_FACES: [[u32; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// Icosphere: an icosahedron's faces cut 1-to-4 `subdivisions` times, every vertex
/// pushed out onto the sphere (so its facets lie inside it, none aligned with a UV
/// grid).
pub fn icosphere(radius: f64, subdivisions: usize) -> Polys {
    let (mut v, mut f) = (icosahedron(), ICOSAHEDRON_FACES.to_vec());
    for _ in 0..subdivisions {
        let mut mids = std::collections::HashMap::new();
        let mut mid = |a: u32, b: u32, v: &mut Vec<[f64; 3]>| {
            *mids.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (v[a as usize], v[b as usize]);
                v.push(std::array::from_fn(|i| 0.5 * (p[i] + q[i])));
                (v.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(4 * f.len());
        for [a, b, c] in f {
            let (ab, bc, ca) = (mid(a, b, &mut v), mid(b, c, &mut v), mid(c, a, &mut v));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    let on = |p: [f64; 3]| {
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|x| radius * x / n)
    };
    (
        v.into_iter().map(on).collect(),
        f.into_iter().map(|t| t.to_vec()).collect(),
    )
}

/// UV sphere: `rings` latitude bands, `segs` longitude segments, triangles at the poles.
pub fn uv_sphere(radius: f64, rings: usize, segs: usize) -> Polys {
    let mut v = vec![[0.0, 0.0, radius]];
    for r in 1..rings {
        let t = PI * r as f64 / rings as f64;
        for s in 0..segs {
            let p = 2.0 * PI * s as f64 / segs as f64;
            v.push([
                radius * t.sin() * p.cos(),
                radius * t.sin() * p.sin(),
                radius * t.cos(),
            ]);
        }
    }
    v.push([0.0, 0.0, -radius]);
    let south = (v.len() - 1) as u32;
    let idx = |r: usize, s: usize| (1 + (r - 1) * segs + s % segs) as u32;
    let mut f = Vec::new();
    for s in 0..segs {
        f.push(vec![0, idx(1, s), idx(1, s + 1)]);
        f.push(vec![south, idx(rings - 1, s + 1), idx(rings - 1, s)]);
    }
    for r in 1..rings - 1 {
        for s in 0..segs {
            f.push(vec![
                idx(r, s),
                idx(r + 1, s),
                idx(r + 1, s + 1),
                idx(r, s + 1),
            ]);
        }
    }
    (v, f)
}

/// `n` × `n` unit quads in the plane z = 0 (open, one-sided): every merge of
/// neighbours is coplanar and costs zero.
pub fn flat_grid(n: u32) -> Polys {
    let v: Vec<[f64; 3]> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| [f64::from(i), f64::from(j), 0.0]))
        .collect();
    let at = move |i: u32, j: u32| j * (n + 1) + i;
    let f: Vec<Vec<u32>> = (0..n)
        .flat_map(|j| {
            (0..n).map(move |i| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
        })
        .collect();
    (v, f)
}

/// Gable roof: a triangular prism along x, base width `w` (y), height `h` (z), length `l`.
pub fn gable_roof(l: f64, w: f64, h: f64) -> Polys {
    let v = vec![
        [0.0, -w / 2.0, 0.0],
        [0.0, w / 2.0, 0.0],
        [0.0, 0.0, h],
        [l, -w / 2.0, 0.0],
        [l, w / 2.0, 0.0],
        [l, 0.0, h],
    ];
    let f = vec![
        vec![0, 2, 1],
        vec![3, 4, 5],
        vec![0, 1, 4, 3],
        vec![0, 3, 5, 2],
        vec![1, 2, 5, 4],
    ];
    (v, f)
}

/// Square plate `size`² of thickness `t` in the z = 0 plane, cut into `n`×`n` cells,
/// with the middle `hole`×`hole` cells removed (a square hole through it).
pub fn plate_with_hole(size: f64, t: f64, n: usize, hole: usize) -> Polys {
    let lo = (n - hole) / 2;
    let solid = |i: usize, j: usize| {
        i < n && j < n && !(i >= lo && i < lo + hole && j >= lo && j < lo + hole)
    };
    let mut v = Vec::new();
    let mut f = Vec::new();
    let c = size / n as f64;
    let id = |i: usize, j: usize, k: usize| ((k * (n + 1) + j) * (n + 1) + i) as u32;
    for k in 0..2 {
        for j in 0..=n {
            for i in 0..=n {
                v.push([i as f64 * c, j as f64 * c, k as f64 * t]);
            }
        }
    }
    for j in 0..n {
        for i in 0..n {
            if solid(i, j) {
                cell(&mut f, (i, j), &id, &solid);
            }
        }
    }
    (v, f)
}

/// The faces of the plate's solid cell `(i, j)`: its bottom and top, and its side
/// walls where the neighbour cell is empty. `id(i, j, k)`: the grid corner's vertex.
fn cell(
    f: &mut Vec<Vec<u32>>,
    (i, j): (usize, usize),
    id: &dyn Fn(usize, usize, usize) -> u32,
    solid: &dyn Fn(usize, usize) -> bool,
) {
    f.push(vec![
        id(i, j, 0),
        id(i, j + 1, 0),
        id(i + 1, j + 1, 0),
        id(i + 1, j, 0),
    ]);
    f.push(vec![
        id(i, j, 1),
        id(i + 1, j, 1),
        id(i + 1, j + 1, 1),
        id(i, j + 1, 1),
    ]);
    // Side walls where the neighbour cell is empty.
    if i == 0 || !solid(i - 1, j) {
        f.push(vec![
            id(i, j, 0),
            id(i, j, 1),
            id(i, j + 1, 1),
            id(i, j + 1, 0),
        ]);
    }
    if !solid(i + 1, j) {
        f.push(vec![
            id(i + 1, j, 0),
            id(i + 1, j + 1, 0),
            id(i + 1, j + 1, 1),
            id(i + 1, j, 1),
        ]);
    }
    if j == 0 || !solid(i, j - 1) {
        f.push(vec![
            id(i, j, 0),
            id(i + 1, j, 0),
            id(i + 1, j, 1),
            id(i, j, 1),
        ]);
    }
    if !solid(i, j + 1) {
        f.push(vec![
            id(i, j + 1, 0),
            id(i, j + 1, 1),
            id(i + 1, j + 1, 1),
            id(i + 1, j + 1, 0),
        ]);
    }
}

/// `p` as OBJ text (1-based indices), for tests that run the CLI on generated meshes.
pub fn obj_text((v, f): &Polys) -> String {
    let mut t = String::new();
    for p in v {
        t += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for face in f {
        let ids: Vec<String> = face.iter().map(|i| (i + 1).to_string()).collect();
        t += &format!("f {}\n", ids.join(" "));
    }
    t
}

/// The built-in demo scene ([`primdecomp::demo_scene`]) as world positions and
/// polygons, read back from its OBJ text: the generator prints each coordinate in
/// the shortest form that parses back to the same f64, so these are its exact values.
pub fn demo_polys() -> Polys {
    let (mut v, mut f) = (Vec::new(), Vec::new());
    for line in crate::DEMO_SCENE_OBJ.lines() {
        let mut t = line.split_whitespace();
        match t.next() {
            Some("v") => {
                let c: Vec<f64> = t.map(|x| x.parse().expect("demo coordinate")).collect();
                v.push([c[0], c[1], c[2]]);
            }
            Some("f") => f.push(
                t.map(|x| x.parse::<u32>().expect("demo index") - 1)
                    .collect(),
            ),
            _ => {}
        }
    }
    (v, f)
}
