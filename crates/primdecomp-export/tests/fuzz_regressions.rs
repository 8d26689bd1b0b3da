//! Results the export fuzzer (`fuzz/fuzz_targets/exports.rs`) found to be written
//! wrongly, each reduced to a test that failed before its fix. The comment on each
//! says what must happen and why.

use primdecomp::{Body, Frame};
use primdecomp_export::{render, ExportOptions, Format};
use primdecomp_testkit::exports;

/// A one-primitive result in every export format, read back by the tests' readers
/// (`crates/testkit/src/exports.rs`); `Err` carries the reader's complaint.
fn export_reads_back(p: primdecomp::Primitive) -> Result<(), String> {
    let objects = [Body {
        name: String::new(),
        frame: Frame::IDENTITY,
        primitives: vec![p],
    }];
    for format in Format::ALL {
        let path = format!("x.{}", format.name());
        let files = render(&objects, format, &ExportOptions::default(), path.as_ref())
            .map_err(|e| e.to_string())?;
        let text = || String::from_utf8(files.main.clone()).unwrap();
        match format {
            Format::Gltf | Format::Glb => exports::gltf(&files.main),
            Format::Mjcf => exports::mjcf(&text()),
            Format::Urdf => exports::urdf(&text()),
            Format::Usda => exports::usda(&text()),
            Format::Tscn => exports::tscn(&text()),
        }
        .map_err(|e| format!("{format:?}: {e}"))?;
    }
    Ok(())
}

/// `fuzz/fuzz_targets/exports.rs`, first run: a capsule whose ends differ by 1.8e-299
/// was written to MJCF by position and `size="r 0"` (its half length rounds to 0), and
/// MuJoCo refuses a size of 0 ("size 1 must be positive in geom"; URDF's cylinder of
/// length 0 likewise). A capsule shorter than 2⁻³⁰ of its radius is written as the
/// sphere around it, in every format.
#[test]
fn a_capsule_of_no_length_is_written_as_a_sphere() {
    let p = primdecomp::Primitive::Capsule(primdecomp::Capsule {
        p0: [0.0, 0.0, 0.0],
        p1: [0.0, -1.8e-299, 0.0],
        radius: 8.4e-8,
    });
    export_reads_back(p).unwrap();
}

/// `fuzz/fuzz_targets/exports.rs`, second run: an object without primitives placed
/// at 1e156 was written to MJCF as a body at 1e156, which no 32-bit reader loads (the
/// range check looked at shapes only). Every object's frame is checked: refused with
/// one sentence naming the object.
#[test]
fn an_empty_object_far_away_is_refused() {
    let sphere = primdecomp::Primitive::Sphere(primdecomp::Sphere {
        center: [0.0; 3],
        radius: 1.0,
    });
    let objects = [
        Body {
            name: "far".into(),
            frame: Frame {
                translation: [443.0, -4.9e140, 2.2e156],
                ..Frame::IDENTITY
            },
            primitives: Vec::new(),
        },
        Body {
            name: "near".into(),
            frame: Frame::IDENTITY,
            primitives: vec![sphere],
        },
    ];
    for format in Format::ALL {
        let e = render(
            &objects,
            format,
            &ExportOptions::default(),
            "x.out".as_ref(),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("object 0 (\"far\"): its origin lies at 2.2e156"),
            "{e}"
        );
    }
}
