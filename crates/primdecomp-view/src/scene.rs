//! What is shown: the input mesh (simplified for display), every level of our
//! result, the peers' hulls and the evaluation's distances, gathered from files.

use crate::geometry::Parts;
use crate::palette;
use crate::simplify::{self, Display};
use crate::source;
use primdecomp::{Error, Primitive};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Results with the library's one error type.
type Result<T> = std::result::Result<T, Error>;

/// How a scene is built.
#[derive(Clone, Debug)]
pub struct Options {
    /// Segments around circles in the primitives' tessellation.
    pub detail: usize,
    /// The input mesh's display budget in triangles.
    pub display_triangles: usize,
    /// World up axis: 1 (y) or 2 (z).
    pub up_axis: usize,
    /// How the input mesh is read: the memory limit (an input whose decomposition
    /// would need more is refused, as by `decompose`) and the glTF URI policy.
    pub load: primdecomp::LoadOptions,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            detail: 24,
            display_triangles: simplify::DISPLAY_TRIANGLES,
            up_axis: 1,
            load: primdecomp::LoadOptions::default(),
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

/// The most parts (primitives and hulls, over every level and peer) one page or
/// picture shows: a browser draws about that many without stalling, and the
/// display geometry stays within [`MAX_PART_TRIANGLES`] at the coarsest detail.
pub const MAX_PARTS: usize = 65_536;

/// The most triangles the parts of a page may have: the primitives' tessellation is
/// made coarser (fewer segments around circles) to stay within it ([`fit_detail`]),
/// and peers' hulls beyond it are refused. With the input's display budget this
/// keeps a page to some tens of MB.
pub const MAX_PART_TRIANGLES: usize = 2_000_000;

/// The coarsest tessellation [`fit_detail`] goes down to: segments around circles.
pub const MIN_DETAIL: usize = 6;

/// The most rows of an evaluation document the page takes (one per collider).
pub const MAX_EVAL_ROWS: usize = 4096;

/// A file read whole: a regular file of at most `MAX_RESULT_BYTES`, in UTF-8.
fn read_text(path: &Path) -> Result<String> {
    let bytes = primdecomp_files::read_regular(path, primdecomp::ResultFile::MAX_BYTES)?;
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

/// One level of a result as read: its primitives (checked by the core's reader), each
/// primitive's JSON object (only the contract's keys), its target and its label.
#[derive(Clone, Debug)]
pub struct LevelDoc {
    pub path: PathBuf,
    pub primitives: Vec<Primitive>,
    pub json: Vec<Value>,
    pub target: Option<u64>,
    /// What was asked and reached ([`level_label`]), when the document says.
    pub label: Option<String>,
}

/// The keys of a primitive's JSON object that the page shows (the result contract's):
/// anything else a document carries stays out of the page.
const PRIMITIVE_KEYS: [&str; 15] = [
    "kind",
    "center",
    "rotation",
    "half_extents",
    "radius",
    "p0",
    "p1",
    "radius0",
    "radius1",
    "half_x",
    "half_y",
    "half_z_top",
    "half_z_bottom",
    "shift_z",
    "faces",
];

/// The levels of one result file: a primdecomp document, or a document whose
/// `levels` array holds one such document per target.
pub fn read_levels(path: &Path) -> Result<Vec<LevelDoc>> {
    let text = read_text(path)?;
    let doc = parse_json(path, &text)?;
    let docs: Vec<&Value> = match doc.get("levels").and_then(Value::as_array) {
        Some(levels) => levels.iter().collect(),
        None => vec![&doc],
    };
    if docs.is_empty() {
        return Err(Error::format(path, "the `levels` array is empty"));
    }
    let wrapped = doc.get("levels").is_some();
    docs.into_iter()
        .enumerate()
        .map(|(i, d)| {
            read_level(path, d).map_err(|e| match (e, wrapped) {
                (Error::Format { path, msg }, true) => Error::Format {
                    path,
                    msg: format!("level {i}: {msg}"),
                },
                (e, _) => e,
            })
        })
        .collect()
}

fn read_level(path: &Path, doc: &Value) -> Result<LevelDoc> {
    let primitives = source::read_primitives(&doc.to_string(), path)?;
    if primitives.is_empty() {
        return Err(Error::format(path, "the document has no primitives"));
    }
    let json = doc
        .get("primitives")
        .and_then(Value::as_array)
        .map(|ps| {
            ps.iter()
                .map(|p| {
                    let mut m = serde_json::Map::new();
                    for k in PRIMITIVE_KEYS {
                        if let Some(v) = p.get(k) {
                            m.insert(k.into(), v.clone());
                        }
                    }
                    Value::Object(m)
                })
                .collect()
        })
        .unwrap_or_default();
    let target = doc
        .get("settings")
        .and_then(|s| s.get("target"))
        .and_then(Value::as_u64);
    Ok(LevelDoc {
        path: path.to_path_buf(),
        primitives,
        json,
        target,
        label: level_label(doc),
    })
}

/// A level's parts tessellated with `detail` segments around circles.
pub fn build_level(doc: &LevelDoc, detail: usize) -> Collider {
    let mut parts = Parts::new();
    let mut bytes = 0;
    for p in &doc.primitives {
        let (v, f) = source::tessellate(p, detail);
        let kind = source::kind(p);
        parts.push_polygons(&v, &f, kind as u8);
        bytes += kind.bytes();
    }
    let label = doc.label.clone().unwrap_or_else(|| file_label(&doc.path));
    Collider {
        label,
        file: doc.path.display().to_string(),
        parts,
        detail: Detail::Primitives {
            target: doc.target,
            json: doc.json.clone(),
            bytes,
        },
    }
}

/// The levels of one result file ([`read_levels`]) tessellated at `opts.detail`.
pub fn load_levels(path: &Path, opts: &Options) -> Result<Vec<Collider>> {
    Ok(read_levels(path)?
        .iter()
        .map(|d| build_level(d, opts.detail))
        .collect())
}

/// Triangles of a primitive's tessellation at `detail`.
fn triangles(p: &Primitive, detail: usize) -> usize {
    let (_, f) = source::tessellate(p, detail);
    f.iter().map(|f| f.len().saturating_sub(2)).sum()
}

/// The finest detail, at most `asked` and at least [`MIN_DETAIL`] (or `asked` if
/// lower), at which `levels`' tessellations and `hull_triangles` more stay within
/// [`MAX_PART_TRIANGLES`]; refuses more than [`MAX_PARTS`] parts, and peers' hulls over
/// the budget on their own. Linear in the primitives: each kind is tessellated once
/// per detail tried.
pub fn fit_detail(
    levels: &[LevelDoc],
    hulls: usize,
    hull_triangles: usize,
    asked: usize,
) -> std::result::Result<usize, String> {
    let parts = levels.iter().map(|l| l.primitives.len()).sum::<usize>() + hulls;
    if parts > MAX_PARTS {
        return Err(format!(
            "{parts} parts (primitives and hulls) to show, more than the {MAX_PARTS} a page \
             shows; view fewer levels, or a coarser one"
        ));
    }
    if hull_triangles > MAX_PART_TRIANGLES {
        return Err(format!(
            "the peers' hulls have {hull_triangles} triangles, more than the \
             {MAX_PART_TRIANGLES} a page shows"
        ));
    }
    // One primitive of each kind stands for all of its kind.
    let mut by_kind: [(Option<&Primitive>, usize); 6] = [(None, 0); 6];
    for p in levels.iter().flat_map(|l| &l.primitives) {
        let e = &mut by_kind[source::kind(p) as usize];
        e.0.get_or_insert(p);
        e.1 += 1;
    }
    let total = |d: usize| -> usize {
        by_kind
            .iter()
            .filter_map(|(p, n)| p.map(|p| triangles(p, d) * n))
            .sum::<usize>()
            + hull_triangles
    };
    let mut d = asked;
    while d > MIN_DETAIL && total(d) > MAX_PART_TRIANGLES {
        d -= 1;
    }
    Ok(d)
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
    let mesh = source::load_input(path, &opts.load)?;
    Ok(input_from(path, &mesh, opts))
}

/// An input mesh already in memory (`decompose --png`).
pub fn input_from(path: &Path, mesh: &source::InputMesh, opts: &Options) -> Input {
    Input {
        file: path.display().to_string(),
        display: simplify::display(mesh, opts.display_triangles),
    }
}

/// A JSON value (or its absence) for a message, control characters made visible and
/// cut to 40 characters.
fn show(v: Option<&Value>) -> String {
    let s = v.map_or("absent".to_string(), |v| {
        primdecomp_files::visible(&v.to_string())
    });
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s
    }
}

/// The rows of an evaluation document, matched to the scene's colliders by path.
pub fn load_eval(path: &Path, levels: &[Collider], peers: &[Collider]) -> Result<Vec<EvalRow>> {
    let text = read_text(path)?;
    let doc = parse_json(path, &text)?;
    check_eval_kind(path, &doc)?;
    let rows = doc
        .get("colliders")
        .and_then(Value::as_array)
        .ok_or_else(|| {
            Error::format(
                path,
                "not an evaluation document: no `colliders` array (write one with `primdecomp eval ... --json FILE`)",
            )
        })?;
    if rows.len() > MAX_EVAL_ROWS {
        return Err(Error::format(
            path,
            format!(
                "{} rows in `colliders`, more than the {MAX_EVAL_ROWS} a page shows",
                rows.len()
            ),
        ));
    }
    (rows.iter().enumerate())
        .map(|(i, r)| eval_row(path, (i, r), levels, peers))
        .collect()
}

/// Refuses a document whose `format` is not an evaluation's or whose `version` is
/// not the one this primdecomp reads.
fn check_eval_kind(path: &Path, doc: &Value) -> Result<()> {
    let (format, version) = (doc.get("format"), doc.get("version"));
    let want = "(write one with `primdecomp eval ... --json FILE`)";
    if format.and_then(Value::as_str) != Some(primdecomp_eval::report::FORMAT) {
        return Err(Error::format(
            path,
            format!(
                "not an evaluation document: its \"format\" is {}, not \"{}\" {want}",
                show(format),
                primdecomp_eval::report::FORMAT
            ),
        ));
    }
    if version.and_then(Value::as_u64) != Some(primdecomp_eval::report::VERSION) {
        return Err(Error::format(
            path,
            format!(
                "the evaluation's \"version\" is {}; this primdecomp reads version {} {want}",
                show(version),
                primdecomp_eval::report::VERSION
            ),
        ));
    }
    Ok(())
}

/// Row `i` of `colliders` (`r`): only what the page shows, the collider's name and
/// the metrics' numbers, matched to a level's or else a peer's collider by path.
fn eval_row(
    path: &Path,
    (i, r): (usize, &Value),
    levels: &[Collider],
    peers: &[Collider],
) -> Result<EvalRow> {
    let row = r
        .as_object()
        .ok_or_else(|| Error::format(path, format!("colliders[{i}] is not an object")))?;
    let mut metrics = serde_json::Map::new();
    for (k, v) in row {
        let keep = match k.as_str() {
            "collider" => v.is_string(),
            "counts" | "matches" => false,
            _ => v.is_number(),
        };
        if keep {
            metrics.insert(k.clone(), v.clone());
        }
    }
    let collider = metrics
        .get("collider")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_owned();
    let matches = levels
        .iter()
        .position(|c| same_file(&c.file, &collider))
        .map(|i| ("level", i))
        .or_else(|| {
            peers
                .iter()
                .position(|c| same_file(&c.file, &collider))
                .map(|i| ("peer", i))
        });
    Ok(EvalRow {
        collider,
        metrics,
        matches,
    })
}

/// Whether two paths name the same file: equal, or equal once canonical.
fn same_file(a: &str, b: &str) -> bool {
    a == b
        || match (Path::new(a).canonicalize(), Path::new(b).canonicalize()) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
}
