//! Memory limit (docs/decisions/limits-memory-estimate.md): an input whose decomposition would need more memory
//! than allowed is refused up front with [`Error::TooLarge`], instead of being killed by
//! the operating system halfway through a batch.
//!
//! The need is a linear model of the input's vertex, face and corner counts, fitted on
//! the peak resident memory of CLI runs (see [`estimate`]). The counts come from the
//! file before parsing (`mesh::io::declared_counts`: header counts for PLY, OFF and
//! binary STL, a byte scan for OBJ and ASCII STL, each capped by what the file's size
//! could hold) and again, exactly, from the parsed mesh (which also covers glTF, whose
//! counts live in its JSON). The parsers themselves cap every reservation by the file
//! size.

use crate::error::{Error, Result};
use std::path::Path;

/// Vertex, face and corner (index) counts of an input.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Counts {
    pub vertices: u64,
    pub faces: u64,
    pub corners: u64,
}

/// Fixed cost of a run (binary, thread stacks, allocator arenas), bytes.
const BASE: u64 = 32 << 20;
/// Bytes per vertex, face and corner. Fitted on the peak resident memory of the
/// default run (the merge-tree cut within 2%, docs/decisions/0037),
/// `primdecomp decompose FILE --max-memory none` under `/usr/bin/time -f %M` (KiB):
/// lucy_100k.obj (99,970 faces) 66.0 MiB, dragon_vrip_res2.ply (202,520 faces)
/// 121.9 MiB, dragon_vrip_full.ply (871,414 faces) 496.2 MiB, i.e. about 9 MB + 590 bytes
/// per triangle (a count's greedy run, `-n 1%`, needs about half). Three triangle
/// meshes cannot separate the three rates; the split below gives 620 bytes a triangle
/// (½ vertex + 1 face + 3 corners) and charges polygons by their corners.
const PER_VERTEX: u64 = 200;
const PER_FACE: u64 = 280;
const PER_CORNER: u64 = 80;

/// Peak bytes a run on an input of these counts is expected to need: the fitted model
/// above plus 25% for what it does not capture (more targets, more threads).
pub(crate) fn estimate(c: Counts) -> u64 {
    let linear = BASE
        .saturating_add(PER_VERTEX.saturating_mul(c.vertices))
        .saturating_add(PER_FACE.saturating_mul(c.faces))
        .saturating_add(PER_CORNER.saturating_mul(c.corners));
    linear.saturating_add(linear / 4)
}

/// Refuses `counts` when their estimate exceeds `limit` bytes.
pub(crate) fn check(path: &Path, counts: Counts, limit: u64) -> Result<()> {
    let needed = estimate(counts);
    if needed <= limit {
        return Ok(());
    }
    Err(Error::TooLarge {
        path: path.to_path_buf(),
        faces: counts.faces,
        vertices: counts.vertices,
        needed,
        limit,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_refuses_above_the_limit() {
        let c = Counts {
            vertices: 1000,
            faces: 2000,
            corners: 6000,
        };
        assert!(check(Path::new("m.obj"), c, estimate(c)).is_ok());
        let e = check(Path::new("m.obj"), c, estimate(c) - 1).unwrap_err();
        assert!(matches!(e, Error::TooLarge { faces: 2000, .. }), "{e}");
        assert_eq!(e.exit_code(), 2);
    }
}
