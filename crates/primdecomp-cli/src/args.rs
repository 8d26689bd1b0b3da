//! `primdecomp decompose`'s options and how inputs are read: `-h` shows the few most
//! runs need, `--help` every option grouped and explained in a user's words (what
//! raising or lowering it does), without the paper's notation.

use clap::Args;
use primdecomp::{Fit, Goal, LoadOptions, Tolerance};
use std::path::PathBuf;

// The cap of a run without -n, named for the help texts.
const MAX_PRIMITIVES: usize = Goal::MAX_PRIMITIVES;

/// How inputs are read (every subcommand that reads a mesh).
#[derive(Args, Debug)]
pub(crate) struct LoadArgs {
    /// glTF: also read buffers outside the glTF's folder.
    ///
    /// By default a glTF's buffers are read only from data: URIs and files inside the
    /// glTF's own folder, so a glTF from an untrusted source cannot make us read other
    /// files. With this flag, absolute paths, paths climbing out of the folder (a
    /// `..`, or a symbolic link leading out) and file: URLs are read too; URLs of other
    /// schemes (http: …) are never read. Every input and buffer must be a regular
    /// file (a pipe, socket, device or directory is refused before reading).
    #[arg(long, hide_short_help = true, help_heading = "Input files")]
    pub allow_external_uris: bool,
}

impl LoadArgs {
    /// The options for `eval` and `sim`, which have no memory limit.
    pub(crate) fn options(&self) -> LoadOptions {
        LoadOptions {
            allow_external_uris: self.allow_external_uris,
            ..LoadOptions::default()
        }
    }
}

#[derive(Args, Debug)]
#[command(after_help = "--help lists every option, explained.")]
#[command(after_long_help = format!(
    "Without -n, --tolerance or --max-bytes: the fewest primitives that all stand within {} \
     of the mesh's size (its bounding-box diagonal), at most {MAX_PRIMITIVES}.",
    Tolerance::DEFAULT
))]
pub(crate) struct DecomposeArgs {
    /// Input meshes: OBJ, PLY, STL, OFF, glTF or GLB.
    ///
    /// With several, -o names a directory and --table prints a table of all results.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,

    // --- What to make ---
    /// About N primitives (a count, or a percentage of the faces such as 1%).
    ///
    /// Several counts (-n 400,100,25) give one result file each from one run. You get
    /// about N: fewer only where the mesh has no more parts worth a primitive of their
    /// own (each further primitive would stand no nearer the surface). A larger N gives
    /// a closer fit and more bytes. With --tolerance or --max-bytes, N is a cap.
    #[arg(
        short = 'n',
        long = "targets",
        value_name = "N",
        value_delimiter = ',',
        allow_hyphen_values = true,
        help_heading = "What to make"
    )]
    pub targets: Option<Vec<String>>,
    /// Every primitive within D of the mesh's surface: a distance, or D% of its size.
    #[arg(
        long,
        long_help = format!(
            "Every primitive within D of the mesh's surface: a distance, or D% of its size.\n\n\
             D in the mesh's units, or a percentage of its bounding-box diagonal (1%). You get \
             the fewest primitives that all stand within D of the surface: a box for a box, a \
             sphere for a sphere. Smaller D: tighter, more primitives. Several (2%,0.5%) give \
             one result file each. The result records the distance reached and, if it could \
             not get within D, why. Default (without -n and --max-bytes): {}, at most \
             {MAX_PRIMITIVES} primitives.",
            Tolerance::DEFAULT
        ),
        value_name = "D",
        value_delimiter = ',',
        allow_hyphen_values = true,
        help_heading = "What to make"
    )]
    pub tolerance: Option<Vec<String>>,
    /// The closest fit stored in at most B bytes (4096, 4K).
    #[arg(
        long,
        long_help = format!(
            "The closest fit stored in at most B bytes (4096, 4K).\n\n\
             Bytes as the paper's Table 2 counts them (4 bytes a number: a box 40, a sphere \
             16, a prism 44). Several give one result file each. Combines with --tolerance, \
             and with -n as a cap (without -n: at most {MAX_PRIMITIVES} primitives)."
        ),
        value_name = "B",
        value_delimiter = ',',
        allow_hyphen_values = true,
        help_heading = "What to make"
    )]
    pub max_bytes: Option<Vec<String>>,
    /// Decompose each object on its own, keeping its name and frame.
    ///
    /// Each glTF node with a mesh (in the node's frame, its transform kept) and each
    /// OBJ o/g group. A count -n N is shared: one primitive each, the rest in
    /// proportion to surface area. A percentage applies to each object. The result
    /// gains an `objects` list, and the exports one body per object.
    #[arg(long, help_heading = "What to make")]
    pub per_object: bool,
    /// Start from the settings of a file (a previous result, or JSON/TOML settings).
    ///
    /// A primdecomp result's `settings` give the same primitives again; a JSON or TOML
    /// file of settings (keys as in a result's `settings`) changes only the keys it
    /// has. Options given on the command line override it.
    #[arg(long, value_name = "FILE", help_heading = "What to make")]
    pub config: Option<PathBuf>,

    // --- Output ---
    /// The result file (default: the input's name + .primdecomp.json, here).
    ///
    /// With several inputs, or when it ends in / or is a directory: the output
    /// directory, where each input writes NAME.primdecomp.json. No output may be an
    /// input or another output of the run (refused before anything is written), and
    /// every file is written whole or not at all. `-o -` (or /dev/stdout) writes the
    /// result to standard output and what the run says to standard error.
    #[arg(short, long, help_heading = "Output")]
    pub out: Option<PathBuf>,
    /// Also write the primitives as an OBJ mesh (each a closed convex mesh around it).
    ///
    /// In a batch (-o naming a directory), the directory where each input writes
    /// NAME.primdecomp.obj.
    #[arg(long, help_heading = "Output")]
    pub obj: Option<PathBuf>,
    /// Also draw the result over the mesh as a PNG picture.
    ///
    /// With several inputs, a directory: one NAME.png each. `primdecomp view` makes an
    /// interactive page.
    #[arg(long, value_name = "OUT.png", help_heading = "Output")]
    pub png: Option<PathBuf>,
    /// Also write the colliders for an engine: .glb/.gltf, .urdf, .usda, .tscn, .xml.
    ///
    /// Repeatable. glTF with Khronos (or, with --gltf-physics omi, OMI) physics
    /// extensions, URDF, USD, a Godot 4 scene, or MuJoCo's MJCF (.xml with --format
    /// mjcf). `primdecomp export` writes them from a result file later.
    #[arg(long, value_name = "OUT.EXT", help_heading = "Output")]
    pub export: Vec<PathBuf>,
    #[command(flatten, next_help_heading = "Export")]
    pub export_opts: crate::commands::export::ExportArgs,
    /// Segments around circles in the OBJ mesh (--obj).
    #[arg(
        long,
        default_value_t = 16,
        hide_short_help = true,
        help_heading = "Output"
    )]
    pub obj_detail: usize,
    /// Print nothing but errors.
    #[arg(short, long, help_heading = "Output")]
    pub quiet: bool,
    /// Also print how the run went: vertices welded, merges, fits, seconds per stage.
    #[arg(short, long, help_heading = "Output")]
    pub verbose: bool,
    /// Print the seconds per stage and the peak memory (even with --quiet), and write
    /// the seconds into the result.
    ///
    /// Without it a result file is the same byte for byte from run to run.
    #[arg(long, hide_short_help = true, help_heading = "Output")]
    pub timings: bool,
    /// Report progress (stage, percent, time left) on stderr even when it is not a
    /// terminal: a line as each stage starts and every few seconds.
    ///
    /// On a terminal a bar shows it anyway for inputs of 100,000 faces or more (not
    /// with --quiet or several inputs at once).
    #[arg(long, hide_short_help = true, help_heading = "Output")]
    pub progress: bool,

    // --- Shape of the primitives ---
    /// Kinds allowed, e.g. box,sphere,capsule (default: all six).
    ///
    /// box, sphere, capsule, cylinder, frustum (a cone cut short) and prism (a box
    /// whose cross-section is a trapezoid).
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "KIND,…",
        help_heading = "Shape"
    )]
    pub kinds: Vec<String>,
    /// Cost factor per kind: a heavier kind is chosen less often.
    #[arg(
        long,
        long_help = format!(
            "Cost factor per kind: a heavier kind is chosen less often.\n\n\
             Defaults {}, which prefer the kinds engines test fastest. Give only the kinds \
             you change.",
            Fit::default().weights_spelled()
        ),
        value_delimiter = ',',
        value_name = "KIND=W,…",
        hide_short_help = true,
        help_heading = "Shape"
    )]
    pub weights: Vec<String>,
    /// The thinnest a primitive may be, a fraction of the mesh's size (default 0.0005).
    ///
    /// Half of the thickness, over the bounding-box diagonal: flat regions become
    /// plates twice this thick. Raise it for thicker plates.
    #[arg(long, value_name = "F", hide_short_help = true, help_heading = "Shape")]
    pub min_extent: Option<f64>,
    /// Fill closed parts into solid primitives instead of shells of plates (slower).
    ///
    /// Merges are priced by the air they add outside the mesh (its inside found on a
    /// voxel grid) instead of their whole volume. Without --solid or --min-thickness,
    /// flat regions are plates 2 × --min-extent thick, which fast bodies can skip
    /// through between two physics steps: for colliders hit by fast bodies use the
    /// engine's continuous collision detection, --min-thickness 0.3 or --solid.
    #[arg(long, hide_short_help = true, help_heading = "Shape")]
    pub solid: bool,
    /// Thicken plates inward to this thickness (a fraction of the mesh's size) where
    /// the part is closed behind them.
    ///
    /// The outer surface stays where it is; at most 0.6 of the part's depth is filled;
    /// open sheets and holes are left as they are. 0.3 fills most closed parts, so fast
    /// bodies stop at them without continuous collision detection, for about twice the
    /// distance to the surface and 1.25 times the time. 0 (default): plates
    /// 2 × --min-extent thick.
    #[arg(long, value_name = "F", hide_short_help = true, help_heading = "Shape")]
    pub min_thickness: Option<f64>,
    /// How hard holes and gaps in flat surfaces resist being covered (default 0.01).
    ///
    /// Merges within a plane are priced as if the primitive were at least this thick
    /// (half of it, a fraction of the mesh's size), so a roof's rim stays a rim instead
    /// of closing into a lid. Raise it to keep more holes open; 0 prices them by their
    /// volume alone.
    #[arg(long, value_name = "F", hide_short_help = true, help_heading = "Shape")]
    pub open_holes: Option<f64>,
    /// How strongly primitives keep off the faces beside them (default 1).
    ///
    /// A plate standing past a wall's top makes a curb that stops rolling bodies;
    /// higher values keep primitives flush with the faces next to them, 0 looks at
    /// volume alone.
    #[arg(long, value_name = "W", hide_short_help = true, help_heading = "Shape")]
    pub rim_weight: Option<f64>,
    /// Centre plates on their faces instead of laying them flush, reaching inward.
    #[arg(long, hide_short_help = true, help_heading = "Shape")]
    pub no_flush_plates: bool,
    /// Keep primitives whose faces all lie inside another primitive.
    #[arg(long, hide_short_help = true, help_heading = "Shape")]
    pub keep_nested: bool,
    /// Stop at exactly N groups of faces, even where the next merges cost nothing.
    ///
    /// By default faces in one plane merge into plates of no more area first, and
    /// plates in one plane are joined where one covers both.
    #[arg(long, hide_short_help = true, help_heading = "Shape")]
    pub no_join_coplanar: bool,
    /// Also remove boxes thinner than this fraction of the mesh's size where others
    /// cover their faces.
    #[arg(long, value_name = "F", hide_short_help = true, help_heading = "Shape")]
    pub remove_thin_boxes: Option<f64>,
    /// Refuse merges adding more than this fraction of the mesh's bounding-box volume.
    ///
    /// Needs --reprice exact (a merge over the cap has no queue entry whose re-pricing
    /// could wait): every merge is priced again at once, which is slower.
    #[arg(long, value_name = "F", hide_short_help = true, help_heading = "Shape")]
    pub max_excess_volume: Option<f64>,
    /// How much a face's edge direction steers its group's orientation (default 0.01).
    ///
    /// Flat groups of faces line up with their edges; 0 turns it off.
    #[arg(long, value_name = "E", hide_short_help = true, help_heading = "Shape")]
    pub tangent_eps: Option<f64>,
    /// Which vertices count as one: exact (default), off, or a distance.
    ///
    /// Vertices at the same position (or within the distance, in the mesh's units)
    /// join the faces around them, so seams between parts are merged like any edge.
    #[arg(
        long,
        value_name = "exact|off|D",
        hide_short_help = true,
        help_heading = "Shape"
    )]
    pub dedup: Option<String>,

    // --- How counts are met ---
    /// For -n: take the paper's greedy merge at N groups, and no more.
    ///
    /// Faster, but on meshes of many separate parts far fewer than N can remain
    /// (the parts inside another's primitive are dropped). By default a count that
    /// comes out short is cut again from the record of merges, keeping the parts apart
    /// where they stand farthest from the mesh.
    #[arg(long, hide_short_help = true, help_heading = "How counts are met",
          conflicts_with_all = ["cut", "fill"])]
    pub greedy: bool,
    /// For -n: always cut the record of merges where primitives stand farthest from
    /// the mesh.
    ///
    /// About half the greedy merge's largest distance on most meshes and the same
    /// mean, in a median 3.5 times the time. --tolerance and --max-bytes always cut.
    #[arg(long, hide_short_help = true, help_heading = "How counts are met")]
    pub cut: bool,
    /// For -n: merge less where removing nested primitives left fewer than N (greedy).
    ///
    /// Searches up to 8N groups, up to four more passes; the result records where the
    /// merge stopped (settings.merge_target).
    #[arg(long, hide_short_help = true, help_heading = "How counts are met")]
    pub fill: bool,

    // --- Speed and memory ---
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long, hide_short_help = true, help_heading = "Speed and memory")]
    pub threads: Option<usize>,
    /// Merge large meshes in K spatial parts side by side first: auto (default) or K.
    ///
    /// auto: 16 parts (or one per 65,536 faces if more) for meshes of 524,288 faces or
    /// more, else 1. 1 merges the whole mesh in one greedy order (the paper's).
    #[arg(
        long,
        value_name = "auto|K",
        hide_short_help = true,
        help_heading = "Speed and memory"
    )]
    pub partitions: Option<String>,
    /// When merges next to a merged group are priced again: exact, deferred, or a
    /// neighbour count (default 64).
    ///
    /// exact: at once (the paper's order); deferred: each when it comes up (faster,
    /// nearly the same order); N: deferred for groups with N or more neighbours.
    #[arg(
        long,
        value_name = "exact|deferred|N",
        hide_short_help = true,
        help_heading = "Speed and memory"
    )]
    pub reprice: Option<String>,
    /// Stay within this much memory: 512M, 8G, available (default) or none.
    ///
    /// An input estimated to need more is decomposed in spatial tiles (--tiles), or
    /// refused when not even tiles would fit.
    #[arg(
        long,
        default_value = "available",
        value_name = "SIZE",
        hide_short_help = true,
        help_heading = "Speed and memory"
    )]
    pub max_memory: String,
    /// Decompose in K spatial tiles, one at a time, as an input over --max-memory is.
    ///
    /// An input whose decomposition would need more than --max-memory is decomposed
    /// in tiles instead of refused: the fewest that fit, each merged to boxes, the
    /// boxes merged on top; every face stays enclosed. This forces K tiles (1 to
    /// 4096). Binary PLY is read a tile at a time; other formats are parsed whole.
    #[arg(
        long,
        value_name = "K",
        hide_short_help = true,
        help_heading = "Speed and memory"
    )]
    pub tiles: Option<usize>,

    // --- Several inputs ---
    /// How many inputs to decompose at once (default: one per thread).
    ///
    /// Each runs on its share of the threads, all within --max-memory together. 1 =
    /// one after another with all threads. The results do not depend on it.
    #[arg(long, hide_short_help = true, help_heading = "Several inputs")]
    pub jobs: Option<usize>,
    /// Print a markdown table of all results at the end.
    #[arg(long, hide_short_help = true, help_heading = "Several inputs")]
    pub table: bool,
    /// Finish a batch (-o DIR) that was interrupted: skip the inputs it finished.
    ///
    /// Inputs that DIR/.primdecomp-manifest.jsonl records as done with the same size,
    /// modification time and settings, and whose outputs are all in place, are
    /// skipped; the rest run again. Without --resume a batch starts a new manifest.
    #[arg(long, hide_short_help = true, help_heading = "Several inputs")]
    pub resume: bool,
    #[command(flatten)]
    pub load: LoadArgs,
}
