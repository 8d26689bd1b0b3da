//! Command-line interface: the `primdecomp` parser (clap), one subcommand per module
//! under `commands/`, and the exit codes (0 ok, 2 bad input or settings, 1 anything
//! else).

use crate::args::DecomposeArgs;
use crate::commands::demo_scene::DemoSceneArgs;
use crate::commands::eval::EvalArgs;
use crate::commands::export::ExportCmd;
use crate::commands::sim::SimArgs;
use crate::commands::view::ViewArgs;
use crate::commands::{decompose, demo_scene, eval, export, sim, view};
use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(
    name = "primdecomp",
    version,
    about = "Decompose a mesh into tight convex primitives for collision detection"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// Decompose INPUT (OBJ, PLY, STL, OFF, glTF/GLB) into boxes, spheres, capsules,
    /// cylinders, frustums and trapezoidal prisms that enclose every face.
    Decompose(Box<DecomposeArgs>),
    /// Measure colliders against their input mesh: distances, enclosure, bytes.
    Eval(EvalArgs),
    /// Drop balls on the input mesh and on each collider in Rapier, time every frame's
    /// physics step and compare where the balls end (the paper's §4.1 benchmark).
    Sim(SimArgs),
    /// Look at colliders: a self-contained HTML viewer page (-o) and/or a PNG render
    /// of its default view (--png) of results, the input mesh and peers' hulls.
    View(ViewArgs),
    /// Write a result's colliders for an engine: glTF/GLB with physics extensions,
    /// MuJoCo MJCF, URDF, USD (.usda) or a Godot 4 scene (.tscn).
    Export(Box<ExportCmd>),
    /// Write the built-in demo scene (stairs, table, pipes, house, ring, washer) as OBJ.
    DemoScene(DemoSceneArgs),
}

/// Runs the command line; returns the process exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { 2 } else { 0 };
        }
    };
    let result = match cli.cmd {
        Cmd::Decompose(a) => decompose::run(*a),
        Cmd::Eval(a) => eval::run(a),
        Cmd::Sim(a) => sim::run(a),
        Cmd::View(a) => view::run(a),
        Cmd::Export(a) => export::run(*a),
        Cmd::DemoScene(a) => demo_scene::run(a),
    };
    match result {
        Ok(()) => 0,
        Err(e) => crate::exit::report(&e),
    }
}
