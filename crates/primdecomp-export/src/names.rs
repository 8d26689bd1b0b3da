//! How names reach the exports: one strategy for every format, so that any object
//! name and any output file name gives a well-formed, loadable file whose names are
//! still readable and still unique.
//!
//! 1. [`primdecomp_files::visible`]: characters no format may hold raw (C0 and C1 control characters,
//!    DEL, the non-characters U+FFFE and U+FFFF, and the bidirectional overrides that
//!    make text display in another order than it is stored) are written as the
//!    visible escape `\u{1b}`. Every name a writer puts in a file goes through it; XML
//!    1.0 forbids most of these characters outright, attribute normalization turns tab
//!    and line ends into spaces, and Godot and USD strings end at a NUL. The line and
//!    paragraph separators U+2028 and U+2029 stay: XML 1.0 allows them, a `.usda`
//!    string holds them (usd-core reads them back, and writes them raw itself), and
//!    Godot's tokenizer ends a string only at `"` or a NUL
//!    (`core/variant/variant_parser.cpp`); `tests/exports/test_hostile.py` reads such
//!    a name back from every format. (The terminal and the viewer's script, where a
//!    reader does break a line there, escape them.)
//! 2. Each format's syntax is then escaped by its writer (quick-xml for MJCF and URDF
//!    attributes, serde for glTF JSON, `usd::quote`, `godot::quote`).
//! 3. Where a format takes identifiers (USD prim names, Godot node names, file
//!    names), [`ident`] keeps `[A-Za-z0-9_-]` and turns the rest into `_`.
//! 4. [`Names`] makes names unique per namespace (`name`, `name_2`, …) and steers clear
//!    of a format's reserved names (MuJoCo's world body is `world`).
//! 5. [`file_name`] caps file names at [`MAX_FILE_NAME`] bytes, keeping them distinct
//!    with a hash of the whole name when cut.

use primdecomp_files::visible;
use std::collections::{HashMap, HashSet};

/// The longest file name (bytes) an export writes: the common limit of Linux, macOS
/// and Windows file systems is 255; a temporary name adds up to about 40 bytes.
pub const MAX_FILE_NAME: usize = 200;

/// An identifier for formats whose names are identifiers: `[A-Za-z0-9_]`, and `-`
/// unless `strict` (USD prim names, which also may not start with a digit); every
/// other character becomes `_`; never empty.
pub fn ident(name: &str, strict: bool) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || (!strict && c == '-') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || (strict && s.starts_with(|c: char| c.is_ascii_digit())) {
        s.insert(0, '_');
    }
    s
}

/// `name` cut to at most `max` bytes on a character boundary; when cut, the end is
/// replaced by `-` and 16 hex digits of a hash of the whole name, so two long names
/// that share their first `max` bytes stay distinct. `max` must be at least 32.
pub fn file_name(name: &str, max: usize) -> String {
    debug_assert!(max >= 32);
    if name.len() <= max {
        return name.to_string();
    }
    let mut cut = max - 17;
    while !name.is_char_boundary(cut) {
        cut -= 1;
    }
    format!("{}-{:016x}", &name[..cut], fnv1a(name.as_bytes()))
}

/// 64-bit FNV-1a: a fixed function of the bytes (file names must not depend on the
/// run).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// A namespace of unique names: each name is given once; a taken or reserved one
/// gets the first free `_2`, `_3`, … suffix. Linear in the names given (a counter per
/// base name, not a scan).
#[derive(Debug, Default)]
pub struct Names {
    used: HashSet<String>,
    next: HashMap<String, usize>,
}

impl Names {
    /// A namespace where `reserved` names are already taken.
    pub fn with_reserved(reserved: &[&str]) -> Names {
        Names {
            used: reserved.iter().map(|s| s.to_string()).collect(),
            next: HashMap::new(),
        }
    }

    /// `base` if free, else `base_k` for the smallest free `k ≥ 2`; taken from now on.
    pub fn unique(&mut self, base: String) -> String {
        if self.used.insert(base.clone()) {
            return base;
        }
        let k = self.next.entry(base.clone()).or_insert(2);
        loop {
            let name = format!("{base}_{k}");
            *k += 1;
            if self.used.insert(name.clone()) {
                return name;
            }
        }
    }
}

/// A double-quoted string for Godot's `.tscn` and USD's `.usda` alike: `\\` and `"`
/// escaped, control characters first made [`visible`] (a NUL would end the string in
/// both engines).
pub fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in visible(s).chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '"' => out.push_str("\\\""),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers() {
        assert_eq!(ident("a \"b\" <c>", false), "a__b___c_");
        assert_eq!(ident("1x-y", true), "_1x_y");
        assert_eq!(ident("", false), "_");
        assert_eq!(ident("日本", false), "__");
    }

    #[test]
    fn long_file_names_are_cut_and_stay_distinct() {
        let a = "x".repeat(300);
        let b = format!("{}y", "x".repeat(299));
        let (fa, fb) = (file_name(&a, 100), file_name(&b, 100));
        assert!(fa.len() <= 100 && fb.len() <= 100, "{fa} {fb}");
        assert_ne!(fa, fb);
        assert_eq!(file_name("short", 100), "short");
        // Cut on a character boundary.
        let wide = "é".repeat(100);
        assert!(file_name(&wide, 41).len() <= 41);
    }

    #[test]
    fn names_are_unique_and_avoid_reserved_ones() {
        let mut n = Names::with_reserved(&["world"]);
        assert_eq!(n.unique("world".into()), "world_2");
        assert_eq!(n.unique("a".into()), "a");
        assert_eq!(n.unique("a".into()), "a_2");
        assert_eq!(n.unique("a_2".into()), "a_2_2");
        assert_eq!(n.unique("a".into()), "a_3");
        // Many duplicates stay linear: 10,000 of one name.
        for _ in 0..10_000 {
            n.unique("dup".into());
        }
        assert_eq!(n.unique("dup".into()), "dup_10001");
    }
}
