//! The PNG render of a corpus mesh's result, decoded and looked at: not blank, every
//! kind the level holds in its palette colour (by hue, as shading darkens it) and no
//! colour of a kind it lacks, the object's silhouette a plausible share of the image
//! and fitted to the frame, peers' hulls in their own pane, and the same bytes for
//! the same scene.

use primdecomp_view::{palette, scene, Scene};
use std::path::{Path, PathBuf};

const MESH: &str = "vhacd_lamp.obj";
const SIZE: usize = 256;

struct Decoded {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

fn decode(bytes: &[u8]) -> Decoded {
    let dec = png::Decoder::new(bytes);
    let mut r = dec.read_info().expect("a PNG header");
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).expect("a PNG frame");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    Decoded {
        width: info.width as usize,
        height: info.height as usize,
        rgb: buf,
    }
}

fn hsv(c: &[u8]) -> (f32, f32, f32) {
    let [r, g, b] = [c[0], c[1], c[2]].map(|x| x as f32);
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    let d = max - min;
    let h = if d == 0.0 {
        0.0
    } else if max == r {
        60.0 * ((g - b) / d).rem_euclid(6.0)
    } else if max == g {
        60.0 * ((b - r) / d + 2.0)
    } else {
        60.0 * ((r - g) / d + 4.0)
    };
    (h, if max > 0.0 { d / max } else { 0.0 }, max / 255.0)
}

/// Pixels in columns `x0..x1` whose hue is within 12° of `c`'s, saturated and lit.
fn hue_count(img: &Decoded, x0: usize, x1: usize, c: [u8; 3]) -> usize {
    let (h0, _, _) = hsv(&c);
    (0..img.height)
        .flat_map(|y| (x0..x1).map(move |x| (y * img.width + x) * 3))
        .filter(|&k| {
            let (h, s, v) = hsv(&img.rgb[k..k + 3]);
            let d = (h - h0).abs();
            s >= 0.3 && v >= 0.15 && d.min(360.0 - d) <= 12.0
        })
        .count()
}

/// Pixels in columns `x0..x1` not of the background, and their bounding box.
fn silhouette(img: &Decoded, x0: usize, x1: usize) -> (usize, [usize; 4]) {
    let bg = palette::BACKGROUND_RGB;
    let mut n = 0;
    let mut bb = [usize::MAX, usize::MAX, 0, 0];
    for y in 0..img.height {
        for x in x0..x1 {
            let k = (y * img.width + x) * 3;
            if img.rgb[k..k + 3] != bg {
                n += 1;
                bb = [bb[0].min(x), bb[1].min(y), bb[2].max(x), bb[3].max(y)];
            }
        }
    }
    (n, bb)
}

/// The corpus mesh decomposed to `target` (its JSON and its tessellation as an OBJ of
/// convex hulls written into `dir`), or `None` without the corpus.
fn result(dir: &Path, target: usize) -> Option<(PathBuf, PathBuf, PathBuf)> {
    let mesh_path = primdecomp_testkit::corpus_dir().join(MESH);
    let mesh = primdecomp_testkit::corpus_mesh(MESH)?;
    let params = primdecomp::Params {
        goal: primdecomp::Goal::counts([target]),
        ..Default::default()
    };
    let dec = primdecomp::decompose(&mesh, &params).expect("decomposes");
    let json = dir.join("lamp.json");
    std::fs::write(&json, dec.to_json(0, &params)).unwrap();
    let obj = dir.join("tessellation.obj");
    std::fs::write(&obj, dec.levels[0].to_obj(16)).unwrap();
    Some((mesh_path, json, obj))
}

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("primdecomp-view-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_render_of_a_corpus_result_shows_its_kinds_in_their_colours() {
    let dir = scratch("png");
    let Some((mesh, json, _)) = result(&dir, 60) else {
        return;
    };
    let opts = scene::Options::default();
    let levels = scene::load_levels(&json, &opts).unwrap();
    let counts = levels[0].counts();
    let s = Scene {
        input: Some(scene::load_input(&mesh, &opts).unwrap()),
        levels,
        peers: Vec::new(),
        eval: Vec::new(),
        up_axis: 1,
    };
    let bytes = primdecomp_view::render_png(&s, SIZE).unwrap();
    assert_eq!(
        primdecomp_view::render_png(&s, SIZE).unwrap(),
        bytes,
        "same scene, same bytes"
    );
    let img = decode(&bytes);
    assert_eq!((img.width, img.height), (SIZE, SIZE), "one pane");
    let (drawn, bb) = silhouette(&img, 0, SIZE);
    let share = drawn as f64 / (SIZE * SIZE) as f64;
    // A lamp post: tall and thin, so well under half the square, but not a speck.
    assert!((0.05..0.6).contains(&share), "silhouette share {share}");
    // The camera fits the box to the frame: the tall side spans most of the height.
    let (w, h) = (bb[2] - bb[0] + 1, bb[3] - bb[1] + 1);
    assert!(w.max(h) as f64 >= 0.6 * SIZE as f64, "silhouette {w}×{h}");
    assert!(
        bb[0] > 0 && bb[1] > 0 && bb[2] < SIZE - 1 && bb[3] < SIZE - 1,
        "inside the frame: {bb:?}"
    );
    let present = counts[..6].iter().filter(|&&n| n > 0).count();
    assert!(present >= 5, "the mesh shows several kinds: {counts:?}");
    for (k, &n) in counts[..6].iter().enumerate() {
        let seen = hue_count(&img, 0, SIZE, palette::KIND_RGB[k]);
        if n > 0 {
            assert!(
                seen >= 15,
                "kind {k} ({n} primitives): {seen} pixels of its hue"
            );
        } else {
            assert!(seen < 15, "kind {k} absent but {seen} pixels of its hue");
        }
    }
    assert!(
        hue_count(&img, 0, SIZE, palette::HULL_RGB) < 40,
        "no hull colour"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn with_peers_the_input_ours_and_the_hulls_stand_side_by_side() {
    let dir = scratch("side");
    let Some((mesh, json, obj)) = result(&dir, 20) else {
        return;
    };
    let opts = scene::Options::default();
    let s = Scene {
        input: Some(scene::load_input(&mesh, &opts).unwrap()),
        levels: scene::load_levels(&json, &opts).unwrap(),
        peers: vec![scene::load_peer(&obj, None).unwrap()],
        eval: Vec::new(),
        up_axis: 1,
    };
    let img = decode(&primdecomp_view::render_png(&s, SIZE).unwrap());
    assert_eq!((img.width, img.height), (3 * SIZE, SIZE), "three panes");
    let pane = |i: usize| (i * SIZE, (i + 1) * SIZE);
    let shares: Vec<f64> = (0..3)
        .map(|i| silhouette(&img, pane(i).0, pane(i).1).0 as f64 / (SIZE * SIZE) as f64)
        .collect();
    for s in &shares {
        assert!((0.03..0.6).contains(s), "pane shares {shares:?}");
    }
    // The input pane is grey; ours has kind colours and no hull colour; the hulls'
    // pane is in the hull colour only.
    let (a, b) = pane(0);
    for c in palette::KIND_RGB.iter().chain([&palette::HULL_RGB]) {
        assert!(hue_count(&img, a, b, *c) < 15, "input pane has {c:?}");
    }
    let (a, b) = pane(1);
    assert!(
        hue_count(&img, a, b, palette::KIND_RGB[0]) >= 15,
        "boxes in our pane"
    );
    assert!(hue_count(&img, a, b, palette::HULL_RGB) < 40);
    let (a, b) = pane(2);
    assert!(
        hue_count(&img, a, b, palette::HULL_RGB) >= 500,
        "hulls in their pane"
    );
    assert!(hue_count(&img, a, b, palette::KIND_RGB[0]) < 15);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_large_scan_is_simplified_to_the_display_budget() {
    let Some(mesh) = primdecomp_testkit::corpus_mesh("dragon_vrip_full.ply") else {
        return;
    };
    let input = primdecomp_view::source::from_core_mesh(&mesh);
    let opts = scene::Options::default();
    let start = std::time::Instant::now();
    let i = scene::input_from(Path::new("dragon_vrip_full.ply"), &input, &opts);
    let secs = start.elapsed().as_secs_f64();
    assert!(i.display.simplified);
    assert!(
        i.display.source_triangles > 800_000,
        "{}",
        i.display.source_triangles
    );
    let n = i.display.triangles.len();
    assert!(
        (opts.display_triangles / 2..=opts.display_triangles).contains(&n),
        "{n} triangles shown"
    );
    eprintln!(
        "dragon: {} → {n} triangles in {secs:.2} s",
        i.display.source_triangles
    );
}
