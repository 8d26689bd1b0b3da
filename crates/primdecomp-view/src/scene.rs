//! What is shown: the input mesh (simplified for display), every level of our
//! result, the peers' hulls and the evaluation's distances, gathered from files.

use crate::geometry::Parts;
use crate::palette;
use crate::simplify::{self, Display};
use crate::source;
use primdecomp::{Error, Result};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// How a scene is built.
#[derive(Clone, Debug)]
pub struct Options {
    /// Segments around circles in the primitives' tessellation.
    pub detail: usize,
    /// The input mesh's display budget in triangles.
    pub display_triangles: usize,
    /// World up axis: 1 (y) or 2 (z).
    pub up_axis: usize,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            detail: 24,
            display_triangles: simplify::DISPLAY_TRIANGLES,
            up_axis: 1,
        }
    }
}

/// One collider: a level of our result or a peer's hulls.
#[derive(Clone, Debug)]
pub struct Collider {
    /// Short label: what the level asked for and reached (`count 150`, `tolerance 2%,
    /// reached 1.31%`), or the peer's name.
    pub label: String,
    /// The file it came from, as given.
    pub file: String,
    pub parts: Parts,
    pub detail: Detail,
}

/// What a collider's parts are.
#[derive(Clone, Debug)]
pub enum Detail {
    Primitives {
        target: Option<u64>,
        /// Each primitive's object in the result document (kind, parameters, faces).
        json: Vec<Value>,
        /// Storage by the paper's Table 2.
        bytes: usize,
    },
    Hulls {
        bytes: usize,
        /// Vertices and triangles per hull.
        sizes: Vec<(usize, usize)>,
    },
}

impl Collider {
    /// Parts per palette index (the six kinds, then hulls).
    pub fn counts(&self) -> [usize; 7] {
        let mut c = [0; 7];
        for &k in &self.parts.colour {
            c[k as usize] += 1;
        }
        c
    }
    pub fn bytes(&self) -> usize {
        match &self.detail {
            Detail::Primitives { bytes, .. } | Detail::Hulls { bytes, .. } => *bytes,
        }
    }
}

/// The input mesh as shown.
#[derive(Clone, Debug)]
pub struct Input {
    pub file: String,
    pub display: Display,
}

/// A row of an evaluation document (`primdecomp eval --json`) and the collider it
/// belongs to, if one of the scene's.
#[derive(Clone, Debug)]
pub struct EvalRow {
    pub collider: String,
    pub metrics: serde_json::Map<String, Value>,
    /// `levels[i]` or `peers[i]`: ("level", i) / ("peer", i).
    pub matches: Option<(&'static str, usize)>,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub input: Option<Input>,
    pub levels: Vec<Collider>,
    pub peers: Vec<Collider>,
    pub eval: Vec<EvalRow>,
    pub up_axis: usize,
}

impl Scene {
    /// Every vertex a triangle of the scene uses (input, all levels, all peers): what
    /// the default view is fitted to.
    pub fn points(&self) -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        let mut add = |pos: &[[f64; 3]], tris: &[[u32; 3]]| {
            let mut used = vec![false; pos.len()];
            for &i in tris.iter().flatten() {
                used[i as usize] = true;
            }
            out.extend(pos.iter().zip(used).filter(|x| x.1).map(|x| *x.0));
        };
        if let Some(i) = &self.input {
            add(&i.display.positions, &i.display.triangles);
        }
        for c in self.levels.iter().chain(&self.peers) {
            add(&c.parts.positions, &c.parts.triangles);
        }
        out
    }

    /// The bounding box of everything shown, if anything is.
    pub fn aabb(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut boxes: Vec<([f64; 3], [f64; 3])> = Vec::new();
        if let Some(i) = &self.input {
            boxes.extend(crate::geometry::aabb(
                &i.display.positions,
                &i.display.triangles,
            ));
        }
        for c in self.levels.iter().chain(&self.peers) {
            boxes.extend(c.parts.aabb());
        }
        boxes.into_iter().reduce(|(a, b), (c, d)| {
            (
                [0, 1, 2].map(|k| a[k].min(c[k])),
                [0, 1, 2].map(|k| b[k].max(d[k])),
            )
        })
    }
}

fn read_text(path: &Path) -> Result<String> {
    let bytes = std::fs::read(path).map_err(|error| Error::Io {
        path: path.to_path_buf(),
        error,
    })?;
    String::from_utf8(bytes).map_err(|e| {
        Error::byte(
            path,
            e.utf8_error().valid_up_to() as u64,
            "the file is not UTF-8",
        )
    })
}

fn parse_json(path: &Path, text: &str) -> Result<Value> {
    serde_json::from_str(text).map_err(|e| Error::format(path, format!("invalid JSON: {e}")))
}

/// The files a result argument names: the file itself, or, when it does not exist,
/// the per-target files a multi-target run wrote for that `-o` (`out.json` →
/// `out_n200.json`, `out_n50.json`), largest target first.
pub fn result_files(path: &Path) -> Vec<PathBuf> {
    if path.exists() {
        return vec![path.to_path_buf()];
    }
    let (Some(stem), Some(dir)) = (path.file_stem(), path.parent()) else {
        return vec![path.to_path_buf()];
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let ext = path.extension().map(|e| e.to_string_lossy().into_owned());
    let prefix = format!("{}_n", stem.to_string_lossy());
    let mut found: Vec<(u64, PathBuf)> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let p = e.path();
            let name = p.file_stem()?.to_string_lossy().into_owned();
            let n: u64 = name.strip_prefix(&prefix)?.parse().ok()?;
            (p.extension().map(|e| e.to_string_lossy().into_owned()) == ext).then_some((n, p))
        })
        .collect();
    if found.is_empty() {
        return vec![path.to_path_buf()];
    }
    found.sort_by(|a, b| b.0.cmp(&a.0).then_with(|| a.1.cmp(&b.1)));
    let base = path.parent().unwrap_or(Path::new(""));
    found
        .into_iter()
        .map(|(_, p)| base.join(p.file_name().unwrap_or_default()))
        .collect()
}

/// The levels of one result file: a primdecomp document, or a document whose
/// `levels` array holds one such document per target.
pub fn load_levels(path: &Path, opts: &Options) -> Result<Vec<Collider>> {
    let text = read_text(path)?;
    let doc = parse_json(path, &text)?;
    let docs: Vec<&Value> = match doc.get("levels").and_then(Value::as_array) {
        Some(levels) => levels.iter().collect(),
        None => vec![&doc],
    };
    if docs.is_empty() {
        return Err(Error::format(path, "the `levels` array is empty"));
    }
    docs.into_iter()
        .enumerate()
        .map(|(i, d)| {
            level(path, d, opts).map_err(|e| match (e, doc.get("levels").is_some()) {
                (Error::Format { path, msg }, true) => Error::Format {
                    path,
                    msg: format!("level {i}: {msg}"),
                },
                (e, _) => e,
            })
        })
        .collect()
}

fn level(path: &Path, doc: &Value, opts: &Options) -> Result<Collider> {
    let prims = source::read_primitives(&doc.to_string(), path)?;
    if prims.is_empty() {
        return Err(Error::format(path, "the document has no primitives"));
    }
    let json = doc
        .get("primitives")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let mut parts = Parts::new();
    let mut bytes = 0;
    for p in &prims {
        let (v, f) = source::tessellate(p, opts.detail);
        let kind = source::kind(p);
        parts.push_polygons(&v, &f, kind as u8);
        bytes += kind.bytes();
    }
    let target = doc
        .get("settings")
        .and_then(|s| s.get("target"))
        .and_then(Value::as_u64);
    let label = level_label(doc).unwrap_or_else(|| file_label(path));
    Ok(Collider {
        label,
        file: path.display().to_string(),
        parts,
        detail: Detail::Primitives {
            target,
            json,
            bytes,
        },
    })
}

/// A level's label: what was asked (a tolerance, a byte size, or a count) and, for a
/// cut, what was reached (the farthest distance, or the bytes used); `None` for a
/// document without `settings.target`.
pub fn level_label(doc: &Value) -> Option<String> {
    let target = doc.get("settings")?.get("target")?.as_u64()?;
    let distance = doc.get("stats").and_then(|s| s.get("distance"));
    let get = |k: &str| distance.and_then(|d| d.get(k)).and_then(Value::as_f64);
    let diagonal = diagonal(doc);
    // A distance as the user gives it: a percentage of the diagonal when the input's
    // bounds are known, else in input units.
    let show = |d: f64| match diagonal {
        Some(g) if g > 0.0 => format!("{}%", short(100.0 * d / g)),
        _ => short(d),
    };
    let worst = get("worst");
    let label = match (get("tolerance"), get("max_bytes")) {
        (Some(t), _) => format!("tolerance {}", show(t)),
        (None, Some(b)) => format!("max {} bytes", b as u64),
        (None, None) => format!("count {target}"),
    };
    Some(match worst {
        Some(w) => format!("{label}, reached {}", show(w)),
        None => label,
    })
}

/// The input's bounding-box diagonal recorded in a result document.
fn diagonal(doc: &Value) -> Option<f64> {
    let input = doc.get("input")?;
    let corner = |k: &str| -> Option<Vec<f64>> {
        input
            .get(k)?
            .as_array()?
            .iter()
            .map(Value::as_f64)
            .collect()
    };
    let (lo, hi) = (corner("aabb_min")?, corner("aabb_max")?);
    (lo.len() == 3 && hi.len() == 3)
        .then(|| (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt())
}

/// Three significant digits, without trailing zeros.
fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.digits$}");
    match s.contains('.') {
        true => s.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => s,
    }
}

fn file_label(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// A peer's hulls from an OBJ file; `label` names it (default: from the path, e.g.
/// `coacd` for `…-coacd-…/hulls.obj` or the file name).
pub fn load_peer(path: &Path, label: Option<&str>) -> Result<Collider> {
    let hulls = source::load_hulls(path)?;
    if hulls.is_empty() {
        return Err(Error::format(path, "the file has no hull with faces"));
    }
    let mut parts = Parts::new();
    let mut sizes = Vec::new();
    let mut bytes = 0;
    for (v, t) in &hulls {
        parts.push_triangles(v, t, palette::HULL);
        sizes.push((v.len(), t.len()));
        // The paper's Table 2: 3 floats per vertex, 3 uint16 per triangle.
        bytes += 12 * v.len() + 6 * t.len();
    }
    Ok(Collider {
        label: label.map(str::to_owned).unwrap_or_else(|| peer_label(path)),
        file: path.display().to_string(),
        parts,
        detail: Detail::Hulls { bytes, sizes },
    })
}

/// A peer's name from its path: CoACD or V-HACD when a path component says so (as
/// benches/compare's cache does), else the file name.
pub fn peer_label(path: &Path) -> String {
    let s = path.display().to_string().to_ascii_lowercase();
    if s.contains("coacd-paper") {
        "CoACD (paper settings)".into()
    } else if s.contains("coacd") {
        "CoACD".into()
    } else if s.contains("vhacd") || s.contains("v-hacd") {
        "V-HACD".into()
    } else {
        file_label(path)
    }
}

/// The input mesh, loaded and prepared for display.
pub fn load_input(path: &Path, opts: &Options) -> Result<Input> {
    let mesh = source::load_input(path)?;
    Ok(input_from(path, &mesh, opts))
}

/// An input mesh already in memory (`decompose --png`).
pub fn input_from(path: &Path, mesh: &source::InputMesh, opts: &Options) -> Input {
    Input {
        file: path.display().to_string(),
        display: simplify::display(mesh, opts.display_triangles),
    }
}

/// The rows of an evaluation document, matched to the scene's colliders by path.
pub fn load_eval(path: &Path, levels: &[Collider], peers: &[Collider]) -> Result<Vec<EvalRow>> {
    let text = read_text(path)?;
    let doc = parse_json(path, &text)?;
    let rows = doc
        .get("colliders")
        .and_then(Value::as_array)
        .ok_or_else(|| {
            Error::format(
                path,
                "not an evaluation document: no `colliders` array (write one with `primdecomp eval ... --json FILE`)",
            )
        })?;
    let same = |a: &str, b: &str| {
        a == b
            || match (Path::new(a).canonicalize(), Path::new(b).canonicalize()) {
                (Ok(x), Ok(y)) => x == y,
                _ => false,
            }
    };
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            let metrics = r
                .as_object()
                .cloned()
                .ok_or_else(|| Error::format(path, format!("colliders[{i}] is not an object")))?;
            let collider = metrics
                .get("collider")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_owned();
            let matches = levels
                .iter()
                .position(|c| same(&c.file, &collider))
                .map(|i| ("level", i))
                .or_else(|| {
                    peers
                        .iter()
                        .position(|c| same(&c.file, &collider))
                        .map(|i| ("peer", i))
                });
            Ok(EvalRow {
                collider,
                metrics,
                matches,
            })
        })
        .collect()
}
