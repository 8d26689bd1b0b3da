//! Results: levels, their primitives as a flat array of tagged structs (the values the
//! JSON holds, bit for bit), and the JSON document itself.

use crate::args::{handle, put, writable};
use crate::status::{guard, Failure, PrimdecompStatus};
use primdecomp::{Decomposition, Level, Params, Primitive, Shortfall};
use primdecomp_math::quat_from_axes;
use std::ffi::{c_char, CString};

/// A finished decomposition: one level per target, and the settings that made it.
/// Immutable: it may be read from several threads at once. Free it with
/// `primdecomp_result_free`.
pub struct PrimdecompResult {
    pub(crate) dec: Decomposition,
    pub(crate) params: Params,
    /// Each level's primitives as C structs, made once.
    flat: Vec<Vec<PrimdecompPrimitive>>,
}

/// A primitive's kind, in the order every count and weight uses.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimdecompKind {
    /// An oriented box: `shape.box`.
    Box = 0,
    /// A ball: `shape.sphere`.
    Sphere = 1,
    /// A segment swept by a ball: `shape.capsule`.
    Capsule = 2,
    /// A capped cylinder: `shape.cylinder`.
    Cylinder = 3,
    /// A truncated cone: `shape.frustum`.
    Frustum = 4,
    /// A trapezoidal prism: `shape.prism`.
    Prism = 5,
}

/// An oriented box: `rotation` (x, y, z, w; local to world) turns the box's axes,
/// `half_extents` along them.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompBox {
    /// Centre.
    pub center: [f64; 3],
    /// Unit quaternion, scalar last.
    pub rotation: [f64; 4],
    /// Half extents along the local x, y, z axes.
    pub half_extents: [f64; 3],
}

/// A ball.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompSphere {
    /// Centre.
    pub center: [f64; 3],
    /// Radius.
    pub radius: f64,
}

/// A capsule: the segment `p0`–`p1` swept by a ball of `radius`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompCapsule {
    /// One end of the segment.
    pub p0: [f64; 3],
    /// The other end.
    pub p1: [f64; 3],
    /// Radius.
    pub radius: f64,
}

/// A capped cylinder from cap centre `p0` to cap centre `p1`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompCylinder {
    /// One cap's centre.
    pub p0: [f64; 3],
    /// The other cap's centre.
    pub p1: [f64; 3],
    /// Radius.
    pub radius: f64,
}

/// A truncated cone from cap centre `p0` (radius `radius0`) to `p1` (`radius1`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompFrustum {
    /// One cap's centre.
    pub p0: [f64; 3],
    /// The other cap's centre.
    pub p1: [f64; 3],
    /// The radius at `p0`.
    pub radius0: f64,
    /// The radius at `p1`.
    pub radius1: f64,
}

/// A trapezoidal prism: extruded along its local x (`half_x`), its y–z section a
/// trapezoid `2 half_y` high whose top side (y = +half_y) is `2 half_z_top` long and
/// bottom side `2 half_z_bottom`; the top side's midpoint at z = `shift_z`, the
/// bottom's at −`shift_z` (0 for the symmetric prism).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompPrism {
    /// Centre.
    pub center: [f64; 3],
    /// Unit quaternion, scalar last.
    pub rotation: [f64; 4],
    /// Half length along the extrusion axis (local x).
    pub half_x: f64,
    /// Half height of the section (local y).
    pub half_y: f64,
    /// Half length of the section's top side (local z).
    pub half_z_top: f64,
    /// Half length of the section's bottom side.
    pub half_z_bottom: f64,
    /// Where the top side's midpoint lies along local z.
    pub shift_z: f64,
}

/// One kind's parameters; `kind` says which member holds.
/// cbindgen:field-names=[box, sphere, capsule, cylinder, frustum, prism]
#[repr(C)]
#[derive(Clone, Copy)]
pub union PrimdecompShape {
    /// `PRIMDECOMP_KIND_BOX`.
    pub box_: PrimdecompBox,
    /// `PRIMDECOMP_KIND_SPHERE`.
    pub sphere: PrimdecompSphere,
    /// `PRIMDECOMP_KIND_CAPSULE`.
    pub capsule: PrimdecompCapsule,
    /// `PRIMDECOMP_KIND_CYLINDER`.
    pub cylinder: PrimdecompCylinder,
    /// `PRIMDECOMP_KIND_FRUSTUM`.
    pub frustum: PrimdecompFrustum,
    /// `PRIMDECOMP_KIND_PRISM`.
    pub prism: PrimdecompPrism,
}

/// One primitive, world coordinates: its kind, how many input faces it was fitted
/// to, and its parameters (the values of the JSON's `primitives` entry).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct PrimdecompPrimitive {
    /// Which member of `shape` holds.
    pub kind: PrimdecompKind,
    /// Input faces it was fitted to.
    pub faces: u32,
    /// The parameters.
    pub shape: PrimdecompShape,
}

impl PrimdecompPrimitive {
    fn new(p: &Primitive, faces: u32) -> PrimdecompPrimitive {
        let (kind, shape) = match *p {
            Primitive::Box(b) => (PrimdecompKind::Box, box_shape(&b)),
            Primitive::Sphere(s) => (
                PrimdecompKind::Sphere,
                PrimdecompShape {
                    sphere: PrimdecompSphere {
                        center: s.center,
                        radius: s.radius,
                    },
                },
            ),
            Primitive::Capsule(c) => (
                PrimdecompKind::Capsule,
                PrimdecompShape {
                    capsule: PrimdecompCapsule {
                        p0: c.p0,
                        p1: c.p1,
                        radius: c.radius,
                    },
                },
            ),
            Primitive::Cylinder(c) => (
                PrimdecompKind::Cylinder,
                PrimdecompShape {
                    cylinder: PrimdecompCylinder {
                        p0: c.p0,
                        p1: c.p1,
                        radius: c.radius,
                    },
                },
            ),
            Primitive::Frustum(f) => (PrimdecompKind::Frustum, frustum_shape(&f)),
            Primitive::Prism(q) => (PrimdecompKind::Prism, prism_shape(&q)),
        };
        PrimdecompPrimitive { kind, faces, shape }
    }
}

/// A box's C shape: its axes as a rotation.
fn box_shape(b: &primdecomp::Obb) -> PrimdecompShape {
    PrimdecompShape {
        box_: PrimdecompBox {
            center: b.center,
            rotation: quat_from_axes(&b.axes),
            half_extents: b.half,
        },
    }
}

/// A frustum's C shape.
fn frustum_shape(f: &primdecomp::Frustum) -> PrimdecompShape {
    PrimdecompShape {
        frustum: PrimdecompFrustum {
            p0: f.p0,
            p1: f.p1,
            radius0: f.r0,
            radius1: f.r1,
        },
    }
}

/// A prism's C shape: its axes as a rotation.
fn prism_shape(q: &primdecomp::Prism) -> PrimdecompShape {
    PrimdecompShape {
        prism: PrimdecompPrism {
            center: q.center,
            rotation: quat_from_axes(&q.axes),
            half_x: q.hx,
            half_y: q.hy,
            half_z_top: q.hz_top,
            half_z_bottom: q.hz_bottom,
            shift_z: q.shift,
        },
    }
}

/// What stopped a level short of its tolerance.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimdecompShortfall {
    /// Nothing: the level is within its tolerance, or none was asked.
    None = 0,
    /// The count ran out first.
    Count = 1,
    /// The byte target ran out first.
    Bytes = 2,
    /// Faces no enabled kind encloses nearer.
    Faces = 3,
}

/// What a level's `distance` is measured to (the JSON's `stats.distance.measured_to`).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimdecompMeasuredTo {
    /// Nothing was measured: a greedy level, whose `distance` is NaN.
    None = 0,
    /// The input's surface: every point of a primitive counts by its distance to the
    /// nearest input face.
    Mesh = 1,
    /// The input's solid (`"solid": true` on a closed input with an inside): a point
    /// of a primitive inside the input stands at 0 (docs/decisions/0056).
    Solid = 2,
}

/// A level's summary (the JSON's `stats`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimdecompLevelInfo {
    /// The target count asked for (the cap of a tolerance or byte target).
    pub target: usize,
    /// Primitives in the level.
    pub primitives: usize,
    /// Storage by the paper's Table 2 (4 bytes a float).
    pub bytes: usize,
    /// Primitives of each kind, indexed by `primdecomp_kind`.
    pub counts: [usize; 6],
    /// The tolerance asked for, in the input's units; NaN when none was.
    pub tolerance: f64,
    /// The byte target asked for; 0 when none was.
    pub max_bytes: usize,
    /// For a cut of the merge tree (a tolerance, byte target or `"cut": true`): an
    /// upper bound of the farthest any primitive stands from the input, in its units
    /// (from its surface or its solid: `primdecomp_result_level_measured_to`); NaN for
    /// a greedy level.
    pub distance: f64,
    /// What kept the level from its tolerance.
    pub shortfall: PrimdecompShortfall,
}

impl PrimdecompResult {
    pub(crate) fn new(dec: Decomposition, params: Params) -> PrimdecompResult {
        let flat = dec
            .levels
            .iter()
            .map(|l| {
                l.primitives
                    .iter()
                    .zip(&l.faces)
                    .map(|(p, &f)| PrimdecompPrimitive::new(p, f))
                    .collect()
            })
            .collect();
        PrimdecompResult { dec, params, flat }
    }

    pub(crate) fn level(&self, i: usize) -> Result<&Level, Failure> {
        self.dec.levels.get(i).ok_or_else(|| {
            Failure::new(
                PrimdecompStatus::OutOfRange,
                format!(
                    "level {i} out of range: the result has {} levels",
                    self.dec.levels.len()
                ),
            )
        })
    }
}

/// The result's levels, one per target (0 for NULL).
///
/// # Safety
/// `result` is NULL or a live result of this library.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_level_count(result: *const PrimdecompResult) -> usize {
    handle(result, "result").map_or(0, |r| r.dec.levels.len())
}

/// A level's summary into `*out`.
///
/// # Safety
/// `result` is a live result of this library; `out` points to a writable
/// `primdecomp_level_info`.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_level(
    result: *const PrimdecompResult,
    level: usize,
    out: *mut PrimdecompLevelInfo,
) -> PrimdecompStatus {
    guard(|| {
        let r = handle(result, "result")?;
        let l = r.level(level)?;
        let info = PrimdecompLevelInfo {
            target: l.target,
            primitives: l.primitives.len(),
            bytes: l.bytes(),
            counts: l.counts(),
            tolerance: l.tolerance.unwrap_or(f64::NAN),
            max_bytes: l.max_bytes.unwrap_or(0),
            distance: l.distance.unwrap_or(f64::NAN),
            shortfall: match l.shortfall {
                None => PrimdecompShortfall::None,
                Some(Shortfall::Count) => PrimdecompShortfall::Count,
                Some(Shortfall::Bytes) => PrimdecompShortfall::Bytes,
                Some(Shortfall::Faces) => PrimdecompShortfall::Faces,
            },
        };
        put(out, info, "out")
    })
}

/// What a level's `distance` is measured to into `*out`: the input's solid under
/// `"solid": true` on a closed input, else its surface; `PRIMDECOMP_MEASURED_TO_NONE`
/// for a greedy level. (A function rather than a field of `primdecomp_level_info`, so
/// that a caller built against an older header, whose struct is smaller, stays safe.)
///
/// # Safety
/// `result` is a live result of this library; `out` points to a writable
/// `primdecomp_measured_to`.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_level_measured_to(
    result: *const PrimdecompResult,
    level: usize,
    out: *mut PrimdecompMeasuredTo,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        let r = handle(result, "result")?;
        let l = r.level(level)?;
        let to = match (l.distance, l.distance_to_solid) {
            (None, _) => PrimdecompMeasuredTo::None,
            (Some(_), false) => PrimdecompMeasuredTo::Mesh,
            (Some(_), true) => PrimdecompMeasuredTo::Solid,
        };
        put(out, to, "out")
    })
}

/// A level's primitives: `*out` points to `*count` structs owned by the result
/// (valid until `primdecomp_result_free`; do not free them).
///
/// # Safety
/// `result` is a live result of this library; `out` and `count` point to writable
/// storage.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_primitives(
    result: *const PrimdecompResult,
    level: usize,
    out: *mut *const PrimdecompPrimitive,
    count: *mut usize,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        writable(count, "count")?;
        let r = handle(result, "result")?;
        r.level(level)?;
        let prims = &r.flat[level];
        put(out, prims.as_ptr(), "out")?;
        put(count, prims.len(), "count")
    })
}

/// A level's JSON document, byte for byte what `primdecomp decompose` writes for the
/// same input and settings: `*out` is a new NUL-terminated string (free it with
/// `primdecomp_string_free`), `*len` (may be NULL) its length without the NUL.
///
/// # Safety
/// `result` is a live result of this library; `out` points to writable storage for
/// a pointer; `len` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_json(
    result: *const PrimdecompResult,
    level: usize,
    out: *mut *mut c_char,
    len: *mut usize,
) -> PrimdecompStatus {
    guard(|| {
        writable(out, "out")?;
        let r = handle(result, "result")?;
        r.level(level)?;
        let json = r.dec.to_json(level, &r.params);
        let n = json.len();
        // JSON escapes every control character: no NUL inside.
        let text = CString::new(json).map_err(|_| Failure::argument("JSON holds a NUL"))?;
        if !len.is_null() {
            put(len, n, "len")?;
        }
        put(out, text.into_raw(), "out")
    })
}

/// Frees a result (NULL is ignored); the primitive arrays it handed out go with it.
///
/// # Safety
/// `result` is NULL or a result of this library, freed only once and not in use.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_result_free(result: *mut PrimdecompResult) {
    if !result.is_null() {
        // SAFETY: a pointer from Box::into_raw in run.rs, freed once.
        drop(unsafe { Box::from_raw(result) });
    }
}

/// Frees a string this library returned (NULL is ignored).
///
/// # Safety
/// `s` is NULL or a string from this library, freed only once.
#[no_mangle]
pub unsafe extern "C" fn primdecomp_string_free(s: *mut c_char) {
    if !s.is_null() {
        // SAFETY: a pointer from CString::into_raw in this library, freed once.
        drop(unsafe { CString::from_raw(s) });
    }
}
