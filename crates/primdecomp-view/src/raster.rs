//! The PNG renderer: a small z-buffer rasteriser of the page's default view, with no
//! browser and no GPU. Each pane draws the input mesh and a collider as the page
//! does (input first, the collider's parts blended over it where they are in front,
//! outlines where the visible part changes or its faces turn by more than
//! [`crate::geometry::FEATURE_ANGLE_DEG`]), at 3×3 samples per pixel, a band of rows
//! at a time. The same scene gives the same bytes.

use crate::camera::Camera;
use crate::geometry::{Parts, FEATURE_ANGLE_DEG};
use crate::palette;

/// Samples per pixel along each axis.
const SS: usize = 3;

/// An RGB image, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
}

/// Vertices and the triangles indexing them.
pub type Triangles<'a> = (&'a [[f64; 3]], &'a [[u32; 3]]);

/// What one pane shows: the input's triangles and/or a collider's parts.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pane<'a> {
    pub input: Option<Triangles<'a>>,
    pub parts: Option<&'a Parts>,
    pub input_opacity: f32,
    pub part_opacity: f32,
}

/// One drawn layer at sample resolution: inverse depth (0 = empty), shaded colour,
/// camera-space normal and the id of the part (1-based).
struct Layer {
    inv_depth: Vec<f64>,
    colour: Vec<[f32; 3]>,
    normal: Vec<[f32; 3]>,
    id: Vec<u32>,
}

impl Layer {
    fn new(n: usize) -> Layer {
        Layer {
            inv_depth: vec![0.0; n],
            colour: vec![[0.0; 3]; n],
            normal: vec![[0.0; 3]; n],
            id: vec![0; n],
        }
    }
}

/// Projection of the camera onto a `w` × `h` sample grid.
struct View {
    eye: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    back: [f64; 3],
    tx: f64,
    ty: f64,
    w: usize,
    h: usize,
    near: f64,
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl View {
    fn new(cam: &Camera, w: usize, h: usize) -> View {
        let (right, up, back) = cam.basis();
        let ty = (0.5 * cam.fov_y_deg.to_radians()).tan();
        View {
            eye: cam.eye,
            right,
            up,
            back,
            tx: ty * w as f64 / h as f64,
            ty,
            w,
            h,
            near: 1e-6 * cam.distance(),
        }
    }

    /// Camera-space position (x right, y up, z towards the viewer).
    fn cam(&self, p: [f64; 3]) -> [f64; 3] {
        let r = [p[0] - self.eye[0], p[1] - self.eye[1], p[2] - self.eye[2]];
        [dot(r, self.right), dot(r, self.up), dot(r, self.back)]
    }

    /// Sample-grid position and inverse depth of a camera-space point in front.
    fn screen(&self, c: [f64; 3]) -> [f64; 3] {
        let d = -c[2];
        [
            (c[0] / d / self.tx + 1.0) * 0.5 * self.w as f64,
            (1.0 - c[1] / d / self.ty) * 0.5 * self.h as f64,
            1.0 / d,
        ]
    }

    /// The triangles in front of the camera, projected: `base(t)` is the colour of
    /// triangle `t` (0..1), `id(t)` its part id (≥ 1).
    fn prepare(
        &self,
        positions: &[[f64; 3]],
        triangles: &[[u32; 3]],
        base: impl Fn(usize) -> [f32; 3],
        id: impl Fn(usize) -> u32,
    ) -> Vec<Projected> {
        let cams: Vec<[f64; 3]> = positions.iter().map(|&p| self.cam(p)).collect();
        let mut out = Vec::new();
        for (ti, t) in triangles.iter().enumerate() {
            let c = t.map(|i| cams[i as usize]);
            if c.iter().any(|p| -p[2] <= self.near) {
                continue;
            }
            let u = [c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]];
            let v = [c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]];
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let len = dot(n, n).sqrt();
            if len == 0.0 || !len.is_finite() {
                continue;
            }
            let s = c.map(|p| self.screen(p));
            let area = (s[1][0] - s[0][0]) * (s[2][1] - s[0][1])
                - (s[1][1] - s[0][1]) * (s[2][0] - s[0][0]);
            if area == 0.0 || !area.is_finite() {
                continue;
            }
            let y0 = s.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            let y1 = s.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
            let ya = (y0 - 0.5).ceil().max(0.0);
            let yb = (y1 - 0.5).floor().min(self.h as f64 - 1.0);
            if yb < ya {
                continue;
            }
            out.push(Projected {
                s,
                n: n.map(|x| x / len),
                inv_area: 1.0 / area,
                rows: (ya as usize, yb as usize),
                colour: base(ti),
                id: id(ti),
            });
        }
        out
    }

    /// Draws the triangles into `layer`, which holds sample rows `row0..` of the
    /// grid. Depth test: nearer wins.
    fn draw(&self, layer: &mut Layer, tris: &[Projected], row0: usize) {
        let rows = layer.id.len() / self.w;
        for t in tris {
            let s = t.s;
            let ya = t.rows.0.max(row0);
            let yb = t.rows.1.min(row0 + rows - 1);
            if yb < ya {
                continue;
            }
            let x0 = s.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            let x1 = s.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
            let xa = (x0 - 0.5).ceil().max(0.0) as usize;
            let xb = ((x1 - 0.5).floor().min(self.w as f64 - 1.0)).max(-1.0);
            if xb < 0.0 {
                continue;
            }
            let xb = xb as usize;
            let (n, inv) = (t.n, t.inv_area);
            for y in ya..=yb {
                let py = y as f64 + 0.5;
                for x in xa..=xb {
                    let px = x as f64 + 0.5;
                    let e = |a: [f64; 3], b: [f64; 3]| {
                        ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) * inv
                    };
                    let (w0, w1, w2) = (e(s[1], s[2]), e(s[2], s[0]), e(s[0], s[1]));
                    if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                        continue;
                    }
                    let z = w0 * s[0][2] + w1 * s[1][2] + w2 * s[2][2];
                    let k = (y - row0) * self.w + x;
                    if z <= layer.inv_depth[k] {
                        continue;
                    }
                    // The point seen, in camera space, and the view direction.
                    let d = 1.0 / z;
                    let p = [
                        ((px / self.w as f64) * 2.0 - 1.0) * self.tx * d,
                        (1.0 - (py / self.h as f64) * 2.0) * self.ty * d,
                        -d,
                    ];
                    let pl = dot(p, p).sqrt();
                    let view = [-p[0] / pl, -p[1] / pl, -p[2] / pl];
                    let nn = if dot(n, view) < 0.0 { n.map(|x| -x) } else { n };
                    let nf = nn.map(|x| x as f32);
                    let sh = palette::shade(nf, view.map(|x| x as f32));
                    layer.inv_depth[k] = z;
                    layer.colour[k] = t.colour.map(|c| c * sh);
                    layer.normal[k] = nf;
                    layer.id[k] = t.id;
                }
            }
        }
    }
}

/// A triangle projected onto the sample grid: its corners (x, y, inverse depth),
/// camera-space unit normal, 1 / twice its signed screen area, the sample rows it
/// may cover, its colour and part id.
struct Projected {
    s: [[f64; 3]; 3],
    n: [f64; 3],
    inv_area: f64,
    rows: (usize, usize),
    colour: [f32; 3],
    id: u32,
}

fn unit_rgb(c: [u8; 3]) -> [f32; 3] {
    c.map(|x| x as f32 / 255.0)
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
}

/// Id of the input's surface in the visible-id buffer.
const INPUT_ID: u32 = u32::MAX;

/// Output rows drawn at a time: the sample buffers hold one band (and a row of
/// samples above and below it for the outlines), so memory does not grow with the
/// image's height.
const BAND: usize = 32;

/// Renders one pane of `width` × `height` pixels seen by `cam`.
pub fn render(pane: &Pane, cam: &Camera, width: usize, height: usize) -> Image {
    let (width, height) = (width.max(1), height.max(1));
    let (w, h) = (width * SS, height * SS);
    let view = View::new(cam, w, h);
    let input = match pane.input {
        Some((pos, tris)) => {
            let c = unit_rgb(palette::INPUT_RGB);
            view.prepare(pos, tris, |_| c, |_| INPUT_ID)
        }
        None => Vec::new(),
    };
    let mut part_base: Vec<[f32; 3]> = Vec::new();
    let parts = match pane.parts {
        Some(p) => {
            part_base = p
                .colour
                .iter()
                .map(|&k| unit_rgb(palette::rgb(k)))
                .collect();
            // Part of each triangle, from the part ranges.
            let mut owner = vec![0u32; p.triangles.len()];
            for (i, w) in p.starts.windows(2).enumerate() {
                owner[w[0] as usize..w[1] as usize].fill(i as u32);
            }
            let base = &part_base;
            view.prepare(
                &p.positions,
                &p.triangles,
                |t| base[owner[t] as usize],
                |t| owner[t] + 1,
            )
        }
        None => Vec::new(),
    };
    let mut rgb = Vec::with_capacity(width * height * 3);
    for band in (0..height).step_by(BAND) {
        let rows = BAND.min(height - band) * SS;
        // Sample rows row0..row0 + n: the band and one row on each side.
        let row0 = (band * SS).saturating_sub(1);
        let n = (band * SS + rows + 1).min(h) - row0;
        let samples = shade_band(&view, pane, &input, &parts, &part_base, row0, n);
        let skip = band * SS - row0;
        downsample(&samples[skip * w..(skip + rows) * w], width, &mut rgb);
    }
    Image { width, height, rgb }
}

/// The final colour of sample rows `row0..row0 + n`, outlines drawn where the
/// visible surface changes or turns (the first and last row only serve as
/// neighbours and are not outlined).
fn shade_band(
    view: &View,
    pane: &Pane,
    input_tris: &[Projected],
    part_tris: &[Projected],
    part_base: &[[f32; 3]],
    row0: usize,
    n_rows: usize,
) -> Vec<[f32; 3]> {
    let n = view.w * n_rows;
    let mut input = Layer::new(n);
    view.draw(&mut input, input_tris, row0);
    let mut parts = Layer::new(n);
    view.draw(&mut parts, part_tris, row0);
    let seen = Seen::of(pane, &input, &parts, part_base);
    outlined(seen, (&input, &parts), view.w, n_rows)
}

/// What is seen at each sample: its colour, the visible surface's id (0: the
/// background) and the colour of its outline.
struct Seen {
    colour: Vec<[f32; 3]>,
    id: Vec<u32>,
    outline: Vec<[f32; 3]>,
}

impl Seen {
    /// The input's and the parts' layers seen through the pane's opacities.
    fn of(pane: &Pane, input: &Layer, parts: &Layer, part_base: &[[f32; 3]]) -> Seen {
        let n = input.id.len();
        let bg = unit_rgb(palette::BACKGROUND_RGB);
        let (ai, ap) = (pane.input_opacity, pane.part_opacity);
        let mut colour = vec![bg; n];
        let mut seen = vec![0u32; n];
        let mut outline = vec![bg; n];
        let input_edge = mix(
            bg,
            unit_rgb(palette::INPUT_RGB).map(|c| c * palette::EDGE_FACTOR),
            ai,
        );
        for k in 0..n {
            let under = if input.id[k] != 0 {
                mix(bg, input.colour[k], ai)
            } else {
                bg
            };
            // Parts win ties with the input (flush plates lie on its faces), as the page
            // pushes the input back with a polygon offset.
            let part_on_top =
                parts.id[k] != 0 && parts.inv_depth[k] >= input.inv_depth[k] * (1.0 - 1e-5);
            if part_on_top {
                colour[k] = mix(under, parts.colour[k], ap);
                seen[k] = parts.id[k];
                let b = part_base[(parts.id[k] - 1) as usize];
                outline[k] = mix(under, b.map(|c| c * palette::EDGE_FACTOR), ap);
            } else if input.id[k] != 0 {
                colour[k] = under;
                seen[k] = INPUT_ID;
                outline[k] = input_edge;
            }
        }
        Seen {
            colour,
            id: seen,
            outline,
        }
    }
}

/// The seen colours of `n_rows` rows of `w` samples, outlined where the visible
/// surface changes or turns.
fn outlined(
    seen: Seen,
    (input, parts): (&Layer, &Layer),
    w: usize,
    n_rows: usize,
) -> Vec<[f32; 3]> {
    let Seen {
        colour,
        id: seen,
        outline,
    } = seen;
    let cos = (FEATURE_ANGLE_DEG.to_radians().cos()) as f32;
    let mut out = colour.clone();
    for y in 0..n_rows {
        for x in 0..w {
            let k = y * w + x;
            if seen[k] == 0 {
                continue;
            }
            let neighbours = [
                (x > 0).then(|| k - 1),
                (x + 1 < w).then(|| k + 1),
                (y > 0).then(|| k - w),
                (y + 1 < n_rows).then(|| k + w),
            ];
            let edge = neighbours.into_iter().flatten().any(|j| {
                if seen[j] != seen[k] {
                    // Between two surfaces, the nearer one draws the line.
                    let (dk, dj) = (
                        depth_of(parts, input, seen[k], k),
                        depth_of(parts, input, seen[j], j),
                    );
                    return dk >= dj;
                }
                if seen[k] == INPUT_ID {
                    return false;
                }
                let (a, b) = (parts.normal[k], parts.normal[j]);
                a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < cos
            });
            if edge {
                out[k] = outline[k];
            }
        }
    }
    out
}

fn depth_of(parts: &Layer, input: &Layer, id: u32, k: usize) -> f64 {
    match id {
        0 => 0.0,
        INPUT_ID => input.inv_depth[k],
        _ => parts.inv_depth[k],
    }
}

/// Appends the pixels of sample rows `hi` (a whole number of pixel rows, `width`
/// pixels wide), each the mean of its SS × SS samples.
fn downsample(hi: &[[f32; 3]], width: usize, rgb: &mut Vec<u8>) {
    let w = width * SS;
    let norm = 1.0 / (SS * SS) as f32;
    for y in 0..hi.len() / w / SS {
        for x in 0..width {
            let mut acc = [0.0f32; 3];
            for dy in 0..SS {
                for dx in 0..SS {
                    let c = hi[(y * SS + dy) * w + x * SS + dx];
                    for i in 0..3 {
                        acc[i] += c[i];
                    }
                }
            }
            for a in acc {
                rgb.push((a * norm * 255.0).round().clamp(0.0, 255.0) as u8);
            }
        }
    }
}

/// Images of equal height side by side, left to right.
pub fn side_by_side(images: &[Image]) -> Image {
    let height = images.iter().map(|i| i.height).max().unwrap_or(0);
    let width: usize = images.iter().map(|i| i.width).sum();
    let bg = palette::BACKGROUND_RGB;
    let mut rgb = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for im in images {
            for x in 0..im.width {
                if y < im.height {
                    let k = (y * im.width + x) * 3;
                    rgb.extend_from_slice(&im.rgb[k..k + 3]);
                } else {
                    rgb.extend_from_slice(&bg);
                }
            }
        }
    }
    Image { width, height, rgb }
}

/// The image as PNG bytes (8-bit RGB; fixed compression settings, so the same image
/// gives the same bytes).
pub fn encode_png(img: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, img.width as u32, img.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Default);
        enc.set_filter(png::FilterType::Paeth);
        let mut w = enc
            .write_header()
            .expect("writing a PNG header to memory cannot fail");
        w.write_image_data(&img.rgb)
            .expect("the buffer holds width × height RGB pixels");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_parts(colour: u8) -> Parts {
        let (v, f) = primdecomp_testkit::shapes::cuboid([0.0; 3], [1.0; 3]);
        let mut p = Parts::new();
        p.push_polygons(&v, &f, colour);
        p
    }

    #[test]
    fn a_cube_covers_the_middle_in_its_colour_with_outlines() {
        let p = cube_parts(0);
        let cam = Camera::three_quarter(&p.positions, 1, 1.0).unwrap();
        let pane = Pane {
            parts: Some(&p),
            part_opacity: 1.0,
            ..Default::default()
        };
        let img = render(&pane, &cam, 64, 64);
        assert_eq!(img.rgb.len(), 64 * 64 * 3);
        let px = |x: usize, y: usize| {
            let k = (y * 64 + x) * 3;
            [img.rgb[k], img.rgb[k + 1], img.rgb[k + 2]]
        };
        assert_eq!(px(0, 0), palette::BACKGROUND_RGB);
        let c = px(32, 32);
        assert!(
            c[2] > c[0] && c[2] > c[1],
            "the box's blue in the middle: {c:?}"
        );
        // Outlines: pixels darker than the pixels 3 away on both sides.
        let sum = |x: usize, y: usize| px(x, y).iter().map(|&c| c as i32).sum::<i32>();
        let lines = (3..61)
            .flat_map(|y| (3..61).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let v = sum(x, y) + 40;
                (v < sum(x - 3, y) && v < sum(x + 3, y)) || (v < sum(x, y - 3) && v < sum(x, y + 3))
            })
            .count();
        assert!(lines > 40, "outlines drawn: {lines} pixels");
        assert_eq!(render(&pane, &cam, 64, 64), img, "same scene, same pixels");
        let png = encode_png(&img);
        assert_eq!(&png[1..4], b"PNG");
    }

    #[test]
    fn the_nearer_part_hides_the_farther_and_the_input_shows_where_it_pokes_out() {
        // A red cube in front of a blue one, seen from +z straight on.
        let mut p = cube_parts(0);
        let red = cube_parts(1);
        let red_front: Vec<[f64; 3]> = red
            .positions
            .iter()
            .map(|v| [v[0], v[1], v[2] + 2.0])
            .collect();
        p.push_triangles(&red_front, &red.triangles, 1);
        let cam = Camera {
            eye: [0.5, 0.5, 10.0],
            target: [0.5, 0.5, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y_deg: 30.0,
        };
        let pane = Pane {
            parts: Some(&p),
            part_opacity: 1.0,
            ..Default::default()
        };
        let img = render(&pane, &cam, 32, 32);
        let k = (16 * 32 + 16) * 3;
        assert!(
            img.rgb[k] > img.rgb[k + 2],
            "red in front: {:?}",
            &img.rgb[k..k + 3]
        );
        // An input triangle in front of everything shows in grey.
        let tri = [[-5.0, -5.0, 5.0], [5.0, -5.0, 5.0], [0.0, 5.0, 5.0]];
        let pane = Pane {
            input: Some((&tri, &[[0, 1, 2]])),
            input_opacity: 1.0,
            ..pane
        };
        let img = render(&pane, &cam, 32, 32);
        let c = &img.rgb[k..k + 3];
        assert!(c[0] == c[1] && c[1] == c[2], "grey input in front: {c:?}");
    }
}
