//! `decompose --tolerance` and `--max-bytes` as a user runs them: a
//! chain of tolerances writes one file per level named by its tolerance, the JSON
//! records what was asked and the distance reached, a single closed box needs no
//! count, and bad values are refused with exit 2 and a message naming the flag.

use primdecomp_testkit::shapes::{cuboid, join, obj_text};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder for one test, removed when the test ends (passed or not).
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn dir(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("primdecomp-tol-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

fn run(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("runs");
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code(), text)
}

/// A closed 2 × 1 × 3 box of 12 triangles, as OBJ.
const CUBE: &str = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 3\nv 2 0 3\nv 2 1 3\nv 0 1 3\n\
                    f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n\
                    f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A closed box (12 triangles) within 1%: one box, as without any target (the
/// default tolerance), where a count of 64 gives a shell of plates; the summary and
/// the JSON say how far it stands and what was asked.
#[test]
fn a_box_within_a_tolerance_is_one_box() {
    let d = dir("box");
    std::fs::write(d.join("cube.obj"), CUBE).unwrap();
    let (code, out) = run(
        &d,
        &[
            "decompose",
            "cube.obj",
            "--tolerance",
            "1%",
            "-o",
            "cube.json",
        ],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("1 primitives (1 box)"), "{out}");
    assert!(out.contains("within the tolerance"), "{out}");
    let v = json(&d.join("cube.json"));
    assert_eq!(v["stats"]["primitives"], 1);
    let dist = &v["stats"]["distance"];
    // A bound, refined to 0.02% of the diagonal where the box lies on the faces.
    assert!(
        dist["worst"].as_f64().unwrap() <= 2e-4 * 14f64.sqrt(),
        "{dist}"
    );
    assert!((dist["tolerance"].as_f64().unwrap() - 0.01 * 14f64.sqrt()).abs() < 1e-12);
    assert_eq!(v["settings"]["tolerance"][0]["diagonal"], 0.01);
    let (code, out) = run(&d, &["decompose", "cube.obj", "-o", "plain.json"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("tolerance 2.00% (at most 1024) → 1 primitives (1 box)"),
        "{out}"
    );
    let plain = std::fs::read(d.join("plain.json")).unwrap();
    let (code, out) = run(
        &d,
        &["decompose", "cube.obj", "--tolerance", "2%", "-o", "t.json"],
    );
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(
        plain,
        std::fs::read(d.join("t.json")).unwrap(),
        "default = 2%"
    );
    // The greedy level of 64 is a shell of plates; a count on one part whose greedy
    // level comes out short is cut again (docs/decisions/0054): one box, as no more
    // primitives would stand nearer, and the summary says so.
    let (code, out) = run(
        &d,
        &[
            "decompose",
            "cube.obj",
            "-n",
            "64",
            "--greedy",
            "-o",
            "cube64.json",
        ],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(
        json(&d.join("cube64.json"))["stats"]["primitives"]
            .as_u64()
            .unwrap()
            > 1
    );
    let (code, out) = run(
        &d,
        &["decompose", "cube.obj", "-n", "64", "-o", "cube64c.json"],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("count    64 → 1 primitives (1 box)"), "{out}");
    assert!(
        out.contains("no more primitives would stand nearer"),
        "{out}"
    );
    // Fill completes a count: without one it is refused, naming -n.
    let (code, out) = run(&d, &["decompose", "cube.obj", "--fill", "-o", "f.json"]);
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("--fill needs -n"), "{out}");
}

/// A byte target below one primitive's size (a box takes 40 bytes) cannot be met:
/// the run still writes the fewest primitives the tree allows, and the summary says
/// it stands over the target rather than naming it as if met.
#[test]
fn a_byte_target_nothing_fits_is_said_to_be_over() {
    let d = dir("bytes");
    std::fs::write(d.join("cube.obj"), CUBE).unwrap();
    for (bytes, over) in [("10", true), ("40", false)] {
        let args = [
            "decompose",
            "cube.obj",
            "--max-bytes",
            bytes,
            "-o",
            "c.json",
        ];
        let (code, out) = run(&d, &args);
        assert_eq!(code, Some(0), "{out}");
        assert!(out.contains("1 primitives (1 box), 40 bytes"), "{out}");
        let said = format!("over the byte target {bytes}");
        assert_eq!(out.contains(&said), over, "{out}");
    }
}

/// `--tolerance 5%,2%,1% --max-bytes 2K` on the demo scene: three files named by the
/// tolerances, more primitives for tighter ones, each within 2048 bytes and within its
/// tolerance or saying it is not; the settings reproduce the run (`--config`).
#[test]
fn a_chain_writes_one_file_per_tolerance() {
    let d = dir("chain");
    assert_eq!(run(&d, &["demo-scene", "-o", "demo.obj"]).0, Some(0));
    let args = [
        "decompose",
        "demo.obj",
        "--tolerance",
        "5%,2%,1%",
        "--max-bytes",
        "2048",
        "-o",
        "d.json",
        "-q",
    ];
    let (code, out) = run(&d, &args);
    assert_eq!(code, Some(0), "{out}");
    let mut counts = Vec::new();
    for t in ["5pct", "2pct", "1pct"] {
        let v = json(&d.join(format!("d_t{t}.json")));
        let dist = &v["stats"]["distance"];
        let (worst, tol) = (dist["worst"].as_f64(), dist["tolerance"].as_f64());
        // The 1% level needs about 1,700 bytes once nested primitives are removed,
        // but the cut counts the bytes of its nodes before that (docs/decisions/0040):
        // over 2048 there, so it is the nearest 2048 bytes reach, and says so.
        match t {
            "1pct" if worst > tol => {
                assert_eq!(dist["limited_by"], "bytes", "{dist}");
                let alone = [
                    "decompose",
                    "demo.obj",
                    "--tolerance",
                    "1%",
                    "-o",
                    "a.json",
                    "-q",
                ];
                assert_eq!(run(&d, &alone).0, Some(0));
                let a = json(&d.join("a.json"));
                let a_dist = &a["stats"]["distance"];
                assert!(a_dist["worst"].as_f64() <= a_dist["tolerance"].as_f64());
                assert!(a["stats"]["bytes"].as_u64().unwrap() <= 2048, "{a_dist}");
            }
            _ => assert!(worst <= tol, "{t}: {dist}"),
        }
        assert!(v["stats"]["bytes"].as_u64().unwrap() <= 2048);
        assert_eq!(v["settings"]["target"], 1024, "the cap without -n");
        counts.push(v["stats"]["primitives"].as_u64().unwrap());
    }
    assert!(
        counts.windows(2).all(|w| w[0] <= w[1]) && counts[0] < counts[2],
        "{counts:?}"
    );
    let (code, out) = run(
        &d,
        &[
            "decompose",
            "demo.obj",
            "--config",
            "d_t2pct.json",
            "-o",
            "again/",
            "-q",
        ],
    );
    assert_eq!(code, Some(0), "{out}");
    let again = json(&d.join("again/demo.primdecomp_t2pct.json"));
    assert_eq!(
        again["primitives"],
        json(&d.join("d_t2pct.json"))["primitives"]
    );
}

#[test]
fn bad_values_are_refused() {
    let d = dir("bad");
    assert_eq!(run(&d, &["demo-scene", "-o", "demo.obj"]).0, Some(0));
    for (args, want) in [
        (
            &["--tolerance", "1mm"][..],
            "--tolerance: expected a positive distance",
        ),
        (&["--tolerance=-1"][..], "--tolerance: '-1' is not positive"),
        // A negative value is a value, not an option (not "unexpected argument '-1'").
        (
            &["--tolerance", "-1%"][..],
            "--tolerance: '-1%' is not positive",
        ),
        (
            &["--tolerance", "2%,1%,0.5%", "-n", "8,4"][..],
            "tolerance has 3 values for 2 targets",
        ),
        (
            &["--max-bytes", "0"][..],
            "--max-bytes: expected a positive byte count",
        ),
        (&["--max-bytes", "100", "--fill"][..], "fill"),
    ] {
        let mut all = vec!["decompose", "demo.obj", "-o", "x.json"];
        all.extend_from_slice(args);
        let (code, out) = run(&d, &all);
        assert_eq!(code, Some(2), "{args:?}: {out}");
        assert!(out.contains(want), "{args:?}: {out}");
        assert!(!d.join("x.json").exists(), "{args:?} wrote an output");
    }
}

/// A closed crate with eight blocks inside: the greedy level of 9 keeps the crate's
/// box alone (the blocks lie inside it and post-processing removes them, §3.4), so
/// the summary must say why the user got 1 of 9 and what keeps parts apart; a cut
/// to a tolerance (which stands its distance) needs no such note.
#[test]
fn a_greedy_level_far_under_its_count_says_why() {
    let d = dir("nested");
    let mut parts = vec![cuboid([0.0; 3], [10.0; 3])];
    for i in 0..8 {
        let lo = [
            1.0 + 4.0 * (i & 1) as f64,
            1.0 + 4.0 * (i >> 1 & 1) as f64,
            1.0 + 4.0 * (i >> 2) as f64,
        ];
        parts.push(cuboid(lo, lo.map(|x| x + 2.0)));
    }
    std::fs::write(d.join("crate.obj"), obj_text(&join(&parts))).unwrap();
    let (code, out) = run(
        &d,
        &[
            "decompose",
            "crate.obj",
            "-n",
            "9",
            "--greedy",
            "-o",
            "g.json",
        ],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("count     9 → 1 primitives (1 box)"), "{out}");
    assert!(out.contains("lay inside those kept"), "{out}");
    // Without --greedy a count on several parts is a cut (docs/decisions/0054): the
    // blocks are hidden in the closed crate, so no split stands nearer and no note.
    let (code, out) = run(&d, &["decompose", "crate.obj", "-n", "9", "-o", "c.json"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("farthest"), "{out}");
    assert!(!out.contains("lay inside those kept"), "{out}");
    let (code, out) = run(
        &d,
        &[
            "decompose",
            "crate.obj",
            "--tolerance",
            "2%",
            "-o",
            "t.json",
        ],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("lay inside those kept"), "{out}");
}

/// Six separate cubes at -n 10: six boxes stand on the faces exactly, so the cut
/// keeps six, and the summary says why a user asking for ten got six (short by more
/// than a few, not under half).
#[test]
fn a_cut_short_of_its_count_says_why() {
    let d = dir("six");
    let parts: Vec<_> = (0..6)
        .map(|i| {
            let lo = [3.0 * i as f64, 0.0, 0.0];
            cuboid(lo, lo.map(|x| x + 1.0))
        })
        .collect();
    std::fs::write(d.join("six.obj"), obj_text(&join(&parts))).unwrap();
    let (code, out) = run(&d, &["decompose", "six.obj", "-n", "10", "-o", "s.json"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("count    10 → 6 primitives (6 box)"), "{out}");
    assert!(
        out.contains("no more primitives would stand nearer"),
        "{out}"
    );
    // Asking for what the parts hold says nothing more.
    let (code, out) = run(&d, &["decompose", "six.obj", "-n", "6", "-o", "e.json"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(!out.contains("no more primitives"), "{out}");
}

/// `--per-object` holds each object to the tolerance of its own diagonal, not the
/// whole mesh's: the summary gives the farthest distance as a share of the whole
/// mesh's diagonal and says how many objects stand within their own tolerance,
/// rather than comparing with the whole mesh's tolerance.
#[test]
fn a_per_object_summary_counts_objects_within_their_own_tolerance() {
    let d = dir("per-object");
    let (big, small) = (
        cuboid([0.0, 0.0, 0.0], [10.0, 10.0, 10.0]),
        cuboid([20.0, 0.0, 0.0], [20.5, 0.5, 0.5]),
    );
    let faces = big.1.len();
    let text = obj_text(&join(&[big, small]));
    let mut obj = String::new();
    let mut f = 0;
    for line in text.lines() {
        if line.starts_with("f ") {
            match f {
                0 => obj += "o big\n",
                n if n == faces => obj += "o small\n",
                _ => {}
            }
            f += 1;
        }
        obj += line;
        obj += "\n";
    }
    std::fs::write(d.join("two.obj"), obj).unwrap();
    let (code, out) = run(
        &d,
        &["decompose", "two.obj", "--per-object", "-o", "two.json"],
    );
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("objects   2"), "{out}");
    assert!(out.contains("of the whole mesh's diagonal"), "{out}");
    assert!(
        out.contains("2 of 2 objects within their own tolerance"),
        "{out}"
    );
    assert!(!out.contains("within the tolerance"), "{out}");
}
