//! The checked-in header is what cbindgen makes of the crate today: a change to the
//! ABI without regenerating `include/primdecomp.h` fails here. Run with
//! `PRIMDECOMP_BLESS=1` to write the header instead.

use std::path::Path;

#[test]
fn header_matches_the_code() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut made = Vec::new();
    cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header")
        .write(&mut made);
    let made = String::from_utf8(made).expect("UTF-8 header");
    let path = dir.join("include/primdecomp.h");
    if std::env::var_os("PRIMDECOMP_BLESS").is_some() {
        std::fs::write(&path, &made).expect("write include/primdecomp.h");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == made,
        "include/primdecomp.h is stale: regenerate it with \
         PRIMDECOMP_BLESS=1 cargo test -p primdecomp-c --test header"
    );
}
