//! Batches that survive a kill: a batch killed with SIGKILL
//! halfway and re-run with `--resume` finishes only what is missing and ends with the
//! same files, byte for byte, as a clean run; what the kill left half-done (a
//! temporary file, an output without its manifest line) and an output damaged since
//! are not trusted.
//!
//! `cargo test --release -p primdecomp-cli --test resume`

use primdecomp_testkit::shapes::{cuboid, cylinder, join, obj_text, uv_sphere};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The manifest's name in the output directory (`src/manifest.rs`).
const MANIFEST: &str = ".primdecomp-manifest.jsonl";

/// Writes `n` different meshes to `root/in/` (a sphere, a box and a cylinder, sizes
/// and tessellations varying with the index); returns their paths relative to root.
fn write_inputs(root: &Path, n: usize) -> Vec<String> {
    std::fs::create_dir_all(root.join("in")).unwrap();
    (0..n)
        .map(|i| {
            let f = i as f64;
            let mut sphere = uv_sphere(1.0 + 0.01 * f, 10 + i % 7, 20 + 2 * (i % 5));
            for p in &mut sphere.0 {
                p[0] += 2.5;
            }
            let lo = [-1.0, -1.0 - 0.02 * f, -0.5];
            let parts = [
                sphere,
                cuboid(lo, [1.0, 1.0, 0.5]),
                cylinder(0.4, 3.0, 12 + i % 9),
            ];
            let name = format!("in/mesh_{i:04}.obj");
            std::fs::write(root.join(&name), obj_text(&join(&parts))).unwrap();
            name
        })
        .collect()
}

/// `primdecomp decompose INPUTS -o OUT/ --obj OUT/ -n 6,2` in `root`: four files per
/// input, two jobs side by side.
fn batch(root: &Path, inputs: &[String], out: &str, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_primdecomp"));
    c.current_dir(root)
        .arg("decompose")
        .args(inputs)
        .args(["-o", out, "--obj", out, "-n", "6,2", "--jobs", "2"])
        .args(extra)
        .stdin(Stdio::null());
    c
}

/// The files of `dir` but the manifest, with their bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| (e.file_name().to_string_lossy().into_owned(), e.path()))
        .filter(|(name, _)| name != MANIFEST)
        .map(|(name, p)| (name, std::fs::read(p).unwrap()))
        .collect()
}

/// The outputs of one input (`mesh_0007.obj` → `mesh_0007.primdecomp_n6.json`, …).
fn outputs_of(input: &str) -> [String; 4] {
    let stem = Path::new(input).file_stem().unwrap().to_string_lossy();
    ["n6.json", "n2.json", "n6.obj", "n2.obj"].map(|s| format!("{stem}.primdecomp_{s}"))
}

/// Inputs the manifest records as done.
fn done_in_manifest(out: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(out.join(MANIFEST)).unwrap_or_default();
    text.lines()
        .skip(1)
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|v| v["status"] == "done")
        .map(|v| v["input"].as_str().unwrap().to_string())
        .collect()
}

fn inode(p: &Path) -> u64 {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata(p).unwrap().ino()
}

/// Starts the batch into `out` and SIGKILLs it as soon as its manifest records two
/// inputs done (so a resume has some to skip and one to find damaged). `None` if the
/// run finished before that could happen, or had written every output when killed
/// (the batch was too short for this machine).
fn run_and_kill(root: &Path, inputs: &[String], out: &str) -> Option<u32> {
    let mut child = batch(root, inputs, out, &["--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("runs");
    let pid = child.id();
    let dir = root.join(out);
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return None;
        }
        if done_in_manifest(&dir).len() >= 2 {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "nothing done after 300 s"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap(); // SIGKILL on Unix
    child.wait().unwrap();
    let complete = inputs
        .iter()
        .filter(|i| outputs_of(i).iter().all(|o| dir.join(o).exists()))
        .count();
    (complete < inputs.len()).then_some(pid)
}

#[test]
fn sigkill_midway_then_resume_matches_a_clean_run() {
    let root = std::env::temp_dir().join(format!("primdecomp-resume-{}", std::process::id()));
    let mut n = 48;
    let (inputs, killed_pid) = loop {
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        let inputs = write_inputs(&root, n);
        if let Some(pid) = run_and_kill(&root, &inputs, "out/") {
            break (inputs, pid);
        }
        // Finished before the kill: a longer batch.
        assert!(
            n < 1000,
            "a batch of {n} inputs still finished before it was killed"
        );
        n *= 2;
    };
    let out = root.join("out");
    let done = done_in_manifest(&out);
    eprintln!("killed with {} of {n} inputs recorded done", done.len());
    assert!(
        (2..n).contains(&done.len()),
        "{} of {n} recorded done",
        done.len()
    );

    // What the kill left, made worse: a temporary file of the killed process, an
    // output with no manifest line that is not what the run writes, and a finished
    // input's output damaged since (cut short).
    let stale = format!(".{}.tmp.{killed_pid}.999", outputs_of(&inputs[n - 1])[0]);
    std::fs::write(out.join(&stale), b"half").unwrap();
    let undone = inputs.iter().rev().find(|i| !done.contains(i)).unwrap();
    std::fs::write(out.join(&outputs_of(undone)[0]), b"{\"format\":").unwrap();
    let damaged = &done[0];
    let p = out.join(&outputs_of(damaged)[1]);
    let bytes = std::fs::read(&p).unwrap();
    std::fs::write(&p, &bytes[..bytes.len() / 2]).unwrap();
    let kept: Vec<(PathBuf, u64)> = done[1..]
        .iter()
        .flat_map(|d| outputs_of(d))
        .map(|o| out.join(o))
        .map(|p| (p.clone(), inode(&p)))
        .collect();

    let res = batch(&root, &inputs, "out/", &["--resume"])
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&res.stdout);
    let stderr = String::from_utf8_lossy(&res.stderr);
    assert_eq!(res.status.code(), Some(0), "{stderr}");
    let skipped = done.len() - 1;
    let line = format!("resume: {skipped} of {n} inputs were done by an earlier run");
    assert!(stdout.contains(&line), "wanted '{line}' in:\n{stdout}");
    for (p, ino) in &kept {
        assert_eq!(inode(p), *ino, "{p:?} was written again");
    }

    let clean = batch(&root, &inputs, "clean/", &["--quiet"])
        .output()
        .expect("runs");
    assert_eq!(clean.status.code(), Some(0));
    let (resumed, clean) = (files(&out), files(&root.join("clean")));
    assert_eq!(resumed.len(), 4 * n, "{:?}", resumed.keys());
    assert_eq!(
        resumed.keys().collect::<Vec<_>>(),
        clean.keys().collect::<Vec<_>>()
    );
    for (name, bytes) in &clean {
        assert!(
            resumed[name] == *bytes,
            "{name} differs from the clean run's"
        );
    }
    std::fs::remove_dir_all(&root).unwrap();
}
