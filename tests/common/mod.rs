//! Shared test helpers.
#![allow(dead_code)]
pub mod basin;
pub mod check;
pub mod contain;
pub mod demo;
pub mod shapes;

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

/// A corpus mesh from `../shared/datasets/corpus`, or `None` after printing "CORPUS
/// ABSENT" (the tests that need the corpus say so loudly and return).
pub fn corpus_mesh(name: &str) -> Option<primdecomp::Mesh> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/datasets/corpus")
        .join(name);
    if !path.is_file() {
        eprintln!("CORPUS ABSENT: {} not found; test skipped", path.display());
        return None;
    }
    Some(primdecomp::mesh::io::load(&path).unwrap_or_else(|e| panic!("{e}")))
}
