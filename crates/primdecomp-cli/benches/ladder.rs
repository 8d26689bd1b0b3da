//! The scale ladder: the dragon from the corpus (871k faces), the dragon subdivided
//! 1, 2 and 3 times with a small seeded displacement (3.5M, 14M, 56M faces) and a
//! made-up city block of tens of thousands of separate parts (about 10M faces), each
//! written here to a binary PLY file (streamed: never the large mesh in memory,
//! never committed, removed after its rung) and decomposed by the release CLI with
//! `--timings`, once to 2,000 primitives (`-n 2000`) and once by default (every
//! primitive within 2%). Per rung and mode: every stage's seconds and microseconds
//! per face, the peak resident memory of each stage and of the run, in MiB and bytes
//! per input face, and its CPU seconds; then each stage's CPU time per face against
//! the dragon's (the linearity the ladder is for; CPU time is what other jobs on a
//! shared machine cannot add to). The dragon against meshoptimizer's simplifier in
//! one run is the `scale` benchmark's.
//!
//! Run: `cargo bench -p primdecomp-cli --bench ladder` (needs
//! `../shared/datasets/corpus`). Settings, by environment:
//! - `LADDER_RUNGS` (default `dragon,x1,x2,x3,city`): which rungs;
//! - `LADDER_MODES` (default `n2000,default`);
//! - `LADDER_THREADS` (default: the machine's): a list such as `1,2` runs each cell
//!   at each count and prints the speed-up;
//! - `LADDER_RUNS` (default 1): runs per cell, the least time kept (the machine's
//!   noise only ever adds time) and the largest memory;
//! - `LADDER_DIR` (default the temporary directory): where the inputs are written;
//!   `LADDER_KEEP=1` keeps them;
//! - `LADDER_BIN` (default: this build's `primdecomp`): the binary to measure;
//! - `LADDER_CANCEL=1`: per rung and mode, runs in this process (`decompose_with`)
//!   cancelled 0.5, 1.5, 3.5, … seconds after they start (doubling the wait until a
//!   run finishes first) and prints the longest time from the cancel to the return
//!   (the answer wanted within 1 s);
//! - `LADDER_EVAL` (default 0): with N > 0, `primdecomp eval --samples N` checks each
//!   result's enclosure of the input and prints the enclosed fraction.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

const TARGET: usize = 2000;

/// One CLI run's figures.
#[derive(Clone, Debug, Default)]
struct Run {
    wall: f64,
    /// The `--timings` stages in order, seconds.
    stages: Vec<(String, f64)>,
    /// Each stage's peak resident memory, MiB.
    memory: Vec<(String, f64)>,
    /// Each stage's CPU seconds (the process's, every thread).
    cpu: Vec<(String, f64)>,
    peak: f64,
    primitives: usize,
    enclosed: Option<f64>,
    /// Why the run failed (its first line on stderr), if it did: an input refused
    /// for the memory available is a result too.
    failed: Option<String>,
}

fn env_list(name: &str, default: &str) -> Vec<String> {
    std::env::var(name)
        .unwrap_or_else(|_| default.into())
        .split(',')
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect()
}

fn env_num(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let corpus = primdecomp_testkit::corpus_dir();
    let dragon = corpus.join("dragon_vrip_full.ply");
    if !dragon.exists() {
        eprintln!(
            "CORPUS ABSENT: {} not found; the ladder needs ../shared/datasets/corpus",
            dragon.display()
        );
        return;
    }
    let bin = std::env::var("LADDER_BIN").map_or_else(
        |_| PathBuf::from(env!("CARGO_BIN_EXE_primdecomp")),
        PathBuf::from,
    );
    let rungs = env_list("LADDER_RUNGS", "dragon,x1,x2,x3,city");
    let modes = env_list("LADDER_MODES", "n2000,default");
    let threads = env_list("LADDER_THREADS", "");
    let runs = env_num("LADDER_RUNS", 1).max(1);
    let samples = env_num("LADDER_EVAL", 0);
    let dir = std::env::var("LADDER_DIR").map_or_else(|_| std::env::temp_dir(), PathBuf::from);
    let keep = std::env::var("LADDER_KEEP").is_ok_and(|v| v == "1");
    let cancel = std::env::var("LADDER_CANCEL").is_ok_and(|v| v == "1");
    let mut answers = Vec::new();
    let source = primdecomp::Mesh::load(&dragon).expect("the dragon loads");
    println!("machine: {}", uptime());
    let mut table: Vec<(String, u64, String, String, Run)> = Vec::new();
    for rung in &rungs {
        let (path, faces) = match rung.as_str() {
            "dragon" => (dragon.clone(), source.face_count() as u64),
            "city" => {
                let path = dir.join("primdecomp_ladder_city.ply");
                let now = Instant::now();
                let (f, _) = primdecomp_testkit::ladder::city_block_ply(40_000, 1, &path)
                    .expect("write the city block");
                eprintln!(
                    "city block: {f} faces written in {:.1} s",
                    now.elapsed().as_secs_f64()
                );
                (path, f)
            }
            x if x.starts_with('x') => {
                let levels: u32 = x[1..].parse().expect("x1, x2 or x3");
                let path = dir.join(format!("primdecomp_ladder_x{levels}.ply"));
                let now = Instant::now();
                let (f, _) = primdecomp_testkit::ladder::subdivided_ply(&source, levels, 49, &path)
                    .expect("write the subdivided dragon");
                eprintln!(
                    "dragon x{levels}: {f} faces written in {:.1} s",
                    now.elapsed().as_secs_f64()
                );
                (path, f)
            }
            other => panic!("unknown rung {other}: dragon, x1, x2, x3 or city"),
        };
        for mode in &modes {
            for t in threads
                .iter()
                .map(Some)
                .chain(threads.is_empty().then_some(None))
            {
                let mut best: Option<Run> = None;
                // In turn with the other cells of the rung would be fairer; the
                // least of `runs` is what the noise cannot lower.
                for _ in 0..runs {
                    let r = cli_run(&bin, &path, mode, t.map(String::as_str), samples);
                    eprintln!(
                        "{rung} {mode} threads {t:?}: {:.2} s, {:.0} MiB",
                        r.wall, r.peak
                    );
                    best = Some(match best {
                        Some(b) if b.wall <= r.wall => Run {
                            peak: b.peak.max(r.peak),
                            ..b
                        },
                        Some(b) => Run {
                            peak: b.peak.max(r.peak),
                            ..r
                        },
                        None => r,
                    });
                }
                let t = t.cloned().unwrap_or_else(|| "-".into());
                table.push((rung.clone(), faces, mode.clone(), t, best.expect("one run")));
            }
        }
        if cancel {
            let mesh = primdecomp::Mesh::load(&path).expect("the rung loads");
            for mode in &modes {
                let (longest, tries) = cancel_answers(&mesh, mode);
                eprintln!("{rung} {mode}: cancel answered within {longest:.3} s over {tries} runs");
                answers.push((rung.clone(), mode.clone(), longest, tries));
            }
        }
        if rung != "dragon" && !keep {
            let _ = std::fs::remove_file(&path);
        }
        // The tables so far after every rung but the last: a long ladder stopped
        // early keeps what it measured.
        if rung != rungs.last().expect("a rung") {
            println!("\n## After {rung}");
            report(&table);
        }
    }
    println!("\n## The ladder");
    report(&table);
    if !answers.is_empty() {
        println!("\n| rung | mode | cancelled runs | longest wait, cancel to return (s) |");
        println!("|---|---|---:|---:|");
        for (rung, mode, longest, tries) in answers {
            println!("| {rung} | {mode} | {tries} | {longest:.3} |");
        }
    }
}

/// Runs `mesh` in `mode` in this process, cancelled after 0.5, 1.5, 3.5, … s
/// until a run finishes before its cancel; the longest time from a cancel to the
/// run's return, and the number of cancelled runs.
fn cancel_answers(mesh: &primdecomp::Mesh, mode: &str) -> (f64, usize) {
    use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
    struct Flag(AtomicBool);
    impl primdecomp::Progress for Flag {
        fn cancelled(&self) -> bool {
            self.0.load(Relaxed)
        }
    }
    let params = primdecomp::Params {
        goal: if mode == "n2000" {
            primdecomp::Goal::counts([TARGET])
        } else {
            primdecomp::Goal::default()
        },
        ..primdecomp::Params::default()
    };
    let (mut longest, mut tries, mut wait) = (0.0f64, 0, 0.5);
    loop {
        let flag = Flag(AtomicBool::new(false));
        let set_at = std::sync::Mutex::new(None);
        let (result, returned) = std::thread::scope(|s| {
            let run = s.spawn(|| {
                let r = primdecomp::decompose_with(mesh, &params, &flag);
                (r, Instant::now())
            });
            let start = Instant::now();
            while !run.is_finished() && start.elapsed().as_secs_f64() < wait {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            if !run.is_finished() {
                *set_at.lock().unwrap() = Some(Instant::now());
                flag.0.store(true, Relaxed);
            }
            run.join().expect("no panic")
        });
        match (result, set_at.into_inner().unwrap()) {
            (Err(primdecomp::Error::Cancelled), Some(at)) => {
                longest = longest.max(returned.duration_since(at).as_secs_f64());
                tries += 1;
                wait = 2.0 * wait + 0.5;
            }
            (Ok(_), _) => return (longest, tries),
            (Err(e), _) => panic!("{e}"),
        }
    }
}

/// One run of the CLI on `input` in `mode`, parsed from its `--timings` lines.
fn cli_run(bin: &Path, input: &Path, mode: &str, threads: Option<&str>, samples: usize) -> Run {
    let out = std::env::temp_dir().join(format!("primdecomp_ladder_{}.json", std::process::id()));
    let mut cmd = Command::new(bin);
    cmd.args(["decompose", "--quiet", "--timings", "-o"])
        .arg(&out);
    if mode == "n2000" {
        cmd.args(["-n", &TARGET.to_string()]);
    }
    if let Some(t) = threads {
        cmd.args(["--threads", t]);
    }
    let start = Instant::now();
    let o = cmd.arg(input).output().expect("run primdecomp");
    let wall = start.elapsed().as_secs_f64();
    if !o.status.success() {
        let why = String::from_utf8_lossy(&o.stderr);
        return Run {
            wall,
            failed: Some(why.lines().next().unwrap_or("failed").to_string()),
            ..Run::default()
        };
    }
    let text = String::from_utf8_lossy(&o.stdout);
    let mut run = Run {
        wall,
        ..Run::default()
    };
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("seconds   ") {
            let stages = rest.split(" | ").next().unwrap_or("");
            run.stages = pairs(stages);
        } else if let Some(rest) = line.strip_prefix("memory    by stage (MiB): ") {
            run.memory = pairs(rest);
        } else if let Some(rest) = line.strip_prefix("cpu       by stage (s): ") {
            run.cpu = pairs(rest);
        } else if let Some(rest) = line.strip_prefix("memory    peak resident ") {
            run.peak = rest
                .split(' ')
                .next()
                .and_then(|m| m.parse().ok())
                .unwrap_or(0.0);
        }
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&out).expect("result written")).expect("JSON");
    run.primitives = json["primitives"].as_array().map_or(0, Vec::len);
    if samples > 0 {
        run.enclosed = Some(enclosed(bin, input, &out, samples));
    }
    let _ = std::fs::remove_file(&out);
    run
}

/// `name value, name value` pairs.
fn pairs(s: &str) -> Vec<(String, f64)> {
    s.split(", ")
        .filter_map(|p| {
            let (n, v) = p.rsplit_once(' ')?;
            Some((n.to_string(), v.parse().ok()?))
        })
        .collect()
}

/// The enclosed fraction of the input's surface that `primdecomp eval` measures.
fn enclosed(bin: &Path, input: &Path, result: &Path, samples: usize) -> f64 {
    let json = std::env::temp_dir().join(format!(
        "primdecomp_ladder_eval_{}.json",
        std::process::id()
    ));
    let o = Command::new(bin)
        .args(["eval", "--samples", &samples.to_string(), "--json"])
        .arg(&json)
        .arg("--input")
        .arg(input)
        .arg(result)
        .output()
        .expect("run primdecomp eval");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&json).expect("eval written")).expect("JSON");
    let _ = std::fs::remove_file(&json);
    find_number(&v, "enclosure").expect("an enclosure fraction in eval's JSON")
}

/// The first number under a key named `key`, anywhere in `v`.
fn find_number(v: &serde_json::Value, key: &str) -> Option<f64> {
    match v {
        serde_json::Value::Object(m) => m
            .get(key)
            .and_then(serde_json::Value::as_f64)
            .or_else(|| m.values().find_map(|x| find_number(x, key))),
        serde_json::Value::Array(a) => a.iter().find_map(|x| find_number(x, key)),
        _ => None,
    }
}

fn uptime() -> String {
    Command::new("uptime")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}

/// The markdown tables: per cell, time and memory; per stage, µs per face and its
/// ratio to the dragon's; the thread speed-ups.
fn report(table: &[(String, u64, String, String, Run)]) {
    let names = names_of(table, |r| &r.stages);
    println!("\n| rung | faces | mode | threads | wall s | µs/face | peak MiB | B/face | primitives | enclosed |");
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    for (rung, faces, mode, t, r) in table {
        if let Some(why) = &r.failed {
            println!("| {rung} | {faces} | {mode} | {t} | failed: {why} | | | | | |");
            continue;
        }
        println!(
            "| {rung} | {faces} | {mode} | {t} | {:.2} | {:.2} | {:.0} | {:.0} | {} | {} |",
            r.wall,
            1e6 * r.wall / *faces as f64,
            r.peak,
            r.peak * 1048576.0 / *faces as f64,
            r.primitives,
            r.enclosed.map_or("-".into(), |e| format!("{e:.6}"))
        );
    }
    println!("\nSeconds per stage (µs per face in brackets):\n");
    println!("| rung | mode | threads | {} |", names.join(" | "));
    println!("|---|---|---|{}", "---:|".repeat(names.len()));
    for (rung, faces, mode, t, r) in table {
        let cells: Vec<String> = names
            .iter()
            .map(|n| match r.stages.iter().find(|s| &s.0 == n) {
                Some((_, s)) => format!("{s:.2} ({:.2})", 1e6 * s / *faces as f64),
                None => "-".into(),
            })
            .collect();
        println!("| {rung} | {mode} | {t} | {} |", cells.join(" | "));
    }
    println!("\nPeak memory per stage, bytes per face:\n");
    let mem_names = names_of(table, |r| &r.memory);
    println!("| rung | mode | threads | {} |", mem_names.join(" | "));
    println!("|---|---|---|{}", "---:|".repeat(mem_names.len()));
    for (rung, faces, mode, t, r) in table {
        let cells: Vec<String> = mem_names
            .iter()
            .map(|n| match r.memory.iter().find(|s| &s.0 == n) {
                Some((_, m)) => format!("{:.0}", m * 1048576.0 / *faces as f64),
                None => "-".into(),
            })
            .collect();
        println!("| {rung} | {mode} | {t} | {} |", cells.join(" | "));
    }
    cpu_table(table);
    growth(table);
    speedups(table);
}

/// Each stage's CPU time per face at every rung over the dragon's (same mode and
/// threads), and the whole run's.
fn growth(table: &[(String, u64, String, String, Run)]) {
    let names = names_of(table, |r| &r.cpu);
    let base: BTreeMap<(String, String), (u64, &Run)> = table
        .iter()
        .filter(|(rung, ..)| rung == "dragon")
        .map(|(_, f, m, t, r)| ((m.clone(), t.clone()), (*f, r)))
        .collect();
    if base.is_empty() {
        return;
    }
    println!("\nCPU time per face over the dragon's (same mode and threads; stages under 0.05 CPU s on the dragon left out):\n");
    println!(
        "| rung | mode | threads | whole run | {} |",
        names.join(" | ")
    );
    println!("|---|---|---|---:|{}", "---:|".repeat(names.len()));
    for (rung, faces, mode, t, r) in table
        .iter()
        .filter(|x| x.0 != "dragon" && x.4.failed.is_none())
    {
        let Some(&(bf, b)) = base.get(&(mode.clone(), t.clone())) else {
            continue;
        };
        let scale = bf as f64 / *faces as f64;
        let cells: Vec<String> = names
            .iter()
            .map(|n| {
                let get = |r: &Run| r.cpu.iter().find(|s| &s.0 == n).map(|s| s.1);
                match (get(r), get(b)) {
                    (Some(x), Some(y)) if y >= 0.05 => format!("{:.2}", x * scale / y),
                    _ => "-".into(),
                }
            })
            .collect();
        let total = |r: &Run| r.cpu.iter().map(|s| s.1).sum::<f64>();
        println!(
            "| {rung} | {mode} | {t} | {:.2} | {} |",
            total(r) * scale / total(b),
            cells.join(" | ")
        );
    }
}

/// The stage names `field` holds over every run of `table`, in order of first use.
fn names_of(
    table: &[(String, u64, String, String, Run)],
    field: impl Fn(&Run) -> &Vec<(String, f64)>,
) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for (.., r) in table {
        for (n, _) in field(r) {
            if !names.contains(n) {
                names.push(n.clone());
            }
        }
    }
    names
}

/// CPU seconds per stage (µs per face in brackets).
fn cpu_table(table: &[(String, u64, String, String, Run)]) {
    let names = names_of(table, |r| &r.cpu);
    println!("\nCPU seconds per stage, every thread (µs per face in brackets):\n");
    println!("| rung | mode | threads | total | {} |", names.join(" | "));
    println!("|---|---|---|---:|{}", "---:|".repeat(names.len()));
    for (rung, faces, mode, t, r) in table {
        let cell = |s: f64| format!("{s:.2} ({:.2})", 1e6 * s / *faces as f64);
        let cells: Vec<String> = names
            .iter()
            .map(|n| {
                r.cpu
                    .iter()
                    .find(|s| &s.0 == n)
                    .map_or("-".into(), |s| cell(s.1))
            })
            .collect();
        let total = r.cpu.iter().map(|s| s.1).sum::<f64>();
        println!(
            "| {rung} | {mode} | {t} | {} | {} |",
            cell(total),
            cells.join(" | ")
        );
    }
}

/// Wall time at one thread over that at each other count, per rung and mode.
fn speedups(table: &[(String, u64, String, String, Run)]) {
    let one: Vec<_> = table.iter().filter(|x| x.3 == "1").collect();
    if one.is_empty() {
        return;
    }
    println!("\n| rung | mode | threads | speed-up over 1 thread |");
    println!("|---|---|---:|---:|");
    for (rung, _, mode, _, r1) in one {
        for (_, _, _, t, r) in table
            .iter()
            .filter(|x| &x.0 == rung && &x.2 == mode && x.3 != "1")
        {
            println!("| {rung} | {mode} | {t} | {:.2} |", r1.wall / r.wall);
        }
    }
}
