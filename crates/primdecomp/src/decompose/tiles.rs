//! Out of core (docs/decisions/out-of-core-tiles.md): an input whose decomposition
//! does not fit the memory limit is decomposed as spatial tiles, one at a time, and
//! the tiles' results are merged on top.
//!
//! 1. **Plan** (one streaming pass over the file): the vertices' bounding box, then a
//!    histogram of the faces' centroids along its longest axis, cut into `K` slabs of
//!    about equal face counts. The plan depends only on the input and `K`.
//! 2. **Each tile** (one pass each): the faces whose centroid falls in the slab and
//!    the vertices they use become a [`Mesh`] of their own, decomposed greedily into
//!    boxes, the tile's share of [`GROUPS_PER_TARGET`] × the largest target (the same
//!    multiple the in-memory spatial parts stop at, §3.3 run on a part); everything
//!    per face is freed before the next tile.
//! 3. **On top**: the tiles' boxes, as closed hexahedra, are one small mesh that the
//!    usual pipeline decomposes with the caller's settings (§3). Every input face lies
//!    in its tile's box (the tile run's enclosure) and every box in a primitive of
//!    every level (the top run's), so enclosure holds without reading the input again.
//!
//! Binary PLY is read from the memory map a tile at a time, its pages released after
//! each pass; other formats are parsed whole and the tiles cut from the parsed mesh.

use crate::error::{Error, Result};
use crate::input::io::{format_of, open_regular, LoadOptions, MeshFormat, PlyLayout};
use crate::input::mesh::{Mesh, MeshBuilder};
use crate::math::V3;
use crate::output::result::Decomposition;
use crate::params::{CountSearch, Fit, Goal, Params, Tolerance};
use crate::primitive::Kind;
use crate::progress::wallclock::Instant;
use crate::progress::{Progress, Stage};
use std::path::Path;

/// The groups tiles merge down to per unit of the largest target, as the in-memory
/// spatial parts (`merge::partition`).
const GROUPS_PER_TARGET: usize = crate::merge::partition::GROUPS_PER_TARGET;
/// A tile stops at no more groups than one per this many faces on a run without a
/// count (a tolerance or byte target resolves to small counts).
const FACES_PER_GROUP: usize = 256;
/// Histogram bins along the slab axis: the finest cut between tiles.
const BINS: usize = 1 << 16;
/// The most tiles a run is cut into.
pub const MAX_TILES: usize = 4096;
/// Bytes read from the map between releases of what was read.
const RELEASE_EVERY: usize = 16 << 20;

/// Decomposes the mesh in `path` as spatial tiles within `options.max_memory`
/// ([`LoadOptions::tiles`] forces their number): for inputs [`crate::Mesh::load_with`]
/// refuses as too large. The result has the levels [`crate::decompose`] would give,
/// each enclosing every face, from a different merge order (the difference is
/// measured in docs/results/out-of-core.md); `stats.tiles` says how many tiles.
/// Deterministic for any thread count.
///
/// ```
/// use primdecomp::{decompose_tiled, Goal, LoadOptions, Params};
///
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
/// let options = LoadOptions { tiles: Some(2), ..LoadOptions::default() };
/// let params = Params { goal: Goal::counts([20]), ..Params::default() };
/// let result = decompose_tiled(path.as_ref(), &params, &options, &|_, _| {})?;
/// assert_eq!(result.stats.tiles, 2);
/// assert!(result.levels[0].primitives.len() <= 20);
/// # Ok::<(), primdecomp::Error>(())
/// ```
///
/// # Errors
/// What [`crate::Mesh::load_with`] and [`crate::decompose`] return, and
/// [`Error::TooLarge`] when even `MAX_TILES` (4096) tiles would not fit the limit (with
/// the need of the smallest tiles).
pub fn decompose_tiled(
    path: &Path,
    params: &Params,
    options: &LoadOptions,
    progress: &dyn Progress,
) -> Result<Decomposition> {
    params.validate()?;
    let started = Instant::now();
    let (file, meta) = open_regular(path)?;
    let format = format_of(path)?;
    if meta.len() == 0 {
        return Err(Error::EmptyMesh {
            path: path.to_path_buf(),
        });
    }
    // SAFETY: read-only and private to this call; a concurrent writer truncating the
    // file could fault, as for every mmap reader (`load_with`).
    let map = unsafe { memmap2::Mmap::map(&file) }.map_err(|error| Error::Io {
        path: path.to_path_buf(),
        error,
    })?;
    let layout = match format {
        MeshFormat::Ply => PlyLayout::of(&map, path)?,
        _ => None,
    };
    let source = match layout {
        Some(layout) => Source::Mapped { map, layout, path },
        None => Source::Whole(whole(path, options)?),
    };
    let plan = Plan::new(&source, path, params, options)?;
    let mut timings = vec![("plan".to_string(), started.elapsed().as_secs_f64())];
    let now = Instant::now();
    let proxy = run_tiles(&source, &plan, params, progress)?;
    timings.push(("tiles".to_string(), now.elapsed().as_secs_f64()));
    drop(source);
    // The tiles' boxes merged on top with the caller's settings (§3).
    let mesh = Mesh::from_builder(proxy.builder);
    let top = of_input(params, proxy.used);
    let mut dec = crate::decompose::decompose_with(&mesh, &top, progress)?;
    timings.append(&mut dec.timings.stages);
    dec.timings.stages = timings;
    dec.input.faces = plan.faces;
    dec.input.vertices = plan.vertices;
    (dec.input.aabb_min, dec.input.aabb_max) = proxy.used;
    dec.stats.tiles = plan.tiles;
    Ok(dec)
}

/// The top run's settings: a tolerance given as a share of the diagonal is of the
/// input's diagonal (`used`, its corners), not of the tiles' boxes', which stand a
/// little beyond it; so a tiled run is held to the distance the user asked for.
fn of_input(params: &Params, used: (V3, V3)) -> Params {
    let Goal::Within {
        caps,
        tolerance,
        max_bytes,
    } = &params.goal
    else {
        return params.clone();
    };
    let (lo, hi) = used;
    let diagonal = crate::math::norm(crate::math::sub(hi, lo));
    let tolerance = tolerance
        .iter()
        .map(|&t| Tolerance::Units(t.in_units(diagonal)))
        .collect();
    Params {
        goal: Goal::Within {
            caps: caps.clone(),
            tolerance,
            max_bytes: max_bytes.clone(),
        },
        ..params.clone()
    }
}

/// The whole mesh parsed, for a format not read a tile at a time: refused when the
/// parsed mesh alone (its positions and polygons) exceeds the limit.
fn whole(path: &Path, options: &LoadOptions) -> Result<Mesh> {
    let unlimited = LoadOptions {
        max_memory: None,
        ..options.clone()
    };
    if let (Some(limit), Ok((_, meta))) = (options.max_memory, open_regular(path)) {
        // The parse maps the file whole: `load_with`'s refusal of a file over the limit.
        if meta.len() > limit {
            crate::input::io::load_with(path, options)?;
        }
    }
    let mesh = crate::input::io::load_with(path, &unlimited)?;
    if let Some(limit) = options.max_memory {
        let need = mesh_bytes(
            mesh.vertex_count() as u64,
            mesh.face_count() as u64,
            mesh.face_indices.len() as u64,
        );
        if need > limit {
            return Err(too_large(path, need, limit));
        }
    }
    Ok(mesh)
}

/// Bytes a parsed [`Mesh`] holds: three f64 a vertex, a u32 a corner and a face.
fn mesh_bytes(vertices: u64, faces: u64, corners: u64) -> u64 {
    vertices
        .saturating_mul(24)
        .saturating_add(corners.saturating_mul(4))
        .saturating_add(faces.saturating_mul(4))
}

/// The parsed mesh alone needs `need` bytes, over `limit`.
fn too_large(path: &Path, need: u64, limit: u64) -> Error {
    let why = "only binary PLY is read a tile at a time (other formats and ASCII PLY are \
               parsed whole first; convert the file to binary PLY)";
    Error::format(
        path,
        format!(
            "read whole before it is cut into tiles, its positions and polygons hold {}, more \
             than the memory limit of {}: \
             {why}; raise the limit with --max-memory SIZE (in the library: the max_memory \
             of primdecomp::LoadOptions)",
            crate::error::show_bytes(need),
            crate::error::show_bytes(limit)
        ),
    )
}

/// Where the faces come from: the memory-mapped binary PLY, or a parsed mesh.
enum Source<'p> {
    Mapped {
        map: memmap2::Mmap,
        layout: PlyLayout,
        path: &'p Path,
    },
    Whole(Mesh),
}

impl Source<'_> {
    fn vertex_count(&self) -> usize {
        match self {
            Source::Mapped { layout, .. } => layout.vertex_count as usize,
            Source::Whole(m) => m.vertex_count(),
        }
    }

    /// Bytes the source keeps resident through the run: the parsed mesh, or the
    /// mapped vertices (read at random while faces are scanned) and the face data
    /// read since the last release.
    fn resident(&self) -> u64 {
        match self {
            Source::Mapped { layout, .. } => {
                layout.vertex_bytes().saturating_add(RELEASE_EVERY as u64)
            }
            Source::Whole(m) => mesh_bytes(
                m.vertex_count() as u64,
                m.face_count() as u64,
                m.face_indices.len() as u64,
            ),
        }
    }

    fn face_count_declared(&self) -> u64 {
        match self {
            Source::Mapped { layout, .. } => layout.face_count,
            Source::Whole(m) => m.face_count() as u64,
        }
    }

    /// Vertex `v`'s world position (`v` in range; the mapped file's checked by
    /// [`Source::vertices`]).
    fn pos(&self, v: u32) -> V3 {
        match self {
            Source::Mapped { map, layout, .. } => layout.pos(map, v as usize),
            Source::Whole(m) => m.world_pos(v),
        }
    }

    /// Visits every vertex's world position in order; the mapped file's are checked
    /// (present and finite) with the whole parse's messages.
    fn vertices(&self, mut visit: impl FnMut(V3)) -> Result<()> {
        match self {
            Source::Mapped { map, layout, path } => {
                let r = layout.vertices(map, path, visit);
                release(map, 0, map.len());
                r
            }
            Source::Whole(m) => {
                (0..m.vertex_count() as u32).for_each(|v| visit(m.world_pos(v)));
                Ok(())
            }
        }
    }

    /// Visits every face's corners in order (an index out of range or data that
    /// ends early is the whole parse's error). The mapped pages read are released
    /// as the scan goes, so a pass keeps little of the file resident.
    fn faces(&self, mut visit: impl FnMut(&[u32])) -> Result<()> {
        match self {
            Source::Mapped { map, layout, path } => {
                let mut released = 0;
                let r = layout.faces(map, path, |corners, at| {
                    visit(corners);
                    if at >= released + RELEASE_EVERY {
                        release(map, released, at - released);
                        released = at;
                    }
                });
                release(map, 0, map.len());
                r
            }
            Source::Whole(m) => {
                (0..m.face_count()).for_each(|f| visit(m.face(f)));
                Ok(())
            }
        }
    }
}

/// Drops the mapped pages of `len` bytes from `offset` from this process's resident
/// memory (they are the file's, read again if needed).
fn release(map: &memmap2::Mmap, offset: usize, len: usize) {
    #[cfg(unix)]
    {
        let page = 4096;
        let start = offset / page * page;
        let len = (offset + len).min(map.len()) - start;
        // SAFETY: the map is read-only and file-backed: dropped pages read back from
        // the file, unchanged.
        let _ =
            unsafe { map.unchecked_advise_range(memmap2::UncheckedAdvice::DontNeed, start, len) };
    }
    #[cfg(not(unix))]
    let _ = (map, offset, len);
}

/// The tiles: slabs of the faces' centroids along the longest axis of the box.
struct Plan {
    tiles: usize,
    axis: usize,
    lo: f64,
    /// Bins per unit length along `axis`.
    scale: f64,
    /// Tile of each bin.
    bin_tile: Vec<u16>,
    /// Faces in each tile.
    tile_faces: Vec<usize>,
    faces: usize,
    vertices: usize,
    /// Groups the tiles merge down to together.
    groups: usize,
}

impl Plan {
    /// The box of every vertex, the histogram of the faces, and the tile count: the
    /// caller's ([`LoadOptions::tiles`]), or the fewest that fit `max_memory`.
    fn new(source: &Source, path: &Path, params: &Params, options: &LoadOptions) -> Result<Plan> {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        source.vertices(|p| {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        })?;
        let ext = [0, 1, 2].map(|k| (hi[k] - lo[k]).max(0.0));
        let axis = (0..3).fold(0, |best, k| if ext[k] > ext[best] { k } else { best });
        let scale = match ext[axis] > 0.0 && ext[axis].is_finite() {
            true => BINS as f64 / ext[axis],
            false => 0.0,
        };
        let mut plan = Plan {
            tiles: 1,
            axis,
            lo: lo[axis],
            scale,
            bin_tile: vec![0; BINS],
            tile_faces: Vec::new(),
            faces: 0,
            vertices: source.vertex_count(),
            groups: 0,
        };
        let mut histogram = vec![0usize; BINS];
        let mut corners = 0u64;
        source.faces(|f| {
            histogram[plan.bin(source, f)] += 1;
            corners += f.len() as u64;
        })?;
        plan.faces = histogram.iter().sum();
        if plan.faces == 0 {
            return Err(Error::EmptyMesh {
                path: path.to_path_buf(),
            });
        }
        debug_assert_eq!(plan.faces as u64, source.face_count_declared());
        let largest = params.goal.targets().into_iter().max().unwrap_or(1);
        plan.groups = GROUPS_PER_TARGET
            .saturating_mul(largest)
            .max(plan.faces / FACES_PER_GROUP)
            .min(plan.faces);
        plan.tiles = match options.tiles {
            Some(k) => k.clamp(1, MAX_TILES),
            None => plan.fewest_tiles(path, corners, source.resident(), params, options)?,
        };
        plan.cut(&histogram);
        Ok(plan)
    }

    /// The bin of a face's centroid.
    fn bin(&self, source: &Source, corners: &[u32]) -> usize {
        let mut c = 0.0;
        for &v in corners {
            c += source.pos(v)[self.axis];
        }
        let c = c / corners.len().max(1) as f64;
        let b = ((c - self.lo) * self.scale).floor();
        // NaN (no corners) and a centroid on the upper bound go to the end bins.
        (if b >= 0.0 { b as usize } else { 0 }).min(BINS - 1)
    }

    /// Bins to tiles, each tile a run of bins holding about its share of the faces.
    fn cut(&mut self, histogram: &[usize]) {
        let k = self.tiles;
        self.tile_faces = vec![0; k];
        let mut seen = 0usize;
        for (b, &n) in histogram.iter().enumerate() {
            // The tile whose share the bin's first face falls in.
            let t = ((seen as u128 * k as u128) / self.faces.max(1) as u128) as usize;
            self.bin_tile[b] = t.min(k - 1) as u16;
            self.tile_faces[t.min(k - 1)] += n;
            seen += n;
        }
    }

    /// The fewest tiles whose largest run fits the limit, by the memory model: a
    /// tile's greedy run on its share (a quarter more, for uneven slabs) beside the
    /// vertex map all tiles share, or the top run on the boxes.
    fn fewest_tiles(
        &self,
        path: &Path,
        corners: u64,
        resident: u64,
        params: &Params,
        options: &LoadOptions,
    ) -> Result<usize> {
        let Some(limit) = options.max_memory else {
            return Ok(1);
        };
        let shared = (4 * self.vertices as u64).saturating_add(resident);
        let top = crate::input::memory::estimate(
            crate::input::memory::Counts {
                vertices: 8 * self.groups as u64,
                faces: 6 * self.groups as u64,
                corners: 24 * self.groups as u64,
            },
            run_of(params),
        );
        let (v, f) = (self.vertices as u64, self.faces as u64);
        for k in 1..=MAX_TILES as u64 {
            let share = |n: u64| (n / k + 1).saturating_add(n / k / 4);
            let tile = crate::input::memory::estimate(
                crate::input::memory::Counts {
                    vertices: share(v),
                    faces: share(f),
                    corners: share(corners),
                },
                crate::input::memory::Run::Greedy,
            );
            if shared.saturating_add(tile.max(top)) <= limit {
                return Ok(k as usize);
            }
        }
        // Not even the most tiles fit: the need of the fewest that would.
        Err(Error::TooLarge {
            path: path.to_path_buf(),
            faces: self.faces as u64,
            vertices: self.vertices as u64,
            needed: shared.saturating_add(top),
            limit,
        })
    }
}

fn run_of(params: &Params) -> crate::input::memory::Run {
    match params.uses_cut() {
        true => crate::input::memory::Run::Cut,
        false => crate::input::memory::Run::Greedy,
    }
}

/// The tiles' boxes as one mesh, and the box of the vertices the faces use.
struct Proxy {
    builder: MeshBuilder,
    used: (V3, V3),
}

/// Decomposes each tile in turn into its groups' boxes.
fn run_tiles(
    source: &Source,
    plan: &Plan,
    params: &Params,
    progress: &dyn Progress,
) -> Result<Proxy> {
    let mut local = vec![u32::MAX; source.vertex_count()];
    let mut proxy = Proxy {
        builder: MeshBuilder::new(),
        used: ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
    };
    for t in 0..plan.tiles {
        if progress.cancelled() {
            return Err(Error::Cancelled);
        }
        if plan.tile_faces[t] == 0 {
            continue;
        }
        let mesh = tile_mesh(source, plan, t, &mut local)?;
        let (lo, hi) = mesh.aabb();
        for k in 0..3 {
            proxy.used.0[k] = proxy.used.0[k].min(lo[k] + mesh.offset[k]);
            proxy.used.1[k] = proxy.used.1[k].max(hi[k] + mesh.offset[k]);
        }
        if mesh.face_count() == 0 {
            continue;
        }
        let share =
            (plan.groups as u128 * plan.tile_faces[t] as u128 / plan.faces as u128) as usize;
        let tile = TileProgress {
            outer: progress,
            done: t,
            of: plan.tiles,
        };
        let dec =
            crate::decompose::decompose_with(&mesh, &tile_params(params, share.max(1)), &tile)?;
        drop(mesh);
        for p in &dec.levels[0].primitives {
            let tess = crate::output::tessellate(p, 4);
            let base = proxy.builder.positions.len() as u32;
            proxy.builder.positions.extend_from_slice(&tess.vertices);
            for f in &tess.faces {
                let face: Vec<u32> = f.iter().map(|&i| base + i).collect();
                proxy.builder.push_face(&face);
            }
        }
    }
    Ok(proxy)
}

/// Tile `t`'s faces and the vertices they use (local ids through `local`, reset
/// before returning), as a mesh of its own.
fn tile_mesh(source: &Source, plan: &Plan, t: usize, local: &mut [u32]) -> Result<Mesh> {
    let mut b = MeshBuilder::new();
    let mut used: Vec<u32> = Vec::new();
    let mut corners = Vec::new();
    source.faces(|f| {
        if plan.bin_tile[plan.bin(source, f)] as usize != t {
            return;
        }
        corners.clear();
        for &v in f {
            if local[v as usize] == u32::MAX {
                local[v as usize] = used.len() as u32;
                used.push(v);
            }
            corners.push(local[v as usize]);
        }
        b.push_face(&corners);
    })?;
    b.positions = used.iter().map(|&v| source.pos(v)).collect();
    for &v in &used {
        local[v as usize] = u32::MAX;
    }
    Ok(Mesh::from_builder(b))
}

/// A tile's settings: greedy boxes down to its share of the groups, with the
/// caller's weights, welding, cleanup and speed settings.
fn tile_params(params: &Params, groups: usize) -> Params {
    let mut kinds = [false; 6];
    kinds[Kind::Box as usize] = true;
    kinds[Kind::Prism as usize] = true;
    Params {
        goal: Goal::Counts {
            counts: vec![groups],
            search: CountSearch::Greedy,
        },
        fit: Fit {
            kinds,
            ..params.fit.clone()
        },
        ..params.clone()
    }
}

/// A tile's progress as a share of the whole run's merge stage.
struct TileProgress<'a> {
    outer: &'a dyn Progress,
    done: usize,
    of: usize,
}

impl Progress for TileProgress<'_> {
    fn update(&self, stage: Stage, fraction: f64) {
        let stages = Stage::Postprocess as usize + 1;
        let within = (stage as usize as f64 + fraction) / stages as f64;
        self.outer
            .update(Stage::Merge, (self.done as f64 + within) / self.of as f64);
    }

    fn cancelled(&self) -> bool {
        self.outer.cancelled()
    }
}
