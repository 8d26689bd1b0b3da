//! How soon a cancelled run returns: decomposes MESH to 2,000 primitives again and
//! again, cancelling each run at a later time after its start, and prints the stage
//! it was in and how long `decompose_with` took to return after the cancel.
//!
//! `cargo run --release -p primdecomp --example cancel_latency -- MESH [SECONDS...]`

use primdecomp::{decompose_with, Error, Goal, Params, Progress, Stage};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Cancels `at` after `start`; remembers the stage last reported before that.
struct CancelAt {
    start: Instant,
    at: Duration,
    stage: Mutex<Option<Stage>>,
}

impl Progress for CancelAt {
    fn update(&self, stage: Stage, _fraction: f64) {
        if self.start.elapsed() < self.at {
            *self.stage.lock().unwrap_or_else(|e| e.into_inner()) = Some(stage);
        }
    }
    fn cancelled(&self) -> bool {
        self.start.elapsed() >= self.at
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .ok_or("usage: cancel_latency MESH [SECONDS...]")?;
    let mut times: Vec<f64> = args.map(|a| a.parse()).collect::<Result<_, _>>()?;
    if times.is_empty() {
        times = vec![0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0];
    }
    let mesh = primdecomp::Mesh::load(path.as_ref())?;
    let params = Params {
        goal: Goal::counts([2000]),
        ..Params::default()
    };
    println!("| cancel at (s) | stage | returned after (s) | latency (s) | cancelled |");
    println!("|---:|---|---:|---:|---|");
    for at in times {
        let p = CancelAt {
            start: Instant::now(),
            at: Duration::from_secs_f64(at),
            stage: Mutex::new(None),
        };
        let run = decompose_with(&mesh, &params, &p);
        let total = p.start.elapsed().as_secs_f64();
        let stage = p
            .stage
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .map(Stage::name);
        println!(
            "| {at:.1} | {} | {total:.3} | {:.3} | {} |",
            stage.unwrap_or("-"),
            (total - at).max(0.0),
            matches!(run, Err(Error::Cancelled))
        );
    }
    Ok(())
}
