//! `decompose -o -` (and `export -o -`, `view -o -`/`--png -`, `eval --json -`): the
//! output goes to standard output, byte for byte what `-o FILE`
//! writes, and everything the run says goes to standard error, so a pipe reads the
//! result alone (`primdecomp decompose m.obj -o - | jq …`); with `-q` it says nothing.

use primdecomp_testkit::shapes::{demo_polys, obj_text};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A folder of this test's own (`tag`) holding the demo scene as `scene.obj`.
fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("primdecomp-stdout-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.obj"), obj_text(&demo_polys())).unwrap();
    dir
}

/// `decompose scene.obj -n 12` with `extra`, in `dir`; asserts it succeeded.
fn decompose(dir: &Path, extra: &[&str]) -> Output {
    let args: Vec<&str> = ["decompose", "scene.obj", "-n", "12"]
        .into_iter()
        .chain(extra.iter().copied())
        .collect();
    run(dir, &args)
}

#[test]
fn the_result_on_standard_output_is_the_files_bytes_and_nothing_else() {
    let dir = scratch("result");
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

/// Runs the CLI in `dir` with `args`.
fn cli(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

/// Runs the CLI in `dir` with `args`; asserts it succeeded.
fn run(dir: &Path, args: &[&str]) -> Output {
    let out = cli(dir, args);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {said}");
    out
}

/// `export -o -`, `view -o -` / `--png -` and `eval --json -` write the bytes their
/// file would hold to standard output, and what they say to standard error; an
/// export to standard output is named after the result, as one to `r.EXT` is.
#[test]
fn export_view_and_eval_write_to_standard_output_what_a_file_would_hold() {
    let dir = scratch("others");
    decompose(&dir, &["-o", "r.json", "-q"]);
    #[rustfmt::skip]
    let cases: [(&[&str], &str, &str); 6] = [
        (&["export", "r.json", "--format", "mjcf", "-o"], "r.xml", "the mjcf export to standard output"),
        (&["export", "r.json", "--format", "glb", "-o"], "r.glb", "the glb export to standard output"),
        (&["export", "r.json", "--format", "usda", "-o"], "r.usda", "the usda export to standard output"),
        (&["view", "r.json", "--input", "scene.obj", "-o"], "v.html", "the page to standard output"),
        (&["view", "r.json", "--input", "scene.obj", "--png-size", "64", "--png"], "v.png", "the picture to standard output"),
        (&["eval", "--input", "scene.obj", "r.json", "--samples", "2000", "--json"], "e.json", "the metrics to standard output"),
    ];
    for (args, file, said) in cases {
        let piped_args: Vec<&str> = args.iter().copied().chain(["-"]).collect();
        let to_file: Vec<&str> = args.iter().copied().chain([file]).collect();
        let written = run(&dir, &to_file);
        let piped = run(&dir, &piped_args);
        let bytes = std::fs::read(dir.join(file)).unwrap();
        assert!(
            piped.stdout == bytes,
            "{piped_args:?}: not the bytes of {file}"
        );
        let stderr = String::from_utf8_lossy(&piped.stderr);
        assert!(
            stderr.contains(said),
            "{piped_args:?}: stderr lacks {said:?}: {stderr}"
        );
        // To a file, the run speaks on standard output as ever.
        assert!(!written.stdout.is_empty(), "{to_file:?}: said nothing");
    }
    assert!(!dir.join("-").exists(), "a file named - was written");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `-q` on every command that writes a file: nothing on standard output or standard
/// error, the same bytes written (to a file or to standard output), and an error still
/// said. `eval -q` without `--json` would keep no metrics at all, so it is refused.
#[test]
fn quiet_runs_say_nothing_and_write_the_same_bytes() {
    let dir = scratch("quiet");
    decompose(&dir, &["-o", "r.json", "-q"]);
    std::fs::create_dir(dir.join("q")).unwrap();
    #[rustfmt::skip]
    let cases: [(&[&str], &str); 5] = [
        (&["export", "r.json", "--format", "mjcf", "-o"], "r.xml"),
        (&["export", "r.json", "-o"], "r.urdf"),
        (&["view", "r.json", "--input", "scene.obj", "--png-size", "64", "--png"], "v.png"),
        (&["eval", "--input", "scene.obj", "r.json", "--samples", "2000", "--json"], "e.json"),
        (&["demo-scene", "-o"], "demo.obj"),
    ];
    for (args, file) in cases {
        let loud: Vec<&str> = args.iter().copied().chain([file]).collect();
        // The same name in another folder: an export names its model after its file.
        let quiet_file = format!("q/{file}");
        let quiet: Vec<&str> = args
            .iter()
            .copied()
            .chain([quiet_file.as_str(), "-q"])
            .collect();
        let said = run(&dir, &loud);
        assert!(!said.stdout.is_empty(), "{loud:?}: said nothing");
        let hushed = run(&dir, &quiet);
        assert!(
            hushed.stdout.is_empty() && hushed.stderr.is_empty(),
            "{quiet:?} said {:?} {:?}",
            String::from_utf8_lossy(&hushed.stdout),
            String::from_utf8_lossy(&hushed.stderr)
        );
        let bytes = std::fs::read(dir.join(file)).unwrap();
        assert!(
            std::fs::read(dir.join(&quiet_file)).unwrap() == bytes,
            "{quiet:?}"
        );
        if args[0] != "demo-scene" && file != "r.urdf" {
            let piped: Vec<&str> = args.iter().copied().chain(["-", "-q"]).collect();
            let out = run(&dir, &piped);
            assert!(out.stdout == bytes && out.stderr.is_empty(), "{piped:?}");
        }
    }
    #[rustfmt::skip]
    let refused: [(&[&str], &str); 2] = [
        (&["eval", "--input", "scene.obj", "r.json", "-q"], "--quiet prints no table"),
        (&["export", "missing.json", "-o", "m.xml", "--format", "mjcf", "-q"], "missing.json"),
    ];
    for (args, want) in refused {
        refuses(&dir, args, want);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// What standard output cannot carry is refused before anything is written (exit 2):
/// an export without --format (a stream has no extension), a URDF whose prisms need
/// mesh files beside it, and two outputs of one run both to standard output.
#[test]
fn what_standard_output_cannot_carry_is_refused() {
    let dir = scratch("refused");
    decompose(&dir, &["-o", "p.json", "-q", "--kinds", "prism"]);
    #[rustfmt::skip]
    let cases: [(&[&str], &str); 3] = [
        (&["export", "p.json", "-o", "-"], "-o -: standard output has no extension to name the format: give --format"),
        (&["export", "p.json", "-o", "-", "--format", "urdf"], "mesh files beside it (for its frustums and prisms), which standard output cannot carry"),
        (&["view", "p.json", "--input", "scene.obj", "-o", "-", "--png", "/dev/stdout"], "-o - and --png /dev/stdout both go to standard output"),
    ];
    for (args, want) in cases {
        refuses(&dir, args, want);
    }
    assert!(!dir.join("-").exists() && !dir.join("p_meshes").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs the CLI in `dir` with `args`; asserts it exited 2 saying `want` on standard
/// error and nothing on standard output.
fn refuses(dir: &Path, args: &[&str], want: &str) {
    let out = cli(dir, args);
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {said}");
    assert!(said.contains(want), "{args:?}: {said}");
    assert!(out.stdout.is_empty(), "{args:?}: wrote to standard output");
}
