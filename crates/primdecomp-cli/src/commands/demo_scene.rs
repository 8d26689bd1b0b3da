//! `primdecomp demo-scene`: writes the library's built-in demo scene as OBJ.

use crate::exit::println;
use clap::Args;
use primdecomp_files::write_atomic;
use std::path::PathBuf;

/// The scene as the repository holds it (`datasets/demo_scene.obj`, which the
/// library's tests check against the scene it builds, `primdecomp::demo_scene`).
const DEMO_SCENE_OBJ: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../datasets/demo_scene.obj"
));

/// `primdecomp demo-scene`.
#[derive(Args, Debug)]
pub struct DemoSceneArgs {
    /// Output file.
    #[arg(short, long, default_value = "datasets/demo_scene.obj")]
    out: PathBuf,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
}

/// Writes the scene to `--out` atomically.
pub fn run(a: DemoSceneArgs) -> anyhow::Result<()> {
    if a.quiet {
        crate::exit::quiet_from_now();
    }
    let out = a.out;
    write_atomic(&out, DEMO_SCENE_OBJ.as_bytes())
        .map_err(anyhow::Error::from)
        .map(|_| println!("wrote {}", out.display()))
}
