//! Memory limit (docs/decisions/limits-memory-estimate.md): an input whose decomposition would need more memory
//! than allowed is refused up front with [`Error::TooLarge`], instead of being killed by
//! the operating system halfway through a batch.
//!
//! The need is a linear model of the input's vertex and triangle counts, one for the
//! greedy run and one for the cut, fitted on the peak resident memory of CLI runs (see
//! [`estimate`]). The counts come from the
//! file before parsing (`input::io::declared_counts`: header counts for PLY, OFF and
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

/// Which decomposition an estimate is for: the two peak differently.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Run {
    /// Counts' levels from the greedy merge alone (`-n N` without `--cut`): its peak
    /// is the surface and seeding step, about 100 bytes a triangle from 3.5M up.
    Greedy,
    /// Levels cut from the merge tree (the default tolerance, `--cut`, a byte target):
    /// the greedy peak plus the triangles' hierarchy and the cut's error samples, about
    /// 150 bytes a triangle from 3.5M up and a larger fixed part on small meshes.
    Cut,
}

/// Bytes a vertex costs either run, as loaded (before welding: an STL's three a
/// triangle): its position and welding's tables. Fitted on the dragon as binary STL
/// against the same dragon as PLY (2.18M more vertices, 46 MiB more at the peak).
const PER_VERTEX: u64 = 32;
/// Fixed cost and bytes a triangle, for [`Run::Greedy`] and [`Run::Cut`]. The fixed
/// cost is the binary, thread stacks and allocator arenas and, for the cut, its error
/// samples, whose number follows the tolerance more than the mesh (the 202,520-face
/// dragon peaks at 131 MiB by default, the 99,970-face Lucy at 69). Fitted on the peak
/// resident memory the release CLI's `--timings` reports, scans from 100k to 56M
/// faces, a city block of many parts and flat grids: the table in
/// docs/decisions/limits-memory-estimate.md.
const BASE: [u64; 2] = [64 << 20, 112 << 20];
const PER_TRIANGLE: [u64; 2] = [92, 128];
/// Bytes each corner past a polygon's third costs the greedy run on top of its fan
/// triangles: a flat grid of a million quads peaked at 590.8 MiB there, the same grid
/// as two million triangles at 321.5 MiB (the cut: 301.9 against 331.3).
const PER_POLYGON_CORNER: [u64; 2] = [256, 0];

/// Peak bytes a `run` on an input of these counts is expected to need: the fitted
/// model above plus a quarter for what it does not capture (other shapes, more
/// targets, more threads). A polygon of k corners counts as its k − 2 fan triangles.
/// The cut's estimate is never below the greedy run's, so an estimate made before the
/// settings are known ([`Run::Cut`], the library's default) covers either run: on a
/// grid of quads the greedy run's fan corners peak above the cut.
pub(crate) fn estimate(c: Counts, run: Run) -> u64 {
    match run {
        Run::Greedy => model(c, Run::Greedy),
        Run::Cut => model(c, Run::Cut).max(model(c, Run::Greedy)),
    }
}

/// The fitted model of one run, with its quarter.
fn model(c: Counts, run: Run) -> u64 {
    let k = run as usize;
    let triangles = c
        .corners
        .saturating_sub(c.faces.saturating_mul(2))
        .max(c.faces);
    let past_third = c.corners.saturating_sub(c.faces.saturating_mul(3));
    let linear = BASE[k]
        .saturating_add(PER_VERTEX.saturating_mul(c.vertices))
        .saturating_add(PER_TRIANGLE[k].saturating_mul(triangles))
        .saturating_add(PER_POLYGON_CORNER[k].saturating_mul(past_third));
    linear.saturating_add(linear / 4)
}

/// Refuses `counts` when their estimate for `run` exceeds `limit` bytes.
pub(crate) fn check(path: &Path, counts: Counts, run: Run, limit: u64) -> Result<()> {
    let needed = estimate(counts, run);
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

/// Hands the pages of what the run freed back to the system (glibc's
/// `malloc_trim`; nothing elsewhere). glibc keeps memory freed in its arenas for
/// later allocations, but a table larger than its mapping threshold is mapped
/// afresh beside it, so the merge stage's freed clusters would still count while
/// the triangles' hierarchy is built: 184 MiB (13 bytes a face) of the 14M-face
/// rung's peak there (docs/results/ladder.md).
pub(crate) fn release_freed() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free pages of glibc's own heaps.
    unsafe {
        libc::malloc_trim(0);
    }
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
        for run in [Run::Greedy, Run::Cut] {
            let need = estimate(c, run);
            assert!(check(Path::new("m.obj"), c, run, need).is_ok());
            let e = check(Path::new("m.obj"), c, run, need - 1).unwrap_err();
            assert!(matches!(e, Error::TooLarge { faces: 2000, .. }), "{e}");
            assert_eq!(e.exit_code(), 2);
        }
    }

    /// The cut holds the greedy run's data and more; a quad costs the cut its two fan
    /// triangles and the greedy run more; counts past any real file saturate instead
    /// of wrapping.
    #[test]
    fn cut_needs_more_and_polygons_count_their_triangles() {
        let tris = Counts {
            vertices: 1000,
            faces: 2000,
            corners: 6000,
        };
        let quads = Counts {
            faces: 1000,
            corners: 4000,
            ..tris
        };
        assert_eq!(estimate(quads, Run::Cut), estimate(tris, Run::Cut));
        assert!(estimate(quads, Run::Greedy) > estimate(tris, Run::Greedy));
        assert!(estimate(tris, Run::Cut) > estimate(tris, Run::Greedy));
        // A million quads: the greedy run's fan corners outweigh the cut's base, and
        // the cut's estimate (what a caller who does not say gets) still covers it.
        let grid = Counts {
            vertices: 1_002_001,
            faces: 1_000_000,
            corners: 4_000_000,
        };
        assert!(model(grid, Run::Greedy) > model(grid, Run::Cut));
        assert_eq!(estimate(grid, Run::Cut), estimate(grid, Run::Greedy));
        let huge = Counts {
            vertices: u64::MAX,
            faces: u64::MAX,
            corners: u64::MAX,
        };
        assert_eq!(estimate(huge, Run::Cut), u64::MAX);
    }
}
