//! Helpers shared by primdecomp's tests: test shapes, result checks, the corpus, and
//! a containment routine independent of the fitting code (`contain`), and readers
//! that check the engine exports are well formed (`exports`).
#![allow(dead_code)]
pub mod basin;
pub mod check;
pub mod contain;
pub mod demo;
pub mod exports;
pub mod inputs;
pub mod ladder;
pub mod shapes;

/// The built-in demo scene as OBJ text, as the repository holds it
/// (`datasets/demo_scene.obj`, checked against `primdecomp::demo_scene` by the
/// library's tests).
pub const DEMO_SCENE_OBJ: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../datasets/demo_scene.obj"
));

/// Fan triangles of polygons (`faces` index `v`).
pub fn fan_triangles(v: &[[f64; 3]], faces: &[Vec<u32>]) -> Vec<[[f64; 3]; 3]> {
    faces
        .iter()
        .flat_map(|f| {
            (1..f.len() - 1)
                .map(move |i| [v[f[0] as usize], v[f[i] as usize], v[f[i + 1] as usize]])
        })
        .collect()
}

/// Runs `f` on a rayon pool of `threads` threads.
pub fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}

/// The repository's root (this crate lives in `crates/testkit`).
pub fn repo_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `../shared/datasets` beside the repository: the corpus and its catalog.
pub fn datasets_dir() -> std::path::PathBuf {
    repo_root().join("../shared/datasets")
}

/// `../shared/datasets/corpus` beside the repository.
pub fn corpus_dir() -> std::path::PathBuf {
    datasets_dir().join("corpus")
}

/// Says loudly that the corpus is missing, where `looked_for` was expected. Under CI
/// (`CI` set and not `false`/`0`) a missing corpus fails the test: CI has it, so its
/// absence there is a broken set-up, never a reason to pass. Written straight to the
/// stderr handle, not through `eprintln!`, so the harness's capture cannot hide it.
pub fn corpus_absent(looked_for: &std::path::Path) {
    use std::io::Write;
    let bar = "!".repeat(72);
    let msg = format!(
        "\n{bar}\nCORPUS ABSENT: ../shared/datasets/corpus not found; corpus test skipped\n\
         (looked for {})\n{bar}\n",
        looked_for.display()
    );
    if in_ci() {
        panic!("{msg}under CI the corpus must be present");
    }
    let _ = std::io::stderr().write_all(msg.as_bytes());
    record_skip("CORPUS ABSENT");
}

/// Appends `test name: reason` to the file `PRIMDECOMP_SKIP_LOG` names (where
/// `scripts/test.sh` counts the Rust tests that skipped their work: the harness counts
/// them as passed). The test's name is its thread's, as the harness names it.
pub fn record_skip(reason: &str) {
    use std::io::Write;
    let Some(log) = std::env::var_os("PRIMDECOMP_SKIP_LOG") else {
        return;
    };
    let name = std::thread::current().name().unwrap_or("?").to_string();
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(log);
    if let Ok(mut f) = file {
        let _ = writeln!(f, "{name}: {reason}");
    }
}

/// Whether this run is CI's (`CI` set to anything but empty, `0` or `false`).
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "0" && v != "false")
}

/// A corpus mesh from `../shared/datasets/corpus`, or `None` after saying "CORPUS
/// ABSENT" (a failure under CI: [`corpus_absent`]).
pub fn corpus_mesh(name: &str) -> Option<primdecomp::Mesh> {
    let path = corpus_dir().join(name);
    if !path.is_file() {
        corpus_absent(&path);
        return None;
    }
    Some(primdecomp::Mesh::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

/// A uniformly random rotation's axes (rows of an orthonormal, right-handed frame),
/// from a uniformly random unit quaternion (rejection sampling in the unit 4-ball).
pub fn random_axes(rng: &mut rand_chacha::ChaCha8Rng) -> [[f64; 3]; 3] {
    use rand::Rng;
    let [w, x, y, z] = loop {
        let q: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let n2: f64 = q.iter().map(|c| c * c).sum();
        if n2 > 1e-4 && n2 <= 1.0 {
            break q.map(|c| c / n2.sqrt());
        }
    };
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + z * w),
            2.0 * (x * z - y * w),
        ],
        [
            2.0 * (x * y - z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + x * w),
        ],
        [
            2.0 * (x * z + y * w),
            2.0 * (y * z - x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}
