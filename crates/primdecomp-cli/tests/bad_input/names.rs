//! Hostile object names in every export: a per-object result whose objects carry
//! names that broke the writers (characters XML 1.0 forbids, a NUL, terminal
//! escapes, markup, MuJoCo's `world`, duplicates, a 240-character name) is exported
//! in every format; each file must read back with its format's reader
//! (`primdecomp_testkit::exports`: quick-xml for MJCF and URDF, the glTF schema, the
//! USD and `.tscn` grammars), every object keep a readable, unique name, and the
//! URDF's mesh files valid names. The table shows what each name becomes.

use super::cell;
use primdecomp_testkit::exports;
use std::path::Path;
use std::process::Command;

/// The names, and what each tests.
const NAMES: [(&str, &str); 14] = [
    ("world", "MuJoCo's world body"),
    ("a\u{0}b", "a NUL"),
    ("\u{1b}[31mred\u{7}", "ESC and BEL"),
    ("tab\tnl\ncr\r", "tab, line feed, carriage return"),
    ("a\u{fffe}b\u{ffff}", "the non-characters U+FFFE, U+FFFF"),
    ("a\u{2028}b\u{2029}c", "U+2028 and U+2029"),
    ("<!--<script>", "markup"),
    ("q\"'&<>", "quotes and XML's specials"),
    ("\u{202e}txt.exe", "a right-to-left override"),
    ("dup", "a name given twice"),
    ("dup", "a name given twice"),
    ("", "empty"),
    ("日本語 ok", "non-ASCII letters, a space"),
    ("x240", "240 characters (one prism: a URDF mesh file)"),
];

/// A prism (written as a hull: a URDF mesh file) and a sphere.
const PRIMS: &str = r#"[{"kind":"prism","center":[0,0,0],"rotation":[0,0,0,1],"half_x":0.5,"half_y":0.5,"half_z_top":0.25,"half_z_bottom":0.5},{"kind":"sphere","center":[1,0,0],"radius":0.5}]"#;

fn name(n: &str) -> String {
    if n == "x240" {
        "x".repeat(240)
    } else {
        n.to_string()
    }
}

/// Short form of a long name in the table.
fn short(s: &str) -> String {
    if s.chars().count() > 40 {
        let head: String = s.chars().take(6).collect();
        format!("{head}…({} characters)", s.chars().count())
    } else {
        s.to_string()
    }
}

/// Exports the result in `dir` in every format and returns the table.
pub fn table(dir: &Path) -> String {
    let objects: Vec<serde_json::Value> = NAMES
        .iter()
        .enumerate()
        .map(|(i, (n, _))| {
            serde_json::json!({
                "name": name(n),
                "translation": [3.0 * i as f64, 0, 0],
                "rotation": [0, 0, 0, 1],
                "scale": 1,
                "primitives": serde_json::from_str::<serde_json::Value>(PRIMS).unwrap(),
            })
        })
        .collect();
    let doc = serde_json::json!({
        "format": "primdecomp",
        "version": 1,
        "primitives": serde_json::from_str::<serde_json::Value>(PRIMS).unwrap(),
        "objects": objects,
    });
    std::fs::write(dir.join("r.json"), doc.to_string()).unwrap();
    let mut read = Vec::new();
    for (out, extra) in [
        ("n.xml", Some("mjcf")),
        ("n.urdf", None),
        ("n.usda", None),
        ("n.tscn", None),
        ("n.gltf", None),
    ] {
        let mut c = Command::new(env!("CARGO_BIN_EXE_primdecomp"));
        c.current_dir(dir).args(["export", "r.json", "-o", out]);
        if let Some(f) = extra {
            c.args(["--format", f]);
        }
        let o = super::output_within(c);
        assert!(
            o.status.success(),
            "{out}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let bytes = std::fs::read(dir.join(out)).unwrap();
        let text = String::from_utf8(bytes.clone()).expect("UTF-8");
        let got = match out {
            "n.xml" => exports::mjcf(&text),
            "n.urdf" => exports::urdf(&text),
            "n.usda" => exports::usda(&text),
            "n.tscn" => exports::tscn(&text),
            _ => exports::gltf(&bytes),
        }
        .unwrap_or_else(|e| panic!("{out} does not read back: {e}"));
        assert_eq!(got.names.len(), NAMES.len(), "{out}: {:?}", got.names);
        for f in &got.files {
            exports::file_name(f).unwrap();
            assert!(dir.join(f).is_file(), "{out}: {f} missing");
        }
        read.push(got);
    }
    let mut table = String::from(
        "| object name (JSON) | what | MJCF body | URDF link, USD and Godot `primdecomp_name`, glTF node | USD prim | Godot node |\n|---|---|---|---|---|---|\n",
    );
    let code = |s: &str| format!("`{}`", cell(&short(s)));
    for (i, (n, what)) in NAMES.iter().enumerate() {
        // As JSON, with the characters a page or terminal would hide escaped too.
        let json: String = serde_json::to_string(&name(n))
            .unwrap()
            .chars()
            .map(|c| match c {
                '\u{fffe}' | '\u{ffff}' | '\u{202a}'..='\u{202e}' => format!("\\u{:04x}", c as u32),
                c => c.to_string(),
            })
            .collect();
        let others = &read[1].names[i];
        for r in [&read[2], &read[3], &read[4]] {
            assert_eq!(&r.names[i], others, "one name in every format but MJCF");
        }
        table += &format!(
            "| {} | {what} | {} | {} | {} | {} |\n",
            code(&json),
            code(&read[0].names[i]),
            code(others),
            code(&read[2].idents[i]),
            code(&read[3].idents[i]),
        );
    }
    let meshes = &read[1].files;
    let longest = meshes.iter().map(|f| f.len()).max().unwrap_or(0);
    table += &format!(
        "\nThe URDF refers to {} mesh files, the longest name {longest} bytes (`{}`).\n",
        meshes.len(),
        cell(meshes.iter().max_by_key(|f| f.len()).unwrap())
    );
    table
}
