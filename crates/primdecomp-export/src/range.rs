//! What an export can write: numbers its readers load as they are meant.
//!
//! Every format's readers hold lengths in 32-bit floats somewhere (glTF accessors and
//! node transforms, USD `point3f`, MuJoCo's mesh vertices, Godot's `real_t`, Rapier
//! and most URDF consumers), and many square them (inertia, bounding spheres). So a
//! shape is written only when, in the format's frame (after `--scale` and the up
//! axis) and as grown by the margin, every number is finite and the shape's
//! magnitude (its farthest coordinate, plus the offset of the frame placing it) lies
//! within [`MIN_LENGTH`, `MAX_LENGTH`]: squares stay finite in f32, and the margin of
//! 2⁻¹⁸ of the magnitude stays above f32's subnormal range, where rounding is no
//! longer relative. MuJoCo also refuses meshes of surface area under about 1e-14
//! ("mesh surface area is too small"); an MJCF hull must have at least
//! [`MJCF_MIN_AREA`]. A shape outside these bounds is refused with one sentence
//! naming it: nothing non-finite or unloadable is ever written
//! (docs/decisions/hostile-input-limits.md).

use primdecomp::Frame;
use primdecomp::Primitive;
use primdecomp::Tess;
use primdecomp_math::short as show;
use primdecomp_math::{cross, norm, sub};

/// The largest magnitude written: its square, 1e36, is within f32's range (3.4e38).
pub const MAX_LENGTH: f64 = 1e18;

/// The smallest magnitude of a shape written: its margin (2⁻¹⁸ of it, about 4e-36)
/// is still a normal f32 (≥ 1.2e-38).
pub const MIN_LENGTH: f64 = 1e-30;

/// The smallest surface area of a hull written as an MJCF mesh (MuJoCo 4.0 refused a
/// cube of side 3e-8, area 5e-15, and loaded one of side 5e-8, area 1.5e-14).
pub const MJCF_MIN_AREA: f64 = 1e-12;

/// Largest absolute coordinate of the primitive's bounding box (the magnitude
/// [`Frame::conservative`] grows a shape by a fraction of).
fn magnitude(p: &Primitive) -> f64 {
    let (lo, hi) = p.aabb();
    lo.iter().chain(&hi).fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Every number of a primitive (coordinates and sizes).
fn numbers(p: &Primitive) -> Vec<f64> {
    let mut v = Vec::with_capacity(16);
    match *p {
        Primitive::Box(b) => {
            v.extend(b.center);
            v.extend(b.axes.iter().flatten());
            v.extend(b.half);
        }
        Primitive::Sphere(s) => {
            v.extend(s.center);
            v.push(s.radius);
        }
        Primitive::Capsule(c) => {
            v.extend(c.p0.iter().chain(&c.p1));
            v.push(c.radius);
        }
        Primitive::Cylinder(c) => {
            v.extend(c.p0.iter().chain(&c.p1));
            v.push(c.radius);
        }
        Primitive::Frustum(f) => {
            v.extend(f.p0.iter().chain(&f.p1));
            v.extend([f.r0, f.r1]);
        }
        Primitive::Prism(q) => {
            v.extend(q.center);
            v.extend(q.axes.iter().flatten());
            v.extend([q.hx, q.hy, q.hz_top, q.hz_bottom, q.shift]);
        }
    }
    v
}

const RESCALE: &str = "give --scale (ExportOptions::scale) to bring the result into range";

/// Refuses a grown shape `q` (in its object's written frame, placed by `frame`, whose
/// scale is written separately when `keep_scale`) whose numbers are not finite or
/// whose magnitude is outside [`MIN_LENGTH`, `MAX_LENGTH`], in the written frame or
/// in the format's world frame; `what` names it.
pub fn check_shape(
    q: &Primitive,
    frame: &Frame,
    keep_scale: bool,
    what: &str,
) -> Result<(), String> {
    if numbers(q).iter().any(|x| !x.is_finite()) {
        return Err(format!(
            "{what}: a number is not finite after --scale and the margin (the result holds \
             values too large to scale); {RESCALE}"
        ));
    }
    let local = magnitude(q);
    let offset = norm(frame.translation);
    let scale = if keep_scale { frame.scale } else { 1.0 };
    let world = scale * local + offset;
    let far = local.max(world).max(offset);
    if far.is_nan() || far > MAX_LENGTH {
        return Err(format!(
            "{what}: its coordinates reach {}, beyond the ±{} that the format's 32-bit \
             readers load and square; {RESCALE}",
            show(far),
            show(MAX_LENGTH)
        ));
    }
    let near = (local + offset / scale).min(world);
    if near < MIN_LENGTH || (keep_scale && scale < MIN_LENGTH) {
        return Err(format!(
            "{what}: it spans only {} from the origin, under the {} that 32-bit floats \
             keep relative precision for; {RESCALE}",
            show(near.min(scale)),
            show(MIN_LENGTH)
        ));
    }
    Ok(())
}

/// Refuses an object's frame (written whatever its shapes) that is not finite or
/// places its origin beyond [`MAX_LENGTH`], or whose written scale (`keep_scale`) is
/// outside [`MIN_LENGTH`, `MAX_LENGTH`]; `what` names the object.
pub fn check_frame(frame: &Frame, keep_scale: bool, what: &str) -> Result<(), String> {
    let far = frame.translation.iter().fold(0.0f64, |m, x| {
        if x.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(x.abs())
        }
    });
    if far.is_nan() || far > MAX_LENGTH {
        return Err(format!(
            "{what}: its origin lies at {}, beyond the ±{} that the format's 32-bit readers \
             load; {RESCALE}",
            show(far),
            show(MAX_LENGTH)
        ));
    }
    let s = frame.scale;
    if keep_scale && !(MIN_LENGTH..=MAX_LENGTH).contains(&s) {
        return Err(format!(
            "{what}: its scale {} is outside [{}, {}], what 32-bit readers keep; {RESCALE}",
            show(s),
            show(MIN_LENGTH),
            show(MAX_LENGTH)
        ));
    }
    Ok(())
}

/// Surface area of a hull's polygons.
pub fn area(t: &Tess) -> f64 {
    t.faces
        .iter()
        .map(|f| {
            let p = |i: usize| t.vertices[f[i] as usize];
            (1..f.len().saturating_sub(1))
                .map(|i| 0.5 * norm(cross(sub(p(i), p(0)), sub(p(i + 1), p(0)))))
                .sum::<f64>()
        })
        .sum()
}

/// Refuses a hull MuJoCo would not load as an MJCF mesh (surface area under
/// [`MJCF_MIN_AREA`]).
pub fn check_mjcf(hull: &Tess, what: &str) -> Result<(), String> {
    let a = area(hull);
    if a.is_nan() || a < MJCF_MIN_AREA {
        return Err(format!(
            "{what}: it is written as a mesh of surface area {}, and MuJoCo refuses \
             meshes under {}; {RESCALE}",
            show(a),
            show(MJCF_MIN_AREA)
        ));
    }
    Ok(())
}

/// Refuses input-mesh vertices (glTF `--input`) beyond [`MAX_LENGTH`] once placed.
pub fn check_points(points: &[[f64; 3]], frame: &Frame) -> Result<(), String> {
    for (i, p) in points.iter().enumerate() {
        let w = frame.point(*p);
        let far = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if far.is_nan() || far > MAX_LENGTH {
            return Err(format!(
                "the input mesh's vertex {} reaches {} once placed, beyond the ±{} that \
                 the format's 32-bit readers load; {RESCALE}",
                i + 1,
                show(far),
                show(MAX_LENGTH)
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use primdecomp::Sphere;

    fn sphere(c: f64, r: f64) -> Primitive {
        Primitive::Sphere(Sphere {
            center: [c, 0.0, 0.0],
            radius: r,
        })
    }

    #[test]
    fn magnitudes_outside_the_range_are_refused() {
        let id = Frame::IDENTITY;
        assert!(check_shape(&sphere(1.0, 0.5), &id, false, "s").is_ok());
        let e = check_shape(&sphere(1e20, 1.0), &id, false, "primitive 0 (sphere)").unwrap_err();
        assert!(
            e.starts_with("primitive 0 (sphere): its coordinates reach 1e20"),
            "{e}"
        );
        let e = check_shape(&sphere(0.0, 1e-35), &id, false, "s").unwrap_err();
        assert!(e.contains("spans only 1e-35"), "{e}");
        let e = check_shape(&sphere(f64::INFINITY, 1.0), &id, false, "s").unwrap_err();
        assert!(e.contains("not finite"), "{e}");
        // A tiny shape far from its node's origin is fine; a huge node scale is not.
        let far = Frame {
            translation: [1.0, 0.0, 0.0],
            ..Frame::IDENTITY
        };
        assert!(check_shape(&sphere(0.0, 1e-35), &far, false, "s").is_ok());
        let big = Frame {
            scale: 1e30,
            ..Frame::IDENTITY
        };
        assert!(check_shape(&sphere(1.0, 1.0), &big, true, "s").is_err());
        assert_eq!(show(2.5e-35), "2.5e-35");
        assert_eq!(show(1e18), "1e18");
    }
}
