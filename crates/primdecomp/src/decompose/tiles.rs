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

mod bytes;
mod source;

use crate::error::{Error, Result};
use crate::input::io::LoadOptions;
use crate::input::mesh::{Mesh, MeshBuilder};
use crate::math::V3;
use crate::output::result::Decomposition;
use crate::params::{Fit, Goal, Params, Tolerance};
use crate::primitive::Kind;
use crate::progress::wallclock::Instant;
use crate::progress::{Progress, Stage};
use bytes::TileResult;
use source::{open, Source};
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
pub(crate) const MAX_TILES: usize = 4096;
/// Bytes read from the map between releases of what was read.
const RELEASE_EVERY: usize = 16 << 20;

impl Tiled {
    /// Decomposes the mesh in `path` as spatial tiles within `options.max_memory`
    /// ([`LoadOptions::tiles`] forces their number): for inputs [`crate::Mesh::load_with`]
    /// refuses as too large. The result has the levels [`crate::decompose`] would give,
    /// each enclosing every face, from a different merge order (the difference is
    /// measured in docs/results/out-of-core.md); `stats.tiles` says how many tiles.
    /// Deterministic for any thread count. The same as [`Tiled::plan`], then
    /// [`Tiled::run_tile`] for each tile and [`Tiled::merge`], with the file opened once.
    ///
    /// ```
    /// use primdecomp::{Goal, LoadOptions, Params, Tiled};
    ///
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
    /// let options = LoadOptions { tiles: Some(2), ..LoadOptions::default() };
    /// let params = Params { goal: Goal::counts([20]), ..Params::default() };
    /// let result = Tiled::decompose(path.as_ref(), &params, &options, &|_, _| {})?;
    /// assert_eq!(result.stats.tiles, 2);
    /// assert!(result.levels[0].primitives.len() <= 20);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    ///
    /// # Errors
    /// What [`crate::Mesh::load_with`] and [`crate::decompose`] return, and
    /// [`Error::TooLarge`] when even `MAX_TILES` (4096) tiles would not fit the limit (with
    /// the need of the smallest tiles).
    pub fn decompose(
        path: &Path,
        params: &Params,
        options: &LoadOptions,
        progress: &dyn Progress,
    ) -> Result<Decomposition> {
        params.validate()?;
        let started = Instant::now();
        let (source, input) = open(path, options)?;
        let tiled = Tiled::of(&source, input, path, params, options)?;
        let mut timings = vec![("plan".to_string(), started.elapsed().as_secs_f64())];
        let now = Instant::now();
        let mut local = vec![u32::MAX; source.vertex_count()];
        let mut results = Vec::with_capacity(tiled.plan.tiles);
        for t in 0..tiled.plan.tiles {
            if progress.cancelled() {
                return Err(Error::Cancelled);
            }
            results.push(tiled.tile_of(&source, t, &mut local, progress)?);
        }
        timings.push(("tiles".to_string(), now.elapsed().as_secs_f64()));
        drop(source);
        let mut dec = tiled.merge(&results, progress)?;
        timings.append(&mut dec.timings);
        dec.timings = timings;
        Ok(dec)
    }
}

/// A tiled run in three steps that can run on different machines (a Ray cluster;
/// the Python package's `primdecomp.ray_tiles`): [`Tiled::plan`] reads the file once
/// and cuts it into tiles; [`Tiled::run_tile`] decomposes one tile, anywhere the same
/// file can be read; [`Tiled::merge`] merges every tile's result into the
/// [`Decomposition`] [`Tiled::decompose`] gives, byte for byte. The plan and the tile
/// results travel as bytes ([`Tiled::to_bytes`], [`Tiled::from_bytes`]; the format
/// is in `decompose/tiles/bytes.rs`), each checked when read: magic, version,
/// checksum, every count and number, the input's size and content hash when a tile
/// runs, and the plan and tile index a result was made for.
///
/// ```
/// use primdecomp::{Goal, LoadOptions, Params, Tiled};
///
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
/// let params = Params { goal: Goal::counts([20]), ..Params::default() };
/// let options = LoadOptions { tiles: Some(3), ..LoadOptions::default() };
/// let bytes = Tiled::plan(path.as_ref(), &params, &options)?.to_bytes();
/// // Elsewhere: the plan's bytes and the same file give each tile's bytes.
/// let plan = Tiled::from_bytes(&bytes)?;
/// let tiles = (0..plan.tiles())
///     .map(|t| plan.run_tile(path.as_ref(), t, &|_, _| {}))
///     .collect::<Result<Vec<_>, _>>()?;
/// let merged = plan.merge(&tiles, &|_, _| {})?;
/// let whole = Tiled::decompose(path.as_ref(), &params, &options, &|_, _| {})?;
/// assert_eq!(merged.to_json(0, &params), whole.to_json(0, &params));
/// // A result altered on the way is refused.
/// let mut bad = tiles[0].clone();
/// bad[40] ^= 1;
/// assert!(plan.check_tile(0, &bad).is_err());
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Debug)]
pub struct Tiled {
    plan: Plan,
    params: Params,
    input: Identity,
    /// The load options a tile needs to read the file as the plan did
    /// (bit 0: `allow_external_uris`, bit 1: `keep_world_coordinates`).
    flags: u8,
    /// The hash of the plan's bytes, which every tile result names.
    id: u128,
}

/// What a plan knows of its input: its size and the hash of its bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Identity {
    size: u64,
    hash: u128,
}

impl Tiled {
    /// The most tiles a run is cut into.
    ///
    /// ```
    /// assert_eq!(primdecomp::Tiled::MAX_TILES, 4096);
    /// ```
    pub const MAX_TILES: usize = MAX_TILES;

    /// Plans a tiled run of the mesh in `path` with `params`: one pass over the file
    /// (its content hash, its vertices' box, its faces' histogram) cuts it into
    /// `options.tiles` tiles, or the fewest that fit `options.max_memory`.
    ///
    /// # Errors
    /// What [`Tiled::decompose`] returns before its first tile.
    pub fn plan(path: &Path, params: &Params, options: &LoadOptions) -> Result<Tiled> {
        params.validate()?;
        let (source, input) = open(path, options)?;
        Tiled::of(&source, input, path, params, options)
    }

    /// The number of tiles ([`Tiled::run_tile`]'s `tile` is below it).
    pub fn tiles(&self) -> usize {
        self.plan.tiles
    }

    /// The settings the run is planned with (the result's JSON records them).
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The plan as bytes, for [`Tiled::from_bytes`] on another machine; the same plan
    /// gives the same bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        self.encode()
    }

    /// The plan [`Tiled::to_bytes`] wrote.
    ///
    /// # Errors
    /// [`Error::ParseByte`] (naming `<tile plan>` and the byte) for bytes that are
    /// not a plan, of another version, altered, truncated, or hold a number out of
    /// range or settings that do not read.
    pub fn from_bytes(bytes: &[u8]) -> Result<Tiled> {
        Tiled::decode(bytes)
    }

    /// Decomposes tile `tile` of the file at `path` (the file the plan was made
    /// from, at any path) into its result's bytes, for [`Tiled::merge`].
    ///
    /// # Errors
    /// [`Error::InvalidParams`] for a tile out of range; [`Error::Format`] when the
    /// file's size or content hash is not the plan's; what [`Tiled::decompose`]
    /// returns for the file and the tile's run ([`Error::Cancelled`] included).
    pub fn run_tile(&self, path: &Path, tile: usize, progress: &dyn Progress) -> Result<Vec<u8>> {
        self.in_range(tile)?;
        let options = LoadOptions {
            allow_external_uris: self.flags & 1 != 0,
            keep_world_coordinates: self.flags & 2 != 0,
            ..LoadOptions::default()
        };
        let (source, input) = open(path, &options)?;
        if input != self.input {
            return Err(Error::format(
                path,
                format!(
                    "not the file this tile plan was made from: {} bytes with content hash \
                     {:032x}, the plan's file {} bytes with {:032x}",
                    input.size, input.hash, self.input.size, self.input.hash
                ),
            ));
        }
        let mut local = vec![u32::MAX; source.vertex_count()];
        self.tile_of(&source, tile, &mut local, progress)
    }

    /// Checks that `bytes` are a result of tile `tile` of this plan, as
    /// [`Tiled::merge`] does: for a cache of tile results, never trusted unread.
    ///
    /// # Errors
    /// [`Error::ParseByte`] (naming `<tile result>` and the byte) for bytes that are
    /// not a tile result, of another version, altered or truncated, of another plan
    /// or tile, or holding a number out of range; [`Error::InvalidParams`] for a tile
    /// out of range.
    pub fn check_tile(&self, tile: usize, bytes: &[u8]) -> Result<()> {
        self.in_range(tile)?;
        TileResult::decode(bytes, self, tile).map(|_| ())
    }

    /// Merges every tile's result (`tiles[t]` of tile `t`, each checked as
    /// [`Tiled::check_tile`] does) on top with the plan's settings: the
    /// [`Decomposition`] of [`Tiled::decompose`], without its `plan` and `tiles`
    /// timings.
    ///
    /// # Errors
    /// [`Error::InvalidParams`] when there are not [`Tiled::tiles`] results; what
    /// [`Tiled::check_tile`] and [`crate::decompose`] return.
    pub fn merge(
        &self,
        tiles: &[impl AsRef<[u8]>],
        progress: &dyn Progress,
    ) -> Result<Decomposition> {
        if tiles.len() != self.plan.tiles {
            return Err(Error::InvalidParams(format!(
                "the plan has {} tiles, {} tile results were given",
                self.plan.tiles,
                tiles.len()
            )));
        }
        let mut builder = MeshBuilder::new();
        let mut used = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (t, bytes) in tiles.iter().enumerate() {
            let tile = TileResult::decode(bytes.as_ref(), self, t)?;
            if let Some((lo, hi)) = tile.used {
                for k in 0..3 {
                    used.0[k] = used.0[k].min(lo[k]);
                    used.1[k] = used.1[k].max(hi[k]);
                }
            }
            let base = builder.positions.len() as u32;
            builder.positions.extend_from_slice(&tile.positions);
            let mut at = 0;
            let mut face = Vec::new();
            for &n in &tile.sizes {
                face.clear();
                face.extend(tile.corners[at..at + n as usize].iter().map(|&c| base + c));
                builder.push_face(&face);
                at += n as usize;
            }
        }
        // The tiles' boxes merged on top with the caller's settings (§3).
        let mesh = Mesh::from_builder(builder);
        let top = of_input(&self.params, used, mesh.aabb());
        let mut dec = crate::decompose::decompose_with(&mesh, &top, progress)?;
        dec.input.faces = self.plan.faces;
        dec.input.vertices = self.plan.vertices;
        (dec.input.aabb_min, dec.input.aabb_max) = used;
        dec.stats.tiles = self.plan.tiles;
        Ok(dec)
    }

    fn in_range(&self, tile: usize) -> Result<()> {
        match tile < self.plan.tiles {
            true => Ok(()),
            false => Err(Error::InvalidParams(format!(
                "tile {tile} out of range: the plan has {} tiles",
                self.plan.tiles
            ))),
        }
    }

    /// The plan of `source` (the file at `path`, of identity `input`).
    fn of(
        source: &Source,
        input: Identity,
        path: &Path,
        params: &Params,
        options: &LoadOptions,
    ) -> Result<Tiled> {
        let plan = Plan::new(source, path, params, options)?;
        let flags = options.allow_external_uris as u8 | (options.keep_world_coordinates as u8) << 1;
        let mut tiled = Tiled {
            plan,
            params: params.clone(),
            input,
            flags,
            id: 0,
        };
        tiled.id = bytes::plan_id(&tiled.encode());
        Ok(tiled)
    }

    /// Tile `t` decomposed into its groups' hexahedra, as bytes.
    fn tile_of(
        &self,
        source: &Source,
        t: usize,
        local: &mut [u32],
        progress: &dyn Progress,
    ) -> Result<Vec<u8>> {
        let plan = &self.plan;
        let mut out = TileResult::default();
        if plan.tile_faces[t] > 0 {
            let mesh = tile_mesh(source, plan, t, local)?;
            let (lo, hi) = mesh.aabb();
            let lo = [0, 1, 2].map(|k| lo[k] + mesh.offset[k]);
            let hi = [0, 1, 2].map(|k| hi[k] + mesh.offset[k]);
            if (0..3).all(|k| lo[k] <= hi[k]) {
                out.used = Some((lo, hi));
            }
            if mesh.face_count() > 0 {
                let share = (plan.groups as u128 * plan.tile_faces[t] as u128 / plan.faces as u128)
                    as usize;
                let tile = TileProgress {
                    outer: progress,
                    done: t,
                    of: plan.tiles,
                };
                let params = tile_params(&self.params, share.max(1));
                let dec = crate::decompose::decompose_with(&mesh, &params, &tile)?;
                drop(mesh);
                for p in &dec.levels[0].primitives {
                    let tess = crate::output::tessellate(p, 4);
                    let base = out.positions.len() as u32;
                    out.positions.extend_from_slice(&tess.vertices);
                    for f in tess.faces.iter().filter(|f| f.len() >= 3) {
                        out.sizes.push(f.len() as u32);
                        out.corners.extend(f.iter().map(|&i| base + i));
                    }
                }
            }
        }
        Ok(out.encode(self.id, t))
    }
}

/// The top run's settings: every setting given as a share of the diagonal (a
/// tolerance, `min_extent`, `open_holes`, `min_thickness`, `remove_thin_boxes`) or
/// of the box's volume (`max_excess_volume`) is of the input's (`used`, its
/// corners), not of the tiles' boxes' (`boxes`), which stand a little beyond it; so a
/// tiled run is held to what the user asked for (to rounding, for all but the
/// tolerance, which becomes a distance).
fn of_input(params: &Params, used: (V3, V3), boxes: (V3, V3)) -> Params {
    let diagonal = |(lo, hi): (V3, V3)| crate::math::norm(crate::math::sub(hi, lo));
    let volume = |(lo, hi): (V3, V3)| (0..3).map(|k| hi[k] - lo[k]).product::<f64>();
    let ratio = |a: f64, b: f64| match a > 0.0 && b > 0.0 && (a / b).is_finite() {
        true => a / b,
        false => 1.0,
    };
    let (d, v) = (
        ratio(diagonal(used), diagonal(boxes)),
        ratio(volume(used), volume(boxes)),
    );
    let mut top = params.clone();
    top.fit.min_extent *= d;
    top.fit.max_excess_volume = top.fit.max_excess_volume.map(|m| m * v);
    top.plates.open_holes *= d;
    top.plates.min_thickness *= d;
    top.plates.remove_thin_boxes = top.plates.remove_thin_boxes.map(|t| t * d);
    if let Goal::Within { tolerance, .. } = &mut top.goal {
        let input = diagonal(used);
        for t in tolerance.iter_mut() {
            *t = Tolerance::Units(t.in_units(input));
        }
    }
    top
}

/// The tiles: slabs of the faces' centroids along the longest axis of the box.
#[derive(Debug)]
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

    /// The first bin of tile `t` ([`BINS`] for a tile without bins): tiles are runs
    /// of bins in order, so these give every bin's tile back.
    fn first_bin(&self, t: usize) -> usize {
        self.bin_tile.partition_point(|&b| (b as usize) < t)
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
        goal: Goal::Greedy {
            counts: vec![groups],
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
