//! `Plates::solid` (docs/decisions/0023-merges-priced-by-the-air-they-add.md): merges priced by
//! the volume their
//! primitive adds outside the input. Off must be the default output exactly; on must
//! keep the enclosure and thread independence; and a closed part must fill into solid
//! primitives where the paper's pricing leaves it a shell of plates.

use primdecomp::{decompose, demo_scene, Goal, Params, Plates};
use primdecomp_testkit::check::{assert_default_output, assert_same_on_threads, assert_valid};
use primdecomp_testkit::shapes::{cuboid, cylinder, join, mesh};

fn params(targets: &[usize], solid: bool) -> Params {
    Params {
        // The greedy pass's pricing, which this measures (docs/decisions/0054).
        goal: Goal::Greedy {
            counts: targets.to_vec(),
        },
        plates: Plates {
            solid,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Off is the default engine, primitive for primitive.
#[test]
fn off_is_the_default_output() {
    let m = demo_scene();
    assert_default_output(&m, &params(&[150, 20], false));
}

/// On, every face stays enclosed (the independent oracle) and the output is the same
/// on 1 and 2 threads.
#[test]
fn solid_pricing_encloses_and_ignores_threads() {
    let m = demo_scene();
    let p = params(&[150, 40, 8], true);
    let dec = assert_same_on_threads(&m, &p);
    assert_valid(&m, &dec, &p);
}

/// A closed 16-sided cylinder (radius 1, height 4) beside a closed 2 × 2 × 0.5 slab.
/// At N = 6 the paper's pricing covers the cylinder with a box, two prisms and two cap
/// disks (filling it costs its volume); priced by the air they add, both parts fill,
/// the shell pieces nest inside and are removed: two primitives, one per part. At
/// N = 12 the paper's pricing splits the slab into six plates; solid pricing keeps it
/// one box (its volume, 2, is all inside).
#[test]
fn closed_parts_fill_instead_of_shells() {
    let m = mesh(&join(&[
        cylinder(1.0, 4.0, 16),
        cuboid([3.0, 0.0, 0.0], [5.0, 2.0, 0.5]),
    ]));
    let level = |n, solid| {
        decompose(&m, &params(&[n], solid))
            .unwrap()
            .levels
            .remove(0)
    };
    let paper = level(6, false);
    assert_eq!(
        paper.primitives.len(),
        6,
        "the shell the paper's pricing leaves"
    );
    let filled = level(6, true);
    let vols: Vec<f64> = filled.primitives.iter().map(|p| p.volume()).collect();
    assert_eq!(vols.len(), 2, "one primitive per closed part: {vols:?}");
    // The circumscribed cylinder of the 16-gon and the slab's own box.
    assert!(
        (vols[0] - 4.0 * std::f64::consts::PI).abs() < 1e-6,
        "{vols:?}"
    );
    assert!((vols[1] - 2.0).abs() < 1e-9, "{vols:?}");
    let slab_boxes =
        |l: &primdecomp::Level| l.primitives.iter().filter(|p| p.aabb().0[0] > 2.9).count();
    assert_eq!(
        slab_boxes(&level(12, false)),
        6,
        "the paper's pricing: six plates"
    );
    assert_eq!(slab_boxes(&level(12, true)), 1, "solid pricing: one box");
}

/// kenney_wall_high at 64 with `--fill`: solid pricing filled the top slab (1.5 × 0.2
/// × 0.7, y from 1.5 to 1.7, bevelled ends) into two boxes that overlapped over 97% of
/// its length, each leaving out one bevelled end, and every ball resting on it touched
/// both. The near-duplicate pair must be absorbed into one primitive reaching both ends;
/// no other primitive may reach the slab's top then. Needs the corpus.
#[test]
fn wall_high_top_slab_is_one_primitive() {
    let Some(m) = primdecomp_testkit::corpus_mesh("kenney_wall_high.glb") else {
        return;
    };
    let p = Params {
        goal: Goal::Fill { counts: vec![64] },
        ..params(&[64], true)
    };
    let dec = decompose(&m, &p).unwrap();
    assert_valid(&m, &dec, &p);
    let top: Vec<_> = dec.levels[0]
        .primitives
        .iter()
        .map(|p| p.aabb())
        .filter(|(lo, hi)| hi[1] > 1.69 && lo[1] < 1.51 && hi[0] - lo[0] > 1.0)
        .collect();
    assert_eq!(top.len(), 1, "boxes across the top slab: {top:?}");
    let (lo, hi) = top[0];
    assert!(
        lo[0] < -0.749 && hi[0] > 0.749,
        "one box end to end: {lo:?} {hi:?}"
    );
}

/// An L-shaped bracket as OBJ text: a foot 4 × 0.5 × 2 with a 1 × 1 square hole
/// through it, and an upright 0.5 thick rising to 3 at one end; the boundary of a set
/// of grid cells (every face between a filled cell and an empty one, wound outwards),
/// closed and manifold, 96 triangles.
fn bracket_obj() -> String {
    let (xs, ys, zs) = (
        [0.0, 0.5, 2.0, 3.0, 4.0],
        [0.0, 0.5, 3.0],
        [0.0, 0.5, 1.5, 2.0],
    );
    let filled = |c: [i32; 3]| {
        let [i, j, k] = c;
        match (0..4).contains(&i) && (0..2).contains(&j) && (0..3).contains(&k) {
            false => false,
            true if j == 0 => !(i == 2 && k == 1),
            true => i == 0,
        }
    };
    let (mut verts, mut tris): (Vec<[i32; 3]>, Vec<[usize; 3]>) = (Vec::new(), Vec::new());
    let mut at = |c: [i32; 3]| match verts.iter().position(|&v| v == c) {
        Some(i) => i + 1,
        None => {
            verts.push(c);
            verts.len()
        }
    };
    for i in 0..4 {
        for j in 0..2 {
            for k in 0..3 {
                if !filled([i, j, k]) {
                    continue;
                }
                for axis in 0..3 {
                    for side in [0, 1] {
                        let mut n = [i, j, k];
                        n[axis] += if side == 1 { 1 } else { -1 };
                        if filled(n) {
                            continue;
                        }
                        let (a, b) = [(1, 2), (2, 0), (0, 1)][axis];
                        let mut base = [i, j, k];
                        base[axis] += side;
                        let mut quad: Vec<usize> = [(0, 0), (1, 0), (1, 1), (0, 1)]
                            .iter()
                            .map(|&(da, db)| {
                                let mut c = base;
                                (c[a], c[b]) = (c[a] + da, c[b] + db);
                                at(c)
                            })
                            .collect();
                        if side == 0 {
                            quad.reverse();
                        }
                        tris.push([quad[0], quad[1], quad[2]]);
                        tris.push([quad[0], quad[2], quad[3]]);
                    }
                }
            }
        }
    }
    let mut text = String::new();
    for [i, j, k] in verts {
        let [x, y, z] = [xs[i as usize], ys[j as usize], zs[k as usize]];
        text += &format!("v {x} {y} {z}\n");
    }
    for [a, b, c] in tris {
        text += &format!("f {a} {b} {c}\n");
    }
    text
}

/// The thinnest a primitive is across the world's axes and its own (a box's, a
/// prism's): where a plate would be thin.
fn thinnest(p: &primdecomp::Primitive) -> f64 {
    let mut dirs = vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    match p {
        primdecomp::Primitive::Box(b) => dirs.extend(b.axes),
        primdecomp::Primitive::Prism(q) => dirs.extend(q.axes),
        _ => {}
    }
    let width = |n: [f64; 3]| p.support(n) + p.support(n.map(|c| -c));
    dirs.into_iter().map(width).fold(f64::INFINITY, f64::min)
}

/// The bracket at the default tolerance (2% of the diagonal). Measured to the
/// surface, a solid box's faces where two boxes meet stand far from it, so `--solid`
/// gave 20 plates 0.003 thick, the shell it promises not to give; measured to the
/// solid (docs/decisions/0056) the cut keeps the few solid boxes a user would place,
/// enclosing every face and within the tolerance by eval's own measure (its own
/// inside test). Without `--solid` the run is the shell of plates it always was.
#[test]
fn a_bracket_with_a_hole_is_a_few_solid_boxes() {
    let m = primdecomp::Mesh::parse(
        bracket_obj().as_bytes(),
        primdecomp::MeshFormat::Obj,
        "bracket.obj".as_ref(),
    )
    .unwrap();
    assert_eq!(m.face_count(), 96);
    let with = |solid: bool| Params {
        plates: Plates {
            solid,
            ..Default::default()
        },
        ..Default::default()
    };
    let foot = 0.5;
    let p = with(true);
    let dec = decompose(&m, &p).unwrap();
    assert_valid(&m, &dec, &p);
    let level = &dec.levels[0];
    let (tolerance, distance) = (level.tolerance.unwrap(), level.distance.unwrap());
    let n = level.primitives.len();
    assert!(n <= 6, "{n} primitives: {:?}", level.primitives);
    for q in &level.primitives {
        assert!(thinnest(q) >= 0.1 * foot, "a plate: {q:?}");
    }
    assert!(
        level.distance_to_solid && distance <= tolerance,
        "{level:?}"
    );
    let input = primdecomp_eval::Input::new(&m).to_solid(true);
    let collider = primdecomp_eval::collider::Collider::Primitives(level.primitives.clone());
    let eval = primdecomp_eval::evaluate(&input, &collider, 50_000, 1);
    let diagonal = input.diagonal();
    assert!(eval.to_solid && eval.enclosure == 1.0, "{eval:?}");
    assert!(
        eval.hausdorff_all * diagonal <= distance + 1e-9 * diagonal,
        "eval's {} over the bound {distance}",
        eval.hausdorff_all * diagonal
    );
    // Without --solid: the surface's measure and the shell of 20 plates.
    let p = with(false);
    let dec = decompose(&m, &p).unwrap();
    let level = &dec.levels[0];
    assert!(!level.distance_to_solid);
    assert_eq!(level.primitives.len(), 20, "{:?}", level.primitives);
    assert!(level.primitives.iter().all(|q| thinnest(q) < 0.01));
    let input = primdecomp_eval::Input::new(&m);
    let collider = primdecomp_eval::collider::Collider::Primitives(level.primitives.clone());
    let eval = primdecomp_eval::evaluate(&input, &collider, 50_000, 1);
    assert!(eval.hausdorff_all * input.diagonal() <= level.distance.unwrap() + 1e-9);
}

/// The bracket with one quad left out is open: through the hole, the grid's vote and
/// another test of inside may disagree, so under `--solid` its tolerance is still
/// measured to the surface (docs/decisions/0056), and every face stays enclosed.
#[test]
fn an_open_bracket_is_measured_to_its_surface() {
    let text = bracket_obj();
    let lines: Vec<&str> = text.lines().collect();
    let open = lines[..lines.len() - 2].join("\n");
    let m = primdecomp::Mesh::parse(
        open.as_bytes(),
        primdecomp::MeshFormat::Obj,
        "open_bracket.obj".as_ref(),
    )
    .unwrap();
    assert_eq!(m.face_count(), 94);
    let p = Params {
        plates: Plates {
            solid: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let dec = decompose(&m, &p).unwrap();
    assert_valid(&m, &dec, &p);
    let level = &dec.levels[0];
    assert!(!level.distance_to_solid, "{level:?}");
    assert!(level.distance.unwrap() <= level.tolerance.unwrap());
}
