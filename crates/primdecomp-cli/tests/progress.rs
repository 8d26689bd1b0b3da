//! What a run says while it runs: nothing on stderr off a terminal unless asked
//! (`--progress`), and with `--progress` a line per stage (its name and percent, the
//! whole run's percent); `--timings` adds each stage's peak memory.

use std::process::Command;

fn decompose(extra: &[&str]) -> (String, String) {
    let input = concat!(env!("CARGO_MANIFEST_DIR"), "/../../datasets/demo_scene.obj");
    let out = std::env::temp_dir().join(format!("primdecomp-progress-{}.json", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_primdecomp"))
        .args(["decompose", input, "-n", "40", "-o"])
        .arg(&out)
        .args(extra)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_file(&out);
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn progress_lines_only_when_asked_off_a_terminal() {
    let (_, quiet) = decompose(&[]);
    assert_eq!(quiet, "", "stderr off a terminal without --progress");
    let (_, said) = decompose(&["--progress"]);
    let lines: Vec<&str> = said.lines().collect();
    for stage in [
        "dedup",
        "adjacency",
        "quadrics",
        "seed",
        "merge",
        "postprocess",
    ] {
        assert!(
            lines
                .iter()
                .any(|l| l.starts_with(&format!("progress  {stage} "))),
            "no line for {stage}: {said}"
        );
    }
    assert!(lines.iter().all(|l| l.contains("%, run ")), "{said}");
    let (_, quiet) = decompose(&["--progress", "--quiet"]);
    assert_eq!(quiet, "", "--quiet wins");
}

#[test]
fn timings_give_each_stage_its_peak_memory() {
    let (out, _) = decompose(&["--quiet", "--timings"]);
    let line = out
        .lines()
        .find_map(|l| l.strip_prefix("memory    by stage (MiB): "))
        .unwrap_or_else(|| panic!("no memory line: {out}"));
    let stages: Vec<&str> = line
        .split(", ")
        .map(|p| p.split(' ').next().unwrap())
        .collect();
    assert_eq!(
        stages,
        [
            "load",
            "dedup",
            "adjacency",
            "quadrics",
            "seed",
            "merge",
            "postprocess"
        ],
        "{line}"
    );
    let peak: f64 = out
        .lines()
        .find_map(|l| l.strip_prefix("memory    peak resident "))
        .and_then(|l| l.split(' ').next()?.parse().ok())
        .expect("a peak line");
    assert!(peak > 0.0);
}
