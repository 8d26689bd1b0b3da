//! Hostile files the tools read back (result files, evaluation and settings files,
//! a batch's manifest), absurd counts and sizes, links planted in the output tree and
//! control characters in names: each command runs in a fresh directory its case sets
//! up; a refusal must exit 2 with one sentence naming the file and leave every file
//! there as it was; a success is checked by its case.

use super::{cell, output_within, snapshot, TRI};
use std::path::Path;
use std::process::Command;

/// A check of a command that succeeded: (its directory, its stdout) → the outcome.
type Check = Box<dyn Fn(&Path, &str) -> String>;

/// What a command must do.
pub enum Want {
    /// Exit 2, stderr holding each fragment, nothing in the directory changed.
    Refused(&'static [&'static str]),
    /// Exit 0; the check (directory, stdout) panics on a wrong result and returns
    /// the outcome for the table.
    Done(Check),
}

pub struct Case {
    /// The command as the table shows it.
    pub show: String,
    pub args: Vec<String>,
    pub what: &'static str,
    pub setup: Box<dyn Fn(&Path)>,
    pub want: Want,
}

const SPHERE: &str = r#"{"kind":"sphere","center":[0,0,0],"radius":1}"#;
const BOX: &str =
    r#"{"kind":"box","center":[0,0,0],"rotation":[0,0,0,1],"half_extents":[0.5,0.5,0.5]}"#;
const PRISM: &str = r#"{"kind":"prism","center":[0,0,0],"rotation":[0,0,0,1],"half_x":0.5,"half_y":0.5,"half_z_top":0.25,"half_z_bottom":0.5}"#;

/// A result document of these primitives.
fn result(prims: &str) -> String {
    format!(r#"{{"format":"primdecomp","version":1,"primitives":[{prims}]}}"#)
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) {
    std::fs::write(dir.join(name), bytes).unwrap();
}

fn fifo(p: &Path) {
    assert!(Command::new("mkfifo").arg(p).status().unwrap().success());
}

fn sparse(p: &Path, len: u64) {
    std::fs::File::create(p).unwrap().set_len(len).unwrap();
}

/// The primdecomp binary in `dir` with `args`.
fn primdecomp(dir: &Path, args: &[&str]) -> std::process::Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_primdecomp"));
    c.current_dir(dir).args(args);
    output_within(c)
}

/// Two meshes decomposed as a batch into `out/` (its manifest, two outputs).
fn batch(dir: &Path) {
    write(dir, "a.obj", format!("{TRI}f 1 2 3\n"));
    write(dir, "b.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n");
    let o = primdecomp(
        dir,
        &[
            "decompose",
            "a.obj",
            "b.obj",
            "-n",
            "2",
            "-o",
            "out/",
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

const MANIFEST: &str = "out/.primdecomp-manifest.jsonl";

/// The manifest with `f` applied to the record of `input`.
fn edit_record(dir: &Path, input: &str, f: impl Fn(&mut serde_json::Value)) {
    let text = std::fs::read_to_string(dir.join(MANIFEST)).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for l in lines.iter_mut().skip(1) {
        let mut v: serde_json::Value = serde_json::from_str(l).unwrap();
        if v["input"] == input {
            f(&mut v);
            *l = v.to_string();
        }
    }
    write(dir, MANIFEST, lines.join("\n") + "\n");
}

fn case(show: &str, what: &'static str, setup: impl Fn(&Path) + 'static, want: Want) -> Case {
    let args = show.split(' ').map(String::from).collect();
    Case {
        show: format!("primdecomp {show}"),
        args,
        what,
        setup: Box::new(setup),
        want,
    }
}

fn done(check: impl Fn(&Path, &str) -> String + 'static) -> Want {
    Want::Done(Box::new(check))
}

#[rustfmt::skip]
pub fn cases() -> Vec<Case> {
    let r = Want::Refused;
    fn sphere(dir: &Path) {
        write(dir, "r.json", result(SPHERE))
    }
    vec![
        // Result files that lie about what they are.
        case("export r.json -o o.glb", "no `format`", |d| write(d, "r.json", format!(r#"{{"version":1,"primitives":[{SPHERE}]}}"#)), r(&["r.json: not a primdecomp result"])),
        case("export r.json -o o.glb", "`format` of an evaluation", |d| write(d, "r.json", result(SPHERE).replace("\"primdecomp\"", "\"primdecomp-eval\"")), r(&["its \"format\" is \"primdecomp-eval\""])),
        case("export r.json -o o.glb", "`version` 2", |d| write(d, "r.json", result(SPHERE).replace("\"version\":1", "\"version\":2")), r(&["\"version\" is 2"])),
        case("export r.json -o o.glb", "`version` \"1\"", |d| write(d, "r.json", result(SPHERE).replace("\"version\":1", "\"version\":\"1\"")), r(&["not the integer 1"])),
        case("export r.json -o o.glb", "`version` -1", |d| write(d, "r.json", result(SPHERE).replace("\"version\":1", "\"version\":-1")), r(&["not the integer 1"])),
        case("export r.json -o o.glb", "`version` 1.5", |d| write(d, "r.json", result(SPHERE).replace("\"version\":1", "\"version\":1.5")), r(&["not the integer 1"])),
        case("export r.json -o o.glb", "`version` 1e400", |d| write(d, "r.json", result(SPHERE).replace("\"version\":1", "\"version\":1e400")), r(&["number out of range"])),
        // Numbers that cannot be written as finite, loadable numbers.
        case("export r.json -o o.glb", "a coordinate of 1e308", |d| write(d, "r.json", result(&SPHERE.replace("[0,0,0]", "[1e308,0,0]"))), r(&["primitive 0 (sphere): it reaches 1e308", "±1e70"])),
        case("export r.json -o o.glb", "a half-extent of 1e308", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308 is beyond 1e60"])),
        case("export r.json -o o.gltf", "the same to glTF (text)", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308"])),
        case("export r.json -o o.urdf", "the same to URDF", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308"])),
        case("export r.json -o o.usda", "the same to USD", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308"])),
        case("export r.json -o o.tscn", "the same to Godot", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308"])),
        case("export r.json -o o.xml --format mjcf", "the same to MuJoCo", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308"])),
        case("export r.json -o o.glb", "a half-extent NaN (not JSON)", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[NaN,"))), r(&["r.json: invalid primdecomp JSON"])),
        case("export r.json -o o.usda", "an object scale of 1e308", |d| write(d, "r.json", result(SPHERE).replace("]}", &format!(r#"],"objects":[{{"name":"a","translation":[0,0,0],"rotation":[0,0,0,1],"scale":1e308,"primitives":[{SPHERE}]}}]}}"#))), r(&["object 0 (\"a\"): primitive 0 (sphere)"])),
        case("export r.json -o o.glb", "a sphere at 1e60 (readable, not writable in f32)", |d| write(d, "r.json", result(&SPHERE.replace("[0,0,0]", "[1e60,0,0]"))), r(&["o.glb: cannot be written as glb", "beyond the ±1e18"])),
        case("export r.json -o o.glb --scale 1e-45", "the same, scaled into range", |d| write(d, "r.json", result(&SPHERE.replace("[0,0,0]", "[1e60,0,0]"))), done(|d, _| {
            let names = primdecomp_testkit::exports::gltf(&std::fs::read(d.join("o.glb")).unwrap()).unwrap().names;
            format!("exit 0, o.glb reads back ({} object)", names.len())
        })),
        case("export r.json -o o.xml --format mjcf", "a prism of half-extents 1e-310 (denormal)", |d| write(d, "r.json", result(&PRISM.replace("0.5", "1e-310").replace("0.25", "1e-310"))), r(&["spans only 1e-310"])),
        case("export r.json -o o.xml --format mjcf", "a prism of half-extents 1e-8: a mesh MuJoCo refuses", |d| write(d, "r.json", result(&PRISM.replace("0.5", "1e-8").replace("0.25", "1e-8"))), r(&["MuJoCo refuses meshes under 1e-12"])),
        case("export r.json -o o.glb", "the same prism to glTF", |d| write(d, "r.json", result(&PRISM.replace("0.5", "1e-8").replace("0.25", "1e-8"))), done(|d, _| {
            primdecomp_testkit::exports::gltf(&std::fs::read(d.join("o.glb")).unwrap()).unwrap();
            "exit 0, o.glb reads back".into()
        })),
        case("sim --input m.obj r.json --balls 4 --frames 2 --quiet", "a sphere at 1e60 in the simulation", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            write(d, "r.json", result(&SPHERE.replace("[0,0,0]", "[1e60,0,0]")));
        }, r(&["r.json: primitive 0 (sphere) reaches", "32-bit floats"])),
        case("eval --input m.obj r.json", "eval of a result at 1e308", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            write(d, "r.json", result(&SPHERE.replace("[0,0,0]", "[1e308,0,0]")));
        }, r(&["r.json: primitive 0 (sphere): it reaches 1e308"])),
        case("view r.json --no-input -o v.html", "view of a result at 1e308", |d| write(d, "r.json", result(&SPHERE.replace("[0,0,0]", "[1e308,0,0]"))), r(&["r.json: primitive 0 (sphere): it reaches 1e308"])),
        case("view r.json --no-input -o v.html", "view of a box of half-extent 1e308", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[1e308,"))), r(&["r.json: primitive 0 (box): a radius or half-extent of 1e308 is beyond 1e60"])),
        case("view r.json --no-input -o v.html", "view of a half-extent NaN (not JSON)", |d| write(d, "r.json", result(&BOX.replace("[0.5,", "[NaN,"))), r(&["r.json: invalid JSON"])),
        case("view r.json --no-input --eval e.json -o v.html", "an evaluation file without `format`", |d| {
            sphere(d);
            write(d, "e.json", r#"{"colliders":[{"collider":"r.json","hausdorff":0.1}]}"#);
        }, r(&["e.json: not an evaluation document"])),
        // Absurd counts and sizes.
        case("export r.json -o o.glb", "no primitive", |d| write(d, "r.json", result("")), r(&["holds no primitive"])),
        case("export r.json -o o.glb", "65,537 primitives", |d| write(d, "r.json", result(&vec![SPHERE; 65_537].join(","))), r(&["an export takes at most 65536"])),
        case("view r.json --no-input -o v.html", "65,537 primitives to view", |d| write(d, "r.json", result(&vec![SPHERE; 65_537].join(","))), r(&["65537 parts", "more than the 65536 a page shows"])),
        case("view r.json --no-input -o v.html", "20,000 spheres: drawn coarser", |d| write(d, "r.json", result(&vec![SPHERE; 20_000].join(","))), done(|d, out| {
            assert!(d.join("v.html").exists());
            let line = out.lines().next().unwrap_or_default();
            format!("exit 0, stdout: `{line}`")
        })),
        case("export r.json -o o.glb --preview --export-detail 1000", "1,000 spheres previewed at 1,000 segments", |d| write(d, "r.json", result(&vec![SPHERE; 1000].join(","))), r(&["would hold 499002000 vertices", "lower --export-detail"])),
        case("view r.json --no-input --detail 100000 -o v.html", "100,000 segments around circles", sphere, r(&["--detail must be from 3 to 1024"])),
        case("decompose m.obj --obj-detail 100000 -o r.json --quiet", "the same for the OBJ", |d| write(d, "m.obj", format!("{TRI}f 1 2 3\n")), r(&["--obj-detail must be from 3 to 1024"])),
        case("decompose m.obj --config c.json -o r.json --quiet", "257 targets in a settings file", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            write(d, "c.json", format!("{{\"targets\":[{}]}}", (1..=257).map(|i| i.to_string()).collect::<Vec<_>>().join(",")));
        }, r(&["257 levels", "at most 256"])),
        case("decompose g.obj --per-object -n 1 -o r.json --quiet", "65,537 one-triangle OBJ groups", |d| {
            let mut s = String::new();
            for i in 0..65_537 {
                s += &format!("g o{i}\nv {i} 0 0\nv {i}.5 0 0\nv {i} 1 0\nf -3 -2 -1\n");
            }
            write(d, "g.obj", s);
        }, r(&["65537 objects", "at most 65536"])),
        case("decompose m.obj --config c.json -o r.json --quiet", "settings: a link to /dev/zero", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            std::os::unix::fs::symlink("/dev/zero", d.join("c.json")).unwrap();
        }, r(&["c.json: is a character device, not a regular file"])),
        case("decompose m.obj --config c.json -o r.json --quiet", "settings: a named pipe", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            fifo(&d.join("c.json"));
        }, r(&["c.json: is a named pipe (FIFO)"])),
        case("decompose m.obj --config c.json -o r.json --quiet", "settings: a result of version 2", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            write(d, "c.json", result(SPHERE).replace("\"version\":1", "\"version\":2").replace("]}", r#"],"settings":{}}"#));
        }, r(&["c.json: invalid setting: the result's \"version\" is 2"])),
        case("decompose m.obj --config c.json -o r.json --quiet", "settings: a sparse file of 300 MiB", |d| {
            write(d, "m.obj", format!("{TRI}f 1 2 3\n"));
            sparse(&d.join("c.json"), 300 << 20);
        }, r(&["c.json: the file holds 300 MiB, more than the 256 MiB"])),
        case("decompose big.obj --max-memory 1G -o r.json --quiet", "a sparse mesh file of 8 GiB", |d| sparse(&d.join("big.obj"), 8 << 30), r(&["big.obj: the file holds 8.0 GiB, more than the memory limit of 1.0 GiB"])),
        case("view r.json --max-memory 1G -o v.html", "view of a result whose input is that file", |d| {
            sparse(&d.join("big.obj"), 8 << 30);
            write(d, "r.json", result(SPHERE).replace("\"version\":1,", "\"version\":1,\"input\":{\"path\":\"big.obj\"},"));
        }, r(&["big.obj: the file holds 8.0 GiB"])),
        // A batch's manifest that lies.
        case("decompose a.obj b.obj -n 2 -o out/ --resume --quiet", "manifest: a.obj's output recorded as ../x", |d| {
            batch(d);
            write(d, "x", "abc");
            std::fs::remove_file(d.join("out/a.primdecomp.json")).unwrap();
            edit_record(d, "a.obj", |v| v["outputs"][0]["file"] = "../x".into());
        }, done(|d, _| {
            assert!(d.join("out/a.primdecomp.json").exists());
            assert_eq!(std::fs::read(d.join("x")).unwrap(), b"abc");
            "exit 0: a.obj decomposed again, `x` untouched".into()
        })),
        case("decompose a.obj b.obj -n 2 -o out/ --resume --quiet", "manifest: a.obj's output recorded by an absolute path outside", |d| {
            batch(d);
            write(d, "x", "abc");
            std::fs::remove_file(d.join("out/a.primdecomp.json")).unwrap();
            let abs = d.join("x").display().to_string();
            edit_record(d, "a.obj", move |v| v["outputs"][0]["file"] = abs.clone().into());
        }, done(|d, _| {
            assert!(d.join("out/a.primdecomp.json").exists());
            "exit 0: a.obj decomposed again".into()
        })),
        case("decompose a.obj b.obj -n 2 -o out/ --resume --quiet", "b.obj's output overwritten with zeros, same size and time", |d| {
            batch(d);
            let p = d.join("out/b.primdecomp.json");
            let m = std::fs::metadata(&p).unwrap();
            std::fs::write(&p, vec![0u8; m.len() as usize]).unwrap();
            std::fs::File::options().write(true).open(&p).unwrap().set_modified(m.modified().unwrap()).unwrap();
        }, done(|d, _| {
            let text = std::fs::read_to_string(d.join("out/b.primdecomp.json")).unwrap();
            assert!(text.starts_with("{\n  \"format\": \"primdecomp\""), "{text}");
            "exit 0: b.obj decomposed again, its output whole".into()
        })),
        case("decompose a.obj b.obj -n 2 -o out/ --resume --quiet", "manifest: a symbolic link to a file outside", |d| {
            batch(d);
            write(d, "outside.txt", "mine\n");
            std::fs::remove_file(d.join(MANIFEST)).unwrap();
            std::os::unix::fs::symlink("../outside.txt", d.join(MANIFEST)).unwrap();
        }, r(&["out/.primdecomp-manifest.jsonl: is a symbolic link"])),
        case("decompose a.obj b.obj -n 2 -o out/ --quiet", "the same without --resume", |d| {
            batch(d);
            write(d, "outside.txt", "mine\n");
            std::fs::remove_file(d.join(MANIFEST)).unwrap();
            std::os::unix::fs::symlink("../outside.txt", d.join(MANIFEST)).unwrap();
        }, done(|d, _| {
            assert_eq!(std::fs::read(d.join("outside.txt")).unwrap(), b"mine\n");
            assert!(std::fs::symlink_metadata(d.join(MANIFEST)).unwrap().is_file());
            "exit 0: the link replaced by a manifest of its own, `outside.txt` untouched".into()
        })),
        case("decompose a.obj b.obj -n 2 -o out/ --resume --quiet", "manifest: a named pipe", |d| {
            batch(d);
            std::fs::remove_file(d.join(MANIFEST)).unwrap();
            fifo(&d.join(MANIFEST));
        }, r(&["out/.primdecomp-manifest.jsonl: is a named pipe (FIFO), not a regular file"])),
        case("decompose a.obj b.obj -n 2 -o out/ --resume --quiet", "manifest: a hard link to a file outside", |d| {
            batch(d);
            std::fs::rename(d.join(MANIFEST), d.join("outside.jsonl")).unwrap();
            std::fs::hard_link(d.join("outside.jsonl"), d.join(MANIFEST)).unwrap();
        }, done(|d, _| {
            let outside = std::fs::read_to_string(d.join("outside.jsonl")).unwrap();
            assert_eq!(outside.lines().count(), 3, "{outside}");
            "exit 0: both inputs skipped, `outside.jsonl` not written through".into()
        })),
        // Links planted in the output tree; the longest file names.
        case("export r.json -o robot.urdf", "`robot_meshes` a symbolic link to a folder elsewhere", |d| {
            write(d, "r.json", result(PRISM));
            std::fs::create_dir(d.join("elsewhere")).unwrap();
            std::os::unix::fs::symlink("elsewhere", d.join("robot_meshes")).unwrap();
        }, r(&["robot_meshes: is a symbolic link (to elsewhere)"])),
        case("export r.json -o robot.urdf", "`robot_meshes` a file", |d| {
            write(d, "r.json", result(PRISM));
            write(d, "robot_meshes", "x");
        }, r(&["robot_meshes: exists and is not a folder"])),
        {
            let long = "r".repeat(250);
            let mut c = case("export r.json -o LONG.urdf", "an output name of 255 bytes", |d| write(d, "r.json", result(PRISM)), done(move |d, _| {
                let urdf = std::fs::read_to_string(d.join(format!("{}.urdf", "r".repeat(250)))).unwrap();
                let got = primdecomp_testkit::exports::urdf(&urdf).unwrap();
                let dir = got.files[0].split('/').next().unwrap().to_string();
                assert!(d.join(&got.files[0]).is_file());
                format!("exit 0: the meshes' folder is named in {} bytes (`{}…{}`)", dir.len(), &dir[..8], &dir[dir.len() - 24..])
            }));
            c.args[3] = format!("{long}.urdf");
            c.show = c.show.replace("LONG", "r…r (250 r)");
            c
        },
        {
            let mut c = case("decompose LONG -n 2 -o out/ --quiet", "an input named in 250 bytes: its output's name would be 262", |d| {
                write(d, &format!("{}.obj", "m".repeat(246)), format!("{TRI}f 1 2 3\n"));
            }, r(&["the file name is 262 bytes long, more than the 255"]));
            c.args[1] = format!("{}.obj", "m".repeat(246));
            c.show = c.show.replace("LONG", "m…m.obj (250 bytes)");
            c
        },
        // Control characters reach the terminal escaped.
        {
            let mut c = case("decompose NAME -o r.json --quiet", "a file name with BEL and ESC", |d| write(d, "bell\u{7}\u{1b}[31m.obj", "v 0 0 0\n"), r(&["bell\\u{7}\\u{1b}[31m.obj: the mesh has no polygon faces"]));
            c.args[1] = "bell\u{7}\u{1b}[31m.obj".into();
            c.show = c.show.replace("NAME", "$'bell\\a\\e[31m.obj'");
            c
        },
        // U+2028 and U+2029 too: a terminal shows them, but a log read by lines
        // (Python's splitlines, editors) would break the message there.
        {
            let mut c = case("decompose NAME -o r.json --quiet", "a file name with U+2028 and U+2029", |d| write(d, "line\u{2028}para\u{2029}.obj", "v 0 0 0\n"), r(&["line\\u{2028}para\\u{2029}.obj: the mesh has no polygon faces"]));
            c.args[1] = "line\u{2028}para\u{2029}.obj".into();
            c.show = c.show.replace("NAME", "$'line\\u2028para\\u2029.obj'");
            c
        },
        {
            let mut c = case("export r.json -o NAME", "an output name with ESC", sphere, done(|_, out| format!("exit 0, stdout: `{}`", out.trim())));
            c.args[3] = "o\u{1b}[2J.glb".into();
            c.show = c.show.replace("NAME", "$'o\\e[2J.glb'");
            c
        },
        {
            let mut c = case("export r.json -o NAME", "an output name with U+2028", sphere, done(|_, out| format!("exit 0, stdout: `{}`", out.trim())));
            c.args[3] = "o\u{2028}.glb".into();
            c.show = c.show.replace("NAME", "$'o\\u2028.glb'");
            c
        },
    ]
}

/// Runs every case, each in a directory of its own below `root`; returns the table.
pub fn table(root: &Path) -> String {
    let mut out =
        String::from("| command | what | outcome | exact message (stderr) |\n|---|---|---|---|\n");
    for (i, c) in cases().into_iter().enumerate() {
        let dir = root.join(format!("{i:02}"));
        std::fs::create_dir_all(&dir).unwrap();
        (c.setup)(&dir);
        let before = snapshot(&dir);
        let args: Vec<&str> = c.args.iter().map(String::as_str).collect();
        let o = primdecomp(&dir, &args);
        let stderr = String::from_utf8_lossy(&o.stderr).trim().to_string();
        let stdout = String::from_utf8_lossy(&o.stdout).to_string();
        let what = &c.show;
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert!(
            !stderr.contains('\u{1b}') && !stdout.contains('\u{1b}'),
            "{what}: raw ESC printed"
        );
        let outcome = match &c.want {
            Want::Refused(frags) => {
                assert_eq!(o.status.code(), Some(2), "{what}: {stderr}");
                for f in *frags {
                    assert!(stderr.contains(f), "{what}: message lacks '{f}': {stderr}");
                }
                assert_eq!(stderr.lines().count(), 1, "{what}: one sentence: {stderr}");
                assert_eq!(snapshot(&dir), before, "{what}: files changed");
                "exit 2, nothing written".to_string()
            }
            Want::Done(check) => {
                assert_eq!(o.status.code(), Some(0), "{what}: {stderr}");
                check(&dir, &stdout)
            }
        };
        let msg = if stderr.is_empty() {
            "—".to_string()
        } else {
            format!("`{}`", cell(&stderr))
        };
        out += &format!(
            "| `{}` | {} | {} | {} |\n",
            cell(what),
            c.what,
            outcome,
            msg
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
    out
}
