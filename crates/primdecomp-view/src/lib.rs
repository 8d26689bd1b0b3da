//! primdecomp-view: pictures of colliders, on top of the core's public API.
//!
//! - [`html::page`]: one self-contained HTML file (WebGL, no library, no network)
//!   showing the input mesh, every level of a result, peers' hulls side by side and
//!   the evaluation's distances; clicking a part shows its parameters.
//! - [`render_png`]: the page's default view rendered in software, for reports,
//!   thumbnails and CI.
//!
//! Both draw the same [`scene::Scene`] with the same colours ([`palette`]), camera
//! ([`camera`]) and shading.

pub mod camera;
pub mod geometry;
pub mod html;
pub mod palette;
pub mod raster;
pub mod scene;
pub mod simplify;
pub mod source;

pub use scene::{Options, Scene};

/// Default PNG pane size in pixels (square).
pub const PNG_SIZE: usize = 640;

/// The widest scene a page draws: positions go into the page as 32-bit floats
/// relative to the scene's centre, and the viewer squares them.
pub const MAX_SPAN: f64 = 1e18;

/// The panes of the default view, as the page lays them out: with two or more
/// colliders (a level of ours and peers' hulls), the input alone first (if any), then
/// each collider over the input, side by side; with one collider, that collider over
/// the input; with none, the input.
pub fn default_panes(scene: &Scene) -> Vec<raster::Pane<'_>> {
    let input = scene.input.as_ref().map(|i| {
        (
            i.display.positions.as_slice(),
            i.display.triangles.as_slice(),
        )
    });
    let pane = |parts| raster::Pane {
        input,
        parts,
        input_opacity: palette::INPUT_OPACITY,
        part_opacity: palette::PART_OPACITY,
    };
    let colliders: Vec<&geometry::Parts> = scene
        .levels
        .first()
        .into_iter()
        .chain(&scene.peers)
        .map(|c| &c.parts)
        .collect();
    let mut panes = Vec::new();
    if colliders.len() != 1 && input.is_some() {
        panes.push(raster::Pane {
            input_opacity: 1.0,
            ..pane(None)
        });
    }
    panes.extend(colliders.into_iter().map(|p| pane(Some(p))));
    panes
}

/// The default view as an image, each pane `size` × `size` pixels, seen from the
/// three-quarter camera fitted to the whole scene; `None` for an empty scene.
pub fn render(scene: &Scene, size: usize) -> Option<raster::Image> {
    let cam = camera::Camera::three_quarter(&scene.points(), scene.up_axis, 1.0)?;
    let images: Vec<raster::Image> = default_panes(scene)
        .iter()
        .map(|p| raster::render(p, &cam, size, size))
        .collect();
    Some(raster::side_by_side(&images))
}

/// [`render`] as PNG bytes.
pub fn render_png(scene: &Scene, size: usize) -> Option<Vec<u8>> {
    render(scene, size).map(|i| raster::encode_png(&i))
}
