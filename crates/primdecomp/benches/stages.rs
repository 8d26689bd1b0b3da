//! One criterion group per stage of the driver (load, dedup, adjacency, quadrics, seed,
//! merge, postprocess, output) on a small input (the demo scene), a medium one
//! (`armadillo_libigl.obj`, 86k faces) and the million-face class
//! (`dragon_vrip_full.ply`, 871k faces), the last two read from
//! `../shared/datasets/corpus` — the bench says so loudly when it is absent.
//! Targets are 1% of the faces. Run: `cargo bench --bench stages` (add a group name,
//! e.g. `cargo bench --bench stages -- merge/medium`, to run one).

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use primdecomp::internals::{
    face_pairs, face_quadrics, fitter, keep_mask, run, run_with, seed_volumes, weld, Cleanup,
    Clusters, StdHeap,
};
use primdecomp::{decompose, demo_scene, Goal, Mesh, Params};
use std::path::PathBuf;
use std::time::Duration;

struct Input {
    name: &'static str,
    path: Option<PathBuf>,
    mesh: Mesh,
}

fn corpus(file: &str) -> Option<PathBuf> {
    let p = primdecomp_testkit::corpus_dir().join(file);
    if p.exists() {
        Some(p)
    } else {
        eprintln!(
            "CORPUS ABSENT: {} not found; that bench input is skipped",
            p.display()
        );
        None
    }
}

fn inputs() -> Vec<Input> {
    let mut v = vec![Input {
        name: "small",
        path: None,
        mesh: demo_scene(),
    }];
    for (name, file) in [
        ("medium", "armadillo_libigl.obj"),
        ("large", "dragon_vrip_full.ply"),
    ] {
        if let Some(p) = corpus(file) {
            let mesh = Mesh::load(&p).expect("corpus mesh loads");
            v.push(Input {
                name,
                path: Some(p),
                mesh,
            });
        }
    }
    v
}

fn params(mesh: &Mesh) -> Params {
    Params {
        goal: Goal::counts([(mesh.face_count() / 100).max(1)]),
        ..Default::default()
    }
}

fn stages(c: &mut Criterion) {
    for inp in inputs() {
        let m = &inp.mesh;
        let p = params(m);
        let mut g = c.benchmark_group(format!("stages/{}", inp.name));
        g.sample_size(10).warm_up_time(Duration::from_millis(500));
        if let Some(path) = &inp.path {
            g.bench_function("load", |b| b.iter(|| Mesh::load(path).unwrap()));
        }
        g.bench_function("dedup", |b| b.iter(|| weld(m, p.fit.dedup)));
        let (welded, _) = weld(m, p.fit.dedup);
        g.bench_function("adjacency", |b| b.iter(|| face_pairs(m, &welded)));
        let pairs = face_pairs(m, &welded);
        // Setup never relies on a bench closure having run (filters skip them).
        let mut q = Vec::new();
        face_quadrics(m, p.fit.tangent_eps, &mut q);
        let mut q_bench = Vec::new();
        g.bench_function("quadrics", |b| {
            b.iter(|| face_quadrics(m, p.fit.tangent_eps, &mut q_bench))
        });
        let fitter = fitter(m, &welded, &p, m.aabb());
        g.bench_function("seed", |b| b.iter(|| seed_volumes(&fitter, &q)));
        let vols = seed_volumes(&fitter, &q);
        let fresh = || Clusters::new(q.clone(), vols.clone(), &pairs);
        g.bench_function("merge", |b| {
            b.iter_batched(
                fresh,
                |cl| run(&fitter, cl, &p.goal.targets()),
                BatchSize::LargeInput,
            )
        });
        // The same merge loop driven by std's BinaryHeap: the radix heap's reference.
        g.bench_function("merge_binary_heap", |b| {
            b.iter_batched(
                fresh,
                |cl| run_with::<StdHeap>(&fitter, cl, &p.goal.targets()),
                BatchSize::LargeInput,
            )
        });
        let merged = run(&fitter, fresh(), &p.goal.targets());
        let snap = &merged.snapshots[0];
        let cleanup = Cleanup {
            diagonal: m.diagonal(),
            remove_nested: true,
            thin_box_half: None,
        };
        g.bench_function("postprocess", |b| {
            b.iter(|| keep_mask(m, &snap.prims, &snap.verts, &snap.members, cleanup))
        });
        let dec = decompose(m, &p).unwrap();
        g.bench_function("output_json", |b| b.iter(|| dec.to_json(0, &p)));
        g.bench_function("end_to_end", |b| b.iter(|| decompose(m, &p).unwrap()));
        g.finish();
    }
}

criterion_group!(benches, stages);
criterion_main!(benches);
