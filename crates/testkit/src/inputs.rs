//! Made-up input files for the checks that run outside Rust (`scripts/test.sh`: the
//! export consumers, the browser, the Python package), written at test time so that a
//! clone without `../shared` runs every consumer for real; the corpus adds breadth
//! where present. `primdecomp-testkit inputs DIR` writes them all:
//!
//! | file | what | why |
//! |---|---|---|
//! | `demo_scene.obj` | the built-in demo scene | the README's run |
//! | `kinds.obj` | six separate parts, one per primitive kind | every kind in every format |
//! | `wedges.off` | two scalene triangles | a skewed prism (docs/decisions/0045) |
//! | `robot.stl` | a z-up arm on a base, binary STL, seven parts | a z-up input, multi-part |
//! | `cabinet.obj` | an open cabinet holding 60 items, knobs and feet outside | a count on many parts inside one box |
//! | `nodes.glb` | five named mesh nodes under a turned, moved parent | per-object frames |
//! | `groups.obj` | three named `g` groups | per-object names |
//! | `lumpy.ply` | a bumpy sphere of 81,920 triangles, binary PLY | a run long enough to interrupt |

use crate::shapes::{cuboid, cylinder, icosphere, join, obj_text, Polys};
use std::f64::consts::PI;
use std::path::Path;

/// Writes every made-up input into `dir` (created if missing); returns the file names.
pub fn write_all(dir: &Path) -> std::io::Result<Vec<&'static str>> {
    std::fs::create_dir_all(dir)?;
    let files: [(&str, Vec<u8>); 8] = [
        ("demo_scene.obj", crate::DEMO_SCENE_OBJ.as_bytes().to_vec()),
        ("kinds.obj", obj_text(&kinds()).into_bytes()),
        ("wedges.off", off_text(&wedges()).into_bytes()),
        ("robot.stl", stl_binary(&robot())),
        ("cabinet.obj", obj_text(&cabinet()).into_bytes()),
        ("nodes.glb", nodes_glb()),
        ("groups.obj", groups_obj().into_bytes()),
        ("lumpy.ply", ply_binary(&lumpy())),
    ];
    let mut names = Vec::new();
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes)?;
        names.push(name);
    }
    Ok(names)
}

/// `p` moved by `t`.
pub fn moved((v, f): Polys, t: [f64; 3]) -> Polys {
    (
        v.into_iter()
            .map(|p| [p[0] + t[0], p[1] + t[1], p[2] + t[2]])
            .collect(),
        f,
    )
}

/// `p` with its coordinates permuted: local z becomes axis `axis` (0 = x, 1 = y),
/// keeping the frame right-handed.
fn along((v, f): Polys, axis: usize) -> Polys {
    let turn = |p: [f64; 3]| match axis {
        0 => [p[2], p[0], p[1]],
        1 => [p[1], p[2], p[0]],
        _ => p,
    };
    (v.into_iter().map(turn).collect(), f)
}

/// Truncated cone along z from radius `r0` at z = 0 to `r1` at z = `h`.
pub fn frustum(r0: f64, r1: f64, h: f64, n: usize) -> Polys {
    let (mut v, f) = cylinder(1.0, h, n);
    for p in &mut v {
        let r = if p[2] == 0.0 { r0 } else { r1 };
        p[0] *= r;
        p[1] *= r;
    }
    (v, f)
}

/// Capsule along z: a cylinder of radius `r` from z = 0 to `len` capped by half
/// spheres (`rings` latitude bands each, `segs` around).
pub fn capsule(r: f64, len: f64, rings: usize, segs: usize) -> Polys {
    let mut v = vec![[0.0, 0.0, -r]];
    // Rings from the bottom pole to the top pole; the two equators bound the body.
    let mut zs = Vec::new();
    for k in 1..=rings {
        let a = -PI / 2.0 + PI / 2.0 * k as f64 / rings as f64;
        zs.push((r * a.cos(), r * a.sin()));
    }
    for k in 0..rings {
        let a = PI / 2.0 * k as f64 / rings as f64;
        zs.push((r * a.cos(), len + r * a.sin()));
    }
    for &(rr, z) in &zs {
        for s in 0..segs {
            let t = 2.0 * PI * s as f64 / segs as f64;
            v.push([rr * t.cos(), rr * t.sin(), z]);
        }
    }
    v.push([0.0, 0.0, len + r]);
    let top = (v.len() - 1) as u32;
    let idx = |ring: usize, s: usize| (1 + ring * segs + s % segs) as u32;
    let mut f = Vec::new();
    for s in 0..segs {
        f.push(vec![0, idx(0, s + 1), idx(0, s)]);
        f.push(vec![top, idx(zs.len() - 1, s), idx(zs.len() - 1, s + 1)]);
    }
    for ring in 0..zs.len() - 1 {
        for s in 0..segs {
            f.push(vec![
                idx(ring, s),
                idx(ring, s + 1),
                idx(ring + 1, s + 1),
                idx(ring + 1, s),
            ]);
        }
    }
    (v, f)
}

/// A prism along x (length `2 hx`) whose y–z section is a trapezoid: `bottom` wide at
/// z = 0, `top` wide at z = `h`.
pub fn trapezoid_prism(hx: f64, bottom: f64, top: f64, h: f64) -> Polys {
    let sec = [
        [-bottom / 2.0, 0.0],
        [bottom / 2.0, 0.0],
        [top / 2.0, h],
        [-top / 2.0, h],
    ];
    let v: Vec<[f64; 3]> = [-hx, hx]
        .iter()
        .flat_map(|&x| sec.iter().map(move |s| [x, s[0], s[1]]))
        .collect();
    let f = vec![
        vec![0, 3, 2, 1],
        vec![4, 5, 6, 7],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 6],
        vec![3, 0, 4, 7],
    ];
    (v, f)
}

/// Six separate parts, one per kind, in a row along x: each is best held by its own
/// kind, so a run at `-n 6` has all six.
pub fn kinds() -> Polys {
    join(&[
        cuboid([0.0, 0.0, 0.0], [1.0, 0.6, 0.8]),
        moved(icosphere(0.5, 3), [2.0, 0.5, 0.5]),
        moved(along(capsule(0.3, 1.2, 6, 20), 1), [3.5, 0.3, 0.5]),
        moved(along(cylinder(0.45, 1.0, 32), 1), [5.0, 0.0, 0.5]),
        moved(along(frustum(0.55, 0.12, 1.1, 32), 1), [6.6, 0.0, 0.5]),
        moved(trapezoid_prism(0.5, 1.0, 0.15, 0.9), [8.2, 0.5, 0.0]),
    ])
}

/// Two scalene triangles sharing an edge, bent out of their plane.
fn wedges() -> Polys {
    (
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [2.0, 1.0, 0.0],
        ],
        vec![vec![0, 1, 2], vec![1, 3, 2]],
    )
}

/// A z-up robot arm: a round base, a turret box, two links, a wrist cylinder and a
/// gripper of two fingers; seven separate closed parts.
fn robot() -> Polys {
    join(&[
        cylinder(0.5, 0.2, 40),
        cuboid([-0.25, -0.25, 0.2], [0.25, 0.25, 0.5]),
        cuboid([-0.1, -0.1, 0.5], [0.1, 0.1, 1.4]),
        moved(along(cylinder(0.12, 0.8, 24), 0), [0.0, 0.0, 1.5]),
        cuboid([0.8, -0.08, 1.3], [1.0, 0.08, 1.75]),
        cuboid([0.85, -0.09, 1.05], [0.9, -0.03, 1.3]),
        cuboid([0.85, 0.03, 1.05], [0.9, 0.09, 1.3]),
    ])
}

/// A cabinet open at the front (walls, back, shelves) holding 60 small items on its
/// shelves, with four knobs and two feet outside: 73 separate parts, most of them
/// inside its bounding box.
fn cabinet() -> Polys {
    let mut parts = vec![
        cuboid([0.0, 0.0, 0.0], [0.05, 2.0, 1.0]),
        cuboid([1.95, 0.0, 0.0], [2.0, 2.0, 1.0]),
        cuboid([0.05, 0.0, 0.0], [1.95, 0.05, 1.0]),
        cuboid([0.05, 1.95, 0.0], [1.95, 2.0, 1.0]),
        cuboid([0.05, 0.05, 0.0], [1.95, 1.95, 0.05]),
        cuboid([0.05, 0.65, 0.05], [1.95, 0.68, 0.95]),
        cuboid([0.05, 1.3, 0.05], [1.95, 1.33, 0.95]),
    ];
    // Items on the three shelves: boxes, jars and balls of varied sizes.
    for k in 0..60u32 {
        let shelf = [0.05, 0.68, 1.33][(k / 20) as usize];
        let (i, j) = (k % 10, (k / 10) % 2);
        let x = 0.15 + 0.18 * f64::from(i);
        let z = 0.25 + 0.45 * f64::from(j);
        let s = 0.04 + 0.012 * f64::from((k * 7) % 5);
        let part = match k % 3 {
            0 => cuboid([x - s, shelf, z - s], [x + s, shelf + 2.0 * s, z + s]),
            1 => moved(along(cylinder(s, 3.0 * s, 16), 1), [x, shelf, z]),
            _ => moved(icosphere(s, 1), [x, shelf + s, z]),
        };
        parts.push(part);
    }
    // Four knobs on the top.
    for x in [0.4, 1.6] {
        parts.push(cuboid([x - 0.1, 2.0, 0.2], [x + 0.1, 2.06, 0.3]));
        parts.push(cuboid([x - 0.1, 2.0, 0.7], [x + 0.1, 2.06, 0.8]));
    }
    // Two feet under the floor.
    parts.push(cuboid([0.1, -0.1, 0.1], [0.3, 0.0, 0.9]));
    parts.push(cuboid([1.7, -0.1, 0.1], [1.9, 0.0, 0.9]));
    join(&parts)
}

/// Three named groups: a table (top and four legs), a lamp, a stack of books.
fn groups_obj() -> String {
    let table = join(&[
        cuboid([0.0, 0.7, 0.0], [1.6, 0.75, 0.8]),
        cuboid([0.05, 0.0, 0.05], [0.1, 0.7, 0.1]),
        cuboid([1.5, 0.0, 0.05], [1.55, 0.7, 0.1]),
        cuboid([0.05, 0.0, 0.7], [0.1, 0.7, 0.75]),
        cuboid([1.5, 0.0, 0.7], [1.55, 0.7, 0.75]),
    ]);
    let lamp = join(&[
        moved(along(cylinder(0.02, 0.45, 12), 1), [1.3, 0.75, 0.4]),
        moved(along(frustum(0.16, 0.08, 0.18, 24), 1), [1.3, 1.15, 0.4]),
    ]);
    let books = join(&[
        cuboid([0.2, 0.75, 0.2], [0.5, 0.8, 0.6]),
        cuboid([0.22, 0.8, 0.25], [0.48, 0.86, 0.55]),
        cuboid([0.25, 0.86, 0.22], [0.45, 0.9, 0.58]),
    ]);
    let mut out = String::new();
    let mut base = 0;
    for (name, p) in [("table", &table), ("lamp", &lamp), ("books", &books)] {
        out += &format!("g {name}\n");
        for q in &p.0 {
            out += &format!("v {} {} {}\n", q[0], q[1], q[2]);
        }
        for face in &p.1 {
            let ids: Vec<String> = face.iter().map(|i| (i + base + 1).to_string()).collect();
            out += &format!("f {}\n", ids.join(" "));
        }
        base += p.0.len() as u32;
    }
    out
}

/// A binary glTF 2.0 scene of five named mesh nodes (a base box, a column, a ball
/// scaled by its node, an arm turned by its node and a lamp) under a parent node that
/// is moved and turned; +Y up as glTF says.
fn nodes_glb() -> Vec<u8> {
    let meshes: [(&str, Polys); 5] = [
        ("base", cuboid([-0.6, 0.0, -0.4], [0.6, 0.2, 0.4])),
        ("column", along(cylinder(0.12, 1.0, 24), 1)),
        ("ball", icosphere(1.0, 2)),
        ("arm", along(capsule(0.08, 0.7, 4, 16), 0)),
        ("lamp", along(frustum(0.2, 0.05, 0.25, 24), 1)),
    ];
    // Node transforms (translation, rotation xyzw, uniform scale) of each mesh node.
    let half = (PI / 8.0).sin();
    let nodes: [([f64; 3], [f64; 4], f64); 5] = [
        ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], 1.0),
        ([0.0, 0.2, 0.0], [0.0, 0.0, 0.0, 1.0], 1.0),
        ([0.0, 1.35, 0.0], [0.0, 0.0, 0.0, 1.0], 0.15),
        ([0.1, 1.1, 0.0], [0.0, 0.0, half, (PI / 8.0).cos()], 1.0),
        ([0.85, 1.3, 0.0], [0.0, 0.0, 0.0, 1.0], 1.0),
    ];
    let mut buf: Vec<u8> = Vec::new();
    let (mut views, mut accessors, mut gl_meshes, mut gl_nodes) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (k, (name, mesh)) in meshes.iter().enumerate() {
        let v = &mesh.0;
        let (pos_at, idx_at) = (buf.len(), buf.len() + 12 * v.len());
        let (tris, [lo, hi]) = append_mesh(&mut buf, mesh);
        views.push(serde_json::json!({"buffer": 0, "byteOffset": pos_at, "byteLength": 12 * v.len(), "target": 34962}));
        views.push(serde_json::json!({"buffer": 0, "byteOffset": idx_at, "byteLength": 4 * tris, "target": 34963}));
        accessors.push(serde_json::json!({"bufferView": 2 * k, "componentType": 5126, "count": v.len(), "type": "VEC3", "min": lo, "max": hi}));
        accessors.push(serde_json::json!({"bufferView": 2 * k + 1, "componentType": 5125, "count": tris, "type": "SCALAR"}));
        gl_meshes.push(serde_json::json!({"name": name, "primitives": [{"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1}]}));
        let (t, r, s) = nodes[k];
        gl_nodes.push(serde_json::json!({"name": name, "mesh": k, "translation": t, "rotation": r, "scale": [s, s, s]}));
    }
    let turn = (PI / 12.0).sin();
    gl_nodes.push(serde_json::json!({
        "name": "stand", "children": [0, 1, 2, 3, 4],
        "translation": [2.0, 0.0, -1.0], "rotation": [0.0, turn, 0.0, (PI / 12.0).cos()],
    }));
    let doc = serde_json::json!({
        "asset": {"version": "2.0", "generator": "primdecomp-testkit inputs"},
        "scene": 0,
        "scenes": [{"nodes": [5]}],
        "nodes": gl_nodes,
        "meshes": gl_meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": buf.len()}],
    });
    glb(&serde_json::to_string(&doc).expect("plain data"), buf)
}

/// Appends a mesh's positions (f32) and then its polygons fanned into triangles (u32
/// indices) to `buf`; returns the number of indices and the positions' bounds.
fn append_mesh(buf: &mut Vec<u8>, (v, f): &Polys) -> (usize, [[f32; 3]; 2]) {
    let tris: Vec<u32> = f
        .iter()
        .flat_map(|p| (1..p.len() - 1).flat_map(move |i| [p[0], p[i], p[i + 1]]))
        .collect();
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in v {
        for (d, &x) in p.iter().enumerate() {
            let x = x as f32;
            buf.extend(x.to_le_bytes());
            lo[d] = lo[d].min(x);
            hi[d] = hi[d].max(x);
        }
    }
    for i in &tris {
        buf.extend(i.to_le_bytes());
    }
    (tris.len(), [lo, hi])
}

/// A GLB file: the 12-byte header, the JSON chunk (padded with spaces) and the binary
/// chunk (padded with zeros), each 4-byte aligned as the specification asks.
fn glb(json: &str, mut bin: Vec<u8>) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    bin.resize(bin.len().div_ceil(4) * 4, 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    for (kind, chunk) in [(*b"JSON", json), (*b"BIN\0", bin)] {
        out.extend((chunk.len() as u32).to_le_bytes());
        out.extend(kind);
        out.extend(chunk);
    }
    out
}

/// A sphere of radius about 1 with smooth bumps, 81,920 triangles.
fn lumpy() -> Polys {
    let (mut v, f) = icosphere(1.0, 6);
    for p in &mut v {
        let bump = 1.0 + 0.08 * (3.0 * p[0]).sin() * (4.0 * p[1]).sin() * (5.0 * p[2]).sin();
        *p = p.map(|x| x * bump);
    }
    (v, f)
}

/// OFF text of polygons.
fn off_text((v, f): &Polys) -> String {
    let mut t = format!("OFF\n{} {} 0\n", v.len(), f.len());
    for p in v {
        t += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for face in f {
        let ids: Vec<String> = face.iter().map(u32::to_string).collect();
        t += &format!("{} {}\n", face.len(), ids.join(" "));
    }
    t
}

/// Binary STL of the polygons, fanned into triangles (normals left zero, as readers
/// recompute them).
fn stl_binary((v, f): &Polys) -> Vec<u8> {
    let tris: Vec<[u32; 3]> = f
        .iter()
        .flat_map(|p| (1..p.len() - 1).map(move |i| [p[0], p[i], p[i + 1]]))
        .collect();
    let mut out = vec![0u8; 80];
    out[..31].copy_from_slice(b"primdecomp-testkit made-up STL ");
    out.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        out.extend([0u8; 12]);
        for i in t {
            for x in v[i as usize] {
                out.extend((x as f32).to_le_bytes());
            }
        }
        out.extend([0u8; 2]);
    }
    out
}

/// Binary little-endian PLY of the polygons (float positions, uchar/int faces).
fn ply_binary((v, f): &Polys) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment primdecomp-testkit made-up\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        v.len(),
        f.len()
    )
    .into_bytes();
    for p in v {
        for x in p {
            out.extend((*x as f32).to_le_bytes());
        }
    }
    for face in f {
        out.push(face.len() as u8);
        for i in face {
            out.extend((*i as i32).to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_input_loads_with_its_faces() {
        let dir = std::env::temp_dir().join(format!("primdecomp-inputs-{}", std::process::id()));
        let names = write_all(&dir).unwrap();
        for name in names {
            let m = primdecomp::Mesh::load(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
            assert!(m.face_count() > 0, "{name}");
        }
        let glb = primdecomp::Mesh::load(&dir.join("nodes.glb")).unwrap();
        assert_eq!(glb.objects().len(), 5);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
