//! `decompose -o -`: the result goes to standard output, byte for byte what `-o FILE`
//! writes, and everything the run says goes to standard error, so a pipe reads the
//! result alone (`primdecomp decompose m.obj -o - | jq …`).

use primdecomp_testkit::shapes::{demo_polys, obj_text};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("primdecomp-stdout-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.obj"), obj_text(&demo_polys())).unwrap();
    dir
}

fn decompose(dir: &Path, extra: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(["decompose", "scene.obj", "-n", "12"])
        .args(extra)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{extra:?}: {said}");
    out
}

#[test]
fn the_result_on_standard_output_is_the_files_bytes_and_nothing_else() {
    let dir = scratch();
    let to_file = decompose(&dir, &["-o", "r.json", "--obj", "r.obj"]);
    let file = std::fs::read(dir.join("r.json")).unwrap();
    // Written to a file, the summary is on standard output as ever.
    assert!(String::from_utf8_lossy(&to_file.stdout).contains("wrote     r.json"));
    for spelling in ["-", "/dev/stdout"] {
        let piped = decompose(&dir, &["-o", spelling, "--obj", "p.obj"]);
        assert!(piped.stdout == file, "-o {spelling}: not the file's bytes");
        let said = String::from_utf8_lossy(&piped.stderr);
        for line in [
            "count ",
            "wrote     the result to standard output",
            "wrote     p.obj",
        ] {
            assert!(
                said.contains(line),
                "-o {spelling}: stderr lacks {line:?}: {said}"
            );
        }
        assert_eq!(
            std::fs::read(dir.join("p.obj")).unwrap(),
            std::fs::read(dir.join("r.obj")).unwrap()
        );
    }
    // No file named "-" (what `-o -` wrote before it meant standard output).
    assert!(!dir.join("-").exists());
    // With --timings too, standard output holds the result alone: it parses whole.
    let timed = decompose(&dir, &["-o", "-", "--timings", "--verbose"]);
    let doc: serde_json::Value = serde_json::from_slice(&timed.stdout).unwrap();
    assert_eq!(doc["format"], "primdecomp");
    assert!(String::from_utf8_lossy(&timed.stderr).contains("memory    peak resident"));
    std::fs::remove_dir_all(&dir).unwrap();
}
