//! A tiled run's plan and tile results as bytes, so that tiles can run on other
//! machines (a Ray cluster) and be cached between runs: small self-describing
//! little-endian records, each opening with an 8-byte magic and a version and closing
//! with an xxh3 checksum of everything before it. Reading checks the magic, the
//! version, the checksum, every count against the bytes that remain (before anything
//! is allocated), every number (finite, in range) and, for a tile, that it belongs to
//! this plan and is the tile asked for: a cached or shipped record is never trusted.
//!
//! Plan (`PDTPLAN\0`, version 1): the input's size (u64) and content hash (xxh3-128);
//! load flags (u8: bit 0 external glTF URIs allowed, bit 1 world coordinates kept);
//! the settings as their JSON (u32 length, UTF-8, the canonical form
//! `serde_json::to_string(&Params)` writes); tiles (u32), axis (u8), the slab axis'
//! lower bound and bins per unit (f64 each); faces, vertices, groups (u64 each); per
//! tile its first bin (u32) and its faces (u64); the checksum (u64).
//!
//! Tile (`PDTTILE\0`, version 1): the plan's id (xxh3-128 of the plan's bytes), the
//! tile index (u32); whether the box of its vertices follows (u8) and the box (six
//! f64); vertex, face and corner counts (u32 each), the positions (f64 × 3 each), each
//! face's corner count (u32), the corners (u32); the checksum (u64).

use super::{Plan, Tiled, BINS, MAX_TILES};
use crate::error::{Error, Result};
use crate::math::V3;
use crate::params::Params;
use std::path::PathBuf;
use xxhash_rust::xxh3::{xxh3_128, xxh3_64};

const PLAN_MAGIC: &[u8; 8] = b"PDTPLAN\0";
const TILE_MAGIC: &[u8; 8] = b"PDTTILE\0";
/// The version of both records this code writes and reads.
const VERSION: u32 = 1;

/// A tile's result: the closed hexahedra of its boxes and prisms, with the box of the
/// vertices its faces use (`None` for a tile without faces).
#[derive(Debug, Default)]
pub(super) struct TileResult {
    pub used: Option<(V3, V3)>,
    pub positions: Vec<V3>,
    /// Corners per face.
    pub sizes: Vec<u32>,
    pub corners: Vec<u32>,
}

/// The id a tile result names its plan by: the hash of the plan's bytes.
pub(super) fn plan_id(plan_bytes: &[u8]) -> u128 {
    xxh3_128(plan_bytes)
}

/// Appends little-endian values.
struct Writer(Vec<u8>);

impl Writer {
    fn u8(&mut self, v: u8) {
        self.0.push(v);
    }
    fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn u128(&mut self, v: u128) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    /// The checksum of everything written, appended: the finished record.
    fn finish(mut self) -> Vec<u8> {
        let sum = xxh3_64(&self.0);
        self.u64(sum);
        self.0
    }
}

/// Reads little-endian values, every failure an error naming the record and the byte.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    what: &'static str,
}

impl<'a> Reader<'a> {
    /// Checks the magic, the version and the checksum; the reader then stands after
    /// the version, with the checksum cut off.
    fn open(bytes: &'a [u8], magic: &[u8; 8], what: &'static str) -> Result<Reader<'a>> {
        let mut r = Reader { bytes, at: 0, what };
        if bytes.len() < 20 || &bytes[..8] != magic {
            return Err(r.bad(format!(
                "not a primdecomp {what} (it does not start with {:?})",
                String::from_utf8_lossy(&magic[..7])
            )));
        }
        r.at = 8;
        let version = r.u32()?;
        if version != VERSION {
            return Err(r.bad_at(
                8,
                format!("version {version}; this primdecomp reads version {VERSION}"),
            ));
        }
        let body = bytes.len() - 8;
        let sum = u64::from_le_bytes(bytes[body..].try_into().expect("8 bytes"));
        if xxh3_64(&bytes[..body]) != sum {
            return Err(r.bad_at(
                body,
                "checksum mismatch: the bytes were altered or truncated".into(),
            ));
        }
        r.bytes = &bytes[..body];
        Ok(r)
    }
    fn bad_at(&self, offset: usize, msg: String) -> Error {
        Error::ParseByte {
            path: PathBuf::from(format!("<tile {}>", self.what)),
            offset: offset as u64,
            msg,
        }
    }
    fn bad(&self, msg: String) -> Error {
        self.bad_at(self.at, msg)
    }
    fn take(&mut self, n: usize) -> Result<&'a [u8]> {
        if self.bytes.len() - self.at < n {
            return Err(self.bad(format!("the record ends early: {n} more bytes expected")));
        }
        self.at += n;
        Ok(&self.bytes[self.at - n..self.at])
    }
    fn u8(&mut self) -> Result<u8> {
        Ok(self.take(1)?[0])
    }
    fn u32(&mut self) -> Result<u32> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4")))
    }
    fn u64(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8")))
    }
    fn u128(&mut self) -> Result<u128> {
        Ok(u128::from_le_bytes(self.take(16)?.try_into().expect("16")))
    }
    /// A finite f64.
    fn f64(&mut self, name: &str) -> Result<f64> {
        let v = f64::from_le_bytes(self.take(8)?.try_into().expect("8"));
        match v.is_finite() {
            true => Ok(v),
            false => Err(self.bad_at(self.at - 8, format!("{name} is not finite ({v})"))),
        }
    }
    /// A count in `lo..=hi`.
    fn count(&mut self, v: u64, name: &str, lo: u64, hi: u64) -> Result<usize> {
        match (lo..=hi).contains(&v) {
            true => Ok(v as usize),
            false => Err(self.bad(format!("{name} {v} out of range [{lo}, {hi}]"))),
        }
    }
    /// Whether `items` records of `size` bytes fit in what remains.
    fn holds(&self, items: u64, size: u64, name: &str) -> Result<()> {
        let left = (self.bytes.len() - self.at) as u64;
        match items.checked_mul(size).is_some_and(|n| n <= left) {
            true => Ok(()),
            false => Err(self.bad(format!(
                "{items} {name} claimed, more than the {left} bytes left can hold"
            ))),
        }
    }
    fn end(&self) -> Result<()> {
        match self.at == self.bytes.len() {
            true => Ok(()),
            false => Err(self.bad(format!(
                "{} bytes after the end of the record",
                self.bytes.len() - self.at
            ))),
        }
    }
}

impl Tiled {
    /// The plan as bytes (the plan's own encoding, checked by [`Tiled::from_bytes`]).
    pub(super) fn encode(&self) -> Vec<u8> {
        let mut w = Writer(Vec::new());
        w.0.extend_from_slice(PLAN_MAGIC);
        w.u32(VERSION);
        w.u64(self.input.size);
        w.u128(self.input.hash);
        w.u8(self.flags);
        let settings = serde_json::to_string(&self.params).expect("settings serialize");
        w.u32(settings.len() as u32);
        w.0.extend_from_slice(settings.as_bytes());
        let p = &self.plan;
        w.u32(p.tiles as u32);
        w.u8(p.axis as u8);
        w.f64(p.lo);
        w.f64(p.scale);
        for n in [p.faces, p.vertices, p.groups] {
            w.u64(n as u64);
        }
        for t in 0..p.tiles {
            w.u32(p.first_bin(t) as u32);
            w.u64(p.tile_faces[t] as u64);
        }
        w.finish()
    }

    /// The plan in `bytes`, checked.
    pub(super) fn decode(bytes: &[u8]) -> Result<Tiled> {
        let mut r = Reader::open(bytes, PLAN_MAGIC, "plan")?;
        let input = super::Identity {
            size: r.u64()?,
            hash: r.u128()?,
        };
        let flags = r.u8()?;
        if flags & !3 != 0 {
            return Err(r.bad(format!("unknown load flags {flags:#x}")));
        }
        let params = r.settings()?;
        let plan = r.plan()?;
        r.end()?;
        Ok(Tiled {
            plan,
            params,
            input,
            flags,
            id: plan_id(bytes),
        })
    }
}

/// The plan's parts, in the order [`Tiled::encode`] writes them.
impl Reader<'_> {
    /// The settings, as JSON in their written form (length first).
    fn settings(&mut self) -> Result<Params> {
        let len = self.u32()? as u64;
        self.holds(len, 1, "bytes of settings")?;
        let at = self.at;
        let text = std::str::from_utf8(self.take(len as usize)?)
            .map_err(|e| self.bad_at(at, format!("the settings are not UTF-8: {e}")))?;
        let params = Params::from_json(text)
            .map_err(|e| self.bad_at(at, format!("the settings do not read: {e}")))?;
        if serde_json::to_string(&params).ok().as_deref() != Some(text) {
            return Err(self.bad_at(at, "the settings are not in their written form".into()));
        }
        Ok(params)
    }

    /// The slabs and the input's counts, then each tile's first bin and faces.
    fn plan(&mut self) -> Result<Plan> {
        let tiles = self.u32()? as u64;
        let tiles = self.count(tiles, "tile count", 1, MAX_TILES as u64)?;
        let axis = self.u8()? as u64;
        let axis = self.count(axis, "axis", 0, 2)?;
        let lo = self.f64("the slabs' lower bound")?;
        let scale = self.f64("bins per unit")?;
        if scale < 0.0 {
            return Err(self.bad(format!("bins per unit {scale} is negative")));
        }
        let faces = self.u64()?;
        let faces = self.count(faces, "face count", 1, u32::MAX as u64)?;
        let vertices = self.u64()?;
        let vertices = self.count(vertices, "vertex count", 1, u32::MAX as u64)?;
        let groups = self.u64()?;
        let groups = self.count(groups, "group count", 1, faces as u64)?;
        let (bin_tile, tile_faces) = self.tiles(tiles, faces)?;
        Ok(Plan {
            tiles,
            axis,
            lo,
            scale,
            bin_tile,
            tile_faces,
            faces,
            vertices,
            groups,
        })
    }

    /// Each bin's tile (a tile's first bins rising from 0) and each tile's faces,
    /// adding up to `faces`.
    fn tiles(&mut self, tiles: usize, faces: usize) -> Result<(Vec<u16>, Vec<usize>)> {
        self.holds(tiles as u64, 12, "tiles")?;
        let mut bin_tile = vec![0u16; BINS];
        let mut tile_faces = Vec::with_capacity(tiles);
        let mut previous = 0;
        for t in 0..tiles {
            let first = self.u32()? as u64;
            let lowest = if t == 0 { 0 } else { previous };
            let high = if t == 0 { 0 } else { BINS as u64 };
            let first = self.count(first, &format!("tile {t}'s first bin"), lowest, high)?;
            bin_tile[first..].fill(t as u16);
            previous = first as u64;
            let n = self.u64()?;
            tile_faces.push(self.count(n, &format!("tile {t}'s faces"), 0, faces as u64)?);
        }
        if tile_faces.iter().sum::<usize>() != faces {
            return Err(self.bad(format!("the tiles' faces do not add up to {faces}")));
        }
        Ok((bin_tile, tile_faces))
    }
}

impl TileResult {
    /// Tile `tile`'s result of the plan `plan_id` as bytes.
    pub(super) fn encode(&self, plan_id: u128, tile: usize) -> Vec<u8> {
        let mut w = Writer(Vec::new());
        w.0.extend_from_slice(TILE_MAGIC);
        w.u32(VERSION);
        w.u128(plan_id);
        w.u32(tile as u32);
        w.u8(self.used.is_some() as u8);
        if let Some((lo, hi)) = self.used {
            lo.iter().chain(&hi).for_each(|&v| w.f64(v));
        }
        w.u32(self.positions.len() as u32);
        w.u32(self.sizes.len() as u32);
        w.u32(self.corners.len() as u32);
        self.positions.iter().flatten().for_each(|&v| w.f64(v));
        self.sizes.iter().for_each(|&n| w.u32(n));
        self.corners.iter().for_each(|&c| w.u32(c));
        w.finish()
    }

    /// Tile `tile` of `tiled`'s plan from `bytes`, checked: the plan and the tile are
    /// the ones asked for, every position is finite, every face has at least three
    /// corners in range, and a tile holds no more faces than six per input face.
    pub(super) fn decode(bytes: &[u8], tiled: &Tiled, tile: usize) -> Result<TileResult> {
        let mut r = Reader::open(bytes, TILE_MAGIC, "result")?;
        r.this_tile(tiled.id, tile)?;
        let input_faces = tiled.plan.tile_faces[tile] as u64;
        let used = r.used_box(input_faces)?;
        let (nv, nf, nc) = (r.u32()? as u64, r.u32()? as u64, r.u32()? as u64);
        r.count(nf, "face count", 0, 6 * input_faces)?;
        r.holds(nv, 24, "vertices")?;
        r.holds(nv * 24 + nf * 4, 1, "bytes of vertices and faces")?;
        r.holds(
            nv * 24 + nf * 4 + nc * 4,
            1,
            "bytes of vertices, faces and corners",
        )?;
        let mut out = TileResult {
            used,
            ..TileResult::default()
        };
        out.positions.reserve(nv as usize);
        for _ in 0..nv {
            out.positions.push([
                r.f64("a position")?,
                r.f64("a position")?,
                r.f64("a position")?,
            ]);
        }
        r.faces(&mut out, nv, nf, nc)?;
        r.end()?;
        Ok(out)
    }
}

/// A tile result's parts, in the order [`TileResult::encode`] writes them.
impl Reader<'_> {
    /// Refuses a result of another plan than `plan_id` or another tile than `tile`.
    fn this_tile(&mut self, plan_id: u128, tile: usize) -> Result<()> {
        if self.u128()? != plan_id {
            return Err(self.bad_at(
                12,
                "made for another plan (another input, settings or tile count)".into(),
            ));
        }
        let index = self.u32()?;
        if index as usize != tile {
            return Err(self.bad_at(28, format!("holds tile {index}, not tile {tile}")));
        }
        Ok(())
    }

    /// The box the tile's output uses, if any: flagged, never empty, and only for a
    /// tile of `input_faces` > 0.
    fn used_box(&mut self, input_faces: u64) -> Result<Option<(V3, V3)>> {
        match self.u8()? {
            0 => Ok(None),
            1 => {
                let mut b = [0.0; 6];
                for v in &mut b {
                    *v = self.f64("the tile's box")?;
                }
                let (lo, hi) = ([b[0], b[1], b[2]], [b[3], b[4], b[5]]);
                if (0..3).any(|k| lo[k] > hi[k]) || input_faces == 0 {
                    return Err(
                        self.bad("the tile's box is empty or for a tile without faces".into())
                    );
                }
                Ok(Some((lo, hi)))
            }
            v => Err(self.bad(format!("the box flag is {v}, not 0 or 1"))),
        }
    }

    /// The `nf` faces' sizes (three corners or more, `nc` in all) and their `nc`
    /// corners, each one of the `nv` vertices.
    fn faces(&mut self, out: &mut TileResult, nv: u64, nf: u64, nc: u64) -> Result<()> {
        let mut total = 0u64;
        for _ in 0..nf {
            let n = self.u32()? as u64;
            out.sizes
                .push(self.count(n, "corners of a face", 3, nc)? as u32);
            total += n;
        }
        if total != nc {
            return Err(self.bad(format!("the faces hold {total} corners, not {nc}")));
        }
        if nc > 0 && nv == 0 {
            return Err(self.bad("corners without vertices".into()));
        }
        for _ in 0..nc {
            let c = self.u32()? as u64;
            out.corners
                .push(self.count(c, "corner", 0, nv.saturating_sub(1))? as u32);
        }
        Ok(())
    }
}
