//! A tiled run in three steps for `primdecomp.ray_tiles` (python/primdecomp/
//! ray_tiles.py): the plan, one tile and the merge, each taking and giving the
//! core's checked bytes (`primdecomp::Tiled`), the work done with the GIL released
//! and Ctrl-C watched. Bad bytes, a file other than the plan's, a tile out of range
//! are `ValueError`s naming what is wrong; the file system's errors `OSError`s.

use crate::{to_py_err, watched, NativeResult};
use primdecomp::{LoadOptions, Params, Tiled};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::Path;

/// The plan of a tiled run of the file at `path` in `tiles` tiles with the settings
/// (the JSON of `Params`), as bytes.
#[pyfunction]
#[pyo3(signature = (path, settings_json, tiles, progress=None))]
fn tiles_plan<'py>(
    py: Python<'py>,
    path: &str,
    settings_json: &str,
    tiles: usize,
    progress: Option<PyObject>,
) -> PyResult<Bound<'py, PyBytes>> {
    let percent = serde_json::from_str::<serde_json::Value>(settings_json)
        .ok()
        .and_then(|v| Some(v.get("targets")?.as_array()?.iter().any(|t| t.is_string())))
        .unwrap_or(false);
    if percent {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "targets: a percentage of the faces needs the whole mesh in memory, and a tiled \
             run decomposes it in tiles: give a count",
        ));
    }
    let params = Params::from_json(settings_json).map_err(to_py_err)?;
    if tiles == 0 || tiles > Tiled::MAX_TILES {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "tiles must be in 1..={}, got {tiles}",
            Tiled::MAX_TILES
        )));
    }
    let options = LoadOptions {
        tiles: Some(tiles),
        ..LoadOptions::default()
    };
    let bytes = watched(py, &params, progress.as_ref(), None, |_| {
        Tiled::plan(Path::new(path), &params, &options).map(|t| t.to_bytes())
    })?;
    Ok(PyBytes::new(py, &bytes))
}

/// The number of tiles of a plan (its bytes checked).
#[pyfunction]
fn tiles_count(plan: &[u8]) -> PyResult<usize> {
    Ok(Tiled::from_bytes(plan).map_err(to_py_err)?.tiles())
}

/// Tile `tile` of the plan run on the file at `path`: the tile's result as bytes.
#[pyfunction]
#[pyo3(signature = (path, plan, tile, progress=None))]
fn tiles_run<'py>(
    py: Python<'py>,
    path: &str,
    plan: &[u8],
    tile: usize,
    progress: Option<PyObject>,
) -> PyResult<Bound<'py, PyBytes>> {
    let tiled = Tiled::from_bytes(plan).map_err(to_py_err)?;
    let params = Params::default();
    let bytes = watched(py, &params, progress.as_ref(), None, |p| {
        tiled.run_tile(Path::new(path), tile, p)
    })?;
    Ok(PyBytes::new(py, &bytes))
}

/// Checks that `result` is tile `tile`'s result of the plan (a ValueError otherwise).
#[pyfunction]
fn tiles_check(py: Python<'_>, plan: &[u8], tile: usize, result: &[u8]) -> PyResult<()> {
    let tiled = Tiled::from_bytes(plan).map_err(to_py_err)?;
    py.allow_threads(|| tiled.check_tile(tile, result))
        .map_err(to_py_err)
}

/// Merges every tile's result (in tile order) on top: the decomposition the CLI's
/// `--tiles` run of `path` gives, byte for byte.
#[pyfunction]
#[pyo3(signature = (path, plan, results, progress=None))]
fn tiles_merge(
    py: Python<'_>,
    path: &str,
    plan: &[u8],
    results: Vec<Bound<'_, PyBytes>>,
    progress: Option<PyObject>,
) -> PyResult<NativeResult> {
    let tiled = Tiled::from_bytes(plan).map_err(to_py_err)?;
    let slices: Vec<&[u8]> = results.iter().map(|b| b.as_bytes()).collect();
    let params = tiled.params().clone();
    let mut dec = watched(py, &params, progress.as_ref(), None, |p| {
        tiled.merge(&slices, p)
    })?;
    dec.input.record_file(Path::new(path));
    Ok(NativeResult { dec, params })
}

pub(crate) fn add(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(tiles_plan, m)?)?;
    m.add_function(wrap_pyfunction!(tiles_count, m)?)?;
    m.add_function(wrap_pyfunction!(tiles_run, m)?)?;
    m.add_function(wrap_pyfunction!(tiles_check, m)?)?;
    m.add_function(wrap_pyfunction!(tiles_merge, m)?)?;
    Ok(())
}
