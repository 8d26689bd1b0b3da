//! Rotations as unit quaternions `[qx, qy, qz, qw]` (scalar last) and as orthonormal
//! right-handed axes (the columns of the rotation matrix, local → world): the JSON
//! contract's rotation convention, shared by export, reading back and the tests.

/// Unit quaternion `[qx, qy, qz, qw]` of the rotation whose matrix has columns
/// `axes[0], axes[1], axes[2]` (orthonormal, right-handed), by Shepperd's method
/// (the branch with the largest diagonal term), normalized, with a canonical sign:
/// `qw > 0`, or if `qw == 0` the first nonzero component positive.
pub fn quat_from_axes(axes: &[[f64; 3]; 3]) -> [f64; 4] {
    // m[i][j] = row i, column j; column j is axes[j].
    let m = |i: usize, j: usize| axes[j][i];
    debug_assert!(
        crate::vec3::dot(crate::vec3::cross(axes[0], axes[1]), axes[2]) > 0.0,
        "axes must be right-handed"
    );
    let (m00, m11, m22) = (m(0, 0), m(1, 1), m(2, 2));
    let trace = m00 + m11 + m22;
    let q = if trace >= m00 && trace >= m11 && trace >= m22 {
        let s = 2.0 * (1.0 + trace).sqrt(); // 4·qw
        [
            (m(2, 1) - m(1, 2)) / s,
            (m(0, 2) - m(2, 0)) / s,
            (m(1, 0) - m(0, 1)) / s,
            0.25 * s,
        ]
    } else if m00 >= m11 && m00 >= m22 {
        let s = 2.0 * (1.0 + m00 - m11 - m22).sqrt(); // 4·qx
        [
            0.25 * s,
            (m(0, 1) + m(1, 0)) / s,
            (m(0, 2) + m(2, 0)) / s,
            (m(2, 1) - m(1, 2)) / s,
        ]
    } else if m11 >= m22 {
        let s = 2.0 * (1.0 + m11 - m00 - m22).sqrt(); // 4·qy
        [
            (m(0, 1) + m(1, 0)) / s,
            0.25 * s,
            (m(1, 2) + m(2, 1)) / s,
            (m(0, 2) - m(2, 0)) / s,
        ]
    } else {
        let s = 2.0 * (1.0 + m22 - m00 - m11).sqrt(); // 4·qz
        [
            (m(0, 2) + m(2, 0)) / s,
            (m(1, 2) + m(2, 1)) / s,
            0.25 * s,
            (m(1, 0) - m(0, 1)) / s,
        ]
    };
    canonical(q)
}

/// Normalizes `q` and fixes its sign as documented on [`quat_from_axes`].
fn canonical(q: [f64; 4]) -> [f64; 4] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut q = q.map(|x| x / n);
    let lead = if q[3] != 0.0 {
        q[3]
    } else {
        q.iter().copied().find(|&x| x != 0.0).unwrap_or(1.0)
    };
    if lead < 0.0 {
        q = q.map(|x| -x);
    }
    q.map(|x| x + 0.0) // no negative zeros in the output
}

/// The axes (columns of the rotation matrix) of quaternion `[qx, qy, qz, qw]`;
/// `q` is normalized first, so slightly non-unit input is fine.
pub fn axes_from_quat(q: [f64; 4]) -> [[f64; 3]; 3] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [x, y, z, w] = q.map(|c| c / n);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + z * w),
            2.0 * (x * z - y * w),
        ],
        [
            2.0 * (x * y - z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + x * w),
        ],
        [
            2.0 * (x * z + y * w),
            2.0 * (y * z - x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// A uniformly random rotation's axes (tests only).
#[cfg(test)]
pub fn random_axes(rng: &mut rand_chacha::ChaCha8Rng) -> [super::V3; 3] {
    axes_from_quat(tests::random_quat(rng))
}

#[cfg(test)]
pub mod tests {
    use super::*;
    use crate::vec3::{cross, dot};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    pub(crate) fn random_quat(rng: &mut ChaCha8Rng) -> [f64; 4] {
        loop {
            let q: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let n2: f64 = q.iter().map(|x| x * x).sum();
            if n2 > 1e-4 && n2 <= 1.0 {
                return canonical(q);
            }
        }
    }

    pub(crate) fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn quaternion_round_trip_random() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..10_000 {
            let q = random_quat(&mut rng);
            let axes = axes_from_quat(q);
            for a in axes {
                assert!((dot(a, a) - 1.0).abs() < 1e-12);
            }
            assert!(close(&cross(axes[0], axes[1]), &axes[2], 1e-12));
            let back = quat_from_axes(&axes);
            assert!(close(&back, &q, 1e-12), "{q:?} -> {back:?}");
            let axes2 = axes_from_quat(back);
            for k in 0..3 {
                assert!(close(&axes2[k], &axes[k], 1e-12));
            }
        }
    }

    #[test]
    fn quaternion_special_cases_and_sign() {
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(quat_from_axes(&id), [0.0, 0.0, 0.0, 1.0]);
        // 180° about x: qw = 0, first nonzero positive.
        let rx = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]];
        assert_eq!(quat_from_axes(&rx), [1.0, 0.0, 0.0, 0.0]);
        // 180° about (0, 1, -1)/√2.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q = [0.0, h, -h, 0.0];
        let got = quat_from_axes(&axes_from_quat([0.0, -h, h, 0.0]));
        assert!(close(&got, &q, 1e-15) && got[1] > 0.0, "{got:?}");
        // 90° about z: local x maps to world y.
        let rz = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(close(&quat_from_axes(&rz), &[0.0, 0.0, h, h], 1e-15));
    }
}
