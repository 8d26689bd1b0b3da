//! The default view shared by the page and the PNG: a three-quarter view from the
//! front right, above, fitted so the scene fills most of the frame. The page's
//! script repeats the fit (`fitCamera` in assets/scene.js) for its panes' aspect.

/// Vertical field of view, degrees.
pub const FOV_Y_DEG: f64 = 30.0;
/// Azimuth from the front towards the right and elevation above the horizon, degrees.
pub const AZIMUTH_DEG: f64 = 35.0;
pub const ELEVATION_DEG: f64 = 25.0;
/// Share of the frame's half-width and half-height the scene may fill.
pub const FILL: f64 = 0.92;
/// Rounds of centring the scene's projection in the frame.
pub const CENTRING_ROUNDS: usize = 4;

/// A perspective camera looking from `eye` at `target`, `up` the world's up axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub up: [f64; 3],
    pub fov_y_deg: f64,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// Min and max corner of `points`, if any.
pub fn bounds(points: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let first = *points.first()?;
    Some(points.iter().fold((first, first), |(lo, hi), p| {
        (
            [0, 1, 2].map(|d| lo[d].min(p[d])),
            [0, 1, 2].map(|d| hi[d].max(p[d])),
        )
    }))
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    a.map(|x| x / l)
}

impl Camera {
    /// The three-quarter view of `points` with world up along axis `up_axis` (1 = y,
    /// 2 = z; y-up scenes face +z, z-up scenes face −y), for an image of width/height
    /// `aspect`: the camera looks at the points' projected centre from as near as
    /// keeps every point within [`FILL`] of the frame. `None` without points.
    pub fn three_quarter(points: &[[f64; 3]], up_axis: usize, aspect: f64) -> Option<Camera> {
        let (lo, hi) = bounds(points)?;
        let (az, el) = (AZIMUTH_DEG.to_radians(), ELEVATION_DEG.to_radians());
        let (side, front, high) = (az.sin() * el.cos(), az.cos() * el.cos(), el.sin());
        let (dir, up) = if up_axis == 2 {
            ([side, -front, high], [0.0, 0.0, 1.0])
        } else {
            ([side, high, front], [0.0, 1.0, 0.0])
        };
        let mut target = [0, 1, 2].map(|d| 0.5 * (lo[d] + hi[d]));
        let mut cam = Camera {
            eye: target,
            target,
            up,
            fov_y_deg: FOV_Y_DEG,
        };
        let (right, cup, back) = cam.basis_for(dir);
        let ty = (0.5 * FOV_Y_DEG.to_radians()).tan() * FILL;
        let tx = ty * aspect.max(1e-3);
        // A point or a flat box: still a camera in front of it.
        let diag = dot(sub(hi, lo), sub(hi, lo)).sqrt();
        let floor = (1e-3 * diag).max(f64::MIN_POSITIVE.sqrt());
        let fit = |target: [f64; 3]| {
            let mut dist = floor;
            for &p in points {
                let r = sub(p, target);
                let (x, y, z) = (dot(r, right), dot(r, cup), dot(r, back));
                dist = dist.max(z + x.abs() / tx).max(z + y.abs() / ty);
            }
            dist
        };
        // Centre the points' projection and fit again from the new target, a few
        // rounds (perspective moves the centre a little each time).
        let mut dist = fit(target);
        for _ in 0..CENTRING_ROUNDS {
            let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for &p in points {
                let r = sub(p, target);
                let depth = dist - dot(r, back);
                let (x, y) = (dot(r, right) / depth / tx, dot(r, cup) / depth / ty);
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
            let (sx, sy) = (0.5 * (x0 + x1) * tx * dist, 0.5 * (y0 + y1) * ty * dist);
            target = [0, 1, 2].map(|d| target[d] + sx * right[d] + sy * cup[d]);
            dist = fit(target);
        }
        cam.target = target;
        cam.eye = [0, 1, 2].map(|d| target[d] + dist * back[d]);
        Some(cam)
    }

    /// Unit right, up and backward (from the target to the eye) vectors.
    pub fn basis(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        self.basis_for(sub(self.eye, self.target))
    }

    fn basis_for(&self, dir: [f64; 3]) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let back = unit(dir);
        let mut right = cross(self.up, back);
        if dot(right, right) < 1e-24 {
            right = cross([1.0, 0.0, 0.0], back);
        }
        let right = unit(right);
        (right, cross(back, right), back)
    }

    /// Distance from the eye to the target.
    pub fn distance(&self) -> f64 {
        let d = sub(self.eye, self.target);
        dot(d, d).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_points_fill_the_frame_centred_seen_from_front_right_above() {
        let (lo, hi) = ([-1.0, 0.0, -2.0], [3.0, 1.0, 2.0]);
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|i| [0, 1, 2].map(|d| if i >> d & 1 == 1 { hi[d] } else { lo[d] }))
            .collect();
        for aspect in [1.0, 0.5, 2.0] {
            let cam = Camera::three_quarter(&corners, 1, aspect).unwrap();
            let (right, up, back) = cam.basis();
            assert!(back[0] > 0.0 && back[1] > 0.0 && back[2] > 0.0, "{back:?}");
            let t = (0.5 * FOV_Y_DEG.to_radians()).tan();
            let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for &c in &corners {
                let r = sub(c, cam.eye);
                let depth = -dot(r, back);
                let (x, y) = (dot(r, right) / depth / (t * aspect), dot(r, up) / depth / t);
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
            let widest = x1.max(-x0).max(y1).max(-y0);
            assert!(widest <= FILL + 1e-9, "inside the frame: {widest}");
            assert!(widest >= FILL - 0.02, "tight: {widest}");
            assert!(
                (x0 + x1).abs() < 0.05 && (y0 + y1).abs() < 0.05,
                "centred: {x0} {x1} {y0} {y1}"
            );
        }
        let z = Camera::three_quarter(&corners, 2, 1.0).unwrap();
        let (_, _, back) = z.basis();
        assert!(back[0] > 0.0 && back[1] < 0.0 && back[2] > 0.0, "{back:?}");
        assert_eq!(Camera::three_quarter(&[], 1, 1.0), None);
    }
}
