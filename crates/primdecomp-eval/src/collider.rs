//! Colliders to evaluate or simulate: our primitives (a primdecomp JSON document,
//! read by [`primdecomp::ResultFile::read`]) or convex hulls in an OBJ file, one
//! hull per `o` object or `g` group, as CoACD and V-HACD write them.
//!
//! The OBJ reader follows the mesh reader's rules (global 1-based or negative
//! relative vertex indices, `v/vt/vn` corners, comments, `\` continuations, any line
//! ending) and fan-triangulates polygons. Faces before the first `o`/`g` form a hull
//! of their own; objects or groups without faces are dropped. Each hull keeps only
//! the vertices its faces use, in f64 world coordinates.

use primdecomp::Error;
use primdecomp::{Kind, Primitive};
use primdecomp_math::V3;
use std::collections::HashMap;
use std::path::Path;

/// Results with the library's one error type.
type Result<T> = std::result::Result<T, Error>;

/// One convex hull as a triangle mesh: `triangles` index `positions`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Hull {
    pub positions: Vec<V3>,
    pub triangles: Vec<[u32; 3]>,
}

impl Hull {
    /// Paper Table 2: 3 floats per vertex and 3 uint16 per triangle, 4 bytes a float.
    pub fn bytes(&self) -> usize {
        12 * self.positions.len() + 6 * self.triangles.len()
    }
}

/// A collider: primitives or convex hulls.
#[derive(Clone, Debug, PartialEq)]
pub enum Collider {
    Primitives(Vec<Primitive>),
    Hulls(Vec<Hull>),
}

impl Collider {
    /// Storage by the paper's Table 2 (4 bytes per float, 2 per triangle index).
    pub fn bytes(&self) -> usize {
        match self {
            Collider::Primitives(p) => p.iter().map(|p| p.bytes()).sum(),
            Collider::Hulls(h) => h.iter().map(Hull::bytes).sum(),
        }
    }
    /// Number of parts (primitives or hulls).
    pub fn len(&self) -> usize {
        match self {
            Collider::Primitives(p) => p.len(),
            Collider::Hulls(h) => h.len(),
        }
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Parts by kind: the six primitive kinds in [`Kind::ALL`] order, then `hull`.
    pub fn counts(&self) -> Vec<(&'static str, usize)> {
        let mut out: Vec<(&'static str, usize)> = Kind::ALL.iter().map(|k| (k.name(), 0)).collect();
        let hulls = match self {
            Collider::Primitives(ps) => {
                for p in ps {
                    out[p.kind() as usize].1 += 1;
                }
                0
            }
            Collider::Hulls(h) => h.len(),
        };
        out.push(("hull", hulls));
        out
    }
}

/// Loads a collider: `.json` is a primdecomp document, `.obj` convex hulls. Like a
/// mesh it must be a regular file ([`primdecomp_files::read_regular`]: a named pipe or
/// device is refused before reading), of at most
/// [`primdecomp::ResultFile::MAX_BYTES`].
pub fn load(path: &Path) -> Result<Collider> {
    let bytes = primdecomp_files::read_regular(path, primdecomp::ResultFile::MAX_BYTES)?;
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("json") => parse_json(&bytes, path),
        Some("obj") => parse_hulls_obj(&bytes, path).map(Collider::Hulls),
        _ => Err(Error::format(
            path,
            "unknown collider extension: expected .json (primdecomp) or .obj (convex hulls)",
        )),
    }
}

/// A primdecomp JSON document's primitives.
pub fn parse_json(bytes: &[u8], path: &Path) -> Result<Collider> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        Error::byte(
            path,
            e.valid_up_to() as u64,
            "the JSON document is not UTF-8",
        )
    })?;
    let prims = primdecomp::ResultFile::read(text, path)?.primitives;
    if prims.is_empty() {
        return Err(Error::format(path, "the document has no primitives"));
    }
    Ok(Collider::Primitives(prims))
}

/// Convex hulls from an OBJ file, one per `o`/`g` with faces: the core's OBJ reader
/// with its objects ([`primdecomp::Mesh::objects`]), each fan-triangulated on the
/// vertices its faces use.
pub fn parse_hulls_obj(bytes: &[u8], path: &Path) -> Result<Vec<Hull>> {
    let mesh = primdecomp::Mesh::parse(bytes, primdecomp::MeshFormat::Obj, path)?;
    let mut hulls = Vec::new();
    for (_, faces) in mesh.objects() {
        let mut local: HashMap<u32, u32> = HashMap::new();
        let mut hull = Hull::default();
        for f in faces {
            let mut ids = mesh.face(f).iter().map(|&c| {
                let next = hull.positions.len() as u32;
                let l = *local.entry(c).or_insert(next);
                if l == next {
                    hull.positions.push(mesh.world_pos(c));
                }
                l
            });
            let first = ids.next().expect("faces have 3 or more corners");
            let mut prev = ids.next().expect("faces have 3 or more corners");
            // Fan triangulation around the first corner.
            for c in ids {
                hull.triangles.push([first, prev, c]);
                prev = c;
            }
        }
        if !hull.triangles.is_empty() {
            hulls.push(hull);
        }
    }
    if hulls.is_empty() {
        return Err(Error::format(
            path,
            "no hull has a face (expected `f` statements with 3 or more corners)",
        ));
    }
    Ok(hulls)
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::Sphere;

    fn hulls(s: &str) -> Result<Vec<Hull>> {
        parse_hulls_obj(s.as_bytes(), Path::new("h.obj"))
    }

    const CUBE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
    const CUBE_FACES: &str = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

    #[test]
    fn one_object_per_hull_with_global_indices() {
        let text = format!("o a\n{CUBE}{CUBE_FACES}o b\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf 9 10 11\n");
        let h = hulls(&text).unwrap();
        assert_eq!(h.len(), 2);
        assert_eq!(h[0].positions.len(), 8);
        assert_eq!(h[0].triangles.len(), 12, "6 quads fan into 12 triangles");
        assert_eq!(
            h[1].positions,
            vec![[5.0, 5.0, 5.0], [6.0, 5.0, 5.0], [5.0, 6.0, 5.0]]
        );
        assert_eq!(h[1].triangles, vec![[0, 1, 2]]);
        // Table 2: 8·12 + 12·6 bytes and 3·12 + 6 bytes.
        assert_eq!(Collider::Hulls(h).bytes(), 8 * 12 + 12 * 6 + 3 * 12 + 6);
    }

    #[test]
    fn negative_indices_groups_and_fans() {
        let s = "g one\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4/1/1 -3//2 -2 -1\n\
                 g two\nv 0 0 2\nv 1 0 2\nv 0 1 2\nf -3 -2 -1\ng empty\n";
        let h = hulls(s).unwrap();
        assert_eq!(h.len(), 2, "the empty group is dropped");
        assert_eq!(h[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(h[1].positions[0], [0.0, 0.0, 2.0]);
    }

    #[test]
    fn faces_before_any_object_form_a_hull() {
        let s = format!("{CUBE}{CUBE_FACES}");
        let h = hulls(&s).unwrap();
        assert_eq!(h.len(), 1);
        assert_eq!(h[0].triangles.len(), 12);
        let o_then_g = format!("o x\ng y\n{CUBE}{CUBE_FACES}");
        assert_eq!(
            hulls(&o_then_g).unwrap(),
            h,
            "an empty `o` before `g` adds nothing"
        );
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = hulls("o a\nv 0 0 0\nv 1 0 0\nf 1 2 3\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("h.obj:4:") && e.contains("out of range"),
            "{e}"
        );
        let e = hulls("v 0 0\n").unwrap_err().to_string();
        assert!(
            e.starts_with("h.obj:1:") && e.contains("2 coordinates"),
            "{e}"
        );
        let e = hulls("v 0 nan 0\n").unwrap_err().to_string();
        assert!(e.contains("not finite"), "{e}");
        let e = hulls("o a\nv 0 0 0\n").unwrap_err().to_string();
        assert!(e.contains("no hull has a face"), "{e}");
        let e = hulls("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n 0\n")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("h.obj:4:") && e.contains("index 0"), "{e}");
    }

    #[test]
    fn json_primitives_and_counts() {
        let ok = br#"{"format":"primdecomp","version":1,
            "primitives":[{"kind":"sphere","center":[1,2,3],"radius":0.5}]}"#;
        let c = parse_json(ok, Path::new("c.json")).unwrap();
        let want = Primitive::Sphere(Sphere {
            center: [1.0, 2.0, 3.0],
            radius: 0.5,
        });
        assert_eq!(c, Collider::Primitives(vec![want]));
        assert_eq!(c.bytes(), 16);
        assert_eq!(c.counts()[1], ("sphere", 1));
        assert_eq!(c.counts()[6], ("hull", 0));
        let e = parse_json(
            b"{\"format\":\"primdecomp\",\"version\":1,\"primitives\": [\n{\"kind\":\"cone\"}]}",
            Path::new("c.json"),
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("c.json:") && e.contains("line 2"), "{e}");
        let e = parse_json(
            br#"{"format":"primdecomp","version":1,"primitives":[]}"#,
            Path::new("c.json"),
        )
        .unwrap_err();
        assert!(e.to_string().contains("no primitives"), "{e}");
    }

    #[test]
    fn load_by_extension() {
        let dir = std::env::temp_dir().join(format!("collider-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let obj = dir.join("c.OBJ");
        std::fs::write(&obj, format!("o c\n{CUBE}{CUBE_FACES}")).unwrap();
        assert!(matches!(load(&obj).unwrap(), Collider::Hulls(h) if h.len() == 1));
        let other = dir.join("c.stl");
        std::fs::write(&other, "x").unwrap();
        assert!(load(&other)
            .unwrap_err()
            .to_string()
            .contains("unknown collider"));
        let missing = dir.join("none.json");
        assert!(matches!(load(&missing), Err(Error::Open { .. })));
        let folder = dir.join("d.json");
        std::fs::create_dir(&folder).unwrap();
        assert!(matches!(load(&folder), Err(Error::NotAFile { .. })));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
