//! Decomposes small arbitrary meshes with arbitrary settings. Invariants:
//! - no panic; an error only for settings `Params::validate` refuses, a mesh without
//!   faces, or vertices beyond the documented extent and position limits;
//! - every level has at most its target's primitives when no excess cap is set
//!   (bridging across components makes every target reachable);
//! - the JSON has no NaN or infinity (the oracle panics on a non-finite number);
//! - every input face lies inside one output primitive, checked by the independent
//!   oracle of the tests (`crates/testkit/src/contain.rs`, compiled here as is), with a
//!   tolerance of 1e-6 × the diagonal plus the round-off of the coordinates' magnitude.
#![no_main]

#[allow(dead_code)]
#[path = "../../crates/testkit/src/contain.rs"]
mod contain;

use arbitrary::{Result, Unstructured};
use primdecomp::{Dedup, Error, Goal, Mesh, Params, Partitions, Reprice, Tolerance, decompose};

/// A number that is usually one of `typical` and sometimes any f64 at all.
fn pick(u: &mut Unstructured, typical: &[f64]) -> Result<f64> {
    let i: u8 = u.arbitrary()?;
    Ok(match typical.get(i as usize) {
        Some(&v) => v,
        None if i >= 250 => u.arbitrary()?,
        None => typical[i as usize % typical.len()],
    })
}

fn params(u: &mut Unstructured) -> Result<Params> {
    let mut p = Params::default();
    let n = u.int_in_range(1..=3)?;
    let mut targets: Vec<usize> = (0..n)
        .map(|_| u.int_in_range(0..=40))
        .collect::<Result<_>>()?;
    for w in &mut p.fit.weights {
        *w = pick(u, &[1.0, 1.05, 2.1, 1.4, 1e-9, 1e9])?;
    }
    let mask: u8 = u.arbitrary()?;
    for (k, on) in p.fit.kinds.iter_mut().enumerate() {
        *on = mask == 0 || mask & (1 << k) != 0;
    }
    p.fit.tangent_eps = pick(u, &[0.01, 0.0, 1.0, 1e3])?;
    p.fit.min_extent = pick(u, &[5e-4, 1e-12, 0.5, 0.999])?;
    p.fit.max_excess_volume = match u.int_in_range(0..=3)? {
        0 => Some(pick(u, &[0.0, 1e-3, 1.0])?),
        _ => None,
    };
    p.fit.dedup = match u.int_in_range(0..=3)? {
        0 => Dedup::Off,
        1 => Dedup::Tolerance(pick(u, &[0.0, 1e-3, 0.5, 10.0])?),
        _ => Dedup::Exact,
    };
    p.plates.remove_nested = u.arbitrary()?;
    p.plates.remove_thin_boxes = match u.arbitrary::<bool>()? {
        true => Some(pick(u, &[0.0, 1e-3, 0.1])?),
        false => None,
    };
    // Read last, so that corpus entries grown before these settings decode as before.
    // The meshes are small: low degrees are what make deferred re-pricing happen.
    p.reprice = match u.int_in_range(0..=5)? {
        0 => Reprice::Exact,
        d => Reprice::Deferred {
            min_degree: [64, 0, 1, 2, 4][d as usize - 1],
        },
    };
    // Once the pricing floor `merge_min_extent_rel` (removed: docs/decisions); its bytes
    // are still read so that the grown corpus keeps its meaning.
    if u.int_in_range(0..=3)? == 0 {
        pick(u, &[2e-3, 0.0, 0.5, 0.999])?;
    }
    // Last again. An exhausted input reads 0 twice, so entries grown before this setting
    // run with it off, as they were grown; otherwise mostly the default (0.01).
    if u.int_in_range(0..=3)? == 0 {
        p.plates.open_holes = pick(u, &[0.0, 0.05, 0.5, 0.999])?;
    }
    // Once `reduction` (the approximate extremes, removed: docs/decisions); read still.
    u.arbitrary::<bool>()?;
    // After that (an exhausted input reads 0: auto, which never splits these small
    // meshes, as grown): a fixed count splits them when 16 × N < faces, so phase 1's
    // lazy parts run on hostile input too.
    p.partitions = match u.int_in_range(0..=3)? {
        0 => Partitions::Auto,
        k => Partitions::Fixed([2, 3, 8][k as usize - 1]),
    };
    // After that (an exhausted input reads false, as grown): the budget search's extra
    // passes (postprocess/fill.rs) on hostile input.
    let fill = u.arbitrary::<bool>()?;
    // Once `outward_weight` (removed: docs/decisions/0022); read still.
    if u.int_in_range(0..=3)? == 1 {
        pick(u, &[1.0, 1e-9, 1e9])?;
    }
    // After that (an exhausted input reads false, as grown): the interior grid's ray
    // parity and the air pricing on hostile input
    // (docs/decisions/0023-merges-priced-by-the-air-they-add.md).
    p.plates.solid = u.arbitrary::<bool>()?;
    // After that (an exhausted input reads 0: the default weight, as grown): the rim
    // reach's adjacency walk and the per-kind output fits at other weights, and off
    // (docs/decisions/0024-output-primitives-priced-by-rim-reach.md).
    p.plates.rim_weight =
        [1.0, 0.0, 1e-9, 1e9][u.int_in_range(0..=3)? as usize];
    // After that (an exhausted input reads false: free merges on, the default, so the
    // grown corpus now runs with them): a target's snapshot held for merges that add
    // no volume, and the exact stop (docs/decisions/0025-free-merges-into-plates.md).
    p.plates.join_coplanar = !u.arbitrary::<bool>()?;
    // After that (an exhausted input reads false: flush plates, the default): output
    // plates moved onto their faces' outer side, and centred
    // (docs/decisions/0026-output-plates-lie-flush.md).
    p.plates.flush_plates = !u.arbitrary::<bool>()?;
    // After that (an exhausted input reads 0: the greedy levels, as grown): the merge
    // tree's cut (docs/decisions/0032), with counts alone, with a
    // tolerance (one, or one per target), a byte target, both, or with no target at
    // all (the default run: the cut at 2% of the diagonal, capped at 1024).
    // A fill of a cut, a tolerance or a byte target is no goal: such inputs decode to
    // nothing (they were refused settings before there was one `Goal`).
    let (mut cut, mut tolerances, mut max_bytes) = (false, Vec::new(), Vec::new());
    match u.int_in_range(0..=5)? {
        0 => {}
        1 => cut = true,
        2 => {
            let n = if u.arbitrary::<bool>()? { targets.len() } else { 1 };
            tolerances = (0..n).map(|_| tolerance(u)).collect::<Result<_>>()?;
        }
        3 => max_bytes = vec![bytes(u)?],
        4 => {
            tolerances = vec![tolerance(u)?];
            max_bytes = vec![bytes(u)?];
        }
        _ => targets.clear(),
    }
    p.goal = match (fill, tolerances.is_empty() && max_bytes.is_empty()) {
        (true, true) if !cut && !targets.is_empty() => Goal::Fill { counts: targets },
        (true, _) => return Err(arbitrary::Error::IncorrectFormat),
        (false, false) => Goal::Within {
            caps: targets,
            tolerance: tolerances,
            max_bytes,
        },
        (false, true) if targets.is_empty() => Goal::default(),
        (false, true) if cut => Goal::Cut { counts: targets },
        (false, true) => Goal::counts(targets),
    };
    Ok(p)
}

/// A tolerance: a fraction of the diagonal or a distance in the input's units, usually
/// a typical one (0 and non-finite values are refused by `Params::validate`).
fn tolerance(u: &mut Unstructured) -> Result<Tolerance> {
    let v = pick(u, &[0.02, 0.005, 0.3, 1e-9, 1e3, 0.0])?;
    Ok(match u.arbitrary::<bool>()? {
        true => Tolerance::Diagonal(v),
        false => Tolerance::Units(v),
    })
}

/// A byte target (the paper's Table 2), usually a typical one (0 is refused).
fn bytes(u: &mut Unstructured) -> Result<usize> {
    Ok(pick(u, &[40.0, 200.0, 1000.0, 1e5, 0.0])? as usize)
}

/// Up to 32 vertices on a small integer grid (many coincide, are collinear or
/// coplanar), scaled by 10^-30..10^30 and offset by up to 10^9; or, sometimes, any
/// finite coordinates at all. Up to 24 polygons of 1 to 8 corners.
fn mesh(u: &mut Unstructured) -> Result<(Vec<[f64; 3]>, Vec<Vec<u32>>)> {
    let nv = u.int_in_range(1..=32)?;
    let raw = u.ratio(1, 16)?;
    let scale = 10f64.powi(u.int_in_range(-30..=30)?);
    let off: [i8; 3] = u.arbitrary()?;
    let off_scale = 10f64.powi(u.int_in_range(0..=9)?);
    let mut verts = Vec::with_capacity(nv);
    for _ in 0..nv {
        let v = if raw {
            let c: [f64; 3] = u.arbitrary()?;
            c.map(|x| if x.is_finite() { x } else { 0.0 })
        } else {
            let c: [i8; 3] = u.arbitrary()?;
            [0, 1, 2].map(|k| f64::from(c[k] % 8) * scale + f64::from(off[k]) * off_scale)
        };
        verts.push(v);
    }
    let nf = u.int_in_range(1..=24)?;
    let mut faces = Vec::with_capacity(nf);
    for _ in 0..nf {
        let k = u.int_in_range(1..=8)?;
        let f = (0..k)
            .map(|_| Ok(u.int_in_range(0..=nv as u32 - 1)?))
            .collect::<Result<Vec<u32>>>()?;
        faces.push(f);
    }
    Ok((verts, faces))
}

fn run(data: &[u8]) -> Result<()> {
    let mut u = Unstructured::new(data);
    let params = params(&mut u)?;
    let (verts, faces) = mesh(&mut u)?;
    if std::env::var_os("PD_FUZZ_PRINT").is_some() {
        // Reproducing a finding as a test: the decoded case, exact to the bit.
        eprintln!("{params:?}\nverts {verts:?}\nfaces {faces:?}");
    }
    // Coordinates are finite and indices in range by construction.
    let mesh = Mesh::from_polygons(&verts, &faces).expect("a valid mesh");
    // The documented limits: 1e60 from the bounding box's centre, ±1e70 from the origin.
    let far = (0..mesh.vertex_count() as u32).any(|v| {
        let d = mesh.pos(v).iter().fold(0.0f64, |m, c| m.max(c.abs()));
        d.is_nan() || d > 1e60
    });
    let beyond = (0..mesh.vertex_count() as u32)
        .any(|v| mesh.world_pos(v).iter().any(|c| c.abs() > 1e70));
    let dec = match decompose(&mesh, &params) {
        Ok(d) => d,
        Err(Error::InvalidParams(_)) if params.validate().is_err() => return Ok(()),
        Err(Error::EmptyMesh { .. }) if mesh.face_count() == 0 => return Ok(()),
        // Documented refusals: beyond 1e60 of the centre or ±1e70 of the origin.
        Err(Error::Extent { .. }) if far => return Ok(()),
        Err(Error::Position { .. }) if beyond => return Ok(()),
        Err(e) => panic!("unexpected error: {e}"),
    };
    assert!(params.validate().is_ok(), "invalid settings accepted");
    let polys: Vec<Vec<[f64; 3]>> = (0..mesh.face_count())
        .map(|f| mesh.face(f).iter().map(|&v| mesh.world_pos(v)).collect())
        .collect();
    let mag = verts.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
    let tol = 1e-6 * mesh.diagonal() + 64.0 * f64::EPSILON * mag;
    for (i, level) in dec.levels.iter().enumerate() {
        if params.fit.max_excess_volume.is_none() {
            assert!(
                level.primitives.len() <= level.target,
                "{} primitives for target {}",
                level.primitives.len(),
                level.target
            );
        }
        let text = dec.to_json(i, &params);
        assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
        let json: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
        let shapes: Vec<_> = json["primitives"]
            .as_array()
            .expect("primitives array")
            .iter()
            .map(contain::parse_primitive)
            .collect();
        let inside = contain::faces_enclosed(&shapes, &polys, tol);
        if let Some(f) = inside.iter().position(|&b| !b) {
            panic!("face {f} {:?} not enclosed at level {i}: {text}", polys[f]);
        }
    }
    Ok(())
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = run(data);
});
