//! What a run returns: the input's description, one [`Level`] of primitives per
//! target, the stages' timings and the merge loop's counters.

use crate::input::io::MeshFormat;
use crate::input::up::Up;
use crate::math::V3;
use crate::primitive::Primitive;
use serde::Serialize;

/// What the input was: its size and bounding box in world coordinates.
///
/// ```
/// use primdecomp::{decompose, Params};
///
/// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tetrahedron = primdecomp::Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
/// let input = decompose(&tetrahedron, &Params::default())?.input;
/// assert_eq!((input.aabb_min, input.aabb_max), ([0.0; 3], [1.0; 3]));
/// assert!((input.diagonal() - 3f64.sqrt()).abs() < 1e-12);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, Default, Serialize)]
pub struct InputInfo {
    /// The file it came from, when the caller says so (the library never sets it).
    pub path: Option<String>,
    /// Polygon faces.
    pub faces: usize,
    /// Vertices as given (before deduplication).
    pub vertices: usize,
    /// Lower corner of the axis-aligned box around the vertices faces use.
    pub aabb_min: V3,
    /// Upper corner of that box.
    pub aabb_max: V3,
    /// Which axis points up in the input, when the caller knows it (the CLI and
    /// Python's `decompose_file` set it from the file format or `--up`,
    /// [`Up::of_format`]); the exports and the viewer turn the result by it. Results
    /// without it are taken as +Y up.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub up: Option<Up>,
    /// Where [`InputInfo::up`] came from: the format's specification, an assumption
    /// for a format that says nothing, or the caller.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub up_from: Option<String>,
}

impl InputInfo {
    /// Records that the input came from the file `path`: its name (`path`) and the up
    /// axis its format states or assumes ([`Up::of_format`]; nothing for an extension
    /// primdecomp does not read). The command line, Python, C and WebAssembly all
    /// record a file's result so, which makes their JSON the same byte for byte.
    ///
    /// ```
    /// use primdecomp::{InputInfo, Up};
    ///
    /// let mut input = InputInfo::default();
    /// input.record_file("parts/gear.stl".as_ref());
    /// assert_eq!(input.path.as_deref(), Some("parts/gear.stl"));
    /// assert_eq!(input.up, Some(Up::Z)); // STL is assumed +Z up
    /// ```
    pub fn record_file(&mut self, path: &std::path::Path) {
        self.path = Some(path.display().to_string());
        if let Some(format) = MeshFormat::from_path(path) {
            let (up, why) = Up::of_format(format);
            (self.up, self.up_from) = (Some(up), Some(why.to_string()));
        }
    }

    /// The length of the bounding box's diagonal (what relative settings such as
    /// [`crate::Fit::min_extent`] and [`crate::Tolerance::Diagonal`] scale by).
    pub fn diagonal(&self) -> f64 {
        crate::math::norm(crate::math::sub(self.aabb_max, self.aabb_min))
    }
}

/// The result for one target count.
///
/// ```
/// use primdecomp::{decompose, Goal, Params};
///
/// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tetrahedron = primdecomp::Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
/// let result = decompose(&tetrahedron, &Params::default())?; // within 2% of the diagonal
/// let level = &result.levels[0];
/// assert!(level.distance.unwrap() <= level.tolerance.unwrap());
/// assert_eq!(level.counts().iter().sum::<usize>(), level.primitives.len());
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Level {
    /// The requested target N.
    pub target: usize,
    /// The target the merge loop stopped at: N, or with [`crate::Goal::Fill`] the
    /// larger count whose post-processed result fills the budget of N best.
    pub merged_to: usize,
    /// Primitives in world coordinates, in a deterministic order.
    pub primitives: Vec<Primitive>,
    /// For each primitive, how many input faces it was fitted to.
    pub faces: Vec<u32>,
    /// The level's tolerance in the input's units, when one was asked for
    /// ([`crate::Goal::Within`]).
    pub tolerance: Option<f64>,
    /// The level's byte target, when one was asked for ([`crate::Goal::Within`]).
    pub max_bytes: Option<usize>,
    /// For a cut of the merge tree ([`crate::Goal::uses_cut`]): an upper bound of the
    /// farthest any point of a primitive stands from the input, in its units, within
    /// 2% of it (docs/decisions/0040): at most the tolerance whenever the level says
    /// it is within it.
    pub distance: Option<f64>,
    /// Whether `distance` (and the tolerance it is held to) is measured to the input's
    /// solid rather than its surface: with [`crate::Plates::solid`] on an input that
    /// has an inside, a point of a primitive inside the input stands at 0
    /// (docs/decisions/0056).
    pub distance_to_solid: bool,
    /// For a cut that stands farther than its tolerance: what stopped it nearer.
    pub shortfall: Option<Shortfall>,
}

/// What keeps a cut of the merge tree from its tolerance ([`Level::shortfall`]).
///
/// ```
/// use primdecomp::{decompose, Goal, Params, Shortfall, Tolerance};
/// // Four primitives cannot stand within 0.5% of the demo scene's parts.
/// let scene = primdecomp::demo_scene();
/// let p = Params {
///     goal: Goal::Within {
///         caps: vec![4],
///         tolerance: vec![Tolerance::Diagonal(0.005)],
///         max_bytes: vec![],
///     },
///     ..Params::default()
/// };
/// let level = &decompose(&scene, &p)?.levels[0];
/// assert_eq!(level.shortfall, Some(Shortfall::Count));
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Shortfall {
    /// The count ([`crate::Goal::targets`], 1024 without one) ran out first.
    Count,
    /// The byte target ([`crate::Goal::Within`]) ran out first.
    Bytes,
    /// Nothing ran out: the farthest primitives enclose faces, alone or a few together,
    /// that no enabled kind encloses nearer (every face must lie inside one primitive).
    Faces,
}

impl Level {
    /// Primitive counts indexed by `Kind as usize` ([`crate::Kind::ALL`] order).
    pub fn counts(&self) -> [usize; 6] {
        let mut c = [0; 6];
        for p in &self.primitives {
            c[p.kind() as usize] += 1;
        }
        c
    }

    /// Storage by the paper's Table 2: 4 bytes per float of each primitive.
    pub fn bytes(&self) -> usize {
        self.primitives.iter().map(|p| p.bytes()).sum()
    }
}

/// Counters of a run, for reports and tuning; they do not depend on the thread count.
///
/// ```
/// use primdecomp::{decompose, Params};
///
/// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tetrahedron = primdecomp::Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
/// let stats = decompose(&tetrahedron, &Params::default())?.stats;
/// assert_eq!(stats.welded_vertices, 4);
/// assert_eq!(stats.adjacency_edges, 6);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Distinct vertices after deduplication.
    pub welded_vertices: usize,
    /// Pairs of faces sharing an edge.
    pub adjacency_edges: usize,
    /// Pairs of clusters linked across gaps once adjacency ran out (§3.4 "Pairwise
    /// Component Merging").
    pub bridge_edges: usize,
    /// Merges done.
    pub merges: usize,
    /// Merges that per-component loops did past the last target (the output is
    /// replayed from their first merges).
    pub merges_past: usize,
    /// Merges whose points were reduced while the batch before them was priced.
    pub merges_ahead: usize,
    /// Candidate merges priced when seeding the queue and when bridging.
    pub fits_seeded: usize,
    /// Candidate merges re-priced right after a merge.
    pub fits_at_once: usize,
    /// Stale candidates re-priced when popped (deferred re-pricing).
    pub fits_when_popped: usize,
    /// Spatial parts merged in parallel before the global loop (1 = none).
    pub partitions: usize,
    /// Out-of-core tiles the input was decomposed in ([`crate::Tiled::decompose`]; 0 =
    /// read whole).
    pub tiles: usize,
}

/// Everything a run produces.
///
/// ```
/// use primdecomp::{decompose, Goal, Params};
///
/// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tetrahedron = primdecomp::Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
/// let result = decompose(&tetrahedron, &Params { goal: Goal::counts([4, 1]), ..Params::default() })?;
/// assert_eq!(result.levels.len(), 2);
/// assert_eq!(result.input.faces, 4);
/// assert!(result.seconds() >= 0.0);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Decomposition {
    /// What the input was.
    pub input: InputInfo,
    /// One level per target, in the order the targets were given.
    pub levels: Vec<Level>,
    /// Wall-clock seconds of each stage, `(stage name, seconds)` in the order the
    /// stages ran ([`Decomposition::seconds`] sums them).
    pub timings: Vec<(String, f64)>,
    /// The merge loop's counters.
    pub stats: Stats,
}

impl Decomposition {
    /// The wall-clock seconds of the run: the sum of [`Decomposition::timings`].
    ///
    /// ```
    /// use primdecomp::{decompose, Params};
    ///
    /// let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let tetrahedron = primdecomp::Mesh::from_triangles(&corners, &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
    /// let result = decompose(&tetrahedron, &Params::default())?;
    /// let sum: f64 = result.timings.iter().map(|(_, s)| s).sum();
    /// assert!((result.seconds() - sum).abs() < 1e-9);
    /// assert!(result.timings.iter().any(|(stage, _)| stage == "merge"));
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn seconds(&self) -> f64 {
        self.timings.iter().map(|s| s.1).sum()
    }
}
