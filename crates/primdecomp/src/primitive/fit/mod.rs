//! Primitive construction from the linear operator (§3.2): the eigenvectors of Q give
//! the axes; each kind's remaining parameters grow to enclose the subsumed points.
//! Every fit streams the points without allocating: one projection pass into the
//! reusable [`FitScratch`], then passes over the local coordinates.

use super::frame::{self, PlaneScratch};
use super::prism::skewed_section;
use super::profile::{fit_profile_sorted, sum_lower_bound, Objective, ProfileScratch};
use super::{Capsule, Cylinder, Frustum, Kind, Obb, Primitive, Prism, Sphere};
use crate::math::{eigen_sym3, fmax, fmin, madd, scale, Sym3, V3};

/// Points as struct-of-arrays slices.
#[derive(Clone, Copy, Debug)]
pub struct Cloud<'a> {
    pub x: &'a [f64],
    pub y: &'a [f64],
    pub z: &'a [f64],
}

impl<'a> Cloud<'a> {
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len()
    }
}

/// Orthonormal right-handed axes (largest eigenvalue first) and the points' bounds along them.
#[derive(Clone, Copy, Debug)]
pub struct AxisBounds {
    pub origin: V3,
    pub axes: [V3; 3],
    pub lo: V3,
    pub hi: V3,
}

/// What the fit may build and how it weighs each kind (§3.3).
#[derive(Clone, Copy, Debug)]
pub struct FitConfig {
    pub weights: [f64; 6],
    pub enabled: [bool; 6],
    /// Smallest half-extent/radius of any primitive (absolute units).
    pub min_half: f64,
    /// Which frames besides Q's eigen-frame a fit tries ([`FrameSearch`]).
    pub frames: FrameSearch,
}

/// Which frames a fit tries besides the eigen-frame of §3.2
/// (docs/decisions/0013-frames-for-degenerate-quadrics.md,
/// docs/decisions/0014-output-fits-turn-about-the-normal.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameSearch {
    /// The eigen-frame alone, as §3.2 (single faces when they price merges).
    Eigen,
    /// Also the hull-edge frames ([`frame`]) where the eigen-frame is degenerate: two
    /// eigenvalues tie or the cluster is coplanar (merge pricing).
    Degenerate,
    /// Also the hull-edge frames turned about the normal axis (the largest eigenvalue's)
    /// for every cluster: the output fits, where a nearly flat cluster's in-plane axes
    /// would otherwise come from the tangent term alone (what `Thorough` starts with;
    /// the tests compare the two).
    #[cfg(test)]
    Always,
    /// The hull-edge frames turned about the normal axis for every cluster, then those turned about the other two
    /// eigen-axes and the input's own axes (output fits,
    /// docs/decisions/0021-thorough-output-frame-search.md): a tilted
    /// cluster of a vehicle's cab gets a box that follows its roof, not Q's axes.
    Thorough,
}

/// Reusable buffers: the points' coordinates in the OBB frame (centred on the OBB).
#[derive(Clone, Debug, Default)]
pub struct FitScratch {
    u: [Vec<f64>; 3],
    /// Point indices sorted along each axis, shared by the frustum and the prisms.
    order: [Vec<u32>; 3],
    /// Whether `order[k]` is sorted for the current points.
    sorted: [bool; 3],
    profile: ProfileScratch,
    plane: PlaneScratch,
    /// The points' extent along each axis of the last frame fitted.
    span: [f64; 3],
    /// The same in Q's eigen-frame, the first frame [`fit_best`] fits (flatness test).
    eigen_span: [f64; 3],
    /// The frames of [`FrameSearch::Thorough`] ([`thorough_frames`]), reused.
    frames: Vec<[V3; 3]>,
}

impl FitScratch {
    /// Whether the points of the last [`fit_best`] were coplanar up to round-off
    /// ([`frame::flat`] on their extents in Q's eigen-frame).
    pub fn was_flat(&self) -> bool {
        frame::flat(self.eigen_span)
    }

    /// Sorts the point indices along axis `k` once per fit, for the profile fits.
    fn sort_axis(&mut self, k: usize) {
        if self.sorted[k] {
            return;
        }
        let (u, o) = (&self.u[k], &mut self.order[k]);
        o.clear();
        o.extend(0..u.len() as u32);
        o.sort_unstable_by(|&a, &b| u[a as usize].total_cmp(&u[b as usize]));
        self.sorted[k] = true;
    }
}

/// The chosen primitive, its volume and its weighted cost k(kind)·V.
#[derive(Clone, Copy, Debug)]
pub struct Fit {
    pub prim: Primitive,
    pub volume: f64,
    pub cost: f64,
}

/// Fits every enabled kind around the eigen-frame of `q` and keeps the cheapest k·V.
/// Where two eigenvalues of `q` tie, the frames aligned with the cluster's hull edges
/// in the tied plane are tried instead (see [`frame`]).
///
/// Kinds whose cheap lower bound on k·V already loses to the best offer so far are
/// skipped without being fitted (capsules, frustum, prisms): the result is the same
/// as fitting all of them, since a skipped fit could not have won (see `lower bounds`
/// below and docs/decisions/perf-fit-pruning-and-profile-bounds.md).
pub fn fit_best(cloud: &Cloud, q: &Sym3, cfg: &FitConfig, s: &mut FitScratch) -> Fit {
    fit_best_frame(cloud, q, cfg, s).0
}

/// [`fit_best`] and the frame its fit was made in: refitting another cloud with the
/// same extreme points in that frame ([`fit_frame`]) gives the same primitive.
pub fn fit_best_frame(
    cloud: &Cloud,
    q: &Sym3,
    cfg: &FitConfig,
    s: &mut FitScratch,
) -> (Fit, [V3; 3]) {
    let eig = eigen_sym3(q);
    let axes = eig.vectors;
    let mut best = (fit_in_frame(cloud, axes, cfg, s, None), axes);
    s.eigen_span = s.span;
    let tied = frame::tied_plane(&eig.values);
    let plane = match cfg.frames {
        FrameSearch::Eigen => None,
        FrameSearch::Degenerate => tied.or_else(|| frame::flat(s.span).then_some((1, 2))),
        #[cfg(test)]
        FrameSearch::Always => tied.or(Some((1, 2))),
        FrameSearch::Thorough => {
            // Every plane's turned frames, then the input's own axes
            // (docs/decisions/0021-thorough-output-frame-search.md).
            let mut frames = std::mem::take(&mut s.frames);
            thorough_frames(cloud, q, s, &mut frames);
            for &f in &frames[1..] {
                best = keep_better(cloud, f, cfg, s, best);
            }
            s.frames = frames;
            return best;
        }
    };
    let Some(plane) = plane else {
        return best;
    };
    turned_fits(cloud, axes, plane, cfg, s, best)
}

/// The frames [`FrameSearch::Thorough`] tries, in the order [`fit_best_frame`] tries
/// them: Q's eigen-frame, the hull-edge frames turned in the tied (else the (1, 2))
/// eigen-plane, then in the two other planes, then the input's axes.
pub fn thorough_frames(cloud: &Cloud, q: &Sym3, s: &mut FitScratch, out: &mut Vec<[V3; 3]>) {
    out.clear();
    let eig = eigen_sym3(q);
    let axes = eig.vectors;
    out.push(axes);
    let first = frame::tied_plane(&eig.values).unwrap_or((1, 2));
    let others = [(0, 1), (0, 2), (1, 2)].into_iter().filter(|&p| p != first);
    for plane in std::iter::once(first).chain(others) {
        let (e0, e1) = (axes[plane.0], axes[plane.1]);
        let dirs = frame::edge_directions(cloud.x, cloud.y, cloud.z, e0, e1, &mut s.plane);
        for k in 0..dirs {
            out.push(frame::turn(axes, plane, frame::direction(&s.plane, k)));
        }
    }
    out.push(WORLD_AXES);
}

/// Every enabled kind in the frame `axes` alone: the cheapest.
pub fn fit_frame(cloud: &Cloud, axes: [V3; 3], cfg: &FitConfig, s: &mut FitScratch) -> Fit {
    fit_in_frame(cloud, axes, cfg, s, None)
}

/// The fit in `axes` with its frame if it beats `best` by the margin, else `best`.
fn keep_better(
    cloud: &Cloud,
    axes: [V3; 3],
    cfg: &FitConfig,
    s: &mut FitScratch,
    best: (Fit, [V3; 3]),
) -> (Fit, [V3; 3]) {
    let f = fit_in_frame(cloud, axes, cfg, s, Some(best.0));
    if f.cost < best.0.cost {
        (f, axes)
    } else {
        best
    }
}

/// The input's axes, a frame the fit tries in [`FrameSearch::Thorough`].
const WORLD_AXES: [V3; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The frames along the hull edges of the points projected on `axes[plane]`, each
/// kept when it beats `best` by the margin.
fn turned_fits(
    cloud: &Cloud,
    axes: [V3; 3],
    plane: (usize, usize),
    cfg: &FitConfig,
    s: &mut FitScratch,
    mut best: (Fit, [V3; 3]),
) -> (Fit, [V3; 3]) {
    let (e0, e1) = (axes[plane.0], axes[plane.1]);
    let dirs = frame::edge_directions(cloud.x, cloud.y, cloud.z, e0, e1, &mut s.plane);
    for k in 0..dirs {
        let turned = frame::turn(axes, plane, frame::direction(&s.plane, k));
        best = keep_better(cloud, turned, cfg, s, best);
    }
    best
}

/// Every enabled kind in the frame `axes`; `bar` (the best fit of another frame, if
/// any) is kept unless something here costs less by more than [`frame::MARGIN`]:
/// equal costs keep the earlier frame — the eigen-frame, the paper's — rather than
/// letting round-off choose (two boxes of equal area around a triangle, one along its
/// legs and one along its hypotenuse, stick out of a wall's footprint very differently).
fn fit_in_frame(
    cloud: &Cloud,
    axes: [V3; 3],
    cfg: &FitConfig,
    s: &mut FitScratch,
    bar: Option<Fit>,
) -> Fit {
    let mut best = Candidate::new(cfg, None);
    best.bar = bar.map_or(f64::INFINITY, |b| b.cost * (1.0 - frame::MARGIN));
    offer_all(cloud, axes, s, &mut best);
    match (best.fit, bar) {
        (Some(f), Some(b)) if f.cost >= best.bar => b,
        (f, b) => f.or(b).expect("at least one kind is enabled"),
    }
}

/// A primitive's penalty ([`fit_frame_priced`]), ≥ 0, asked with the primitive's k·V
/// and the score it must stay under: it may stop at a part of its sum once k·V plus
/// that part reaches the score (the whole, no less, cannot win either).
pub type Penalty<'a> = &'a dyn Fn(&Primitive, f64, f64) -> f64;

/// The enabled kind in the frame `axes` with the least k·V + `penalty(primitive)`
/// (`penalty` ≥ 0, so the kinds' lower bounds on k·V still prune), with that score;
/// `None` unless the score is below `bar`. One projection of the points serves every
/// kind. The output fit prices its rim and outward reaches this way (`merge::cost`).
pub fn fit_frame_priced(
    cloud: &Cloud,
    axes: [V3; 3],
    cfg: &FitConfig,
    s: &mut FitScratch,
    penalty: Penalty,
    bar: f64,
) -> Option<(Fit, f64)> {
    let mut best = Candidate::new(cfg, Some(penalty));
    best.bar = bar;
    offer_all(cloud, axes, s, &mut best);
    best.fit
        .filter(|_| best.score < bar)
        .map(|f| (f, best.score))
}

/// Offers every enabled kind fitted in the frame `axes` to `best`.
fn offer_all(cloud: &Cloud, axes: [V3; 3], s: &mut FitScratch, best: &mut Candidate) {
    let cfg = best.cfg;
    let (frame, obb) = centred(cloud, axes, cfg.min_half, s);
    best.offer(Kind::Box, Primitive::Box(obb), obb.volume());
    let ext = Extents::of(s);
    if cfg.enabled[Kind::Sphere as usize] {
        let sph = Sphere {
            center: obb.center,
            radius: ext.r2.sqrt().max(cfg.min_half),
        };
        best.offer(Kind::Sphere, Primitive::Sphere(sph), sph.volume());
    }
    let r2 = ext.radial2;
    let radial = [r2[0].sqrt(), r2[1].sqrt(), r2[2].sqrt()];
    let cyl = |k| fit_cylinder(&obb, &radial, k, cfg.min_half);
    let cyls = [cyl(0), cyl(1), cyl(2)];
    let cyl_volumes = [cyls[0].volume(), cyls[1].volume(), cyls[2].volume()];
    let best_cyl = (0..3)
        .min_by(|&a, &b| cyl_volumes[a].total_cmp(&cyl_volumes[b]))
        .unwrap_or(0);
    if cfg.enabled[Kind::Cylinder as usize] {
        best.offer(
            Kind::Cylinder,
            Primitive::Cylinder(cyls[best_cyl]),
            cyl_volumes[best_cyl],
        );
    }
    if cfg.enabled[Kind::Capsule as usize] {
        for k in 0..3 {
            let extent = frame.hi[k] - frame.lo[k];
            if best.beats(
                Kind::Capsule,
                capsule_bound(radial[k], extent, cfg.min_half),
            ) {
                continue;
            }
            let c = fit_capsule(s, &obb, radial[k], k, cfg.min_half);
            best.offer(Kind::Capsule, Primitive::Capsule(c), c.volume());
        }
    }
    offer_profiles(s, &obb, &ext, best_cyl, best);
}

/// The points in the frame `axes`, their bounds and their box; the scratch holds
/// their coordinates relative to the box's centre (§3.2: other primitives start
/// there), none sorted yet.
fn centred(cloud: &Cloud, axes: [V3; 3], min_half: f64, s: &mut FitScratch) -> (AxisBounds, Obb) {
    let frame = project(cloud, axes, s);
    // Explicit 3-element arrays, not `array::map`: its `try_map` is not always inlined
    // (docs/decisions/perf-fit-loop.md).
    let (lo, hi) = (frame.lo, frame.hi);
    s.span = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let obb = Obb::from_frame(&frame, min_half);
    let mid = [
        0.5 * (lo[0] + hi[0]),
        0.5 * (lo[1] + hi[1]),
        0.5 * (lo[2] + hi[2]),
    ];
    for k in 0..3 {
        s.u[k].iter_mut().for_each(|v| *v -= mid[k]);
    }
    s.sorted = [false; 3];
    (frame, obb)
}

/// The least-volume skewed prism of the 6 orderings in the frame `axes`: the
/// section's two slanted sides fitted each on its own, not mirrored ([`skewed_section`];
/// a triangle in the y–z plane is then its own section). For the cut's nearest fits
/// only (docs/decisions/0045-skewed-prisms-where-the-cut-cannot-split.md); `None`
/// without points.
pub fn fit_skewed_prism(
    cloud: &Cloud,
    axes: [V3; 3],
    min_half: f64,
    s: &mut FitScratch,
) -> Option<Prism> {
    if cloud.len() == 0 {
        return None;
    }
    let (_, obb) = centred(cloud, axes, min_half, s);
    let mut best: Option<Prism> = None;
    for [x, y, z] in ORDERINGS {
        s.sort_axis(y);
        let hy = obb.half[y];
        let Some(sec) = skewed_section(&s.u[y], &s.u[z], &s.order[y], hy, &mut s.profile) else {
            continue;
        };
        // A flipped z flips the shift with it.
        let (axes, sign) = prism_axes(obb.axes, [x, y, z]);
        let p = Prism {
            center: madd(obb.center, obb.axes[z], sec.middle),
            axes,
            hx: obb.half[x],
            hy,
            hz_top: sec.top.max(min_half),
            hz_bottom: sec.bottom.max(min_half),
            shift: sign * sec.shift,
        };
        if best.is_none_or(|b| p.volume() < b.volume()) {
            best = Some(p);
        }
    }
    best
}

/// The frustum on the best cylinder's axis and the prisms of the 6 orderings, each
/// fitted only when its lower bound does not already lose: first the bound from the
/// [`Extents`], then the tight one ([`sum_lower_bound`], a few linear passes), and
/// only then the sort and hull of the exact fit.
fn offer_profiles(
    s: &mut FitScratch,
    obb: &Obb,
    ext: &Extents,
    best_cyl: usize,
    best: &mut Candidate,
) {
    let cfg = best.cfg;
    let k = best_cyl;
    let frustum = |m: f64| frustum_volume_bound(obb.half[k], m, cfg.min_half);
    let loses = |m: f64| best.beats(Kind::Frustum, frustum(m));
    if cfg.enabled[Kind::Frustum as usize]
        && !loses(ext.frustum_sum(k))
        && !loses(frustum_sum_tight(s, obb, k, loses))
    {
        s.sort_axis(k);
        let f = fit_frustum(s, obb, k, cfg.min_half);
        best.offer(Kind::Frustum, Primitive::Frustum(f), f.volume());
    }
    if cfg.enabled[Kind::Prism as usize] {
        for order in ORDERINGS {
            let [x, y, z] = order;
            let prism = |m: f64| prism_volume_bound(obb.half[x], obb.half[y], m, cfg.min_half);
            let loses = |m: f64| best.beats(Kind::Prism, prism(m));
            if loses(sum_bound(ext.side[y][z])) || loses(prism_sum_tight(s, obb, y, z, loses)) {
                continue;
            }
            s.sort_axis(y);
            let p = fit_prism(s, obb, order, cfg.min_half);
            best.offer(Kind::Prism, Primitive::Prism(p), p.volume());
        }
    }
}

/// Frustum of half-length `h` whose profile has `l0 + l1 ≥ m` before both ends are
/// clamped up to `min_half`: the clamped ends sum to at least `M = max(m, 2·min_half)`
/// and `l0² + l0·l1 + l1² ≥ ¾(l0 + l1)²`, so V = ⅔π·h·(…) ≥ π·h·M²/2.
fn frustum_volume_bound(h: f64, m: f64, min_half: f64) -> f64 {
    let m = m.max(2.0 * min_half);
    0.5 * std::f64::consts::PI * h * m * m
}

/// Prism with half-extents `hx`, `hy` whose half-widths (before the clamp to
/// `min_half`) sum to at least `m`: V = 4·hx·hy·(a + b) ≥ 4·hx·hy·max(m, 2·min_half).
fn prism_volume_bound(hx: f64, hy: f64, m: f64, min_half: f64) -> f64 {
    4.0 * hx * hy * m.max(2.0 * min_half)
}

/// Lower bound on a capsule's volume around an axis: radius `r` (as fitted), and a
/// segment at least as long as the points' extent minus the two end caps.
fn capsule_bound(radial: f64, extent: f64, min_half: f64) -> f64 {
    let r = radial.max(min_half);
    std::f64::consts::PI * r * r * ((extent - 2.0 * r).max(0.0) + 4.0 / 3.0 * r)
}

/// Squared extents of the centred points gathered in one pass: the sphere's and each
/// axis' radial reach, and for the profile bounds, per axis `y` and side of `y = 0`
/// (0: `u_y ≥ 0`, 1: `u_y < 0`), the largest `u_z²` for each other axis `z` and the
/// largest radial reach around `y`.
struct Extents {
    r2: f64,
    radial2: [f64; 3],
    /// `side[y][z]`, `z ≠ y` (the diagonal stays 0: no bound uses it).
    side: [[[f64; 2]; 3]; 3],
    side_radial2: [[f64; 2]; 3],
}

impl Extents {
    /// Branchless: each side's maxima take the point's value or 0 (every value is a
    /// square or a sum of squares, ≥ +0, and every maximum starts at +0, so a 0 leaves
    /// it unchanged), in registers, where indexing by the side kept them in memory.
    /// The same maxima as testing the side per point: max is exact and ignores order.
    fn of(s: &FitScratch) -> Extents {
        let [u0, u1, u2] = &s.u;
        let n = u0.len();
        let (u1, u2) = (&u1[..n], &u2[..n]);
        // Per axis y, on the side u_y ≥ 0 (`pos`) and u_y < 0 (`neg`): the maxima of
        // (radial reach around y, u_z² for the next axis z, for the one after).
        let mut pos = [[0.0f64; 3]; 3];
        let mut neg = [[0.0f64; 3]; 3];
        let mut r2 = 0.0;
        for i in 0..n {
            let u = [u0[i], u1[i], u2[i]];
            let sq = [u[0] * u[0], u[1] * u[1], u[2] * u[2]];
            r2 = fmax(r2, sq[0] + sq[1] + sq[2]);
            let radial = [sq[1] + sq[2], sq[0] + sq[2], sq[0] + sq[1]];
            for y in 0..3 {
                let v = [radial[y], sq[(y + 1) % 3], sq[(y + 2) % 3]];
                let below = u[y] < 0.0;
                for j in 0..3 {
                    let (p, m) = if below { (0.0, v[j]) } else { (v[j], 0.0) };
                    pos[y][j] = fmax(pos[y][j], p);
                    neg[y][j] = fmax(neg[y][j], m);
                }
            }
        }
        let mut e = Extents {
            r2,
            radial2: [0.0; 3],
            side: [[[0.0; 2]; 3]; 3],
            side_radial2: [[0.0; 2]; 3],
        };
        for y in 0..3 {
            e.side_radial2[y] = [pos[y][0], neg[y][0]];
            e.radial2[y] = fmax(pos[y][0], neg[y][0]);
            e.side[y][(y + 1) % 3] = [pos[y][1], neg[y][1]];
            e.side[y][(y + 2) % 3] = [pos[y][2], neg[y][2]];
        }
        e
    }

    /// Lower bound on the `l0 + l1` of the frustum on axis `k` (see [`sum_bound`]).
    fn frustum_sum(&self, k: usize) -> f64 {
        sum_bound(self.side_radial2[k])
    }
}

/// The least `l0 + l1` of any line over the radial profile on axis `k` (up to
/// round-off; [`sum_lower_bound`]), a lower bound on the fitted frustum's.
fn frustum_sum_tight(s: &FitScratch, obb: &Obb, k: usize, enough: impl Fn(f64) -> bool) -> f64 {
    let (ub, uc) = (&s.u[(k + 1) % 3], &s.u[(k + 2) % 3]);
    let radial = |i: usize| (ub[i] * ub[i] + uc[i] * uc[i]).sqrt();
    sum_lower_bound(&s.u[k], radial, obb.half[k], enough)
}

/// Exact (up to round-off) `hz_top + hz_bottom` of the prism with trapezoid height
/// axis `y` and width axis `z`, before the clamp ([`sum_lower_bound`]).
fn prism_sum_tight(
    s: &FitScratch,
    obb: &Obb,
    y: usize,
    z: usize,
    enough: impl Fn(f64) -> bool,
) -> f64 {
    let uz = &s.u[z];
    sum_lower_bound(&s.u[y], |i| uz[i].abs(), obb.half[y], enough)
}

/// Lower bound on `l0 + l1` for any enclosing linear profile `l(s)` over points whose
/// largest squared heights are `sq[0]` for `s ≥ ½` and `sq[1]` for `s < ½`. A line
/// over a point of height `z` has `l0 + l1 ≥ z` (both ends non-negative), and
/// `l0 + l1 = 2·l(½)`, where a line above a point on each side of `½` passes above
/// the lower of the two.
fn sum_bound(sq: [f64; 2]) -> f64 {
    let (r, l) = (sq[0].sqrt(), sq[1].sqrt());
    r.max(l).max(2.0 * r.min(l))
}

/// Keeps the lowest weighted cost among the offers of enabled kinds; ties keep the first.
/// `bar` is the cost another frame's fit already reached (less the margin): kinds whose
/// lower bound cannot beat it are not fitted.
struct Candidate<'a> {
    cfg: &'a FitConfig,
    fit: Option<Fit>,
    bar: f64,
    /// Added to each offer's k·V when comparing ([`fit_frame_priced`]); `None` = 0.
    penalty: Option<Penalty<'a>>,
    /// The best offer's k·V plus its penalty.
    score: f64,
}

impl<'a> Candidate<'a> {
    fn new(cfg: &'a FitConfig, penalty: Option<Penalty<'a>>) -> Self {
        Candidate {
            cfg,
            fit: None,
            bar: f64::INFINITY,
            penalty,
            score: f64::INFINITY,
        }
    }
    /// True when a primitive of `kind` with volume at least `bound` cannot win: the
    /// bound, shrunk by a margin far above round-off, still costs more than the best.
    fn beats(&self, kind: Kind, bound: f64) -> bool {
        #[cfg(test)]
        if tests::NO_PRUNING.get() {
            return false;
        }
        let w = self.cfg.weights[kind as usize];
        w * bound * (1.0 - 1e-9) > self.score.min(self.bar)
    }
    fn offer(&mut self, kind: Kind, prim: Primitive, volume: f64) {
        if !self.cfg.enabled[kind as usize] {
            return;
        }
        let cost = self.cfg.weights[kind as usize] * volume;
        // The penalty is ≥ 0: an offer whose k·V alone does not beat the best's score
        // cannot win, whatever its penalty.
        if self.fit.is_some() && cost >= self.score {
            return;
        }
        let score = match self.penalty {
            None => cost,
            Some(p) => {
                // A priced offer at or over the bar never leaves `fit_frame_priced`,
                // which keeps a best under it only; dropping it leaves the best under
                // the bar, and `beats`, as they were. Its penalty, and one over the best
                // so far, may stop short: it cannot win.
                let score = cost + p(&prim, cost, self.score.min(self.bar));
                if score >= self.bar {
                    return;
                }
                score
            }
        };
        if self.fit.is_none() || score < self.score {
            self.fit = Some(Fit { prim, volume, cost });
            self.score = score;
        }
    }
}

/// One pass: coordinates along the axes into the scratch, with their bounds.
fn project(cloud: &Cloud, axes: [V3; 3], s: &mut FitScratch) -> AxisBounds {
    let n = cloud.len();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for k in 0..3 {
        let a = axes[k];
        let u = &mut s.u[k];
        u.clear();
        let xyz = cloud.x.iter().zip(cloud.y).zip(cloud.z);
        u.extend(xyz.map(|((x, y), z)| a[0] * x + a[1] * y + a[2] * z));
        for &v in u.iter() {
            lo[k] = fmin(lo[k], v);
            hi[k] = fmax(hi[k], v);
        }
        if n == 0 {
            (lo[k], hi[k]) = (0.0, 0.0);
        }
    }
    AxisBounds {
        origin: [0.0; 3],
        axes,
        lo,
        hi,
    }
}

/// Axis `k` of the frame, signed so that its largest component is positive: the
/// p0→p1 direction of a round primitive must not depend on which way round-off turned
/// a degenerate eigenvector (for a pipe, the two in-plane eigenvalues tie).
fn canonical_axis(obb: &Obb, k: usize) -> (V3, f64) {
    let a = obb.axes[k];
    let big = (0..3).fold(0, |m, i| if a[i].abs() > a[m].abs() { i } else { m });
    if a[big] < 0.0 {
        (scale(a, -1.0), -1.0)
    } else {
        (a, 1.0)
    }
}

/// §3.2 "Capped Cylinders" along axis `k`: the points' axial extent is the OBB's.
fn fit_cylinder(obb: &Obb, radial: &[f64; 3], k: usize, min_half: f64) -> Cylinder {
    let (a, _) = canonical_axis(obb, k);
    let h = obb.half[k];
    Cylinder {
        p0: madd(obb.center, a, -h),
        p1: madd(obb.center, a, h),
        radius: radial[k].max(min_half),
    }
}

/// §3.2 "Capsules" along axis `k`: radius as the cylinder's; each point bounds the
/// segment's ends by how far its ball section reaches along the axis.
fn fit_capsule(s: &FitScratch, obb: &Obb, radial: f64, k: usize, min_half: f64) -> Capsule {
    let r = radial.max(min_half);
    let r2 = r * r;
    let (ua, ub, uc) = (&s.u[k], &s.u[(k + 1) % 3], &s.u[(k + 2) % 3]);
    let (mut top, mut bottom) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..ua.len() {
        let reach = fmax(r2 - ub[i] * ub[i] - uc[i] * uc[i], 0.0).sqrt();
        top = fmax(top, ua[i] - reach);
        bottom = fmin(bottom, ua[i] + reach);
    }
    if ua.is_empty() {
        (top, bottom) = (0.0, 0.0);
    }
    if bottom > top {
        // Every point fits in one ball: a zero-length segment at the middle.
        let mid = 0.5 * (top + bottom);
        (top, bottom) = (mid, mid);
    }
    // `top` and `bottom` are along the frame's axis; p0→p1 must run along the
    // canonical one, so the ends swap where the two point opposite ways.
    let (a, sign) = canonical_axis(obb, k);
    let (first, last) = if sign > 0.0 {
        (bottom, top)
    } else {
        (top, bottom)
    };
    Capsule {
        p0: madd(obb.center, a, sign * first),
        p1: madd(obb.center, a, sign * last),
        radius: r,
    }
}

/// §3.2 "Frustum" on the best cylinder's axis `k`: exact profile fit (see `profile`).
fn fit_frustum(s: &mut FitScratch, obb: &Obb, k: usize, min_half: f64) -> Frustum {
    let h = obb.half[k];
    let (ua, ub, uc) = (&s.u[k], &s.u[(k + 1) % 3], &s.u[(k + 2) % 3]);
    let pt = |i: usize| {
        let sa = ((ua[i] + h) / (2.0 * h)).clamp(0.0, 1.0);
        (sa, (ub[i] * ub[i] + uc[i] * uc[i]).sqrt())
    };
    let (r0, r1) = fit_profile_sorted(&s.order[k], pt, Objective::Cone, &mut s.profile);
    let (a, sign) = canonical_axis(obb, k);
    let (r0, r1) = if sign > 0.0 { (r0, r1) } else { (r1, r0) };
    // The profile encloses the points in the frame's coordinates; `on_axis` keeps that
    // true of the two rounded end points it stores, whose tilt the slope amplifies.
    Frustum::on_axis(obb.center, a, h, r0.max(min_half), r1.max(min_half))
}

/// The 6 orderings (x = extrusion, y = trapezoid height, z = trapezoid width) of Alg. 3.
const ORDERINGS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// The prism frame of the ordering `[x, y, z]` of `axes` (x = extrusion, y = height,
/// z = width), right-handed: odd permutations flip z; with the sign z was given.
fn prism_axes(axes: [V3; 3], [x, y, z]: [usize; 3]) -> ([V3; 3], f64) {
    let even = matches!([x, y, z], [0, 1, 2] | [1, 2, 0] | [2, 0, 1]);
    let sign = if even { 1.0 } else { -1.0 };
    ([axes[x], axes[y], scale(axes[z], sign)], sign)
}

/// §3.2 "Isosceles Trapezoidal Prisms" for one axis ordering.
fn fit_prism(s: &mut FitScratch, obb: &Obb, [x, y, z]: [usize; 3], min_half: f64) -> Prism {
    let hy = obb.half[y];
    let (uy, uz) = (&s.u[y], &s.u[z]);
    let pt = |i: usize| (((uy[i] + hy) / (2.0 * hy)).clamp(0.0, 1.0), uz[i].abs());
    let (b, a) = fit_profile_sorted(&s.order[y], pt, Objective::Sum, &mut s.profile);
    // z enters only through |z|, so its flip changes nothing.
    let (axes, _) = prism_axes(obb.axes, [x, y, z]);
    Prism {
        center: obb.center,
        axes,
        hx: obb.half[x],
        hy,
        hz_top: a.max(min_half),
        hz_bottom: b.max(min_half),
        shift: 0.0,
    }
}

#[cfg(test)]
mod tests;
