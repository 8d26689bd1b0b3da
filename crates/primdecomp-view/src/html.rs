//! The viewer page: one HTML file holding its JavaScript (WebGL with no library: see
//! [`SCRIPTS`]), its style and the scene's data (JSON with geometry as base64
//! little-endian arrays), so it opens from disk with no network. The same scene gives
//! the same bytes.

use crate::camera;
use crate::geometry::{Parts, FEATURE_ANGLE_DEG};
use crate::palette;
use crate::scene::{Collider, Detail, Input, Scene};
use serde_json::{json, Value};

const TEMPLATE: &str = include_str!("../assets/page.html");

/// The page's script, by its marker in page.html, in the order it runs:
/// `assets/scene.js` decodes the data and places the camera, `assets/gl.js` draws,
/// `assets/viewer.js` runs the page (panes, panel, picking, events) with the other two.
/// page.html puts the three in one function scope, so they add no globals but the
/// `window.primdecompView` that viewer.js exposes for tests.
const SCRIPTS: [(&str, &str); 3] = [
    (
        "__PRIMDECOMP_SCENE_JS__",
        include_str!("../assets/scene.js"),
    ),
    ("__PRIMDECOMP_GL_JS__", include_str!("../assets/gl.js")),
    (
        "__PRIMDECOMP_VIEWER_JS__",
        include_str!("../assets/viewer.js"),
    ),
];

/// Whether `js` can sit inside a `<script>` element as it is: it holds no `</script`
/// (which ends the element, in any case) and no `<!--` (which, before a `<script`,
/// switches the HTML parser into its escaped states).
fn fits_a_script_element(js: &str) -> bool {
    let lower = js.to_ascii_lowercase();
    !lower.contains("</script") && !lower.contains("<!--")
}

/// The page for `scene`.
pub fn page(scene: &Scene, title: &str) -> String {
    let data = script_json(&data(scene, title).to_string());
    debug_assert!(SCRIPTS.iter().all(|s| fits_a_script_element(s.1)));
    let title = escape_html(&primdecomp_files::visible(title));
    let mut values = vec![("__PRIMDECOMP_TITLE__", title.as_str())];
    values.extend(SCRIPTS);
    values.push(("__PRIMDECOMP_DATA__", &data));
    fill(TEMPLATE, &values)
}

/// The template with each marker replaced, in one pass over the template (a value
/// holding a marker's text stays as it is).
fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut out =
        String::with_capacity(template.len() + values.iter().map(|v| v.1.len()).sum::<usize>());
    let mut rest = template;
    while let Some((at, (marker, value))) = values
        .iter()
        .filter_map(|v| rest.find(v.0).map(|i| (i, *v)))
        .min_by_key(|x| x.0)
    {
        out.push_str(&rest[..at]);
        out.push_str(value);
        rest = &rest[at + marker.len()..];
    }
    out.push_str(rest);
    out
}

/// JSON text made safe as the content of a `<script>` element: `<`, `>` and `&` are
/// written as `\u003c`, `\u003e` and `\u0026`. In JSON they occur only inside strings,
/// where the escapes mean the same characters, so the data parses to the same values,
/// and the element's content holds no `<` at all: no `</script`, `<!--` or `<script`
/// in a file or collider name can end the element early or switch the HTML parser into
/// its escaped states, which would swallow the viewer's own script. U+2028 and U+2029
/// are escaped too, for readers that take the block as JavaScript.
pub fn script_json(json: &str) -> String {
    let mut out = String::with_capacity(json.len());
    for c in json.chars() {
        match c {
            '<' => out.push_str("\\u003c"),
            '>' => out.push_str("\\u003e"),
            '&' => out.push_str("\\u0026"),
            '\u{2028}' => out.push_str("\\u2028"),
            '\u{2029}' => out.push_str("\\u2029"),
            c => out.push(c),
        }
    }
    out
}

fn escape_html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for i in 0..4 {
            if i <= c.len() {
                out.push(A[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn f32s(origin: [f64; 3], positions: &[[f64; 3]]) -> String {
    let mut b = Vec::with_capacity(positions.len() * 12);
    for p in positions {
        for d in 0..3 {
            b.extend_from_slice(&((p[d] - origin[d]) as f32).to_le_bytes());
        }
    }
    base64(&b)
}

fn u32s(v: impl IntoIterator<Item = u32>) -> String {
    let b: Vec<u8> = v.into_iter().flat_map(u32::to_le_bytes).collect();
    base64(&b)
}

fn mesh(origin: [f64; 3], p: &Parts) -> Value {
    json!({
        "positions": f32s(origin, &p.positions),
        "indices": u32s(p.triangles.iter().flatten().copied()),
        "starts": u32s(p.starts.iter().copied()),
        "colours": p.colour,
        "edges": u32s(p.edges.iter().flatten().copied()),
    })
}

fn collider(origin: [f64; 3], c: &Collider) -> Value {
    let counts = c.counts();
    let mut by_kind = serde_json::Map::new();
    for k in primdecomp::Kind::ALL {
        by_kind.insert(k.name().into(), json!(counts[k as usize]));
    }
    by_kind.insert("hull".into(), json!(counts[palette::HULL as usize]));
    let (kind, parts, target) = match &c.detail {
        Detail::Primitives { target, json, .. } => ("primitives", json.clone(), *target),
        Detail::Hulls { sizes, .. } => (
            "hulls",
            sizes
                .iter()
                .map(|(v, t)| json!({"vertices": v, "triangles": t}))
                .collect(),
            None,
        ),
    };
    json!({
        "label": c.label,
        "file": c.file,
        "kind": kind,
        "target": target,
        "bytes": c.bytes(),
        "count": c.parts.len(),
        "counts": by_kind,
        "parts": parts,
        "mesh": mesh(origin, &c.parts),
    })
}

/// The data the page embeds.
pub fn data(scene: &Scene, title: &str) -> Value {
    let (lo, hi) = scene.aabb().unwrap_or(([-1.0; 3], [1.0; 3]));
    let origin = [0, 1, 2].map(|d| 0.5 * (lo[d] + hi[d]));
    let rel = |p: [f64; 3]| [0, 1, 2].map(|d| p[d] - origin[d]);
    // The direction of the default view; the page fits the distance and the target
    // to its panes as camera.rs does.
    let cam = camera::Camera::three_quarter(&scene.points(), scene.up_axis, 1.0).unwrap_or(
        camera::Camera {
            eye: [0.0, 0.0, 1.0],
            target: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            fov_y_deg: camera::FOV_Y_DEG,
        },
    );
    let (_, _, back) = cam.basis();
    let input = scene.input.as_ref().map(|i| input_json(origin, i));
    let eval: Vec<Value> = scene
        .eval
        .iter()
        .map(|r| {
            let mut m = r.metrics.clone();
            m.remove("counts");
            m.insert("matches".into(), json!(r.matches));
            Value::Object(m)
        })
        .collect();
    json!({
        "format": "primdecomp-view",
        "version": 1,
        "title": title,
        "palette": palette_json(),
        "feature_angle_deg": FEATURE_ANGLE_DEG,
        "camera": {
            "lo": rel(lo),
            "hi": rel(hi),
            "back": back,
            "up": cam.up,
            "fov_y_deg": cam.fov_y_deg,
            "fill": camera::FILL,
            "centring_rounds": camera::CENTRING_ROUNDS,
        },
        "origin": origin,
        "input": input,
        "levels": scene.levels.iter().map(|c| collider(origin, c)).collect::<Vec<_>>(),
        "peers": scene.peers.iter().map(|c| collider(origin, c)).collect::<Vec<_>>(),
        "eval": eval,
    })
}

/// The input's display mesh as the page draws it, positions relative to `origin`.
fn input_json(origin: [f64; 3], i: &Input) -> Value {
    let d = &i.display;
    json!({
        "file": i.file,
        "faces": d.source_faces,
        "source_triangles": d.source_triangles,
        "triangles": d.triangles.len(),
        "simplified": d.simplified,
        "positions": f32s(origin, &d.positions),
        "indices": u32s(d.triangles.iter().flatten().copied()),
    })
}

/// The colours and light the page shades with (the PNG renders' own, [`palette`]).
fn palette_json() -> Value {
    json!({
        "kinds": primdecomp::Kind::ALL.iter().map(|k| json!({
            "name": k.name(),
            "rgb": palette::hex(palette::KIND_RGB[*k as usize]),
        })).collect::<Vec<_>>(),
        "hull": palette::hex(palette::HULL_RGB),
        "input": palette::hex(palette::INPUT_RGB),
        "background": palette::hex(palette::BACKGROUND_RGB),
        "edge_factor": palette::EDGE_FACTOR,
        "part_opacity": palette::PART_OPACITY,
        "input_opacity": palette::INPUT_OPACITY,
        "light": {
            "key": palette::KEY_LIGHT,
            "ambient": palette::AMBIENT,
            "key_weight": palette::KEY,
            "head_weight": palette::HEAD,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_are_filled_once_and_values_are_not_rescanned() {
        let t = "a __X__ b __Y__ c __X__";
        assert_eq!(
            fill(t, &[("__X__", "__Y__"), ("__Y__", "y")]),
            "a __Y__ b y c __Y__"
        );
    }

    /// No string can end the data block or change how the page parses: the block
    /// holds no `<`, and parses back to the same value.
    #[test]
    fn the_data_block_holds_no_markup() {
        let hostile = [
            "</script><script>alert(1)</script>",
            "<!--<script>",
            "a & b > c \u{2028} \u{2029}",
            "</SCRIPT",
            "\\u003c",
        ];
        let v = serde_json::json!({ "names": hostile, "<key>": 1 });
        let block = script_json(&v.to_string());
        assert!(
            !block.contains(['<', '>', '&', '\u{2028}', '\u{2029}']),
            "{block}"
        );
        let back: serde_json::Value = serde_json::from_str(&block).unwrap();
        assert_eq!(back, v);
    }

    /// Every part of the script can sit in the page's `<script>` element, and the page
    /// holds each part once, in the order of [`SCRIPTS`], with no marker left.
    #[test]
    fn the_page_holds_each_script_once_in_order() {
        for (marker, js) in SCRIPTS {
            assert!(fits_a_script_element(js), "{marker}");
            assert_eq!(TEMPLATE.matches(marker).count(), 1, "{marker}");
        }
        assert!(!fits_a_script_element("a </SCRIPT> b"));
        assert!(!fits_a_script_element("a <!-- b"));
        let scene = Scene {
            input: None,
            levels: Vec::new(),
            peers: Vec::new(),
            eval: Vec::new(),
            up_axis: 1,
        };
        let page = page(&scene, "t");
        let at: Vec<usize> = SCRIPTS
            .iter()
            .map(|(marker, js)| {
                assert_eq!(page.matches(js).count(), 1, "{marker}");
                page.find(js).unwrap()
            })
            .collect();
        assert!(at.windows(2).all(|w| w[0] < w[1]), "{at:?}");
        assert!(!page.contains("__PRIMDECOMP_"));
    }

    #[test]
    fn base64_matches_the_rfc_examples() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (i, o) in cases {
            assert_eq!(base64(i.as_bytes()), o);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0xfd]), "//79");
    }
}
