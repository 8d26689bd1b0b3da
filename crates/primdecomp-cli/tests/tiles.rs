//! `decompose --max-memory` / `--tiles`: an input over the limit is decomposed in
//! tiles (and the terminal says how many and why) instead of refused; the tiled
//! JSON is the same bytes on 1 and 2 threads and the library's; what needs the whole
//! mesh is refused with exit 2.

use primdecomp::{Goal, LoadOptions, Params, Tiled};
use primdecomp_testkit::shapes::{icosphere, ply_bytes};
use std::path::Path;
use std::process::Command;

fn run(dir: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).trim().to_string(),
    )
}

#[test]
fn over_the_limit_tiles_instead_of_refusing() {
    let dir = std::env::temp_dir().join(format!("primdecomp-cli-tiles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // 327,680 triangles: read whole, the greedy run is estimated at about 124 MiB.
    std::fs::write(dir.join("ball.ply"), ply_bytes(&icosphere(1.0, 7))).unwrap();
    let (code, out, err) = run(
        &dir,
        &[
            "decompose",
            "ball.ply",
            "-n",
            "50",
            "--max-memory",
            "115M",
            "-o",
            "a.json",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
    let line = out.lines().find(|l| l.starts_with("tiles")).unwrap_or("");
    assert!(
        line.contains("read whole it would need about")
            && line.contains("more than --max-memory 115 MiB"),
        "{out}"
    );
    // Forced tiles: the same bytes on 1 and 2 threads, and the library's.
    for (threads, name) in [("1", "t1.json"), ("2", "t2.json")] {
        let args = [
            "decompose",
            "ball.ply",
            "-n",
            "50",
            "--tiles",
            "3",
            "--threads",
            threads,
        ];
        let (code, _, err) = run(&dir, &[&args[..], &["-o", name, "--quiet"]].concat());
        assert_eq!(code, Some(0), "{err}");
    }
    let t1 = std::fs::read_to_string(dir.join("t1.json")).unwrap();
    assert_eq!(t1, std::fs::read_to_string(dir.join("t2.json")).unwrap());
    let params = Params {
        goal: Goal::counts([50]),
        ..Params::default()
    };
    let options = LoadOptions {
        tiles: Some(3),
        ..LoadOptions::default()
    };
    let dec = Tiled::decompose(&dir.join("ball.ply"), &params, &options, &|_, _| {}).unwrap();
    // The same document but for where the CLI says the input came from.
    let bare = |text: &str| {
        let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
        let input = v["input"].as_object_mut().unwrap();
        input.retain(|k, _| !matches!(k.as_str(), "path" | "up" | "up_from"));
        v
    };
    assert_eq!(bare(&t1), bare(&dec.to_json(0, &params)));
    // What needs the whole mesh is refused.
    let (code, _, err) = run(
        &dir,
        &[
            "decompose",
            "ball.ply",
            "--tiles",
            "2",
            "--per-object",
            "-o",
            "p.json",
        ],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--per-object needs the whole mesh"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
