//! The one colour definition of the page and the PNG renderer: a colour per primitive
//! kind (in [`primdecomp::Kind::ALL`] order), one for peer hulls, one for the input
//! mesh, the background, and the shading both apply. The page gets these values from
//! the data it embeds; it defines no colour of its own for the scene.

/// Colour per kind, in `Kind::ALL` order: box, sphere, capsule, cylinder, frustum,
/// prism. Hues at least 30° apart, saturated enough to survive shading, so a test can
/// find each kind in a screenshot by its hue.
pub const KIND_RGB: [[u8; 3]; 6] = [
    [0x3d, 0x74, 0xd6], // box: blue, hue 218°
    [0xe0, 0x3c, 0x3c], // sphere: red, hue 0°
    [0x2f, 0xa8, 0x4a], // capsule: green, hue 134°
    [0xf0, 0x8a, 0x1c], // cylinder: orange, hue 31°
    [0x9a, 0x4f, 0xd0], // frustum: purple, hue 275°
    [0x16, 0xb0, 0xb0], // prism: teal, hue 180°
];

/// Peer hulls (CoACD, V-HACD): yellow, hue 48°.
pub const HULL_RGB: [u8; 3] = [0xe6, 0xc0, 0x2a];

/// The input mesh: neutral grey.
pub const INPUT_RGB: [u8; 3] = [0xa8, 0xa8, 0xa8];

/// Background of the page's canvas and of the PNG.
pub const BACKGROUND_RGB: [u8; 3] = [0xf7, 0xf7, 0xf5];

/// Default opacity of the primitives (and hulls) drawn over the input mesh.
pub const PART_OPACITY: f32 = 0.88;

/// Default opacity of the input mesh.
pub const INPUT_OPACITY: f32 = 0.8;

/// Outline colour factor: outlines are the surface colour times this.
pub const EDGE_FACTOR: f32 = 0.45;

/// Shading of a surface with unit normal `n` (turned towards the viewer) at a point
/// seen along unit `v` (from the point to the eye), both in camera space (x right, y
/// up, z towards the viewer): ambient, a key light from the upper left and a headlight.
/// The page's fragment shader computes the same expression.
pub fn shade(n: [f32; 3], v: [f32; 3]) -> f32 {
    let l = KEY_LIGHT;
    let key = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0);
    let head = (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]).max(0.0);
    AMBIENT + KEY * key + HEAD * head
}

/// Camera-space direction towards the key light (unit length).
pub const KEY_LIGHT: [f32; 3] = [-0.408_248_3, 0.408_248_3, 0.816_496_6];
pub const AMBIENT: f32 = 0.28;
pub const KEY: f32 = 0.42;
pub const HEAD: f32 = 0.30;

/// `#rrggbb`.
pub fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// Palette index of the hull colour, after the six kinds.
pub const HULL: u8 = 6;

/// The colour of palette index `i` (a kind, or [`HULL`]).
pub fn rgb(i: u8) -> [u8; 3] {
    match KIND_RGB.get(i as usize) {
        Some(c) => *c,
        None => HULL_RGB,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hue(c: [u8; 3]) -> f32 {
        let [r, g, b] = c.map(|x| x as f32 / 255.0);
        let (max, min) = (r.max(g).max(b), r.min(g).min(b));
        let d = max - min;
        let h = if max == r {
            60.0 * ((g - b) / d).rem_euclid(6.0)
        } else if max == g {
            60.0 * ((b - r) / d + 2.0)
        } else {
            60.0 * ((r - g) / d + 4.0)
        };
        h.rem_euclid(360.0)
    }

    #[test]
    fn kind_and_hull_hues_are_apart() {
        let all: Vec<[u8; 3]> = KIND_RGB.iter().copied().chain([HULL_RGB]).collect();
        for (i, a) in all.iter().enumerate() {
            for b in &all[i + 1..] {
                let d = (hue(*a) - hue(*b)).abs();
                assert!(d.min(360.0 - d) >= 15.0, "{a:?} {b:?}: {d}");
            }
        }
        for (i, a) in KIND_RGB.iter().enumerate() {
            for b in &KIND_RGB[i + 1..] {
                let d = (hue(*a) - hue(*b)).abs();
                assert!(d.min(360.0 - d) >= 30.0, "{a:?} {b:?}: {d}");
            }
        }
    }

    #[test]
    fn key_light_is_unit_and_shade_spans_ambient_to_one() {
        let l = KEY_LIGHT;
        assert!((l[0] * l[0] + l[1] * l[1] + l[2] * l[2] - 1.0).abs() < 1e-6);
        assert!((shade(l, [0.0, 0.0, 1.0]) - (AMBIENT + KEY + HEAD * l[2])).abs() < 1e-6);
        assert!((shade([0.0, 0.0, -1.0], [0.0, 0.0, 1.0]) - AMBIENT).abs() < 1e-6);
    }
}
