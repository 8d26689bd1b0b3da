//! The mesh as the algorithm needs it (§3: V and polygon faces F, |F_i| ≥ 3):
//! struct-of-arrays positions, re-centred in f64, and polygons in CSR form.
//! Nothing else from the file is kept.

use crate::math::{aabb_of, V3};

/// Largest distance of any vertex from the centre of the mesh's bounding box that the
/// engine accepts. Fits take cubes (volumes) and fourth powers (squared quadric entries
/// in the eigen-solver) of lengths; 1e60 keeps both far below f64's 1.8e308 even with
/// large kind weights. Coordinates of 1e300 crashed the frustum fit before this limit.
pub(crate) const MAX_EXTENT: f64 = 1e60;

/// Largest magnitude of any world coordinate the engine accepts. Cylinders and
/// frustums are written with their ends pushed out by up to about 320 ε × the
/// coordinates' magnitude (`primitive::world`), so that rounding cannot tilt their axes
/// out of the fitted solid; below 1e70 that stays under 1e-13 × 1e70 ≈ 1e57, inside the
/// engine's range of lengths ([`MAX_EXTENT`]). Beyond it, the written lengths would
/// exceed 1e154 at the top of the f64 range, and squaring them overflows.
pub(crate) const MAX_POSITION: f64 = 1e70;

/// What a reader skipped, so that a caller can say it ([`Mesh::skipped_faces`],
/// [`Mesh::skipped_other`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct SkipCounts {
    /// `l` elements, 2-vertex "faces" and other faces with fewer than 3 distinct indices.
    pub(crate) short_faces: u64,
    /// Non-triangle glTF primitives (points, lines) and similar unsupported elements.
    pub(crate) other: u64,
}

/// What a parser produces: world coordinates in f64 and CSR polygons.
#[derive(Clone, Debug, Default)]
pub(crate) struct MeshBuilder {
    pub positions: Vec<[f64; 3]>,
    /// `face_offsets[f]..face_offsets[f+1]` indexes `face_indices`; starts with 0.
    pub face_offsets: Vec<u32>,
    pub face_indices: Vec<u32>,
    pub skipped: SkipCounts,
    /// Named objects in file order: each name with the first face it holds (OBJ `o`
    /// and `g`, glTF mesh nodes). Empty when the file names none.
    pub objects: Vec<(String, u32)>,
    /// Per entry of `objects`: the node's world transform for glTF mesh nodes
    /// (column-major 4×4, glTF's layout), `None` for OBJ objects.
    pub object_transforms: Vec<Option<Transform>>,
}

/// A column-major affine 4×4 matrix (`m[column][row]`, glTF's layout).
pub type Transform = [[f64; 4]; 4];

impl MeshBuilder {
    pub fn new() -> Self {
        MeshBuilder {
            face_offsets: vec![0],
            ..Default::default()
        }
    }
    /// Appends a polygon; polygons with fewer than 3 vertices are counted and skipped.
    /// Indices must already be validated against `positions.len()` by the parser.
    pub fn push_face(&mut self, idx: &[u32]) {
        if idx.len() < 3 {
            self.skipped.short_faces += 1;
            return;
        }
        self.face_indices.extend_from_slice(idx);
        self.face_offsets.push(self.face_indices.len() as u32);
    }
    pub fn face_count(&self) -> usize {
        self.face_offsets.len() - 1
    }
    /// Starts a named object at the next face; an earlier object that got no face is
    /// dropped. Faces before the first name form an unnamed object of their own.
    pub fn start_object(&mut self, name: String) {
        self.start_object_at(name, None);
    }
    /// [`MeshBuilder::start_object`] for a glTF mesh node: its faces are in world
    /// coordinates, `transform` is the node's world transform.
    pub fn start_node(&mut self, name: String, transform: Transform) {
        self.start_object_at(name, Some(transform));
    }
    fn start_object_at(&mut self, name: String, transform: Option<Transform>) {
        let first = self.face_count() as u32;
        self.object_transforms.resize(self.objects.len(), None);
        if self.objects.is_empty() && first > 0 {
            self.objects.push((String::new(), 0));
            self.object_transforms.push(None);
        }
        if self.objects.last().is_some_and(|o| o.1 == first) {
            self.objects.pop();
            self.object_transforms.pop();
        }
        self.objects.push((name, first));
        self.object_transforms.push(transform);
    }
}

/// A polygon mesh as the engine reads it: positions in f64 struct-of-arrays,
/// re-centred on their bounding box (so a scan a million units from the origin keeps
/// its detail), and polygons as offsets into one index array. Nothing else from a file
/// is kept. Build one with [`crate::Mesh::load`], [`Mesh::from_triangles`] or
/// [`Mesh::from_polygons`].
///
/// ```
/// use primdecomp::Mesh;
///
/// let mesh = Mesh::from_triangles(
///     &[[10.0, 0.0, 0.0], [11.0, 0.0, 0.0], [10.0, 1.0, 0.0]],
///     &[[0, 1, 2]],
/// )?;
/// assert_eq!((mesh.face_count(), mesh.vertex_count()), (1, 3));
/// assert_eq!(mesh.world_pos(1), [11.0, 0.0, 0.0]);
/// assert_eq!(mesh.centre(), [10.5, 0.5, 0.0]);
/// assert_eq!(mesh.pos(1), [0.5, -0.5, 0.0]);
/// # Ok::<(), primdecomp::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub(crate) x: Vec<f64>,
    pub(crate) y: Vec<f64>,
    pub(crate) z: Vec<f64>,
    /// Subtracted from every input coordinate (the centre of the input's AABB).
    pub(crate) offset: V3,
    pub(crate) face_offsets: Vec<u32>,
    pub(crate) face_indices: Vec<u32>,
    pub(crate) skipped: SkipCounts,
    /// Named objects: each name with its first face (see [`Mesh::objects`]).
    pub(crate) object_starts: Vec<(String, u32)>,
    /// Per entry of `object_starts`: the glTF node's world transform, if any.
    pub(crate) object_transforms: Vec<Option<Transform>>,
}

/// A named part of a mesh: an OBJ `o` object or `g` group, with its faces.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct MeshObject<'a> {
    /// The name the file gives it; empty for faces before the first name.
    pub(crate) name: &'a str,
    /// Its faces, a contiguous range of face indices.
    pub(crate) faces: std::ops::Range<usize>,
    /// For a glTF mesh node, its world transform (the faces are already in world
    /// coordinates); `None` for OBJ objects and files without nodes.
    pub(crate) transform: Option<&'a Transform>,
}

impl Mesh {
    /// Re-centres the builder's f64 coordinates on their AABB centre, so that a scan
    /// at a 10^6 offset keeps its detail in every later computation.
    pub(crate) fn from_builder(b: MeshBuilder) -> Mesh {
        let (lo, hi) = aabb_of(b.positions.iter().copied());
        let offset = if b.positions.is_empty() {
            [0.0; 3]
        } else {
            [
                0.5 * (lo[0] + hi[0]),
                0.5 * (lo[1] + hi[1]),
                0.5 * (lo[2] + hi[2]),
            ]
        };
        let n = b.positions.len();
        let (mut x, mut y, mut z) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for p in &b.positions {
            x.push(p[0] - offset[0]);
            y.push(p[1] - offset[1]);
            z.push(p[2] - offset[2]);
        }
        Mesh {
            x,
            y,
            z,
            offset,
            face_offsets: b.face_offsets,
            face_indices: b.face_indices,
            skipped: b.skipped,
            object_transforms: {
                let mut t = b.object_transforms;
                t.resize(b.objects.len(), None);
                t
            },
            object_starts: b.objects,
        }
    }

    /// Replaces the re-centred coordinates by `world` (the same vertices as read), with
    /// the origin as centre ([`crate::LoadOptions::keep_world_coordinates`]).
    pub(crate) fn set_world_coordinates(&mut self, world: &[[f64; 3]]) {
        self.x = world.iter().map(|p| p[0]).collect();
        self.y = world.iter().map(|p| p[1]).collect();
        self.z = world.iter().map(|p| p[2]).collect();
        self.offset = [0.0; 3];
    }

    /// A mesh of triangles: `positions` in world coordinates, `triangles` indexing
    /// them. Copies both once into the engine's layout (struct-of-arrays, re-centred).
    ///
    /// # Errors
    /// [`crate::Error::Format`] naming the first non-finite coordinate or index out of
    /// range.
    pub fn from_triangles(
        positions: &[[f64; 3]],
        triangles: &[[u32; 3]],
    ) -> crate::error::Result<Mesh> {
        check_positions(positions)?;
        let mut b = MeshBuilder::new();
        b.positions.extend_from_slice(positions);
        b.face_offsets
            .extend((1..=triangles.len()).map(|t| 3 * t as u32));
        b.face_indices.extend(triangles.iter().flatten());
        check_indices(&b.face_indices, positions.len())?;
        Ok(Mesh::from_builder(b))
    }

    /// A mesh of polygons (triangles, quads, n-gons; each a list of indices into
    /// `positions`, world coordinates). Polygons are kept whole: the engine treats a
    /// planar quad as one face. Polygons of fewer than 3 corners are skipped and
    /// counted ([`Mesh::skipped_faces`]), as the file readers do.
    ///
    /// # Errors
    /// [`crate::Error::Format`] naming the first non-finite coordinate or index out of
    /// range.
    pub fn from_polygons<F: AsRef<[u32]>>(
        positions: &[[f64; 3]],
        faces: &[F],
    ) -> crate::error::Result<Mesh> {
        check_positions(positions)?;
        let mut b = MeshBuilder::new();
        b.positions.extend_from_slice(positions);
        for f in faces {
            b.push_face(f.as_ref());
        }
        check_indices(&b.face_indices, positions.len())?;
        Ok(Mesh::from_builder(b))
    }

    /// The mesh's named objects in file order, each its name (empty for faces before
    /// the first name) and its faces, a contiguous range of face indices; one unnamed
    /// object holding every face when the file names none. Objects without faces are
    /// left out. An OBJ file's `o` objects and `g` groups, a glTF file's mesh nodes.
    ///
    /// ```
    /// use primdecomp::{Mesh, MeshFormat};
    ///
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no lid\nf 1 2 3\no sides\nf 1 2 4\nf 1 4 3\n";
    /// let mesh = Mesh::parse(obj, MeshFormat::Obj, "box.obj".as_ref())?;
    /// assert_eq!(mesh.objects(), [("lid", 0..1), ("sides", 1..3)]);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn objects(&self) -> Vec<(&str, std::ops::Range<usize>)> {
        self.parts()
            .into_iter()
            .map(|o| (o.name, o.faces))
            .collect()
    }

    /// [`Mesh::objects`] with each glTF node's world transform.
    pub(crate) fn parts(&self) -> Vec<MeshObject<'_>> {
        let n = self.face_count();
        if self.object_starts.is_empty() {
            return vec![MeshObject {
                name: "",
                faces: 0..n,
                transform: None,
            }];
        }
        let ends = self.object_starts.iter().skip(1).map(|o| o.1 as usize);
        self.object_starts
            .iter()
            .zip(ends.chain([n]))
            .enumerate()
            .filter(|(_, (o, end))| (o.1 as usize) < *end)
            .map(|(i, (o, end))| MeshObject {
                name: &o.0,
                faces: o.1 as usize..end,
                transform: self.object_transforms.get(i).and_then(Option::as_ref),
            })
            .collect()
    }

    /// The centre of the input's bounding box, subtracted from every coordinate.
    pub fn centre(&self) -> V3 {
        self.offset
    }

    /// Faces the reader (or constructor) skipped because they have fewer than 3
    /// distinct vertices (OBJ `l` elements, 2-vertex faces).
    ///
    /// ```
    /// use primdecomp::{Mesh, MeshFormat};
    ///
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n";
    /// let mesh = Mesh::parse(obj, MeshFormat::Obj, "bits.obj".as_ref())?;
    /// assert_eq!(mesh.skipped_faces(), 1); // the line
    /// assert_eq!(mesh.skipped_other(), 0);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn skipped_faces(&self) -> u64 {
        self.skipped.short_faces
    }

    /// Elements the reader skipped because it does not read them (glTF points and
    /// lines), besides [`Mesh::skipped_faces`].
    ///
    /// ```
    /// use primdecomp::{Mesh, MeshFormat};
    ///
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    /// let mesh = Mesh::parse(obj, MeshFormat::Obj, "one.obj".as_ref())?;
    /// assert_eq!(mesh.skipped_other(), 0);
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn skipped_other(&self) -> u64 {
        self.skipped.other
    }

    /// Number of polygon faces.
    #[inline]
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }
    /// Number of vertices (as given, before any welding).
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.x.len()
    }
    /// Vertex indices of face `f`.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_indices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }
    /// Newell's normal of face `f` from its own vertices: unnormalised, its length
    /// twice the (planar) polygon's area, along the winding's right-hand normal.
    pub(crate) fn newell(&self, f: usize) -> V3 {
        let vs = self.face(f);
        let mut n = [0.0; 3];
        for (i, &v) in vs.iter().enumerate() {
            let c = crate::math::cross(self.pos(v), self.pos(vs[(i + 1) % vs.len()]));
            n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
        }
        n
    }
    /// Position of vertex `v` relative to [`Mesh::centre`] (how the engine computes).
    #[inline]
    pub fn pos(&self, v: u32) -> V3 {
        let v = v as usize;
        [self.x[v], self.y[v], self.z[v]]
    }
    /// World position of vertex `v` (`pos(v) + centre()`, rounded once).
    #[inline]
    pub fn world_pos(&self, v: u32) -> V3 {
        crate::math::add(self.pos(v), self.offset)
    }
    /// The first vertex (0-based) farther than [`MAX_EXTENT`] from the re-centring
    /// origin on some axis (or not finite), with that distance.
    pub(crate) fn vertex_out_of_range(&self) -> Option<(usize, f64)> {
        let reach = |i: usize| self.x[i].abs().max(self.y[i].abs()).max(self.z[i].abs());
        // A NaN distance (from an infinite offset) counts as out of range.
        let out = |d: f64| d.is_nan() || d > MAX_EXTENT;
        // One pass without an early exit first (it vectorises): almost every mesh has
        // no such vertex, and the search below finds the same first one when it has.
        if !(0..self.vertex_count()).fold(false, |any, i| any | out(reach(i))) {
            return None;
        }
        (0..self.vertex_count()).find_map(|i| out(reach(i)).then(|| (i, reach(i))))
    }
    /// The first vertex (0-based) with a world coordinate beyond ±[`MAX_POSITION`],
    /// with that coordinate.
    pub(crate) fn vertex_beyond_position_limit(&self) -> Option<(usize, f64)> {
        // The largest magnitude is over the limit iff some coordinate's is (a NaN's
        // never is): one pass without an early exit first, as above.
        let beyond = |i: usize| {
            let p = self.world_pos(i as u32);
            (p[0].abs() > MAX_POSITION) | (p[1].abs() > MAX_POSITION) | (p[2].abs() > MAX_POSITION)
        };
        if !(0..self.vertex_count()).fold(false, |any, i| any | beyond(i)) {
            return None;
        }
        (0..self.vertex_count()).find_map(|i| {
            let p = self.world_pos(i as u32);
            let c = p
                .into_iter()
                .fold(0.0f64, |m, c| if c.abs() > m.abs() { c } else { m });
            (c.abs() > MAX_POSITION).then_some((i, c))
        })
    }
    /// [`Mesh::vertex_out_of_range`] and [`Mesh::vertex_beyond_position_limit`] as the
    /// errors for `path`.
    pub(crate) fn check_extent(&self, path: &std::path::Path) -> crate::error::Result<()> {
        if let Some((i, d)) = self.vertex_out_of_range() {
            return Err(crate::error::Error::Extent {
                path: path.to_path_buf(),
                vertex: i as u64 + 1,
                distance: d,
                limit: MAX_EXTENT,
            });
        }
        match self.vertex_beyond_position_limit() {
            None => Ok(()),
            Some((i, c)) => Err(crate::error::Error::Position {
                path: path.to_path_buf(),
                vertex: i as u64 + 1,
                coordinate: c,
                limit: MAX_POSITION,
            }),
        }
    }
    /// Bounding box (min, max) of the vertices faces use, relative to [`Mesh::centre`].
    ///
    /// The vertices the faces use are marked first, then each axis' bounds taken over
    /// the marked ones in vertex order: a bound that is not zero is the one value
    /// below (above) every other, so the order it was found in cannot change its bits,
    /// and it is the bound of the corners in face order (`aabb_by_corners`). A
    /// zero bound may be +0 or −0 depending on that order: then the corners are
    /// walked in face order after all.
    pub fn aabb(&self) -> (V3, V3) {
        let mut used = vec![false; self.vertex_count()];
        for &v in &self.face_indices {
            used[v as usize] = true;
        }
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (k, c) in [&self.x, &self.y, &self.z].into_iter().enumerate() {
            for (&v, &u) in c.iter().zip(&used) {
                if u {
                    lo[k] = lo[k].min(v);
                    hi[k] = hi[k].max(v);
                }
            }
        }
        if lo.iter().chain(&hi).any(|&b| b == 0.0) {
            return self.aabb_by_corners();
        }
        if lo[0] > hi[0] {
            return ([0.0; 3], [0.0; 3]);
        }
        (lo, hi)
    }
    /// [`Self::aabb`] as every corner of every face in order gives it.
    pub(crate) fn aabb_by_corners(&self) -> (V3, V3) {
        aabb_of(self.face_indices.iter().map(|&v| self.pos(v)))
    }
    /// Length of the bounding box's diagonal: the scale every relative setting
    /// ([`crate::Fit::min_extent`], …) is a fraction of.
    pub fn diagonal(&self) -> f64 {
        let (lo, hi) = self.aabb();
        crate::math::norm(crate::math::sub(hi, lo))
    }
}

/// Face `f`'s outward unit normal (Newell's normal of its own vertices times its sign
/// in `signs`, +1 when `signs` is empty) and the Newell normal's length (twice the
/// area); `None` for a face of zero area.
pub fn outward_normal(mesh: &Mesh, signs: &[i8], f: u32) -> Option<(V3, f64)> {
    let n = mesh.newell(f as usize);
    let len = crate::math::norm(n);
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let k = signs.get(f as usize).map_or(1.0, |&s| f64::from(s)) / len;
    Some(([n[0] * k, n[1] * k, n[2] * k], len))
}

/// Face `f`'s outward unit normal ([`outward_normal`]), its centroid (the mean of its
/// vertices) and the Newell normal's length (twice its area); `None` for a face of
/// zero area.
pub(crate) fn outward_normal_and_centre(
    mesh: &Mesh,
    signs: &[i8],
    f: u32,
) -> Option<(V3, V3, f64)> {
    let (n, len) = outward_normal(mesh, signs, f)?;
    let vs = mesh.face(f as usize);
    let mut c = [0.0; 3];
    for &v in vs {
        let p = mesh.pos(v);
        c = [c[0] + p[0], c[1] + p[1], c[2] + p[2]];
    }
    let m = 1.0 / vs.len() as f64;
    Some((n, [c[0] * m, c[1] * m, c[2] * m], len))
}

/// Refuses non-finite coordinates (as the readers do).
fn check_positions(positions: &[[f64; 3]]) -> crate::error::Result<()> {
    match positions
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        None => Ok(()),
        Some(i) => Err(crate::error::Error::Format {
            path: "<mesh>".into(),
            msg: format!("vertex {i} has a non-finite coordinate {:?}", positions[i]),
        }),
    }
}

/// Refuses indices past the last vertex.
fn check_indices(indices: &[u32], vertices: usize) -> crate::error::Result<()> {
    match indices.iter().find(|&&v| v as usize >= vertices) {
        None => Ok(()),
        Some(v) => Err(crate::error::Error::Format {
            path: "<mesh>".into(),
            msg: format!("face index {v} is out of range ({vertices} vertices)"),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// A mesh over `x`, `y`, `z` as given (no re-centring), of triangles `tris`.
    fn raw(x: Vec<f64>, y: Vec<f64>, z: Vec<f64>, tris: &[[u32; 3]]) -> Mesh {
        Mesh {
            x,
            y,
            z,
            offset: [0.0; 3],
            face_offsets: (0..=tris.len() as u32).map(|f| 3 * f).collect(),
            face_indices: tris.iter().flatten().copied().collect(),
            skipped: SkipCounts::default(),
            object_starts: Vec::new(),
            object_transforms: Vec::new(),
        }
    }

    fn bits((lo, hi): (V3, V3)) -> [u64; 6] {
        let b = |v: f64| v.to_bits();
        [b(lo[0]), b(lo[1]), b(lo[2]), b(hi[0]), b(hi[1]), b(hi[2])]
    }

    /// A coordinate drawn from few values, signed zeros, NaN and infinities among
    /// them, so that bounds tie, are zero of either sign, or are not finite.
    fn coordinate(r: &mut impl Rng, zeros: bool) -> f64 {
        match r.gen_range(0..12) {
            0 if zeros => 0.0,
            1 if zeros => -0.0,
            2 => f64::NAN,
            3 => f64::INFINITY,
            4 => f64::NEG_INFINITY,
            5 => 1e65,
            6 => -1e75,
            k => f64::from(k) * r.gen_range(-2.0..2.0),
        }
    }

    /// The bounds from the used vertices are bit for bit those of the corners in face
    /// order, on meshes with unused vertices, repeated values, signed zeros, NaN and
    /// infinite coordinates, flat axes and no faces at all.
    #[test]
    fn aabb_is_the_corners_bounds_bit_for_bit() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for case in 0..4000 {
            let n = r.gen_range(1..40);
            let zeros = case % 2 == 0;
            let mut axis = |flat: bool| -> Vec<f64> {
                (0..n)
                    .map(|_| match flat {
                        true => [0.0, -0.0][r.gen_range(0..2)],
                        false => coordinate(&mut r, zeros),
                    })
                    .collect()
            };
            let (x, y, z) = (axis(case % 7 == 0), axis(case % 5 == 0), axis(false));
            let faces = r.gen_range(0..6);
            let tris: Vec<[u32; 3]> = (0..faces)
                .map(|_| [0; 3].map(|_| r.gen_range(0..n as u32)))
                .collect();
            let m = raw(x, y, z, &tris);
            assert_eq!(bits(m.aabb()), bits(m.aabb_by_corners()), "case {case}");
        }
    }

    /// The checks of the coordinates' reach find the same first vertex and value as a
    /// search alone (the old form), with and without vertices beyond the limits.
    #[test]
    fn extent_checks_find_the_first_vertex_beyond_the_limits() {
        let first_far = |m: &Mesh| {
            (0..m.vertex_count()).find_map(|i| {
                let d = m.x[i].abs().max(m.y[i].abs()).max(m.z[i].abs());
                (d.is_nan() || d > MAX_EXTENT).then_some((i, d))
            })
        };
        let first_beyond = |m: &Mesh| {
            (0..m.vertex_count()).find_map(|i| {
                let p = m.world_pos(i as u32);
                let c = p
                    .into_iter()
                    .fold(0.0f64, |m, c| if c.abs() > m.abs() { c } else { m });
                (c.abs() > MAX_POSITION).then_some((i, c))
            })
        };
        let same = |a: Option<(usize, f64)>, b: Option<(usize, f64)>| {
            a.map(|(i, v)| (i, v.to_bits())) == b.map(|(i, v)| (i, v.to_bits()))
        };
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for case in 0..4000 {
            let n = r.gen_range(0..30);
            let mut axis = || -> Vec<f64> {
                (0..n)
                    .map(|_| match r.gen_range(0..40) {
                        0 => coordinate(&mut r, true),
                        _ => r.gen_range(-1e3..1e3),
                    })
                    .collect()
            };
            let (x, y, z) = (axis(), axis(), axis());
            let mut m = raw(x, y, z, &[]);
            m.offset = [[0.0; 3], [1e69, 0.0, -1e69], [-1e50, 1e60, 0.0]][case % 3];
            assert!(same(m.vertex_out_of_range(), first_far(&m)), "case {case}");
            assert!(
                same(m.vertex_beyond_position_limit(), first_beyond(&m)),
                "case {case}"
            );
        }
    }
}
