//! The C ABI of primdecomp: `libprimdecomp_c.so` / `libprimdecomp_c.a` and the header
//! `include/primdecomp.h` (generated from this crate by cbindgen; `tests/header.rs`
//! fails when it is stale). A thin layer over the core library's public API:
//!
//! - meshes from a file ([`mesh::primdecomp_mesh_load`]), from bytes in memory
//!   ([`mesh::primdecomp_mesh_parse`]) or from float/double vertex and `uint32_t`
//!   index arrays ([`mesh::primdecomp_mesh_from_floats`],
//!   [`mesh::primdecomp_mesh_from_doubles`]);
//! - [`run::primdecomp_decompose`] with the settings as the JSON a result file
//!   carries (`settings`), a progress callback and a cancel flag;
//! - results as a flat array of tagged primitive structs
//!   ([`result::primdecomp_result_primitives`]), as the CLI's JSON
//!   ([`result::primdecomp_result_json`]) and in every format the CLI exports
//!   ([`export::primdecomp_result_export`], [`export::primdecomp_result_export_to_memory`]);
//! - a status code from every call that can fail and the reason in
//!   [`status::primdecomp_last_error`] (per thread); no panic crosses the boundary
//!   (each call's body runs under `catch_unwind`); every allocation handed out has its
//!   free function.
//!
//! `examples/decompose.c` is a complete program; `tests/abi_test.cpp` is the C++ test
//! `tests/run.sh` builds with the system's compilers under AddressSanitizer.

// The modules in the order the header lists them (cbindgen keeps parse order).
pub mod status;

pub mod mesh;

pub mod run;

pub mod result;

pub mod export;

mod args;

use std::ffi::c_char;

/// The library's version, `"MAJOR.MINOR.PATCH"` (a static string).
#[no_mangle]
pub extern "C" fn primdecomp_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}
