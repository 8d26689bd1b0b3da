//! `primdecomp eval` output: the JSON document (keys in a fixed order) and the
//! readable table.

use super::Metrics;
use serde::Serialize;

#[derive(Serialize)]
struct Counts {
    #[serde(rename = "box")]
    boxes: usize,
    sphere: usize,
    capsule: usize,
    cylinder: usize,
    frustum: usize,
    prism: usize,
    hull: usize,
}

#[derive(Serialize)]
struct Row<'a> {
    collider: &'a str,
    hausdorff: f64,
    chamfer: f64,
    hausdorff_all: f64,
    chamfer_all: f64,
    reverse_hausdorff: f64,
    reverse_chamfer: f64,
    enclosure: f64,
    bytes: usize,
    counts: Counts,
    /// `"solid"` where `hausdorff` … `chamfer_all` are to the input's solid
    /// (`eval --solid`); absent for its surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    measured_to: Option<&'static str>,
}

/// The `format` of an evaluation document (`primdecomp view --eval` checks it).
pub const FORMAT: &str = "primdecomp-eval";

/// The `version` of the evaluation document.
pub const VERSION: u64 = 1;

#[derive(Serialize)]
struct Doc<'a> {
    format: &'static str,
    version: u64,
    input: &'a str,
    colliders: Vec<Row<'a>>,
}

fn count(m: &Metrics, name: &str) -> usize {
    m.counts
        .iter()
        .find(|(k, _)| *k == name)
        .map_or(0, |(_, n)| *n)
}

/// `{"input": …, "colliders": [{"collider": path, "hausdorff": …, …, "counts": {…}}]}`,
/// pretty-printed, ending in a newline.
pub fn to_json(input: &str, rows: &[(String, Metrics)]) -> String {
    let colliders = rows
        .iter()
        .map(|(path, m)| Row {
            collider: path,
            hausdorff: m.hausdorff,
            chamfer: m.chamfer,
            hausdorff_all: m.hausdorff_all,
            chamfer_all: m.chamfer_all,
            reverse_hausdorff: m.reverse_hausdorff,
            reverse_chamfer: m.reverse_chamfer,
            enclosure: m.enclosure,
            bytes: m.bytes,
            counts: Counts {
                boxes: count(m, "box"),
                sphere: count(m, "sphere"),
                capsule: count(m, "capsule"),
                cylinder: count(m, "cylinder"),
                frustum: count(m, "frustum"),
                prism: count(m, "prism"),
                hull: count(m, "hull"),
            },
            measured_to: m.to_solid.then_some("solid"),
        })
        .collect();
    let doc = Doc {
        format: FORMAT,
        version: VERSION,
        input,
        colliders,
    };
    let mut s = serde_json::to_string_pretty(&doc).expect("plain data serializes");
    s.push('\n');
    s
}

/// A fixed-width table, one collider a row.
pub fn table(rows: &[(String, Metrics)]) -> String {
    let mut out = format!(
        "{:<40} {:>6} {:>9} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>9}\n",
        "collider",
        "parts",
        "bytes",
        "hausdorff",
        "chamfer",
        "haus_all",
        "cham_all",
        "rev_haus",
        "rev_cham",
        "enclosure"
    );
    for (path, m) in rows {
        let parts: usize = m.counts.iter().map(|c| c.1).sum();
        out.push_str(&format!(
            "{:<40} {:>6} {:>9} {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e} {:>9.6}\n",
            path,
            parts,
            m.bytes,
            m.hausdorff,
            m.chamfer,
            m.hausdorff_all,
            m.chamfer_all,
            m.reverse_hausdorff,
            m.reverse_chamfer,
            m.enclosure
        ));
    }
    if rows.iter().any(|(_, m)| m.to_solid) {
        out.push_str(
            "hausdorff … cham_all: to the input's solid (--solid), a sample inside it at 0\n",
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_has_exactly_the_documented_keys_in_order() {
        let m = Metrics {
            hausdorff: 0.5,
            chamfer: 0.25,
            hausdorff_all: 0.75,
            chamfer_all: 0.3,
            reverse_hausdorff: 0.1,
            reverse_chamfer: 0.05,
            enclosure: 1.0,
            bytes: 40,
            counts: vec![("box", 1), ("hull", 0)],
            to_solid: false,
        };
        let s = to_json("in.obj", &[("c.json".into(), m.clone())]);
        let v: serde_json::Value = serde_json::from_str(&s).unwrap();
        assert_eq!(v["input"], "in.obj");
        let c = &v["colliders"][0];
        let keys: Vec<&String> = c.as_object().unwrap().keys().collect();
        let mut want = vec![
            "bytes",
            "chamfer",
            "chamfer_all",
            "collider",
            "counts",
            "enclosure",
            "hausdorff",
            "hausdorff_all",
            "reverse_chamfer",
            "reverse_hausdorff",
        ];
        want.sort();
        assert_eq!(keys, want);
        assert_eq!(c["counts"]["box"], 1);
        assert_eq!(c["counts"]["prism"], 0);
        assert!(s.find("\"collider\"").unwrap() < s.find("\"hausdorff\"").unwrap());
        assert!(table(&[]).starts_with("collider"));
        // Measured to the solid, the row says so (and only then).
        let solid = Metrics {
            to_solid: true,
            ..m
        };
        let s = to_json("in.obj", &[("c.json".into(), solid.clone())]);
        let v: serde_json::Value = serde_json::from_str(&s).unwrap();
        assert_eq!(v["colliders"][0]["measured_to"], "solid");
        assert!(table(&[("c.json".into(), solid)]).contains("solid"));
    }
}
