//! `primdecomp view` and `decompose --png` through the real binary, on the demo
//! scene: the page and the PNG are byte-identical across runs, `decompose --png`
//! draws what `view --png` draws for the same result, every level of a multi-target
//! run is in the page, and bad input fails with exit 2 (1 for a missing file) and a
//! message naming the file, writing nothing.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn demo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../datasets/demo_scene.obj")
}

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("primdecomp-cli-view-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("runs")
}

fn ok(dir: &Path, args: &[&str]) {
    let o = run(dir, args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The embedded data of a page.
fn page_data(html: &str) -> serde_json::Value {
    let start = html.find("id=\"primdecomp-data\">").expect("data element") + 21;
    let end = start + html[start..].find("</script>").unwrap();
    serde_json::from_str(&html[start..end].replace("<\\/", "</")).expect("data is JSON")
}

#[test]
fn page_and_png_are_deterministic_and_hold_every_level() {
    let dir = scratch("det");
    let demo = demo();
    let demo = demo.to_str().unwrap();
    ok(
        &dir,
        &[
            "decompose",
            demo,
            "-n",
            "150,40",
            "-o",
            "demo.json",
            "--quiet",
            "--png",
            "dec.png",
        ],
    );
    for i in 0..2 {
        ok(
            &dir,
            &[
                "view",
                "demo.json",
                "--input",
                demo,
                "-o",
                &format!("v{i}.html"),
                "--png",
                &format!("v{i}.png"),
            ],
        );
    }
    let read = |n: &str| std::fs::read(dir.join(n)).unwrap();
    assert!(read("v0.html") == read("v1.html"), "same page bytes");
    assert!(read("v0.png") == read("v1.png"), "same PNG bytes");
    // decompose --png renders the first level over the input: what view draws of it
    // (the camera is fitted to every level given, so only that level).
    ok(
        &dir,
        &[
            "view",
            "demo_n150.json",
            "--input",
            demo,
            "--png",
            "first.png",
        ],
    );
    assert!(
        read("dec.png") == read("first.png"),
        "decompose --png = view --png"
    );
    assert!(
        read("dec.png") != read("v0.png"),
        "the other level widens the view"
    );
    let html = String::from_utf8(read("v0.html")).unwrap();
    assert!(
        !html.contains("http://") && !html.contains("https://"),
        "no network reference"
    );
    let data = page_data(&html);
    let levels = data["levels"].as_array().unwrap();
    assert_eq!(
        levels.len(),
        2,
        "both levels of demo.json (demo_n150, demo_n40)"
    );
    for (l, t) in levels.iter().zip(["150", "40"]) {
        let doc: serde_json::Value =
            serde_json::from_slice(&read(&format!("demo_n{t}.json"))).unwrap();
        assert_eq!(l["count"], doc["stats"]["primitives"]);
        assert_eq!(l["parts"], doc["primitives"], "each primitive's parameters");
        assert_eq!(l["target"].to_string(), t);
    }
    assert_eq!(data["input"]["faces"], 1829);
    assert_eq!(data["input"]["simplified"], false);
    // With a small display budget the input is simplified and says so.
    ok(
        &dir,
        &[
            "view",
            "demo_n40.json",
            "--input",
            demo,
            "--display-faces",
            "500",
            "-o",
            "s.html",
        ],
    );
    let s = page_data(&String::from_utf8(read("s.html")).unwrap());
    assert_eq!(s["input"]["simplified"], true);
    assert!(s["input"]["triangles"].as_u64().unwrap() <= 500);
    // No temporary files left beside the outputs.
    for e in std::fs::read_dir(&dir).unwrap() {
        let n = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!n.contains(".tmp"), "left over: {n}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_input_fails_naming_the_file_and_writes_nothing() {
    let dir = scratch("bad");
    std::fs::write(dir.join("broken.json"), b"{\"primitives\": [").unwrap();
    std::fs::write(
        dir.join("empty.json"),
        b"{\"format\": \"primdecomp\", \"version\": 1, \"primitives\": []}",
    )
    .unwrap();
    std::fs::write(dir.join("noeval.json"), b"{\"input\": 1}").unwrap();
    std::fs::write(
        dir.join("r.json"),
        br#"{"format": "primdecomp", "version": 1,
            "primitives": [{"kind": "sphere", "center": [0, 0, 0], "radius": 1}]}"#,
    )
    .unwrap();
    std::fs::write(dir.join("bad.obj"), b"v 0 0 0\nf 1 2 3\n").unwrap();
    let cases: &[(&[&str], i32, &[&str])] = &[
        (
            &["view", "broken.json", "-o", "o.html"],
            2,
            &["broken.json", "invalid JSON"],
        ),
        (
            &["view", "empty.json", "-o", "o.html"],
            2,
            &["empty.json", "no primitives"],
        ),
        (
            &["view", "missing.json", "-o", "o.html"],
            2,
            &["missing.json", "cannot open"],
        ),
        (
            &["view", "r.json", "--compare", "r.json", "-o", "o.html"],
            2,
            &["r.json", "OBJ"],
        ),
        (
            &["view", "r.json", "--compare", "bad.obj", "-o", "o.html"],
            2,
            &["bad.obj"],
        ),
        (
            &["view", "r.json", "--eval", "noeval.json", "-o", "o.html"],
            2,
            &["noeval.json", "not an evaluation document"],
        ),
        (
            &["view", "r.json", "--input", "bad.obj", "-o", "o.html"],
            2,
            &["bad.obj"],
        ),
        (&["view", "r.json"], 2, &["nothing to write"]),
        (&["view", "-o", "o.html"], 2, &["nothing to show"]),
        (
            &["view", "r.json", "--png", "o.png", "--png-size", "3"],
            2,
            &["--png-size"],
        ),
    ];
    for (args, code, fragments) in cases {
        let o = run(&dir, args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(o.status.code(), Some(*code), "{args:?}: {err}");
        for f in *fragments {
            assert!(err.contains(f), "{args:?}: '{f}' not in {err}");
        }
        assert!(
            !dir.join("o.html").exists() && !dir.join("o.png").exists(),
            "{args:?} wrote output"
        );
    }
    // The good file alone works, for both outputs.
    ok(&dir, &["view", "r.json", "-o", "o.html", "--png", "o.png"]);
    assert!(dir.join("o.html").exists() && dir.join("o.png").exists());
    std::fs::remove_dir_all(&dir).ok();
}
