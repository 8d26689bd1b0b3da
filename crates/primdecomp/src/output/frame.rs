//! Object frames and the conservative margin of the engine exports
//! (docs/decisions/exports-engine-conventions.md).
//!
//! A [`Frame`] is a similarity: `x ↦ translation + scale · R(rotation) · x`, the
//! placement of a per-object result (a glTF mesh node's transform, or the identity)
//! and of the up-axis and scale conversion of the exports. Primitives are moved by
//! frames exactly in form (a box stays a box), but not in arithmetic: rounding in the
//! composition, and the 32-bit floats many consumers store (glTF node transforms and
//! accessors, USD `point3f`, MuJoCo's mesh vertices, Godot's `real_t`), move a
//! surface by up to a few 2⁻²⁴ of the coordinates' magnitude. So every exported
//! shape is first grown by [`Frame::GROW_REL`] of its magnitude ([`grow`]: a shape that
//! contains the original's neighbourhood of that radius), which keeps the enclosure
//! guarantee through every export (docs/decisions/exports-engine-conventions.md).

use crate::math::quat::{axes_from_quat, quat_from_axes};
use crate::math::{add, cross, dot, madd, norm, normalize, scale, sub, V3};
use crate::primitive::{Capsule, Cylinder, Frustum, Obb, Primitive, Prism, Sphere};

/// A similarity transform `x ↦ translation + scale · R(rotation) · x`, rotation a
/// unit quaternion `[x, y, z, w]` (scalar last, as in the JSON contract).
///
/// ```
/// use primdecomp::Frame;
///
/// let lifted = Frame { translation: [0.0, 0.0, 2.0], rotation: [0.0, 0.0, 0.0, 1.0], scale: 3.0 };
/// assert_eq!(lifted.point([1.0, 0.0, 0.0]), [3.0, 0.0, 2.0]);
/// assert_eq!(lifted.inverse_point([3.0, 0.0, 2.0]), [1.0, 0.0, 0.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Where the local origin lands.
    pub translation: V3,
    /// Unit quaternion `[x, y, z, w]`.
    pub rotation: [f64; 4],
    /// Uniform scale, positive.
    pub scale: f64,
}

impl Default for Frame {
    fn default() -> Self {
        Frame::IDENTITY
    }
}

/// Hamilton product `a ⊗ b` of scalar-last quaternions (rotate by `b`, then `a`).
pub fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// `R(q) · v`.
pub fn rotate(q: [f64; 4], v: V3) -> V3 {
    let a = axes_from_quat(q);
    [
        a[0][0] * v[0] + a[1][0] * v[1] + a[2][0] * v[2],
        a[0][1] * v[0] + a[1][1] * v[1] + a[2][1] * v[2],
        a[0][2] * v[0] + a[1][2] * v[1] + a[2][2] * v[2],
    ]
}

impl Frame {
    /// Margin of the exports, relative to a shape's magnitude (its farthest coordinate
    /// from the origin of the frame it is written in, plus that frame's own offset):
    /// 2⁻¹⁸ ≈ 3.8e-6, 64 times the 2⁻²⁴ rounding of a 32-bit float.
    pub const GROW_REL: f64 = 1.0 / 262_144.0;

    /// Shortest cylinder, frustum or capsule axis written, relative to its radius: a
    /// consumer derives the axis from the written ends or centre, and a flatter disc
    /// would let the ends' rounding tilt its rim out of the margin.
    pub const MIN_AXIS_REL: f64 = 1.0 / 1_073_741_824.0;

    /// `p` placed by this frame and grown by [`Frame::GROW_REL`] of (its magnitude +
    /// `offset`), where `offset` is the magnitude of whatever frame a consumer places it
    /// in beyond this one: a shape of the same kind that still contains `p` after the
    /// consumer's rounding (32-bit floats included). Solids of revolution come out at
    /// least [`Frame::MIN_AXIS_REL`] of their radius long.
    ///
    /// ```
    /// use primdecomp::{Frame, Primitive, Sphere};
    ///
    /// let frame = Frame { translation: [1.0, 0.0, 0.0], ..Frame::IDENTITY };
    /// let ball = Primitive::Sphere(Sphere { center: [0.0; 3], radius: 1.0 });
    /// let Primitive::Sphere(placed) = frame.conservative(&ball, 0.0) else { unreachable!() };
    /// assert_eq!(placed.center, [1.0, 0.0, 0.0]);
    /// assert!(placed.radius > 1.0 && placed.radius < 1.0 + 1e-5);
    /// ```
    pub fn conservative(&self, p: &Primitive, offset: f64) -> Primitive {
        conservative(p, self, offset)
    }

    /// The identity: local coordinates are world coordinates.
    pub const IDENTITY: Frame = Frame {
        translation: [0.0; 3],
        rotation: [0.0, 0.0, 0.0, 1.0],
        scale: 1.0,
    };

    /// The image of point `p`.
    pub fn point(&self, p: V3) -> V3 {
        add(
            self.translation,
            scale(rotate(self.rotation, p), self.scale),
        )
    }

    /// The image of direction (or difference) `d`: scaled and rotated.
    pub fn vector(&self, d: V3) -> V3 {
        scale(rotate(self.rotation, d), self.scale)
    }

    /// The preimage of point `p` (`scale` must be positive).
    pub fn inverse_point(&self, p: V3) -> V3 {
        let [x, y, z, w] = self.rotation;
        let d = sub(p, self.translation);
        scale(rotate([-x, -y, -z, w], d), 1.0 / self.scale)
    }

    /// `self ∘ inner`: first `inner`, then `self`.
    pub fn then(&self, outer: &Frame) -> Frame {
        Frame {
            translation: outer.point(self.translation),
            rotation: normalized(quat_mul(outer.rotation, self.rotation)),
            scale: outer.scale * self.scale,
        }
    }

    /// The similarity part of a column-major affine matrix (`m[column][row]`, glTF's
    /// layout): its translation, the rotation of its columns orthonormalized in order
    /// (Gram–Schmidt, the third flipped to keep it right-handed), and their mean length
    /// as the scale when the three lengths agree within 1e-6 and the matrix keeps
    /// orientation; otherwise scale 1 (a non-uniform scale, shear or mirror stays in
    /// the geometry, expressed in this frame). A degenerate or non-finite matrix
    /// gives its translation alone (or the identity).
    pub fn from_matrix(m: &[[f64; 4]; 4]) -> Frame {
        let t = [m[3][0], m[3][1], m[3][2]];
        let t = if t.iter().all(|x| x.is_finite()) {
            t
        } else {
            [0.0; 3]
        };
        let cols: [V3; 3] = std::array::from_fn(|c| [m[c][0], m[c][1], m[c][2]]);
        let plain = Frame {
            translation: t,
            ..Frame::IDENTITY
        };
        let Some(a0) = normalize(cols[0]) else {
            return plain;
        };
        let Some(a1) = normalize(madd(cols[1], a0, -dot(cols[1], a0))) else {
            return plain;
        };
        let a2 = cross(a0, a1);
        if !a0.iter().chain(&a1).chain(&a2).all(|x| x.is_finite()) {
            return plain;
        }
        let lens = cols.map(norm);
        let det = dot(cross(cols[0], cols[1]), cols[2]);
        let mean = (lens[0] + lens[1] + lens[2]) / 3.0;
        let similar = det > 0.0
            && mean > 0.0
            && mean.is_finite()
            && lens.iter().all(|l| (l - mean).abs() <= 1e-6 * mean)
            && dot(cols[0], cols[1]).abs() <= 1e-6 * mean * mean
            && dot(cols[0], cols[2]).abs() <= 1e-6 * mean * mean
            && dot(cols[1], cols[2]).abs() <= 1e-6 * mean * mean;
        Frame {
            translation: t,
            rotation: quat_from_axes(&[a0, a1, a2]),
            scale: if similar { mean } else { 1.0 },
        }
    }

    /// The frame as a column-major affine matrix.
    pub fn matrix(&self) -> [[f64; 4]; 4] {
        let a = axes_from_quat(self.rotation);
        let c = |i: usize| {
            [
                a[i][0] * self.scale,
                a[i][1] * self.scale,
                a[i][2] * self.scale,
                0.0,
            ]
        };
        let t = self.translation;
        [c(0), c(1), c(2), [t[0], t[1], t[2], 1.0]]
    }
}

fn normalized(q: [f64; 4]) -> [f64; 4] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 0.0 && n.is_finite() {
        let q = q.map(|x| x / n);
        // Canonical sign, as quat_from_axes: w ≥ 0.
        if q[3] < 0.0 {
            q.map(|x| -x + 0.0)
        } else {
            q
        }
    } else {
        [0.0, 0.0, 0.0, 1.0]
    }
}

/// The primitive moved by `f` (no margin: see [`conservative`]). Solids of revolution
/// move by their centre and half axis, so that the axis direction is as exact as
/// the rotation.
pub fn transform(p: &Primitive, f: &Frame) -> Primitive {
    let s = f.scale;
    let axes = |a: &[V3; 3]| {
        let r = a.map(|v| rotate(f.rotation, v));
        orthonormal(r)
    };
    let ends = |p0: V3, p1: V3| {
        let c = f.point(scale(add(p0, p1), 0.5));
        let h = f.vector(scale(sub(p1, p0), 0.5));
        (sub(c, h), add(c, h))
    };
    match *p {
        Primitive::Box(b) => Primitive::Box(Obb {
            center: f.point(b.center),
            axes: axes(&b.axes),
            half: b.half.map(|h| h * s),
        }),
        Primitive::Sphere(b) => Primitive::Sphere(Sphere {
            center: f.point(b.center),
            radius: b.radius * s,
        }),
        Primitive::Capsule(c) => {
            let (p0, p1) = ends(c.p0, c.p1);
            Primitive::Capsule(Capsule {
                p0,
                p1,
                radius: c.radius * s,
            })
        }
        Primitive::Cylinder(c) => {
            let (p0, p1) = ends(c.p0, c.p1);
            Primitive::Cylinder(Cylinder {
                p0,
                p1,
                radius: c.radius * s,
            })
        }
        Primitive::Frustum(c) => {
            let (p0, p1) = ends(c.p0, c.p1);
            Primitive::Frustum(Frustum {
                p0,
                p1,
                r0: c.r0 * s,
                r1: c.r1 * s,
            })
        }
        Primitive::Prism(q) => Primitive::Prism(Prism {
            center: f.point(q.center),
            axes: axes(&q.axes),
            hx: q.hx * s,
            hy: q.hy * s,
            hz_top: q.hz_top * s,
            hz_bottom: q.hz_bottom * s,
            shift: q.shift * s,
        }),
    }
}

/// Re-orthonormalizes rotated axes (Gram–Schmidt in order, third = first × second).
fn orthonormal(a: [V3; 3]) -> [V3; 3] {
    let a0 = normalize(a[0]).unwrap_or([1.0, 0.0, 0.0]);
    let a1 = normalize(madd(a[1], a0, -dot(a[1], a0))).unwrap_or_else(|| {
        let (u, _) = crate::math::circle_frame(a0);
        u
    });
    let a2 = cross(a0, a1);
    if dot(a2, a[2]) >= 0.0 {
        [a0, a1, a2]
    } else {
        // A left-handed input keeps its handedness (the tessellation winds by it).
        [a0, a1, scale(a2, -1.0)]
    }
}

/// Largest absolute coordinate of the primitive's bounding box.
pub fn magnitude(p: &Primitive) -> f64 {
    let (lo, hi) = p.aabb();
    lo.iter().chain(&hi).fold(0.0f64, |m, x| m.max(x.abs()))
}

/// A primitive of the same kind that contains every point within `m` of `p`
/// (the Minkowski sum with a ball of radius `m`), and whose solids of revolution
/// are at least [`Frame::MIN_AXIS_REL`] of their radius long.
pub fn grow(p: &Primitive, m: f64) -> Primitive {
    let m = m.max(0.0);
    match *p {
        Primitive::Box(b) => Primitive::Box(Obb {
            half: b.half.map(|h| h + m),
            ..b
        }),
        Primitive::Sphere(s) => Primitive::Sphere(Sphere {
            radius: s.radius + m,
            ..s
        }),
        Primitive::Capsule(c) => Primitive::Capsule(Capsule {
            radius: c.radius + m,
            ..c
        }),
        Primitive::Cylinder(c) => {
            let (p0, p1) = extend(c.p0, c.p1, m, c.radius);
            Primitive::Cylinder(Cylinder {
                p0,
                p1,
                radius: c.radius + m,
            })
        }
        Primitive::Frustum(f) => {
            let len = norm(sub(f.p1, f.p0));
            let (p0, p1) = extend(f.p0, f.p1, m, f.r0.max(f.r1));
            let wide = f.r0.max(f.r1) + m;
            if len <= 0.0 {
                return Primitive::Cylinder(Cylinder {
                    p0,
                    p1,
                    radius: wide,
                });
            }
            // The side line r(t) = r0 + k·t pushed out by m (perpendicular), over
            // the extended axis; or the cylinder of the wider end, if smaller.
            let k = (f.r1 - f.r0) / len;
            let out = m * (1.0 + k * k).sqrt();
            let (r0, r1) = (f.r0 - k * m + out, f.r1 + k * m + out);
            if r0 * r0 + r0 * r1 + r1 * r1 <= 3.0 * wide * wide {
                Primitive::Frustum(Frustum { p0, p1, r0, r1 })
            } else {
                Primitive::Cylinder(Cylinder {
                    p0,
                    p1,
                    radius: wide,
                })
            }
        }
        Primitive::Prism(q) => Primitive::Prism(q.grown(m)),
    }
}

/// Ends pushed out by `m` along the axis, and further apart if needed to be at
/// least [`Frame::MIN_AXIS_REL`]·`r` long; a zero-length axis becomes z.
fn extend(p0: V3, p1: V3, m: f64, r: f64) -> (V3, V3) {
    let len = norm(sub(p1, p0));
    let a = normalize(sub(p1, p0)).unwrap_or([0.0, 0.0, 1.0]);
    let e = m.max(0.5 * (Frame::MIN_AXIS_REL * r - len)).max(0.0);
    let c = scale(add(p0, p1), 0.5);
    let h = 0.5 * len + e;
    (madd(c, a, -h), madd(c, a, h))
}

/// `p` moved by `f`, grown by [`Frame::GROW_REL`] of (its magnitude + `offset`), where
/// `offset` is the magnitude of whatever frame the consumer places it in beyond `f`.
pub fn conservative(p: &Primitive, f: &Frame, offset: f64) -> Primitive {
    let q = transform(p, f);
    let m = Frame::GROW_REL * (magnitude(&q) + offset);
    grow(&q, m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: V3, b: V3, tol: f64) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
    }

    #[test]
    fn frame_round_trip_and_matrix() {
        let f = Frame {
            translation: [1.0, -2.0, 3.0],
            rotation: normalized([0.1, 0.7, -0.2, 0.6]),
            scale: 2.5,
        };
        let p = [0.3, -1.2, 4.0];
        assert!(close(f.inverse_point(f.point(p)), p, 1e-12));
        let g = Frame::from_matrix(&f.matrix());
        assert!(close(g.translation, f.translation, 1e-12));
        assert!((g.scale - 2.5).abs() < 1e-12);
        assert!(close(g.point(p), f.point(p), 1e-12));
        // Composition: first f, then h.
        let h = Frame {
            translation: [0.0, 5.0, 0.0],
            rotation: [
                std::f64::consts::FRAC_1_SQRT_2,
                0.0,
                0.0,
                std::f64::consts::FRAC_1_SQRT_2,
            ],
            scale: 0.5,
        };
        assert!(close(f.then(&h).point(p), h.point(f.point(p)), 1e-12));
    }

    #[test]
    fn non_uniform_matrix_keeps_rigid_part() {
        let m = [
            [2.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [4.0, 5.0, 6.0, 1.0],
        ];
        let f = Frame::from_matrix(&m);
        assert_eq!(f.scale, 1.0);
        assert_eq!(f.translation, [4.0, 5.0, 6.0]);
        assert!(close(f.point([1.0, 1.0, 1.0]), [5.0, 6.0, 7.0], 1e-12));
        let zero = [[0.0; 4]; 4];
        assert_eq!(Frame::from_matrix(&zero), Frame::IDENTITY);
    }

    #[test]
    fn grown_shapes_contain_the_margin() {
        let m = 0.01;
        let prims = [
            Primitive::Frustum(Frustum {
                p0: [0.0, 0.0, 0.0],
                p1: [0.0, 0.0, 1.0],
                r0: 1.0,
                r1: 0.2,
            }),
            Primitive::Prism(Prism {
                center: [0.0; 3],
                axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                hx: 1.0,
                hy: 0.5,
                hz_top: 0.1,
                hz_bottom: 0.9,
                shift: 0.0,
            }),
            Primitive::Cylinder(Cylinder {
                p0: [1.0; 3],
                p1: [1.0; 3],
                radius: 0.3,
            }),
        ];
        for p in prims {
            let g = grow(&p, m);
            // Points on p's surface pushed out by m along a sampled normal direction
            // must stay inside the grown shape: sample points near p and move them.
            for i in 0..2000 {
                let t = i as f64 * 0.618_033_988_75;
                let dir = normalize([t.sin() * 1.3, (2.0 * t).cos(), (3.7 * t).sin()]).unwrap();
                // The support point of p along dir, pushed out by m.
                let s = p.support(dir);
                let (lo, hi) = p.aabb();
                let c = scale(add(lo, hi), 0.5);
                // Move from the centre along dir until the support plane, then by m.
                let x = madd(c, dir, s - dot(dir, c));
                if p.contains(x, 1e-12) {
                    assert!(g.contains(madd(x, dir, m * 0.999), 1e-12), "{p:?} {dir:?}");
                }
                assert!(g.support(dir) >= s + m * 0.999, "{p:?} {dir:?}");
            }
        }
    }
}
