//! Both cores and the cost against meshoptimizer, in one run: the corpus's dragon
//! (871k faces) decomposed by the release CLI to 2,000 primitives (`-n 2000`) and by
//! default, each on one thread and on two (`--threads`), and meshoptimizer's
//! simplifier taking the same mesh to 2,000 triangles, all in turn, round after
//! round, so that every cell sees the same machine; the least wall time of each cell
//! is kept (the noise of a shared machine only ever adds time). Prints, per binary
//! and mode, the wall times, the two-thread speed-up (the target: at least 1.8), the
//! ratio to meshoptimizer (targets: 3 for `-n 2000`, 4 by default) and the CPU
//! seconds `--timings` reports, and the machine's load average before and after.
//!
//! Run: `cargo bench -p primdecomp-cli --bench throughput` (needs
//! `../shared/datasets/corpus`). Settings, by environment:
//! - `THROUGHPUT_BINS` (default this build's `primdecomp`): binaries to compare,
//!   comma-separated, run in turn within each round;
//! - `THROUGHPUT_ROUNDS` (default 3).

#[path = "shared/meshopt_time.rs"]
mod meshopt_time;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

const TARGET: usize = 2000;

fn main() {
    let dragon = primdecomp_testkit::corpus_dir().join("dragon_vrip_full.ply");
    if !dragon.exists() {
        eprintln!(
            "CORPUS ABSENT: {} not found; the throughput bench needs ../shared/datasets/corpus",
            dragon.display()
        );
        return;
    }
    let bins: Vec<PathBuf> = std::env::var("THROUGHPUT_BINS").map_or_else(
        |_| vec![PathBuf::from(env!("CARGO_BIN_EXE_primdecomp"))],
        |s| s.split(',').map(PathBuf::from).collect(),
    );
    let rounds: usize = std::env::var("THROUGHPUT_ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let mesh = primdecomp::Mesh::load(&dragon).expect("the dragon loads");
    let (pos, idx) = meshopt_time::flat(&mesh);
    println!("load average before: {}", uptime());
    // Per binary, mode, threads: the least wall and that run's CPU seconds.
    let cells = bins.len() * 4;
    let mut best = vec![(f64::INFINITY, 0.0); cells];
    let mut meshopt = f64::INFINITY;
    for round in 0..rounds {
        meshopt = meshopt.min(meshopt_time::simplify_seconds(&idx, &pos, TARGET));
        for (b, bin) in bins.iter().enumerate() {
            for (m, mode) in ["n2000", "default"].iter().enumerate() {
                for (t, threads) in ["1", "2"].iter().enumerate() {
                    let (wall, cpu) = cli_run(bin, &dragon, mode, threads);
                    eprintln!(
                        "round {round} {} {mode} --threads {threads}: {wall:.2} s",
                        bin.display()
                    );
                    let cell = &mut best[b * 4 + m * 2 + t];
                    if wall < cell.0 {
                        *cell = (wall, cpu);
                    }
                }
            }
        }
    }
    println!("load average after: {}", uptime());
    println!(
        "\nmeshoptimizer's simplifier to {TARGET} triangles: {meshopt:.3} s (least of {rounds})\n"
    );
    println!("| binary | mode | 1 thread s (CPU s) | 2 threads s (CPU s) | speed-up | 2 threads / meshoptimizer |");
    println!("|---|---|---:|---:|---:|---:|");
    for (b, bin) in bins.iter().enumerate() {
        for (m, mode) in ["-n 2000", "default"].iter().enumerate() {
            let (one, two) = (best[b * 4 + m * 2], best[b * 4 + m * 2 + 1]);
            println!(
                "| {} | {mode} | {:.2} ({:.2}) | {:.2} ({:.2}) | {:.2} | {:.1} |",
                bin.display(),
                one.0,
                one.1,
                two.0,
                two.1,
                one.0 / two.0,
                two.0 / meshopt
            );
        }
    }
}

/// Wall seconds of one CLI run (load to written JSON) and the CPU seconds its
/// `--timings` reports (every stage, every thread).
fn cli_run(bin: &Path, input: &Path, mode: &str, threads: &str) -> (f64, f64) {
    let out =
        std::env::temp_dir().join(format!("primdecomp_throughput_{}.json", std::process::id()));
    let mut cmd = Command::new(bin);
    cmd.args([
        "decompose",
        "--quiet",
        "--timings",
        "--threads",
        threads,
        "-o",
    ])
    .arg(&out);
    if mode == "n2000" {
        cmd.args(["-n", &TARGET.to_string()]);
    }
    let start = Instant::now();
    let o = cmd.arg(input).output().expect("run primdecomp");
    let wall = start.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    let cpu = text
        .lines()
        .find_map(|l| l.strip_prefix("cpu       by stage (s): "))
        .map_or(0.0, |l| {
            l.split(", ")
                .filter_map(|s| s.rsplit(' ').next()?.parse::<f64>().ok())
                .sum()
        });
    let _ = std::fs::remove_file(&out);
    (wall, cpu)
}

fn uptime() -> String {
    std::fs::read_to_string("/proc/loadavg").map_or_else(
        |_| "unknown".into(),
        |s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "),
    )
}
