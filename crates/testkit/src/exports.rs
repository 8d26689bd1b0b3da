//! Readers of the engine exports for the tests and the `exports` fuzz target: each
//! checks that a file is well formed in its format's grammar (as far as we parse it:
//! XML 1.0 by quick-xml for MJCF and URDF, the glTF JSON schema by the `gltf` crate
//! and the physics extensions' constraints, the USD text and Godot `.tscn` grammars of
//! what the writers emit), that every number is finite and within f32's range, that
//! names are unique where the consumers key by them, and returns the object names
//! and the files the export refers to. Compiled into the fuzz target as is (`#[path]`),
//! so it uses no other module of this crate.

use std::collections::{HashMap, HashSet};

/// What a well-formed export holds: its objects' names as a consumer reads them
/// (MJCF bodies, URDF links below the root, USD `primdecomp:name`, Godot
/// `metadata/primdecomp_name`, glTF scene nodes), and the files it refers to (URDF
/// meshes, relative to the URDF).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Checked {
    pub names: Vec<String>,
    pub files: Vec<String>,
    /// The objects' identifiers where the format takes identifiers (USD prim names,
    /// Godot node names).
    pub idents: Vec<String>,
}

/// f32's largest finite value: every number must load as a finite 32-bit float.
const F32_MAX: f64 = f32::MAX as f64;

fn number(tok: &str) -> Result<f64, String> {
    let x: f64 = tok
        .parse()
        .map_err(|_| format!("'{tok}' is not a number"))?;
    if x.is_finite() && x.abs() <= F32_MAX {
        Ok(x)
    } else {
        Err(format!("{tok} is not a finite 32-bit float"))
    }
}

fn numbers(s: &str, n: Option<usize>) -> Result<Vec<f64>, String> {
    let v = s
        .split_ascii_whitespace()
        .map(number)
        .collect::<Result<Vec<_>, _>>()?;
    match n {
        Some(n) if v.len() != n => Err(format!("'{s}': {} numbers, not {n}", v.len())),
        _ => Ok(v),
    }
}

/// The XML 1.0 `Char` production (what a document may hold at all).
fn xml_char(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{d7ff}' | '\u{e000}'..='\u{fffd}' | '\u{10000}'..)
}

/// One element: its name, attributes (unescaped) and parent.
struct Elem {
    name: String,
    attrs: HashMap<String, String>,
    parent: Option<usize>,
}

impl Elem {
    fn get(&self, k: &str) -> Result<&str, String> {
        self.attrs
            .get(k)
            .map(String::as_str)
            .ok_or_else(|| format!("<{}> has no {k}", self.name))
    }
}

/// Parses an XML document with quick-xml (end names checked, attributes unescaped
/// and checked for duplicates) into its elements.
fn xml(text: &str) -> Result<Vec<Elem>, String> {
    use quick_xml::events::Event;
    if let Some(c) = text.chars().find(|&c| !xml_char(c)) {
        return Err(format!(
            "character U+{:04X} is not allowed in XML 1.0",
            c as u32
        ));
    }
    let mut r = quick_xml::Reader::from_str(text);
    r.config_mut().check_end_names = true;
    let mut elems: Vec<Elem> = Vec::new();
    let mut stack: Vec<usize> = Vec::new();
    let mut roots = 0;
    loop {
        let ev = r.read_event().map_err(|e| format!("XML: {e}"))?;
        let (start, empty) = match &ev {
            Event::Start(e) => (Some(e.clone()), false),
            Event::Empty(e) => (Some(e.clone()), true),
            Event::End(_) => {
                stack.pop();
                continue;
            }
            Event::Eof => break,
            Event::Text(t) if !t.chars().all(|c| c.is_ascii_whitespace()) => {
                return Err("text outside the elements".into())
            }
            Event::DocType(_) | Event::PI(_) | Event::CData(_) | Event::GeneralRef(_) => {
                return Err("unexpected XML construct".into())
            }
            _ => (None, false),
        };
        let Some(e) = start else { continue };
        let mut attrs = HashMap::new();
        for a in e.attributes() {
            let a = a.map_err(|e| format!("XML attribute: {e}"))?;
            let v = a
                .normalized_value(quick_xml::XmlVersion::Explicit1_0)
                .map_err(|e| format!("XML attribute value: {e}"))?;
            attrs.insert(a.key.0.to_string(), v.into_owned());
        }
        if stack.is_empty() {
            roots += 1;
        }
        elems.push(Elem {
            name: e.name().0.to_string(),
            attrs,
            parent: stack.last().copied(),
        });
        if !empty {
            stack.push(elems.len() - 1);
        }
    }
    if roots != 1 || !stack.is_empty() {
        return Err("not one closed root element".into());
    }
    Ok(elems)
}

fn unique<'a>(what: &str, names: impl IntoIterator<Item = &'a str>) -> Result<(), String> {
    let mut seen = HashSet::new();
    for n in names {
        if !seen.insert(n) {
            return Err(format!("{what} name {n:?} is repeated"));
        }
    }
    Ok(())
}

/// A MuJoCo MJCF document as `primdecomp export --format mjcf` writes it.
pub fn mjcf(text: &str) -> Result<Checked, String> {
    let e = xml(text)?;
    if e[0].name != "mujoco" {
        return Err("the root is not <mujoco>".into());
    }
    let of = |n: &'static str| e.iter().filter(move |x| x.name == n);
    let bodies: Vec<&str> = of("body")
        .map(|b| b.get("name"))
        .collect::<Result<_, _>>()?;
    unique("body", bodies.iter().copied())?;
    if bodies.contains(&"world") {
        return Err("a body is named 'world', MuJoCo's world body".into());
    }
    unique(
        "geom",
        of("geom").filter_map(|g| g.attrs.get("name").map(String::as_str)),
    )?;
    let meshes: Vec<&str> = of("mesh")
        .map(|m| m.get("name"))
        .collect::<Result<_, _>>()?;
    unique("mesh", meshes.iter().copied())?;
    for m in of("mesh") {
        let v = numbers(m.get("vertex")?, None)?;
        if v.len() < 12 || v.len() % 3 != 0 {
            return Err(format!(
                "mesh {:?}: {} vertex numbers",
                m.get("name")?,
                v.len()
            ));
        }
    }
    for b in of("body") {
        numbers(b.get("pos")?, Some(3))?;
        numbers(b.get("quat")?, Some(4))?;
    }
    for g in of("geom") {
        let size = numbers(g.get("size").unwrap_or("1"), None)?;
        if size.iter().any(|&s| s <= 0.0) {
            return Err(format!("geom {:?}: a size is not positive", g.get("name")?));
        }
        for (k, n) in [("pos", 3), ("quat", 4), ("fromto", 6)] {
            if let Some(v) = g.attrs.get(k) {
                numbers(v, Some(n))?;
            }
        }
        if g.get("type")? == "mesh" && !meshes.contains(&g.get("mesh")?) {
            return Err(format!("geom {:?} names no mesh", g.get("name")?));
        }
    }
    Ok(Checked {
        names: bodies.into_iter().map(String::from).collect(),
        ..Checked::default()
    })
}

/// A relative file name an export refers to: `/`-separated components of letters,
/// digits, `_`, `-` and `.` (not `.` or `..`), each at most 255 bytes.
pub fn file_name(rel: &str) -> Result<(), String> {
    let ok = !rel.is_empty()
        && rel.split('/').all(|c| {
            !c.is_empty()
                && c != "."
                && c != ".."
                && c.len() <= 255
                && c.bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b"_-.".contains(&b))
        });
    if ok {
        Ok(())
    } else {
        Err(format!("{rel:?} is not a valid relative file name"))
    }
}

/// A URDF document as `primdecomp export` writes it.
pub fn urdf(text: &str) -> Result<Checked, String> {
    let e = xml(text)?;
    if e[0].name != "robot" {
        return Err("the root is not <robot>".into());
    }
    let of = |n: &'static str| e.iter().filter(move |x| x.name == n && x.parent == Some(0));
    let links: Vec<&str> = of("link")
        .map(|l| l.get("name"))
        .collect::<Result<_, _>>()?;
    unique("link", links.iter().copied())?;
    let joints: Vec<&str> = of("joint")
        .map(|j| j.get("name"))
        .collect::<Result<_, _>>()?;
    unique("joint", joints.iter().copied())?;
    let children = joint_children(&e, &links)?;
    unique("joint child", children.iter().copied())?;
    let files = urdf_values(&e)?;
    // The root link is the one no joint has as its child.
    let names = links
        .iter()
        .filter(|l| children.contains(l))
        .map(|l| l.to_string())
        .collect();
    Ok(Checked {
        names,
        files,
        ..Checked::default()
    })
}

/// Each joint's child link, every joint's parent and child naming a link of `links`.
fn joint_children<'a>(e: &'a [Elem], links: &[&str]) -> Result<Vec<&'a str>, String> {
    let mut children = Vec::new();
    for (i, j) in e.iter().enumerate().filter(|(_, x)| x.name == "joint") {
        let link = |tag: &str| -> Result<&'a str, String> {
            let l = e
                .iter()
                .find(|x| x.name == tag && x.parent == Some(i))
                .ok_or_else(|| format!("joint {:?} has no <{tag}>", j.attrs.get("name")))?
                .get("link")?;
            if links.contains(&l) {
                Ok(l)
            } else {
                Err(format!("joint {:?}: no link {l:?}", j.attrs.get("name")))
            }
        };
        link("parent")?;
        children.push(link("child")?);
    }
    Ok(children)
}

/// Checks the URDF's origins and shape sizes; returns the mesh files it names.
fn urdf_values(e: &[Elem]) -> Result<Vec<String>, String> {
    let mut files = Vec::new();
    for x in e {
        match x.name.as_str() {
            "origin" => {
                numbers(x.get("xyz")?, Some(3))?;
                numbers(x.get("rpy")?, Some(3))?;
            }
            "box" if numbers(x.get("size")?, Some(3))?.iter().any(|&s| s <= 0.0) => {
                return Err("a box size is not positive".into());
            }
            "sphere" | "cylinder" | "capsule" => {
                for k in ["radius", "length"] {
                    if let Some(v) = x.attrs.get(k) {
                        if numbers(v, Some(1))?[0] <= 0.0 {
                            return Err(format!("a {} {k} is not positive", x.name));
                        }
                    }
                }
            }
            "mesh" => {
                let f = x.get("filename")?;
                file_name(f)?;
                files.push(f.to_string());
            }
            _ => {}
        }
    }
    Ok(files)
}

/// Tokens of the USD text and `.tscn` grammars as the writers emit them.
#[derive(Debug, PartialEq)]
enum Tok {
    Str(String),
    Num(f64),
    Word(String),
    Punct(char),
}

/// Tokenizes `text`: strings in double quotes (escapes `\\`, `\"` and the letters
/// `n t r`; no raw control character or line end inside), numbers (finite, within
/// f32), words (letters, digits, `_ : / . -` not starting as a number), punctuation;
/// `#` comments when `comments`. Brackets must balance.
fn tokens(text: &str, comments: bool) -> Result<Vec<Tok>, String> {
    let mut out = Vec::new();
    let mut depth: Vec<char> = Vec::new();
    let mut it = text.char_indices().peekable();
    while let Some((i, c)) = it.next() {
        match c {
            c if c.is_whitespace() => {}
            '#' if comments => {
                while it.peek().is_some_and(|&(_, c)| c != '\n') {
                    it.next();
                }
            }
            '"' => out.push(Tok::Str(quoted(&mut it)?)),
            '(' | '[' | '{' => {
                depth.push(c);
                out.push(Tok::Punct(c));
            }
            ')' | ']' | '}' => {
                let open = match c {
                    ')' => '(',
                    ']' => '[',
                    _ => '{',
                };
                if depth.pop() != Some(open) {
                    return Err(format!("unbalanced '{c}' at byte {i}"));
                }
                out.push(Tok::Punct(c));
            }
            '=' | ',' | '<' | '>' => out.push(Tok::Punct(c)),
            c if word_char(c) => out.push(word(c, &mut it)?),
            c if c.is_control() => return Err(format!("raw control character U+{:04X}", c as u32)),
            c => return Err(format!("unexpected character {c:?} at byte {i}")),
        }
    }
    if !depth.is_empty() {
        return Err("unclosed bracket".into());
    }
    Ok(out)
}

/// The characters tokenized as `tokens` goes.
type Chars<'a> = std::iter::Peekable<std::str::CharIndices<'a>>;

/// A string's contents after its opening quote, through its closing one.
fn quoted(it: &mut Chars) -> Result<String, String> {
    let mut s = String::new();
    loop {
        let Some((_, c)) = it.next() else {
            return Err("a string does not end".into());
        };
        match c {
            '"' => return Ok(s),
            '\\' => match it.next().map(|x| x.1) {
                Some('\\') => s.push('\\'),
                Some('"') => s.push('"'),
                Some('n') => s.push('\n'),
                Some('t') => s.push('\t'),
                Some('r') => s.push('\r'),
                e => return Err(format!("bad escape \\{e:?} in a string")),
            },
            c if c.is_control() => {
                return Err(format!(
                    "raw control character U+{:04X} in a string",
                    c as u32
                ))
            }
            c => s.push(c),
        }
    }
}

/// A character of a word or a number.
fn word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || "_-.+:/".contains(c)
}

/// The word or number starting with `c`: a number when it starts as one (finite,
/// within f32).
fn word(c: char, it: &mut Chars) -> Result<Tok, String> {
    let mut w = String::from(c);
    while let Some(&(_, d)) = it.peek() {
        if !word_char(d) {
            break;
        }
        w.push(d);
        it.next();
    }
    if matches!(w.to_ascii_lowercase().as_str(), "inf" | "nan" | "infinity") {
        return Err(format!("the non-finite number {w}"));
    }
    let numeric = w.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+' || c == '.');
    Ok(if numeric {
        Tok::Num(number(&w)?)
    } else {
        Tok::Word(w)
    })
}

/// A USD identifier (a prim name).
fn usd_ident(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A `.usda` stage as `primdecomp export` writes it: the header, then `def TYPE
/// "name" (…)? { … }` prims whose names are identifiers, unique among siblings.
pub fn usda(text: &str) -> Result<Checked, String> {
    let body = text
        .strip_prefix("#usda 1.0\n")
        .ok_or("the first line is not #usda 1.0")?;
    let t = tokens(body, true)?;
    let mut names = Vec::new();
    let mut idents = Vec::new();
    // Prim names by nesting depth of `{`.
    let mut siblings: Vec<HashSet<String>> = vec![HashSet::new()];
    let mut i = 0;
    while i < t.len() {
        match &t[i] {
            Tok::Word(w) if w == "def" => {
                let (Some(Tok::Word(_)), Some(Tok::Str(name))) = (t.get(i + 1), t.get(i + 2))
                else {
                    return Err("a def without a type and a quoted name".into());
                };
                if !usd_ident(name) {
                    return Err(format!("prim name {name:?} is not an identifier"));
                }
                // The objects are the root prim's children.
                if siblings.len() == 2 {
                    idents.push(name.clone());
                }
                let level = siblings.last_mut().ok_or("unbalanced braces")?;
                if !level.insert(name.clone()) {
                    return Err(format!("prim name {name:?} is repeated"));
                }
                i += 3;
            }
            Tok::Punct('{') => {
                siblings.push(HashSet::new());
                i += 1;
            }
            Tok::Punct('}') => {
                siblings.pop();
                i += 1;
            }
            Tok::Word(w) if w == "primdecomp:name" => {
                let (Some(Tok::Punct('=')), Some(Tok::Str(s))) = (t.get(i + 1), t.get(i + 2))
                else {
                    return Err("primdecomp:name without a string".into());
                };
                names.push(s.clone());
                i += 3;
            }
            _ => i += 1,
        }
    }
    Ok(Checked {
        names,
        idents,
        ..Checked::default()
    })
}

/// A Godot node name: no character Godot forbids in one.
fn godot_node(s: &str) -> bool {
    !s.is_empty() && !s.chars().any(|c| ".:@/\"%".contains(c) || c.is_control())
}

/// A Godot 4 `.tscn` scene as `primdecomp export` writes it: the `[gd_scene]` header
/// with `load_steps` one more than the sub-resources, `[sub_resource]` and `[node]`
/// sections, `key = value` lines whose values tokenize, nodes named as Godot allows
/// and unique among siblings, every `SubResource("id")` defined.
pub fn tscn(text: &str) -> Result<Checked, String> {
    let mut scene = Tscn::default();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let t = tokens(line, false).map_err(|e| format!("line {}: {e}", n + 1))?;
        match t.get(1) {
            Some(Tok::Word(w)) if t[0] == Tok::Punct('[') => scene.section(w, &t)?,
            _ => scene.value_line(&t)?,
        }
    }
    let (steps, resources) = (scene.steps, scene.ids.len());
    if steps != Some(resources + 1) {
        return Err(format!(
            "load_steps {steps:?} for {resources} sub-resources"
        ));
    }
    if let Some(r) = scene.refs.iter().find(|r| !scene.ids.contains(*r)) {
        return Err(format!("SubResource({r:?}) is not defined"));
    }
    Ok(Checked {
        names: scene.names,
        idents: scene.idents,
        ..Checked::default()
    })
}

/// What [`tscn`] gathers line by line.
#[derive(Default)]
struct Tscn {
    names: Vec<String>,
    idents: Vec<String>,
    ids: HashSet<String>,
    refs: Vec<String>,
    siblings: HashMap<String, HashSet<String>>,
    steps: Option<usize>,
}

/// The value of `k = value` in a line's tokens.
fn attr<'a>(t: &'a [Tok], k: &str) -> Option<&'a Tok> {
    t.windows(3)
        .find(|w| w[0] == Tok::Word(k.into()) && w[1] == Tok::Punct('='))
        .map(|w| &w[2])
}

/// The string value of `k = "value"` in a line's tokens.
fn str_attr(t: &[Tok], k: &str) -> Option<String> {
    match attr(t, k) {
        Some(Tok::Str(s)) => Some(s.clone()),
        _ => None,
    }
}

impl Tscn {
    /// A `[section …]` line: the header's step count, a sub-resource's id, a node's
    /// name.
    fn section(&mut self, w: &str, t: &[Tok]) -> Result<(), String> {
        match w {
            "gd_scene" => match attr(t, "load_steps") {
                Some(Tok::Num(x)) => self.steps = Some(*x as usize),
                _ => return Err("gd_scene without load_steps".into()),
            },
            "sub_resource" => {
                let id = str_attr(t, "id").ok_or("sub_resource without an id")?;
                if !self.ids.insert(id.clone()) {
                    return Err(format!("sub_resource id {id:?} is repeated"));
                }
            }
            "node" => {
                let name = str_attr(t, "name").ok_or("node without a name")?;
                if !godot_node(&name) {
                    return Err(format!("node name {name:?} is not allowed in Godot"));
                }
                let parent = str_attr(t, "parent").unwrap_or_else(|| "(root)".into());
                if parent == "." {
                    self.idents.push(name.clone());
                }
                if !self
                    .siblings
                    .entry(parent)
                    .or_default()
                    .insert(name.clone())
                {
                    return Err(format!("node name {name:?} is repeated"));
                }
            }
            w => return Err(format!("unknown section [{w}")),
        }
        Ok(())
    }

    /// A `key = value` line: an object's name, the sub-resources it refers to.
    fn value_line(&mut self, t: &[Tok]) -> Result<(), String> {
        if let Some(Tok::Word(k)) = t.first() {
            if k == "metadata/primdecomp_name" {
                match t.get(2) {
                    Some(Tok::Str(s)) => self.names.push(s.clone()),
                    _ => return Err("primdecomp_name without a string".into()),
                }
            }
        }
        for w in t.windows(4) {
            if w[0] == Tok::Word("SubResource".into()) {
                if let Tok::Str(id) = &w[2] {
                    self.refs.push(id.clone());
                }
            }
        }
        Ok(())
    }
}

/// Every number in `v` (no `null` where a number belongs: serde writes non-finite
/// floats as `null`) is finite within f32.
fn json_numbers(v: &serde_json::Value, at: &str) -> Result<(), String> {
    match v {
        serde_json::Value::Null => Err(format!("{at} is null")),
        serde_json::Value::Number(n) => number(&n.to_string()).map(|_| ()),
        serde_json::Value::Array(a) => a.iter().try_for_each(|x| json_numbers(x, at)),
        serde_json::Value::Object(o) => o
            .iter()
            .try_for_each(|(k, x)| json_numbers(x, &format!("{at}.{k}"))),
        _ => Ok(()),
    }
}

/// A glTF 2.0 document (`.gltf` text or `.glb`) as `primdecomp export` writes it:
/// valid for the `gltf` crate (the schema's checks), no `null` or non-f32 number in
/// accessors, nodes or physics shapes, shape sizes positive.
pub fn gltf(bytes: &[u8]) -> Result<Checked, String> {
    let doc = gltf::Gltf::from_slice(bytes).map_err(|e| format!("glTF: {e}"))?;
    let json = doc.document.into_json();
    let v = serde_json::to_value(&json).map_err(|e| e.to_string())?;
    for k in ["accessors", "nodes"] {
        if let Some(x) = v.get(k) {
            json_numbers(x, k)?;
        }
    }
    let raw: serde_json::Value = if bytes.starts_with(b"glTF") {
        let len = u32::from_le_bytes(bytes[12..16].try_into().map_err(|_| "short GLB")?) as usize;
        serde_json::from_slice(&bytes[20..20 + len]).map_err(|e| e.to_string())?
    } else {
        serde_json::from_slice(bytes).map_err(|e| e.to_string())?
    };
    for ext in ["KHR_implicit_shapes", "OMI_physics_shape"] {
        let shapes = raw["extensions"][ext]["shapes"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        for s in &shapes {
            json_numbers(s, ext)?;
            let ty = s["type"].as_str().ok_or("a shape without a type")?;
            for (k, x) in s[ty].as_object().into_iter().flatten() {
                let sizes: Vec<f64> = match x {
                    serde_json::Value::Array(a) => a.iter().filter_map(|n| n.as_f64()).collect(),
                    n => n.as_f64().into_iter().collect(),
                };
                let positive = match k.as_str() {
                    "size" | "radius" => sizes.iter().all(|&s| s > 0.0),
                    _ => sizes.iter().all(|&s| s >= 0.0),
                };
                if !positive {
                    return Err(format!("{ext}: a {ty} {k} is not positive"));
                }
            }
        }
    }
    let scene = raw["scenes"][0]["nodes"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    let names = scene
        .iter()
        .map(|i| &raw["nodes"][i.as_u64().unwrap_or(u64::MAX) as usize])
        // The input mesh (`--input`) is a node with a mesh; objects hold colliders.
        .filter(|n| n.get("mesh").is_none())
        .filter_map(|n| n["name"].as_str())
        .map(String::from)
        .collect();
    Ok(Checked {
        names,
        ..Checked::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_readers_refuse_what_consumers_refuse() {
        let ok = r#"<?xml version="1.0"?><mujoco model="m"><worldbody><body name="a" pos="0 0 0" quat="1 0 0 0"><geom name="a/box_0" type="box" size="1 1 1"/></body></worldbody></mujoco>"#;
        assert_eq!(mjcf(ok).unwrap().names, ["a"]);
        assert!(mjcf(&ok.replace("name=\"a\"", "name=\"world\"")).is_err());
        assert!(mjcf(&ok.replace("size=\"1 1 1\"", "size=\"1 NaN 1\"")).is_err());
        assert!(mjcf(&ok.replace("model=\"m\"", "model=\"\u{1}\"")).is_err());
        assert!(mjcf(&ok.replace("</body>", "")).is_err());
        assert!(usda(
            "#usda 1.0\ndef Xform \"a\" {\n custom string primdecomp:name = \"x\\\"y\"\n}\n"
        )
        .is_ok());
        assert!(usda("#usda 1.0\ndef Xform \"1a\" {\n}\n").is_err());
        assert!(usda("#usda 1.0\ndef Xform \"a\" {\n double x = inf\n}\n").is_err());
        assert!(tscn("[gd_scene load_steps=1 format=3]\n\n[node name=\"a\" type=\"Node3D\"]\nmetadata/primdecomp_name = \"a\u{0}\"\n").is_err());
        assert!(file_name("a_meshes/0_x_prism_0.obj").is_ok());
        assert!(file_name("../x.obj").is_err());
        assert!(file_name(&"x".repeat(256)).is_err());
    }
}
