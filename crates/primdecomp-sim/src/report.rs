//! The simulation's outputs as text: the JSON report (its keys, one entry
//! per collider with the reference first), the per-frame CSV and the balls' end
//! points CSV.

use super::profile::Profile;
use super::scene::{BALL_RADIUS_REL, DT, GRAVITY, PERTURBATION_RADII, SCENE_DIAGONAL};
use super::Run;
use primdecomp_math::V3;
use serde::Serialize;
use std::fmt::Write;

#[derive(Serialize)]
struct InputJson<'a> {
    path: &'a str,
    faces: usize,
    aabb_min: V3,
    aabb_max: V3,
}

#[derive(Serialize)]
struct SceneJson {
    ball_radius: f64,
    ball_radius_rel: f64,
    scene_diagonal_m: f64,
    gravity: f64,
    dt: f64,
    up: &'static str,
    seed: u64,
    /// The perturbed reference's largest start offset per axis, in ball radii
    /// (absent entry when the run had none).
    perturbation_radii: Option<f64>,
    threads: usize,
    /// Each collider's parts given to Rapier as one compound shape.
    compound: bool,
}

#[derive(Serialize)]
struct ColliderJson<'a> {
    collider: &'a str,
    kind: &'a str,
    shapes: usize,
    skipped_parts: usize,
    frame_ms_mean: f64,
    frame_ms_median: f64,
    frame_ms_p95: f64,
    frame_ms_total: f64,
    cpu_ms_mean: f64,
    cpu_ms_median: f64,
    cpu_ms_p95: f64,
    cpu_ms_total: f64,
    similarity: f64,
    similarity_set: f64,
    on_object: f64,
    resting: f64,
    on_object_agreement: f64,
    mean_displacement: f64,
    mean_displacement_rel: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    profile: Option<&'a Profile>,
}

#[derive(Serialize)]
struct ReportJson<'a> {
    format: &'static str,
    version: u32,
    input: InputJson<'a>,
    balls: usize,
    frames: usize,
    scene: SceneJson,
    colliders: Vec<ColliderJson<'a>>,
}

/// The JSON report of `run` on the input at `path` with `faces` faces.
pub fn to_json(run: &Run, path: &str, faces: usize) -> String {
    let sc = &run.scene;
    let world = |p: V3| sc.frame.to_world(p);
    let colliders = run
        .outcomes
        .iter()
        .map(|o| ColliderJson {
            collider: &o.label,
            kind: o.kind,
            shapes: o.shapes,
            skipped_parts: o.skipped,
            frame_ms_mean: o.stats.mean,
            frame_ms_median: o.stats.median,
            frame_ms_p95: o.stats.p95,
            frame_ms_total: o.stats.total,
            cpu_ms_mean: o.cpu_stats.mean,
            cpu_ms_median: o.cpu_stats.median,
            cpu_ms_p95: o.cpu_stats.p95,
            cpu_ms_total: o.cpu_stats.total,
            similarity: o.behaviour.similarity,
            similarity_set: o.behaviour.similarity_set,
            on_object: o.behaviour.on_object,
            resting: o.behaviour.resting,
            on_object_agreement: o.behaviour.on_object_agreement,
            mean_displacement: o.behaviour.mean_displacement,
            mean_displacement_rel: o.behaviour.mean_displacement_rel,
            profile: o.profile.as_ref(),
        })
        .collect();
    let doc = ReportJson {
        format: "primdecomp-sim",
        // 2: the perturbed reference is the second entry (kind `mesh_perturbed`).
        version: 2,
        input: InputJson {
            path,
            faces,
            aabb_min: world(sc.aabb.0),
            aabb_max: world(sc.aabb.1),
        },
        balls: run.settings.balls,
        frames: run.settings.frames,
        scene: SceneJson {
            ball_radius: sc.radius_world(),
            ball_radius_rel: BALL_RADIUS_REL,
            scene_diagonal_m: SCENE_DIAGONAL,
            gravity: GRAVITY,
            dt: DT,
            up: ["x", "y", "z"][sc.up],
            seed: run.settings.seed,
            perturbation_radii: run.settings.perturbed.then_some(PERTURBATION_RADII),
            threads: run.settings.threads,
            compound: run.settings.compound,
        },
        colliders,
    };
    let mut s = serde_json::to_string_pretty(&doc).unwrap_or_default();
    s.push('\n');
    s
}

/// The step-time attribution of a profiled run as a Markdown table, one row per
/// collider (mean per frame: Rapier's stage times, ms; balls awake and touching two
/// or more static shapes, and their contacts with them; the shapes' AABB reach;
/// pairs, `touching/pairs`, by kind); empty without profiles.
pub fn profile_table(run: &Run) -> String {
    let mut s = String::new();
    if run.outcomes.iter().all(|o| o.profile.is_none()) {
        return s;
    }
    s.push_str("| collider | step | broad | narrow | islands | solver | CCD | update | awake | on ≥2 shapes | their contacts | AABB reach | pairs touching/all by kind |\n");
    s.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (name, o) in column_names(run).iter().zip(&run.outcomes) {
        let Some(p) = &o.profile else { continue };
        let pairs: Vec<String> = p
            .pairs
            .iter()
            .map(|(k, c)| format!("{k} {:.1}/{:.1}", c.touching, c.pairs))
            .collect();
        let _ = writeln!(
            s,
            "| {name} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.1} | {:.1} | {:.1} | {:.2} | {} |",
            p.step_ms,
            p.broad_phase_ms,
            p.narrow_phase_ms,
            p.islands_ms,
            p.solver_ms,
            p.ccd_ms,
            p.update_ms,
            p.awake_balls,
            p.balls_on_several_shapes,
            p.contacts_of_balls_on_several,
            p.shape_aabb_reach,
            pairs.join(", ")
        );
    }
    s
}

/// Column names: collider labels, made unique with `#k` suffixes where repeated.
pub fn column_names(run: &Run) -> Vec<String> {
    let labels: Vec<&str> = run.outcomes.iter().map(|o| o.label.as_str()).collect();
    labels
        .iter()
        .enumerate()
        .map(|(i, l)| {
            if labels.iter().filter(|m| *m == l).count() > 1 {
                format!("{l}#{i}")
            } else {
                l.to_string()
            }
        })
        .collect()
}

/// CSV of physics-step times: `frame` then one column per collider, ms.
pub fn frame_csv(run: &Run) -> String {
    let mut s = String::from("frame");
    for c in column_names(run) {
        let c = c.replace('"', "\"\"");
        let _ = write!(s, ",\"{c}\"");
    }
    s.push('\n');
    for f in 0..run.settings.frames {
        let _ = write!(s, "{f}");
        for o in &run.outcomes {
            let _ = write!(s, ",{:.6}", o.frame_ms[f]);
        }
        s.push('\n');
    }
    s
}

/// CSV of where each ball ends, input coordinates: `collider,ball,x,y,z,speed`, one
/// row per collider and ball (speed in m/s of the scene), for plotting where colliders
/// send balls that the mesh keeps.
pub fn ends_csv(run: &Run) -> String {
    let mut s = String::from("collider,ball,x,y,z,speed\n");
    for (name, o) in column_names(run).iter().zip(&run.outcomes) {
        let name = name.replace('"', "\"\"");
        for (i, (p, v)) in o.end.iter().zip(&o.speed).enumerate() {
            let w = run.scene.frame.to_world(*p);
            let _ = writeln!(s, "\"{name}\",{i},{},{},{},{v:.4}", w[0], w[1], w[2]);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{run, Entry, Geometry, Settings};
    use primdecomp::{Obb, Primitive};
    use primdecomp_eval::collider::Collider;

    /// The end-points CSV has one row per collider and ball, in input coordinates: a
    /// ball resting on a 1-high box at y = 0…1 ends at y = 1 + its world radius.
    #[test]
    fn ends_csv_rows_are_input_coordinates() {
        let mesh = crate::cuboid_mesh([10.0, 0.0, 10.0], [12.0, 1.0, 12.0]);
        let prim = Primitive::Box(Obb {
            center: [11.0, 0.5, 11.0],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            half: [1.0, 0.5, 1.0],
        });
        let e = [Entry {
            label: "box".into(),
            geometry: Geometry::Collider(Collider::Primitives(vec![prim])),
        }];
        let s = Settings {
            balls: 2,
            frames: 150,
            ..Default::default()
        };
        let r = run(&mesh, "m", &e, &s, &|_| {}).unwrap();
        let csv = ends_csv(&r);
        let rows: Vec<&str> = csv.lines().skip(1).collect();
        assert_eq!(rows.len(), 3 * 2);
        let top = 1.0 + r.scene.radius_world();
        for row in rows {
            let y: f64 = row.split(',').nth(3).unwrap().parse().unwrap();
            assert!((y - top).abs() < 0.01 * r.scene.radius_world(), "{row}");
        }
    }
}
