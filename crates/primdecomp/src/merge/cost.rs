//! Collapse cost (§3.3, Eq. 1 with the per-kind weights): for clusters p0, p1,
//! C = k(kind)·V(merge(p0, p1)) − (V(p0) + V(p1)), where merge fits every enabled kind
//! to the union of their points around the eigen-frame of Q0 + Q1.

use super::cluster::Clusters;
use super::heap::Candidate;
use super::rim::{clamp_to_points, rim_penalty, FaceAdjacency, Rim, Surroundings};
use crate::input::dedup::{Corners, Weld};
use crate::input::mesh::outward_normal;
use crate::input::mesh::Mesh;
use crate::input::solid::Solid;
use crate::math::hull::{hull_vertices_checked, HullWorkspace};
use crate::math::marks::distinct_increasing;
use crate::math::Sym3;
use crate::math::{dot, V3};
use crate::primitive::fit::{
    fit_best_frame, fit_frame, fit_frame_priced, Fit, FitConfig, FrameSearch,
};
use crate::primitive::fit::{fit_skewed_prism, thorough_frames};
use crate::primitive::{fit_best, frame, Cloud, FitScratch, Kind, Primitive};
use crate::progress::Ask;

/// Faces whose outward normal is within about 0.8° of a plate's axis face along it
/// ([`Fitter::flush`]): a flat cluster's faces lie at round-off from it.
const PARALLEL: f64 = 0.9999;

/// Faces gathered, searched for rims or laid flush between two asks of a checked
/// output fit (milliseconds of work).
const FACES_PER_ASK: usize = 1 << 16;

/// Faces of an output fit, at least, whose sorted list is marked in checked blocks
/// instead of sorted in one step.
const MARKED_FROM: usize = 1 << 18;

/// Per-thread reusable buffers: the gathered points and the fit's scratch.
#[derive(Debug, Default)]
pub struct Workspace {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    fit: FitScratch,
    /// The output fit's frame search runs on the points' hull vertices
    /// (docs/decisions/0021-thorough-output-frame-search.md).
    hull: HullWorkspace,
    keep: Vec<u32>,
    hx: Vec<f64>,
    hy: Vec<f64>,
    hz: Vec<f64>,
    /// The output fit's candidate frames, when the rim reach is priced.
    frames: Vec<[V3; 3]>,
    /// The output cluster's faces, sorted, and its rims (`Plates::rim_weight`).
    members: Vec<u32>,
    rims: Vec<Rim>,
}

impl Workspace {
    fn clear(&mut self) {
        self.x.clear();
        self.y.clear();
        self.z.clear();
    }
}

/// What pricing a merge needs of one cluster: its root id, points, operator, volume
/// and the merge clock. A copy of these (`merge::worker`) prices like the cluster itself.
#[derive(Clone, Copy, Debug)]
pub struct Side<'s> {
    pub id: u32,
    pub verts: Corners<'s>,
    pub q: Sym3,
    pub volume: f64,
    /// The merge clock when the snapshot was taken (the candidate's time stamp).
    pub t: u32,
}

/// The input as the merge and the stages after it read it: its positions, welded
/// faces, the surface around each face and its interior. Built once per run from the
/// input stages' results (`decompose::stages::Around`); a spatial part prices on its
/// own sub-mesh's view (`merge::partition`).
#[derive(Clone, Copy, Debug)]
pub struct InputView<'a> {
    pub(crate) mesh: &'a Mesh,
    /// Each vertex's weld target: a face's welded corners are its own read through it.
    pub(crate) weld: &'a Weld,
    /// Per face, ±1: the winding that faces outward (`input::orient`); empty = the
    /// faces' own windings (set only when `Plates::rim_weight` > 0 or `flush_plates`).
    pub(crate) face_sign: &'a [i8],
    /// The input's face adjacency, for the output clusters' rims (read only when
    /// `Pricing::rim_weight` > 0); empty = no rims (set when `face_sign` is).
    pub(crate) face_adj: FaceAdjacency<'a>,
    /// The input's interior (`Plates::solid`,
    /// docs/decisions/0023-merges-priced-by-the-air-they-add.md): merges are priced by the
    /// volume their primitive adds outside it; `None` = the paper's whole volume.
    pub(crate) solid: Option<&'a Solid>,
}

impl<'a> InputView<'a> {
    /// The view of `mesh` welded by `weld` alone: no surface, no interior.
    pub fn new(mesh: &'a Mesh, weld: &'a Weld) -> Self {
        InputView {
            mesh,
            weld,
            face_sign: &[],
            face_adj: FaceAdjacency::default(),
            solid: None,
        }
    }
}

/// The settings made absolute for one input (`merge::setup::pricing`): how merges are
/// priced (§3.3), when the merge loop re-prices and merges free, and how output
/// primitives are chosen.
#[derive(Clone, Copy, Debug)]
pub struct Pricing {
    /// The kinds, weights, floor half-extent and frame search of every fit.
    pub(crate) fit: FitConfig,
    /// Largest excess volume one merge may add (absolute); `INFINITY` = no limit.
    pub(crate) max_excess: f64,
    /// Costs are rounded to multiples of this volume (a fixed fraction of the input's
    /// diagonal cubed), so that round-off from units or position cannot reorder merges
    /// whose exact costs tie — coplanar merges cost exactly 0, and there are many.
    pub(crate) cost_unit: f64,
    /// Factor on the cost of a merge whose points are coplanar (≥ 1): such merges are
    /// priced as if primitives were `Plates::open_holes` thick instead of the minimum
    /// extent (area across gaps and holes costs that thickness); 1 = off.
    pub(crate) flat_scale: f64,
    /// Distance below which a point counts as on a hull face (point reduction only).
    pub(crate) hull_eps: f64,
    /// Merges whose clusters' neighbour lists hold at least this many entries are
    /// re-priced lazily (`Params::reprice`); `u32::MAX` = always at once (exact).
    pub(crate) defer_degree: u32,
    /// `Plates::join_coplanar`: free merges into plates run before a target's snapshot
    /// (`merge::driver::free`, docs/decisions/0025).
    pub(crate) free_merges: bool,
    /// `Plates::rim_weight`: the rim reach's weight in the output frame choice
    /// (docs/decisions/0024-output-primitives-priced-by-rim-reach.md).
    pub(crate) rim_weight: f64,
    /// `Plates::flush_plates`: output plates lie flush on their faces
    /// (docs/decisions/0026-output-plates-lie-flush.md).
    pub(crate) flush_plates: bool,
}

/// Fits primitives to clusters of one input and prices their merges: the input's view
/// with the settings made absolute for it. The merge loop, the cut and post-processing
/// fit through it.
#[derive(Clone, Copy, Debug)]
pub struct Fitter<'a> {
    pub(crate) input: InputView<'a>,
    pub(crate) pricing: Pricing,
}

impl<'a> Fitter<'a> {
    /// The points priced for cluster `c`: a single face's own indices until it merges,
    /// then the hull vertices of its faces (`merge::driver` keeps them reduced).
    pub fn verts<'b>(&'b self, cl: &'b Clusters, c: u32) -> Corners<'b> {
        let v = cl.verts(c);
        if v.is_empty() {
            self.face(cl.head(c))
        } else {
            Corners::plain(v)
        }
    }

    /// Welded vertex indices of face `f`.
    fn face(&self, f: u32) -> Corners<'a> {
        self.input.weld.face(self.input.mesh, f as usize)
    }

    /// Appends the positions of vertices `vs`: one exact-size `extend` per coordinate
    /// (a capacity check per call, not per point).
    fn push_points(&self, vs: impl ExactSizeIterator<Item = u32> + Clone, ws: &mut Workspace) {
        let m = self.input.mesh;
        ws.x.extend(vs.clone().map(|v| m.x[v as usize]));
        ws.y.extend(vs.clone().map(|v| m.y[v as usize]));
        ws.z.extend(vs.map(|v| m.z[v as usize]));
    }

    /// The gathered points' best fit under `cfg`.
    fn fit_points(&self, q: &Sym3, cfg: &FitConfig, ws: &mut Workspace) -> Fit {
        let cloud = Cloud {
            x: &ws.x,
            y: &ws.y,
            z: &ws.z,
        };
        fit_best(&cloud, q, cfg, &mut ws.fit)
    }

    /// The share of `prim` outside the input (1 unless `solid` is set): the part of
    /// its volume a merge is priced for (docs/decisions/0023-merges-priced-by-the-air-they-add.md).
    pub fn air(&self, prim: &Primitive) -> f64 {
        self.input
            .solid
            .map_or(1.0, |s| 1.0 - s.inside_fraction(prim))
    }

    /// The primitive of face `f` alone, with its operator `q` (before any merge), in
    /// the eigen-frame only: it prices merges (its volume is subtracted from theirs),
    /// and the hull-edge frames there changed the order of a scan's merges for worse
    /// Hausdorff distances (docs/decisions/0013-frames-for-degenerate-quadrics.md); a
    /// face that ends up alone in the output is refitted by [`Self::fit_cluster_exact`] with them.
    pub fn fit_face(&self, f: u32, q: &Sym3, ws: &mut Workspace) -> Fit {
        ws.clear();
        self.push_points(self.face(f).iter(), ws);
        let cfg = FitConfig {
            frames: FrameSearch::Eigen,
            ..self.pricing.fit
        };
        self.fit_points(q, &cfg, ws)
    }

    /// The volume face `f` seeds the loop with (Alg. 1, line 2): its own primitive's
    /// ([`Self::fit_face`], operator `q`) times [`Self::air`].
    pub fn seed_volume(&self, f: u32, q: &Sym3, ws: &mut Workspace) -> f64 {
        let fit = self.fit_face(f, q, ws);
        fit.volume * self.air(&fit.prim)
    }

    /// The primitive of one cluster fitted on every vertex of its faces (walking the
    /// cyclic face list), independent of any point reduction: this is what we output.
    pub fn fit_cluster_exact(&self, cl: &Clusters, c: u32, ws: &mut Workspace) -> Fit {
        self.fit_output(cl.faces(c), &cl.q[c as usize], ws)
    }

    /// The output fit of `faces` with operator `q` (their summed quadrics). It uses the
    /// faces' own vertices, not the welded ones: a tolerance weld moves a corner onto
    /// its group's first vertex (transitively, so arbitrarily far), and the output must
    /// enclose the faces as given.
    pub fn fit_output(
        &self,
        faces: impl Iterator<Item = u32> + Clone,
        q: &Sym3,
        ws: &mut Workspace,
    ) -> Fit {
        let fit = self.fit_output_checked(faces, q, ws, &|| true);
        fit.expect("a fit never told to stop")
    }

    /// [`Self::fit_output`] asking `go_on` between blocks of [`FACES_PER_ASK`] faces
    /// gathered, sorted, searched for rims or laid flush, between the steps of the
    /// fit and inside its hull reduction (`hull_vertices_checked`): the same fit, or
    /// `None` as soon as it said stop. A fit over the millions of faces of a group of
    /// the merge tree's nodes is otherwise one step of seconds, which keeps a cancel
    /// waiting (docs/results/throughput.md, "Cancellation").
    pub fn fit_output_checked(
        &self,
        faces: impl Iterator<Item = u32> + Clone,
        q: &Sym3,
        ws: &mut Workspace,
        go_on: Ask,
    ) -> Option<Fit> {
        self.gather(faces.clone(), ws, go_on)?;
        ws.rims.clear();
        if self.prices_rims() {
            self.members_of(faces.clone(), ws, go_on)?;
            let (members, around) = (&ws.members, self.surroundings());
            if members.len() <= FACES_PER_ASK {
                around.rims(members, &mut ws.rims);
            } else {
                // A large cluster's rims, the same in the same order, a block at a time.
                let outside = |g| members.binary_search(&g).is_err();
                for block in members.chunks(FACES_PER_ASK) {
                    if !go_on() {
                        return None;
                    }
                    around.rims_added(block, outside, &mut ws.rims);
                }
            }
        }
        self.fit_gathered(faces, q, ws, false, go_on)
    }

    /// `faces`, sorted and distinct, into `ws.members`: marked in checked blocks
    /// ([`distinct_increasing`]) from [`MARKED_FROM`] faces, else sorted.
    fn members_of(
        &self,
        faces: impl Iterator<Item = u32> + Clone,
        ws: &mut Workspace,
        go_on: Ask,
    ) -> Option<()> {
        ws.members.clear();
        ws.members.extend(faces);
        if ws.members.len() < MARKED_FROM {
            ws.members.sort_unstable();
            ws.members.dedup();
            return Some(());
        }
        let blocks = ws.members.chunks(FACES_PER_ASK).map(|b| b.iter().copied());
        let range = self.input.mesh.face_count();
        ws.members = distinct_increasing(range, blocks, go_on)?;
        Some(())
    }

    /// Every point of `faces` (their own vertices, repeats kept) into `ws`'s points,
    /// asking `go_on` every [`FACES_PER_ASK`] faces; `None` when it said stop.
    fn gather(
        &self,
        faces: impl Iterator<Item = u32>,
        ws: &mut Workspace,
        go_on: Ask,
    ) -> Option<()> {
        ws.clear();
        for (i, f) in faces.enumerate() {
            if i % FACES_PER_ASK == FACES_PER_ASK - 1 && !go_on() {
                return None;
            }
            self.push_points(self.input.mesh.face(f as usize).iter().copied(), ws);
        }
        Some(())
    }

    /// [`Self::fit_output`] on `hull`, the hull vertices of `faces` (their own vertex
    /// indices, as `cut::hulls` keeps them), with the rims found from `boundary`, the
    /// faces with a neighbour outside them (increasing), told by `outside`: the same
    /// fit but for points within the hull's tolerance of it, which it may leave out,
    /// without gathering every face below a node of the merge tree again at every
    /// level (docs/decisions/0035).
    pub fn fit_on_vertices(
        &self,
        faces: impl Iterator<Item = u32> + Clone,
        hull: &[u32],
        boundary: &[u32],
        outside: impl Fn(u32) -> bool,
        q: &Sym3,
        ws: &mut Workspace,
    ) -> Fit {
        ws.clear();
        self.push_points(hull.iter().copied(), ws);
        ws.rims.clear();
        if self.prices_rims() {
            self.surroundings()
                .rims_where(boundary, outside, &mut ws.rims);
        }
        let fit = self.fit_gathered(faces, q, ws, true, &|| true);
        fit.expect("a fit never told to stop")
    }

    /// Every enabled kind fitted on every point of `faces` in every frame of the
    /// thorough output search, plates laid flush as [`Self::fit_output`] lays them,
    /// into `out`: output fits for a caller that chooses among them by another
    /// measure than k·V (the merge tree's cut, by distance: docs/decisions/0041).
    /// Asks `go_on` as [`Self::fit_output_checked`] does and before each fit: false,
    /// `out` not to be used, once it said stop.
    pub fn output_candidates(
        &self,
        faces: impl Iterator<Item = u32> + Clone,
        q: &Sym3,
        ws: &mut Workspace,
        out: &mut Vec<Primitive>,
        go_on: Ask,
    ) -> bool {
        out.clear();
        if self.gather(faces.clone(), ws, go_on).is_none() {
            return false;
        }
        let all = Cloud {
            x: &ws.x,
            y: &ws.y,
            z: &ws.z,
        };
        thorough_frames(&all, q, &mut ws.fit, &mut ws.frames);
        let kinds = Kind::ALL
            .into_iter()
            .filter(|&k| self.pricing.fit.enabled[k as usize]);
        for kind in kinds {
            let mut enabled = [false; 6];
            enabled[kind as usize] = true;
            let cfg = FitConfig {
                enabled,
                ..self.pricing.fit
            };
            for &axes in &ws.frames {
                if !go_on() {
                    return false;
                }
                out.push(fit_frame(&all, axes, &cfg, &mut ws.fit).prim);
                if kind == Kind::Prism {
                    // The skewed section holds a scalene triangle the isosceles
                    // mirrors a corner off (docs/decisions/0045).
                    let skewed = fit_skewed_prism(&all, axes, cfg.min_half, &mut ws.fit);
                    out.extend(skewed.map(Primitive::Prism));
                }
            }
        }
        if self.pricing.flush_plates {
            for p in out.iter_mut() {
                if !self.flush(faces.clone(), ws, p, go_on) {
                    return false;
                }
            }
        }
        true
    }

    /// Whether output fits price the rim reach (`Plates::rim_weight`).
    pub fn prices_rims(&self) -> bool {
        self.pricing.rim_weight > 0.0 && !self.input.face_adj.is_empty()
    }

    fn surroundings(&self) -> Surroundings<'a> {
        Surroundings {
            mesh: self.input.mesh,
            weld: self.input.weld,
            adj: self.input.face_adj,
            signs: self.input.face_sign,
        }
    }

    /// The output fit of the points gathered in `ws` for `faces`, with their rims in
    /// `ws.rims`; `on_hull`: the points are already their hull's vertices. `None`
    /// when `go_on`, asked between its steps, said stop.
    fn fit_gathered(
        &self,
        faces: impl Iterator<Item = u32> + Clone,
        q: &Sym3,
        ws: &mut Workspace,
        on_hull: bool,
        go_on: Ask,
    ) -> Option<Fit> {
        // Output only: every cluster also tries the frames turned about each of its
        // axes and the input's axes (docs/decisions/0014-output-fits-turn-about-the-normal.md,
        // docs/decisions/0021-thorough-output-frame-search.md); merges
        // stay priced as before.
        let cfg = FitConfig {
            frames: FrameSearch::Thorough,
            ..self.pricing.fit
        };
        let mut fit = if ws.rims.is_empty() {
            self.fit_on_hull(q, &cfg, ws, on_hull, go_on)?
        } else {
            self.fit_priced(q, &cfg, ws, on_hull, go_on)?
        };
        if self.pricing.flush_plates && !self.flush(faces, ws, &mut fit.prim, go_on) {
            return None;
        }
        Some(fit)
    }

    /// docs/decisions/0026-output-plates-lie-flush.md: a plate at the output floor thickness whose
    /// faces all face one way
    /// along its thin axis moves inward by its reach past their farthest vertex, so its
    /// outer side lies on the faces as the mesh's surface does (centred on them it stood
    /// `cfg.min_half` proud, and balls rested that high). Its cross-section is the
    /// same all along that axis, so the faces stay inside. `ws` holds the faces' points
    /// as gathered for the fit. Asks `go_on` every [`FACES_PER_ASK`] faces: false
    /// when it said stop (`prim` unchanged).
    fn flush(
        &self,
        faces: impl Iterator<Item = u32>,
        ws: &Workspace,
        prim: &mut Primitive,
        go_on: Ask,
    ) -> bool {
        let Some(axis) = prim.plate_axis(self.pricing.fit.min_half) else {
            return true;
        };
        // The faces' common outward side along the axis: +1 or −1, 0 when they disagree.
        let mut side = 0.0;
        for (i, f) in faces.enumerate() {
            if i % FACES_PER_ASK == FACES_PER_ASK - 1 && !go_on() {
                return false;
            }
            let Some((n, _)) = outward_normal(self.input.mesh, self.input.face_sign, f) else {
                continue;
            };
            let c = dot(n, axis);
            let s = if c >= PARALLEL {
                1.0
            } else if c <= -PARALLEL {
                -1.0
            } else {
                0.0
            };
            if s == 0.0 || (side != 0.0 && s != side) {
                return true;
            }
            side = s;
        }
        if side == 0.0 {
            return true;
        }
        let n = axis.map(|x| x * side);
        let top = (0..ws.x.len())
            .map(|i| dot(n, [ws.x[i], ws.y[i], ws.z[i]]))
            .fold(f64::NEG_INFINITY, f64::max);
        let reach = prim.support(n) - top;
        if reach > 0.0 && reach.is_finite() {
            *prim = prim.translated(n.map(|x| -x * reach));
        }
        true
    }

    /// The output fit with the rim reach priced: every frame of the thorough search
    /// fitted on the points' hull vertices, every enabled kind in it compared by
    /// k·V + w·rim (the reach differs between kinds of one frame), the least kept (earlier frames win ties within [`frame::MARGIN`]) and
    /// its frame refitted on every point.
    fn fit_priced(
        &self,
        q: &Sym3,
        cfg: &FitConfig,
        ws: &mut Workspace,
        on_hull: bool,
        go_on: Ask,
    ) -> Option<Fit> {
        // The search runs on the hull's vertices, or on every point when all are (or
        // `on_hull` says the points are their hull's vertices already).
        let (x, y, z) = if !on_hull && self.gather_hull(ws, go_on)? {
            (&ws.hx, &ws.hy, &ws.hz)
        } else {
            (&ws.x, &ws.y, &ws.z)
        };
        clamp_to_points(&mut ws.rims, x, y, z);
        let hull = Cloud { x, y, z };
        thorough_frames(&hull, q, &mut ws.fit, &mut ws.frames);
        let rims = &ws.rims;
        let w = self.pricing.rim_weight;
        let penalty = |p: &Primitive, cost, limit| rim_penalty(p, rims, w, cost, limit);
        let mut best: Option<(f64, [V3; 3])> = None;
        for &axes in &ws.frames {
            let bar = best.map_or(f64::INFINITY, |(b, _)| b * (1.0 - frame::MARGIN));
            if let Some((_, score)) = fit_frame_priced(&hull, axes, cfg, &mut ws.fit, &penalty, bar)
            {
                best = Some((score, axes));
            }
        }
        // No finite score anywhere (a reach overflowing at an extreme weight): k·V alone.
        let Some((_, axes)) = best else {
            return self.fit_on_hull(q, cfg, ws, on_hull, go_on);
        };
        let all = Cloud {
            x: &ws.x,
            y: &ws.y,
            z: &ws.z,
        };
        if !go_on() {
            return None;
        }
        Some(
            match fit_frame_priced(&all, axes, cfg, &mut ws.fit, &penalty, f64::INFINITY) {
                Some((fit, _)) => fit,
                None => fit_frame(&all, axes, cfg, &mut ws.fit),
            },
        )
    }

    /// Copies the gathered points' hull vertices to `ws.hx/hy/hz`; false (nothing
    /// copied) when every point is one, `None` when `go_on` said stop.
    fn gather_hull(&self, ws: &mut Workspace, go_on: Ask) -> Option<bool> {
        let eps = self.pricing.hull_eps;
        let (x, y, z) = (&ws.x, &ws.y, &ws.z);
        if !hull_vertices_checked(x, y, z, eps, &mut ws.hull, &mut ws.keep, go_on) {
            return None;
        }
        if ws.keep.len() == ws.x.len() {
            return Some(false);
        }
        for (dst, src) in [
            (&mut ws.hx, &ws.x),
            (&mut ws.hy, &ws.y),
            (&mut ws.hz, &ws.z),
        ] {
            dst.clear();
            dst.extend(ws.keep.iter().map(|&i| src[i as usize]));
        }
        Some(true)
    }

    /// [`fit_best`] of the gathered points, its frames tried on the points' hull
    /// vertices (a convex primitive encloses the points iff it encloses those) and only
    /// the winning frame refitted on every point: the same fit for ~20 frames at the
    /// price of one on every point (docs/decisions/0021-thorough-output-frame-search.md);
    /// `on_hull`: the gathered points are their hull's vertices already.
    fn fit_on_hull(
        &self,
        q: &Sym3,
        cfg: &FitConfig,
        ws: &mut Workspace,
        on_hull: bool,
        go_on: Ask,
    ) -> Option<Fit> {
        if on_hull || !self.gather_hull(ws, go_on)? {
            return go_on().then(|| self.fit_points(q, cfg, ws));
        }
        let hull = Cloud {
            x: &ws.hx,
            y: &ws.hy,
            z: &ws.hz,
        };
        let (_, axes) = fit_best_frame(&hull, q, cfg, &mut ws.fit);
        let all = Cloud {
            x: &ws.x,
            y: &ws.y,
            z: &ws.z,
        };
        go_on().then(|| fit_frame(&all, axes, cfg, &mut ws.fit))
    }

    /// Distinct vertices of every face of cluster `c` (the faces' own, not welded), sorted.
    pub fn all_verts(&self, cl: &Clusters, c: u32) -> Vec<u32> {
        let mut v: Vec<u32> = cl
            .faces(c)
            .flat_map(|f| self.input.mesh.face(f as usize).iter().copied())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// What pricing a merge needs of root `c` (see [`Side`]).
    pub fn side<'b>(&'b self, cl: &'b Clusters, c: u32) -> Side<'b> {
        Side {
            id: c,
            verts: self.verts(cl, c),
            q: cl.q[c as usize],
            volume: cl.volume[c as usize],
            t: cl.clock,
        }
    }

    /// The merge of roots `a` and `b` as a queue entry with its fit, or `None` when it
    /// would add more excess volume than allowed (§3.3 "Excess Volume Thresholding").
    pub fn candidate(
        &self,
        cl: &Clusters,
        a: u32,
        b: u32,
        ws: &mut Workspace,
    ) -> Option<(Candidate, Fit)> {
        self.candidate_of(self.side(cl, a), self.side(cl, b), ws)
    }

    /// [`Self::candidate`] from the two clusters' snapshots: the same arithmetic in the
    /// same order, so a copy of the sides prices bit for bit like the clusters.
    pub fn candidate_of(&self, a: Side, b: Side, ws: &mut Workspace) -> Option<(Candidate, Fit)> {
        let (a, b) = if a.id <= b.id { (a, b) } else { (b, a) };
        // Points shared by both clusters are streamed twice; max/min fits don't care.
        ws.clear();
        self.push_points(a.verts.iter(), ws);
        self.push_points(b.verts.iter(), ws);
        let q = a.q.add(&b.q);
        let fit = self.fit_points(&q, &self.pricing.fit, ws);
        let air = self.air(&fit.prim);
        let volume = fit.volume * air;
        let before = a.volume + b.volume;
        if volume - before > self.pricing.max_excess {
            return None;
        }
        let mut cost = fit.cost * air - before;
        let flat = ws.fit.was_flat();
        // A coplanar merge's volumes are all area × 2·floor, so scaling its cost is
        // pricing it at the thicker floor (Plates::open_holes).
        if self.pricing.flat_scale > 1.0 && flat {
            cost *= self.pricing.flat_scale;
        }
        let c = Candidate {
            cost: (cost / self.pricing.cost_unit).round(),
            volume,
            a: a.id,
            b: b.id,
            t: a.t.max(b.t),
            flat,
        };
        Some((c, fit))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::adjacency::{face_pairs, neighbour_lists};
    use crate::params::Params;

    /// An output fit over more faces than [`MARKED_FROM`] with its rims priced asks
    /// as it gathers, sorts, finds rims and reduces the hull, and gives the fit it
    /// gives unasked; told to stop at any of its asks, it stops there.
    #[test]
    fn a_large_output_fit_asks_as_it_goes_and_stops_when_told() {
        let n = 380u32;
        let mut p = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (f64::from(i), f64::from(j));
                p.push([x, y, 0.01 * (x * 0.37).sin() * (y * 0.23).cos() * x]);
            }
        }
        let at = |i: u32, j: u32| i * (n + 1) + j;
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                tris.push(vec![at(i, j), at(i + 1, j), at(i, j + 1)]);
                tris.push(vec![at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let mesh = Mesh::from_polygons(&p, &tris).unwrap();
        let pairs = face_pairs(&mesh.face_offsets, &mesh.face_indices);
        let (offsets, adj) = neighbour_lists(mesh.face_count(), &pairs);
        let unwelded = Weld::none();
        let mut fitter =
            crate::merge::setup::fitter(&mesh, &unwelded, &Params::default(), mesh.aabb());
        fitter.input.face_adj = FaceAdjacency {
            offsets: &offsets,
            adj: &adj,
        };
        assert!(fitter.prices_rims());
        // All but the last rows, from the back: rims inside the grid, not in order.
        let faces: Vec<u32> = (0..mesh.face_count() as u32 - 2000).rev().collect();
        assert!(faces.len() >= MARKED_FROM);
        let q = Sym3::ZERO;
        let mut ws = Workspace::default();
        let want = fitter.fit_output(faces.iter().copied(), &q, &mut ws).prim;
        let asked = std::sync::atomic::AtomicUsize::new(0);
        let count = || {
            asked.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            true
        };
        let got = fitter.fit_output_checked(faces.iter().copied(), &q, &mut ws, &count);
        assert_eq!(got.map(|f| f.prim), Some(want));
        let asks = asked.load(std::sync::atomic::Ordering::Relaxed);
        assert!(asks >= 3 * faces.len() / FACES_PER_ASK, "{asks} asks");
        for stop_at in [1, asks / 3, asks / 2, asks] {
            asked.store(0, std::sync::atomic::Ordering::Relaxed);
            let until = || asked.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1 < stop_at;
            let got = fitter.fit_output_checked(faces.iter().copied(), &q, &mut ws, &until);
            assert!(got.is_none(), "went on after the stop at ask {stop_at}");
        }
    }
}
