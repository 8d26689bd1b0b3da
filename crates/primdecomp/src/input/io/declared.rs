//! The vertex, face and corner counts an input declares, read before parsing and
//! without allocating, for the memory limit (`crate::input::memory`).

use super::{text, MeshFormat};
use crate::input::memory::Counts;

/// Counts an input claims, read without allocating: `None` for glTF/GLB (its counts
/// live in the JSON; the parsed mesh is checked instead) and for files whose header
/// does not parse (the parser reports those). Each count is capped by the most the
/// file's size could hold, so a lying header gets the parser's precise error.
pub(crate) fn declared_counts(bytes: &[u8], format: MeshFormat) -> Option<Counts> {
    let len = bytes.len() as u64;
    let c = match format {
        MeshFormat::Obj => obj_counts(bytes),
        MeshFormat::Stl => stl_counts(bytes),
        MeshFormat::Ply => {
            let (v, f) = super::ply_declared(bytes)?;
            // Smallest records: 3 one-byte coordinates; a count byte and 3 one-byte indices.
            Counts {
                vertices: v.min(len / 3),
                faces: f.min(len / 4),
                corners: 3 * f.min(len / 4),
            }
        }
        MeshFormat::Off => {
            let (v, f) = super::off_declared(bytes)?;
            // Smallest lines: "0 0 0\n" and "3 0 0 0\n".
            Counts {
                vertices: v.min(len / 6),
                faces: f.min(len / 8),
                corners: 3 * f.min(len / 8),
            }
        }
        MeshFormat::Gltf | MeshFormat::Glb => return None,
    };
    Some(c)
}

/// `v` and `f` statements and the corners of the `f` lines.
fn obj_counts(bytes: &[u8]) -> Counts {
    let mut c = Counts::default();
    for (_, line) in text::Lines::new(bytes) {
        let mut t = text::tokens(line);
        match t.next() {
            Some(b"v") => c.vertices += 1,
            Some(b"f") => {
                c.faces += 1;
                c.corners += t.count() as u64;
            }
            _ => {}
        }
    }
    c
}

/// Binary: the declared count, capped by the file's size; ASCII: `vertex` lines.
fn stl_counts(bytes: &[u8]) -> Counts {
    let head = bytes.get(80..84).and_then(|b| b.first_chunk::<4>());
    let declared = head.map(|b| u64::from(u32::from_le_bytes(*b)));
    let binary = !bytes.trim_ascii_start().starts_with(b"solid")
        || declared.is_some_and(|n| 84 + 50 * n == bytes.len() as u64);
    if binary {
        let tris = declared
            .unwrap_or(0)
            .min((bytes.len() as u64).saturating_sub(84) / 50);
        return Counts {
            vertices: 3 * tris,
            faces: tris,
            corners: 3 * tris,
        };
    }
    let corners = text::Lines::new(bytes)
        .filter(|(_, l)| text::tokens(l).next() == Some(b"vertex"))
        .count() as u64;
    Counts {
        vertices: corners,
        faces: corners / 3,
        corners,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_before_parsing() {
        let obj = b"v 0 0 0\nv 1 0 0\r\nv 0 1 0\nvt 0 0\nf 1 2 3\nf 1/1 2/1 3/1 1\n";
        let want = Counts {
            vertices: 3,
            faces: 2,
            corners: 7,
        };
        assert_eq!(declared_counts(obj, MeshFormat::Obj), Some(want));
        // A PLY header claiming 4e9 vertices in a 200-byte file is capped by the size.
        let ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 7\nproperty list uchar int vertex_indices\nend_header\n";
        let c = declared_counts(ply, MeshFormat::Ply).unwrap();
        assert_eq!((c.vertices, c.faces), (ply.len() as u64 / 3, 7));
        let off = b"OFF\n# c\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let c = declared_counts(off, MeshFormat::Off).unwrap();
        assert_eq!((c.vertices, c.faces, c.corners), (3, 1, 3));
        let mut stl = vec![0u8; 84 + 100];
        stl[80] = 200; // declares 200 triangles, holds 2
        let c = declared_counts(&stl, MeshFormat::Stl).unwrap();
        assert_eq!((c.faces, c.vertices), (2, 6));
        assert_eq!(declared_counts(b"{}", MeshFormat::Gltf), None);
    }
}
