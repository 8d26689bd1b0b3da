//! PNG plot of physics-step time against frame number, one line per collider, like
//! the paper's simulation figures (Fig. 6 and the appendix). Drawn by plotters into
//! an RGB buffer and encoded with `png`.
//!
//! Text needs a TrueType font and nothing else (no fontconfig): the file named by
//! `PRIMDECOMP_FONT`, else the first of [`FONT_PATHS`] that exists. On Debian and
//! Ubuntu `apt-get install fonts-dejavu-core` provides one.

use super::report::column_names;
use super::Run;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Where the font is looked for, in order, after `PRIMDECOMP_FONT`.
pub const FONT_PATHS: [&str; 5] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

const SIZE: (u32, u32) = (1000, 560);

/// Registers the font once per process as "sans-serif"; the error says what to
/// install.
fn register_font() -> std::result::Result<(), String> {
    static DONE: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        let candidates: Vec<PathBuf> = std::env::var_os("PRIMDECOMP_FONT")
            .map(PathBuf::from)
            .into_iter()
            .chain(FONT_PATHS.iter().map(PathBuf::from))
            .collect();
        let Some((path, bytes)) = candidates
            .iter()
            .find_map(|p| std::fs::read(p).ok().map(|b| (p, b)))
        else {
            return Err(format!(
                "no TrueType font found for the plot's text: set PRIMDECOMP_FONT to a .ttf file \
                 or install one at {} (Debian/Ubuntu: apt-get install fonts-dejavu-core)",
                FONT_PATHS[0]
            ));
        };
        // plotters keeps fonts for the process's lifetime.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
            .map_err(|_| format!("{}: not a usable TrueType font", path.display()))
    })
    .clone()
}

/// Draws the frame-time plot of `run` into an RGB buffer.
fn draw(run: &Run, title: &str, buf: &mut [u8]) -> std::result::Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let root = BitMapBackend::with_buffer(buf, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let frames = run.settings.frames as f64;
    let ymax = run
        .outcomes
        .iter()
        .flat_map(|o| o.frame_ms.iter().copied())
        .fold(0.0f64, f64::max)
        .max(1e-3)
        * 1.05;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..frames, 0.0..ymax)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("frame")
        .y_desc("physics step (ms)")
        .label_style(("sans-serif", 15))
        .draw()
        .map_err(|e| err(&e))?;
    for (i, (o, name)) in run.outcomes.iter().zip(column_names(run)).enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let points = o.frame_ms.iter().enumerate().map(|(f, &t)| (f as f64, t));
        chart
            .draw_series(LineSeries::new(points, color.stroke_width(1)))
            .map_err(|e| err(&e))?
            .label(format!("{name} (median {:.2} ms)", o.stats.median))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 15))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))
}

/// The plot as PNG bytes.
pub fn to_png(run: &Run, title: &str) -> std::result::Result<Vec<u8>, String> {
    register_font()?;
    let (w, h) = SIZE;
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    draw(run, title, &mut rgb)?;
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Best);
    let mut writer = enc.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(&rgb).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

/// Why a plot was not written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// It could not be drawn (no usable font, drawing failed).
    #[error("{path}: cannot draw the plot: {msg}")]
    Draw {
        path: std::path::PathBuf,
        msg: String,
    },
    /// It could not be written.
    #[error(transparent)]
    Write(#[from] primdecomp_files::Error),
}

/// Writes the plot to `path` atomically.
pub fn write_png(run: &Run, title: &str, path: &Path) -> std::result::Result<(), PlotError> {
    let bytes = to_png(run, title).map_err(|msg| PlotError::Draw {
        path: path.to_path_buf(),
        msg,
    })?;
    Ok(primdecomp_files::write_atomic(path, &bytes)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether this run is CI's (`CI` set to anything but empty, `0` or `false`).
    fn in_ci() -> bool {
        std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "0" && v != "false")
    }

    /// A small run plots to a PNG of the documented size. Needs a font: without one
    /// the test says FONT ABSENT and skips, a failure under CI (scripts/test.sh
    /// installs fonts-dejavu-core).
    #[test]
    fn plot_is_a_png_of_the_documented_size() {
        if let Err(e) = register_font() {
            eprintln!("FONT ABSENT: skipping the plot test: {e}");
            // Counted as a skip by scripts/test.sh (as testkit::record_skip does).
            if let Some(log) = std::env::var_os("PRIMDECOMP_SKIP_LOG") {
                use std::io::Write;
                let f = std::fs::OpenOptions::new()
                    .create(true)
                    .append(true)
                    .open(log);
                let _ =
                    f.map(|mut f| writeln!(f, "plot_is_a_png_of_the_documented_size: FONT ABSENT"));
            }
            assert!(!in_ci(), "FONT ABSENT under CI: {e}");
            return;
        }
        let mesh = primdecomp::Mesh::from_polygons(
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            &[vec![0, 1, 2]],
        )
        .unwrap();
        let settings = crate::Settings {
            balls: 3,
            frames: 5,
            ..Default::default()
        };
        let run = crate::run(&mesh, "tri", &[], &settings, &|_| {}).unwrap();
        let png = to_png(&run, "test").unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let dims: Vec<u32> = [16, 20]
            .iter()
            .map(|&o| u32::from_be_bytes(png[o..o + 4].try_into().unwrap()))
            .collect();
        assert_eq!(dims, [SIZE.0, SIZE.1]);
    }
}
