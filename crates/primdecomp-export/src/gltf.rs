//! glTF 2.0 / GLB export with physics colliders, written with `gltf-json`.
//!
//! Khronos form (default): `KHR_implicit_shapes` (document-level `shapes`: box with
//! full `size`, sphere `radius`, capsule `height` between the cap centres with
//! `radiusTop`/`radiusBottom`, cylinder full `height` with two radii — a frustum is a
//! cylinder whose radii differ — all centred and along local +Y) and
//! `KHR_physics_rigid_bodies` (a node's `collider.geometry.shape`). Prisms (and
//! anything else without a native shape) are `geometry: {node, convexHull: true}`
//! over a node outside the scene that holds the hull's mesh in the collider node's
//! frame. Colliders without a `motion` ancestor are static, which colliders are.
//!
//! OMI form (`Physics::Omi`, which Godot 4 imports): `OMI_physics_shape` shapes of
//! the same parameters (convex hulls as `{"type": "convex", "convex": {"mesh": i}}`;
//! frustums as convex hulls: OMI's tapered cylinders are optional for importers) and
//! `OMI_physics_body` (`collider.shape` on each collider node, `motion: static` on
//! the object's node).
//!
//! Layout: one scene node per object (its name, and its transform with the up-axis
//! turn — glTF is +Y up — and the scale applied: its children move with it), one
//! child node per collider placing its shape. Optionally (`preview`) each collider's
//! conservative tessellation as a coloured, half-transparent mesh beside it, and
//! (`input_mesh`) the input mesh, so one file is both the import and a preview.

use super::engine::{prepare, quat_between, ExportOptions, Format, Physics, Prepared, Shape};
use gltf_json as json;
use json::validation::{Checked::Valid, USize64};
use json::Index;
use primdecomp::Body;
use primdecomp::Frame;
use primdecomp::Kind;
use primdecomp::Tess;
use primdecomp_math::V3;
use serde_json::{json as j, Value};

/// Preview colours per kind (RGBA, half transparent), in [`Kind::ALL`] order.
const COLOURS: [[f32; 4]; 6] = [
    [0.90, 0.45, 0.10, 0.5],
    [0.20, 0.55, 0.90, 0.5],
    [0.25, 0.75, 0.30, 0.5],
    [0.85, 0.20, 0.55, 0.5],
    [0.60, 0.40, 0.85, 0.5],
    [0.95, 0.80, 0.15, 0.5],
];

/// Geometry buffer being assembled: one buffer, 4-byte aligned views.
struct Buf<'r> {
    root: &'r mut json::Root,
    data: Vec<u8>,
}

impl Buf<'_> {
    fn view(&mut self, bytes: &[u8], target: json::buffer::Target) -> Index<json::buffer::View> {
        while self.data.len() % 4 != 0 {
            self.data.push(0);
        }
        let offset = self.data.len();
        self.data.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: Index::new(0),
            byte_length: USize64(bytes.len() as u64),
            byte_offset: Some(USize64(offset as u64)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// A triangle mesh (polygons fanned) of f32 positions; returns the mesh index.
    fn mesh(
        &mut self,
        name: &str,
        vertices: &[V3],
        polygons: &[Vec<u32>],
        material: Option<Index<json::Material>>,
    ) -> Index<json::Mesh> {
        let pos: Vec<[f32; 3]> = vertices.iter().map(|v| v.map(|x| x as f32)).collect();
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &pos {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let bytes: Vec<u8> = pos.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let pv = self.view(&bytes, json::buffer::Target::ArrayBuffer);
        let mut idx: Vec<u32> = Vec::new();
        for f in polygons {
            for i in 1..f.len().saturating_sub(1) {
                idx.extend([f[0], f[i], f[i + 1]]);
            }
        }
        let ib: Vec<u8> = idx.iter().flat_map(|i| i.to_le_bytes()).collect();
        let iv = self.view(&ib, json::buffer::Target::ElementArrayBuffer);
        let pa = self.root.push(accessor(
            pv,
            pos.len(),
            json::accessor::ComponentType::F32,
            json::accessor::Type::Vec3,
            Some((lo, hi)),
        ));
        let ia = self.root.push(accessor(
            iv,
            idx.len(),
            json::accessor::ComponentType::U32,
            json::accessor::Type::Scalar,
            None,
        ));
        let mut attributes = std::collections::BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), pa);
        self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.to_string()),
            primitives: vec![json::mesh::Primitive {
                attributes,
                extensions: None,
                extras: Default::default(),
                indices: Some(ia),
                material,
                mode: Valid(json::mesh::Mode::Triangles),
                targets: None,
            }],
            weights: None,
        })
    }
}

fn accessor(
    view: Index<json::buffer::View>,
    count: usize,
    ct: json::accessor::ComponentType,
    ty: json::accessor::Type,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> json::Accessor {
    json::Accessor {
        buffer_view: Some(view),
        byte_offset: None,
        count: USize64(count as u64),
        component_type: Valid(json::accessor::GenericComponentType(ct)),
        extensions: None,
        extras: Default::default(),
        type_: Valid(ty),
        min: bounds.map(|b| j!(b.0)),
        max: bounds.map(|b| j!(b.1)),
        name: None,
        normalized: false,
        sparse: None,
    }
}

fn node(name: &str) -> json::Node {
    json::Node {
        name: Some(name.to_string()),
        ..Default::default()
    }
}

/// Sets a node's TRS from a frame (identity parts left out).
fn place(n: &mut json::Node, f: &Frame) {
    if f.translation != [0.0; 3] {
        n.translation = Some(f.translation.map(|x| x as f32));
    }
    if f.rotation != [0.0, 0.0, 0.0, 1.0] {
        n.rotation = Some(json::scene::UnitQuaternion(f.rotation.map(|x| x as f32)));
    }
    if f.scale != 1.0 {
        let s = f.scale as f32;
        n.scale = Some([s, s, s]);
    }
}

fn with_extension(n: &mut json::Node, name: &str, v: Value) {
    let ext = n.extensions.get_or_insert_with(Default::default);
    ext.others.insert(name.to_string(), v);
}

/// The shape's placement in its object's frame and its shape JSON (KHR or OMI; the
/// parameters are the same), or `None` for a hull.
fn implicit(shape: &Shape) -> Option<(Frame, Value)> {
    let at = |c: V3, q: [f64; 4]| Frame {
        translation: c,
        rotation: q,
        scale: 1.0,
    };
    let y = [0.0, 1.0, 0.0];
    match shape {
        Shape::Box {
            center,
            rotation,
            half,
        } => Some((
            at(*center, *rotation),
            j!({"type": "box", "box": {"size": half.map(|h| 2.0 * h)}}),
        )),
        Shape::Sphere { center, radius } => Some((
            at(*center, [0.0, 0.0, 0.0, 1.0]),
            j!({"type": "sphere", "sphere": {"radius": radius}}),
        )),
        Shape::Capsule { p0, p1, radius } => {
            let (c, a, h) = Shape::axis(*p0, *p1);
            Some((
                at(c, quat_between(y, a)),
                j!({"type": "capsule", "capsule": {"height": 2.0 * h, "radiusTop": radius, "radiusBottom": radius}}),
            ))
        }
        Shape::Round { p0, p1, r0, r1 } => {
            // +Y from p0 (bottom, r0) to p1 (top, r1).
            let (c, a, h) = Shape::axis(*p0, *p1);
            Some((
                at(c, quat_between(y, a)),
                j!({"type": "cylinder", "cylinder": {"height": 2.0 * h, "radiusTop": r1, "radiusBottom": r0}}),
            ))
        }
        Shape::Hull(_) => None,
    }
}

/// The glTF document (`.gltf` text with the buffer as a data URI, or `.glb` bytes), or
/// why it cannot be written ([`prepare`]).
pub fn to_gltf(objects: &[Body], opts: &ExportOptions, binary: bool) -> Result<Vec<u8>, String> {
    let prepared = prepare(objects, Format::Gltf, opts, true)?;
    let mut root = json::Root {
        asset: json::Asset {
            copyright: None,
            extensions: None,
            extras: Default::default(),
            generator: Some(format!("primdecomp {}", env!("CARGO_PKG_VERSION"))),
            min_version: None,
            version: "2.0".into(),
        },
        ..Default::default()
    };
    let mut data = Vec::new();
    let mut shapes: Vec<Value> = Vec::new();
    let nodes = build(&mut root, &mut data, &mut shapes, &prepared, opts);
    root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some(primdecomp_files::visible(&opts.model)),
        nodes,
    });
    root.scene = Some(Index::new(0));
    extensions(&mut root, shapes, opts.physics);
    while data.len() % 4 != 0 {
        data.push(0);
    }
    if !data.is_empty() {
        root.push(json::Buffer {
            byte_length: USize64(data.len() as u64),
            name: None,
            uri: (!binary)
                .then(|| format!("data:application/octet-stream;base64,{}", base64(&data))),
            extensions: None,
            extras: Default::default(),
        });
    }
    let text = root
        .to_string_pretty()
        .expect("serializing plain data cannot fail");
    if binary {
        glb(text.as_bytes(), &data)
    } else {
        let mut t = text.into_bytes();
        t.push(b'\n');
        Ok(t)
    }
}

/// Lists the physics extensions used, and the shapes colliders refer to.
fn extensions(root: &mut json::Root, shapes: Vec<Value>, physics: Physics) {
    let (shape_ext, body_ext) = match physics {
        Physics::Khr => ("KHR_implicit_shapes", "KHR_physics_rigid_bodies"),
        Physics::Omi => ("OMI_physics_shape", "OMI_physics_body"),
    };
    // A shape extension no collider uses is not listed (KHR: every collider a
    // prism's or frustum's hull, which are meshes, not shapes).
    root.extensions_used = if shapes.is_empty() {
        vec![body_ext.into()]
    } else {
        vec![shape_ext.into(), body_ext.into()]
    };
    if !shapes.is_empty() {
        let mut ext = json::extensions::root::Root::default();
        ext.others
            .insert(shape_ext.into(), j!({ "shapes": shapes }));
        root.extensions = Some(ext);
    }
}

/// Adds the node tree; returns the scene's nodes.
fn build(
    root: &mut json::Root,
    data: &mut Vec<u8>,
    shapes: &mut Vec<Value>,
    prepared: &[Prepared],
    opts: &ExportOptions,
) -> Vec<Index<json::Node>> {
    let mut buf = Buf {
        root,
        data: std::mem::take(data),
    };
    let materials = materials(&mut buf, opts);
    let mut object_nodes = Vec::new();
    for o in prepared {
        object_nodes.push(object(&mut buf, shapes, o, &materials, opts));
    }
    if let Some((positions, polygons)) = &opts.input_mesh {
        // The input mesh in result coordinates, under the result → glTF conversion.
        let mesh = buf.mesh("input", positions, polygons, None);
        let mut n = node("input");
        n.mesh = Some(mesh);
        place(&mut n, &super::engine::format_frame(Format::Gltf, opts));
        object_nodes.push(buf.root.push(n));
    }
    *data = std::mem::take(&mut buf.data);
    object_nodes
}

/// The previews' material of each kind (none without previews).
fn materials(buf: &mut Buf, opts: &ExportOptions) -> Vec<Option<Index<json::Material>>> {
    Kind::ALL
        .iter()
        .map(|k| {
            opts.preview.then(|| {
                let mut m = json::Material {
                    name: Some(format!("primdecomp {}", k.name())),
                    alpha_mode: Valid(json::material::AlphaMode::Blend),
                    double_sided: true,
                    ..Default::default()
                };
                m.pbr_metallic_roughness.base_color_factor =
                    json::material::PbrBaseColorFactor(COLOURS[*k as usize]);
                m.pbr_metallic_roughness.metallic_factor = json::material::StrengthFactor(0.0);
                buf.root.push(m)
            })
        })
        .collect()
}

/// Object `o`'s node, placed by its frame, with a collider node per shape (and its
/// preview's node).
fn object(
    buf: &mut Buf,
    shapes: &mut Vec<Value>,
    o: &Prepared,
    materials: &[Option<Index<json::Material>>],
    opts: &ExportOptions,
) -> Index<json::Node> {
    let mut children = Vec::new();
    for (i, (kind, shape)) in o.shapes.iter().enumerate() {
        let label = format!("{}_{}_{i}", o.name, kind.name());
        let n = collider(buf, shapes, &label, shape, opts.physics);
        children.push(buf.root.push(n));
        if opts.preview {
            let t = preview_tess(shape, opts.detail);
            let mesh = buf.mesh(
                &format!("{label}_preview"),
                &t.vertices,
                &t.faces,
                materials[*kind as usize],
            );
            let mut pn = node(&format!("{label}_preview"));
            pn.mesh = Some(mesh);
            children.push(buf.root.push(pn));
        }
    }
    let mut on = node(&o.name);
    place(&mut on, &o.frame);
    if opts.physics == Physics::Omi {
        with_extension(
            &mut on,
            "OMI_physics_body",
            j!({"motion": {"type": "static"}}),
        );
    }
    on.children = (!children.is_empty()).then_some(children);
    buf.root.push(on)
}

/// The collider node `label` of `shape`: an implicit shape, or a convex hull of a
/// mesh (KHR: on a node outside the scene; OMI: a convex shape).
fn collider(
    buf: &mut Buf,
    shapes: &mut Vec<Value>,
    label: &str,
    shape: &Shape,
    physics: Physics,
) -> json::Node {
    let mut n = node(label);
    match (implicit(shape), shape) {
        (Some((at, v)), _) => {
            place(&mut n, &at);
            let s = shapes.len();
            shapes.push(v);
            let (name, ext) = match physics {
                Physics::Khr => (
                    "KHR_physics_rigid_bodies",
                    j!({"collider": {"geometry": {"shape": s}}}),
                ),
                Physics::Omi => ("OMI_physics_body", j!({"collider": {"shape": s}})),
            };
            with_extension(&mut n, name, ext);
        }
        (None, Shape::Hull(t)) => {
            let mesh = buf.mesh(label, &t.vertices, &t.faces, None);
            match physics {
                Physics::Khr => {
                    let mut holder = node(&format!("{label}_hull"));
                    holder.mesh = Some(mesh);
                    // Outside the scene: referenced by the collider only.
                    let h = buf.root.push(holder);
                    let geometry = j!({"node": h.value(), "convexHull": true});
                    with_extension(
                        &mut n,
                        "KHR_physics_rigid_bodies",
                        j!({"collider": {"geometry": geometry}}),
                    );
                }
                Physics::Omi => {
                    let s = shapes.len();
                    shapes.push(j!({"type": "convex", "convex": {"mesh": mesh.value()}}));
                    with_extension(&mut n, "OMI_physics_body", j!({"collider": {"shape": s}}));
                }
            }
        }
        (None, _) => {}
    }
    n
}

/// The conservative tessellation of a shape in its object's frame.
fn preview_tess(shape: &Shape, detail: usize) -> Tess {
    use primdecomp::{Capsule, Cylinder, Frustum, Obb, Primitive, Sphere};
    let p = match shape {
        Shape::Hull(t) => return t.clone(),
        Shape::Box {
            center,
            rotation,
            half,
        } => Primitive::Box(Obb {
            center: *center,
            axes: primdecomp_math::axes_from_quat(*rotation),
            half: *half,
        }),
        Shape::Sphere { center, radius } => Primitive::Sphere(Sphere {
            center: *center,
            radius: *radius,
        }),
        Shape::Capsule { p0, p1, radius } => Primitive::Capsule(Capsule {
            p0: *p0,
            p1: *p1,
            radius: *radius,
        }),
        Shape::Round { p0, p1, r0, r1 } if r0 == r1 => Primitive::Cylinder(Cylinder {
            p0: *p0,
            p1: *p1,
            radius: *r0,
        }),
        Shape::Round { p0, p1, r0, r1 } => Primitive::Frustum(Frustum {
            p0: *p0,
            p1: *p1,
            r0: *r0,
            r1: *r1,
        }),
    };
    p.tessellate(detail)
}

/// Standard base64 with padding.
fn base64(b: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(b.len().div_ceil(3) * 4);
    for c in b.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A GLB container: header, JSON chunk (space-padded), BIN chunk (zero-padded); or
/// why not (its header declares the length in 32 bits).
fn glb(json: &[u8], bin: &[u8]) -> Result<Vec<u8>, String> {
    let mut j = json.to_vec();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut total = 12 + 8 + j.len();
    if !bin.is_empty() {
        total += 8 + bin.len();
    }
    if total > u32::MAX as usize {
        return Err(format!(
            "the GLB would hold {total} bytes, more than the 4 GiB its header can declare \
             (leave out --input or --preview)"
        ));
    }
    let mut v = Vec::with_capacity(total);
    v.extend_from_slice(b"glTF");
    v.extend_from_slice(&2u32.to_le_bytes());
    v.extend_from_slice(&(total as u32).to_le_bytes());
    v.extend_from_slice(&(j.len() as u32).to_le_bytes());
    v.extend_from_slice(b"JSON");
    v.extend_from_slice(&j);
    if !bin.is_empty() {
        v.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        v.extend_from_slice(b"BIN\0");
        v.extend_from_slice(bin);
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_known_values() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }

    /// Prisms alone are hulls (meshes), no implicit shape: `KHR_implicit_shapes` is
    /// not listed as used (a skewed prism, as the cut's nearest fit makes one);
    /// OMI lists its shape extension, whose shapes hold the hulls.
    #[test]
    fn an_unused_shape_extension_is_not_listed() {
        let prism = primdecomp::Primitive::Prism(primdecomp::Prism {
            center: [0.0; 3],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            hx: 0.01,
            hy: 0.5,
            hz_top: 0.01,
            hz_bottom: 0.7,
            shift: 0.3,
        });
        let objects = [Body {
            name: String::new(),
            frame: Frame::IDENTITY,
            primitives: vec![prism],
        }];
        let used = |physics| {
            let opts = ExportOptions {
                physics,
                ..ExportOptions::default()
            };
            let doc: Value =
                serde_json::from_slice(&to_gltf(&objects, &opts, false).unwrap()).unwrap();
            doc["extensionsUsed"].clone()
        };
        assert_eq!(used(Physics::Khr), j!(["KHR_physics_rigid_bodies"]));
        assert_eq!(
            used(Physics::Omi),
            j!(["OMI_physics_shape", "OMI_physics_body"])
        );
    }
}
