//! Shapes: `obj` and `ply` files, `rectangle`, `cube`, `disk`
//! (tessellated), `sphere` (analytic), and `shapegroup` + `instance` (each
//! mesh stored once, drawn by one [`InstanceDesc`] per instance). A
//! shape's `to_world` becomes its instance transform; a sphere's is applied
//! to its centre and radius (so it must scale uniformly). A shape's
//! interior and exterior media (`media.rs`) give it a material of its own
//! (also inside a shape group, whose instances then share it).

use super::bsdfs::set;
use super::doc::{elements, Doc, XNode};
use super::emitters::area_radiance;
use super::transform::to_world;
use super::values::{boolean, float, integer, point};
use super::{tessellate, Builder};
use crate::desc::{
    BsdfDesc, InstanceDesc, MaterialDesc, MediumInterface, MeshDesc, SphereDesc, TextureSlot,
};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4, Vec3};

/// A shape's surface material: one shared with other shapes (a named
/// BSDF's, the default), or one of its own, not yet in the scene.
enum Surface {
    Shared(usize),
    Own(Box<MaterialDesc>),
}

/// A shape of a group, in the group's space.
#[derive(Clone, Debug)]
pub(super) enum GroupItem {
    Mesh { mesh: usize, transform: Mat4 },
    Sphere(SphereDesc),
}

impl Builder {
    /// A `<shape>`; inside a shape group its parts go to `group` instead of
    /// the world.
    pub(super) fn shape(
        &mut self,
        doc: &Doc,
        node: XNode,
        group: Option<&mut Vec<GroupItem>>,
    ) -> Result<(), LoadError> {
        let kind = doc.plugin_type(node)?;
        let name = doc.attr(node, "id")?.unwrap_or_else(|| kind.clone());
        let loc = doc.loc(node);
        let mut mesh = match kind.as_str() {
            "obj" | "ply" => {
                let path = self.existing_file(doc, node)?;
                let mut m = if kind == "obj" {
                    crate::obj::read_obj_mesh(&path, &mut self.warnings)?
                } else {
                    crate::ply::read_ply_mesh(&path, &mut self.warnings)?
                };
                smooth_or_faceted(&mut m, boolean(doc, node, "face_normals", false)?);
                m.name = name.clone();
                m.loc = loc;
                m
            }
            "serialized" => {
                let path = self.existing_file(doc, node)?;
                let index = integer(doc, node, "shape_index", 0)?;
                let index = u32::try_from(index).map_err(|_| {
                    doc.err(
                        node,
                        ErrorKind::BadValue,
                        format!("shape_index {index} is negative"),
                    )
                })?;
                let read = super::serialized::read_serialized(&path, index)?;
                let mut m = read.mesh;
                let faceted = read.face_normals || boolean(doc, node, "face_normals", false)?;
                smooth_or_faceted(&mut m, faceted);
                if m.name.is_empty() {
                    m.name = name.clone();
                }
                m.loc = loc;
                m
            }
            "rectangle" => tessellate::rectangle(name.clone(), loc),
            "cube" => tessellate::cube(name.clone(), loc),
            "disk" => tessellate::disk(name.clone(), loc),
            "cylinder" => cylinder(doc, node, name.clone(), loc)?,
            "sphere" => return self.sphere(doc, node, name, group),
            "shapegroup" => return self.shape_group(doc, node, group.is_some()),
            "instance" => return self.instance(doc, node, group.is_some()),
            "bsplinecurve" | "linearcurve" | "sdfgrid" | "ellipsoids" | "ellipsoidsmesh" => {
                return self.warn(
                    doc,
                    node,
                    format!("shape type \"{kind}\" is not supported (skipped)"),
                )
            }
            other => {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("unknown shape type \"{other}\""),
                ))
            }
        };
        if kind != "obj" {
            image_rows_from_the_top(&mut mesh);
        }
        if boolean(doc, node, "flip_normals", false)? {
            tessellate::flip(&mut mesh);
        }
        let transform = checked_transform(doc, node)?;
        mesh.material = self.shape_material(doc, node)?;
        self.scene.meshes.push(mesh);
        let index = self.scene.meshes.len() - 1;
        match group {
            Some(g) => g.push(GroupItem::Mesh {
                mesh: index,
                transform,
            }),
            None => self.scene.instances.push(InstanceDesc {
                mesh: index,
                world_from_object: transform,
                material: None,
                loc,
            }),
        }
        Ok(())
    }

    fn sphere(
        &mut self,
        doc: &Doc,
        node: XNode,
        name: String,
        group: Option<&mut Vec<GroupItem>>,
    ) -> Result<(), LoadError> {
        let center = point(doc, node, "center")?.unwrap_or(Vec3::ZERO);
        let radius = float(doc, node, "radius", 1.0)?;
        if radius <= 0.0 {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("sphere radius {radius} is not positive"),
            ));
        }
        let material = self.shape_material(doc, node)?;
        let transform = checked_transform(doc, node)?;
        let Some((center, radius, rotation)) = place_sphere(transform, center, radius) else {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                "a sphere's to_world must scale uniformly",
            ));
        };
        let sphere = SphereDesc {
            name,
            center,
            radius,
            material,
            // Mitsuba's sphere: v = θ/π from the pole on its local +z, u
            // around it from +x toward +y. Candela's v is 1 − Mitsuba's (see
            // `image_rows_from_the_top`), which is θ measured from −z with
            // u unchanged: the pole axis reversed.
            axes: rotation * Mat3::from_diagonal(Vec3::new(1.0, 1.0, -1.0)),
            // flip_normals turns its front (BSDF, emission) to the inside.
            inward: boolean(doc, node, "flip_normals", false)?,
            loc: doc.loc(node),
        };
        match group {
            Some(g) => g.push(GroupItem::Sphere(sphere)),
            None => self.scene.spheres.push(sphere),
        }
        Ok(())
    }

    fn shape_group(&mut self, doc: &Doc, node: XNode, nested: bool) -> Result<(), LoadError> {
        if nested {
            return Err(doc.err(node, ErrorKind::BadValue, "shape groups cannot be nested"));
        }
        let id = doc.required(node, "id")?;
        let mut items = Vec::new();
        for c in elements(node) {
            if c.tag_name().name() == "shape" {
                self.shape(doc, c, Some(&mut items))?;
            } else {
                self.warn(
                    doc,
                    c,
                    "only <shape> elements belong in a shape group (ignored)",
                )?;
            }
        }
        self.groups.insert(id, items);
        Ok(())
    }

    fn instance(&mut self, doc: &Doc, node: XNode, nested: bool) -> Result<(), LoadError> {
        if nested {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                "instances cannot be part of a shape group",
            ));
        }
        let Some(r) = elements(node).find(|c| c.tag_name().name() == "ref") else {
            return Err(doc.err(
                node,
                ErrorKind::MissingElement,
                "an instance needs a <ref id> to a shape group",
            ));
        };
        let id = doc.required(r, "id")?;
        let Some(items) = self.groups.get(&id).cloned() else {
            return Err(doc.err(
                r,
                ErrorKind::MissingReference,
                format!("no shape group with id \"{id}\""),
            ));
        };
        let transform = checked_transform(doc, node)?;
        for item in items {
            match item {
                GroupItem::Mesh {
                    mesh,
                    transform: local,
                } => self.scene.instances.push(InstanceDesc {
                    mesh,
                    world_from_object: transform * local,
                    material: None,
                    loc: doc.loc(node),
                }),
                GroupItem::Sphere(s) => {
                    let Some((center, radius, rotation)) =
                        place_sphere(transform, s.center, s.radius)
                    else {
                        return Err(doc.err(
                            node,
                            ErrorKind::BadValue,
                            "an instance of a sphere must scale uniformly",
                        ));
                    };
                    self.scene.spheres.push(SphereDesc {
                        center,
                        radius,
                        axes: rotation * s.axes,
                        loc: doc.loc(node),
                        ..s
                    });
                }
            }
        }
        Ok(())
    }

    /// The material of a shape: its surface's (see [`Self::surface`]), or
    /// a copy of it when the shape has media, with the media recorded in
    /// [`crate::SceneDesc::medium_interfaces`]. Mitsuba attaches media to
    /// shapes, the description to materials, so a shape with media gets a
    /// material of its own (never the one cached for a named BSDF, which
    /// other shapes share).
    fn shape_material(&mut self, doc: &Doc, node: XNode) -> Result<usize, LoadError> {
        let sides = self.shape_media(doc, node)?;
        let surface = self.surface(doc, node)?;
        if sides == MediumInterface::default() {
            return Ok(match surface {
                Surface::Shared(i) => i,
                Surface::Own(m) => self.push_material(*m),
            });
        }
        let material = match surface {
            Surface::Shared(i) => self.scene.materials[i].clone(),
            Surface::Own(m) => *m,
        };
        let i = self.push_material(material);
        self.scene.medium_interfaces.push((i, sides));
        Ok(i)
    }

    /// The surface of a shape: its `<bsdf>` or `<ref>` (a reference to a
    /// medium is no BSDF: see `media.rs`), plus the radiance of its area
    /// `<emitter>`. Without a BSDF, Mitsuba gives a shape a one-sided grey
    /// diffuse, but an emitting shape a black one: its lamps reflect
    /// nothing unless the scene says so (measured: Mitsuba renders a lamp
    /// without a BSDF exactly as one with a black `diffuse`).
    fn surface(&mut self, doc: &Doc, node: XNode) -> Result<Surface, LoadError> {
        let (mut inline, mut named, mut emission, mut emission_texture) = (None, None, None, None);
        for c in elements(node) {
            match c.tag_name().name() {
                "bsdf" => inline = Some(self.bsdf(doc, c)?),
                "ref" => {
                    let id = doc.required(c, "id")?;
                    if self.is_medium_id(&id) {
                        continue;
                    }
                    let side = doc.attr(c, "name")?;
                    if matches!(side.as_deref(), Some("interior" | "exterior"))
                        && !self.bsdfs.contains_key(&id)
                    {
                        return Err(doc.err(
                            c,
                            ErrorKind::MissingReference,
                            format!("no <medium> with id \"{id}\" (defined before this shape)"),
                        ));
                    }
                    named = Some((self.named_bsdf(doc, c, &id)?, id));
                }
                "emitter" => {
                    let (radiance, texture) = area_radiance(self, doc, c)?;
                    emission = Some(radiance);
                    emission_texture = texture;
                }
                _ => {}
            }
        }
        if emission.is_none() {
            if let Some((m, id)) = &named {
                if let Some(&i) = self.bsdf_materials.get(id) {
                    return Ok(Surface::Shared(i));
                }
                let i = self.push_material(m.clone());
                self.bsdf_materials.insert(id.clone(), i);
                return Ok(Surface::Shared(i));
            }
        }
        let material = match inline.or(named.map(|(m, _)| m)) {
            Some(m) => m,
            None if emission.is_none() => {
                if let Some(i) = self.default_material {
                    return Ok(Surface::Shared(i));
                }
                let i = self.push_material(Self::default_diffuse());
                self.default_material = Some(i);
                return Ok(Surface::Shared(i));
            }
            None => MaterialDesc {
                bsdf: BsdfDesc::Black,
                ..Self::default_diffuse()
            },
        };
        let mut material = MaterialDesc {
            emission,
            ..material
        };
        set(
            &mut material.textures,
            TextureSlot::Emission,
            emission_texture,
        );
        Ok(Surface::Own(Box::new(material)))
    }

    fn push_material(&mut self, m: MaterialDesc) -> usize {
        self.scene.materials.push(m);
        self.scene.materials.len() - 1
    }
}

/// Mitsuba reads a texture at uv with v = 0 on the image's *top* row;
/// Candela's v = 0 is the bottom row (the OBJ convention). Mitsuba's OBJ
/// reader flips v to its own convention (so OBJ files need nothing), but
/// its PLY reader and its built-in shapes (rectangle: uv (0, 0) at corner
/// (-1, -1)) keep v as it is: their images would come out upside down
/// unless v becomes 1 − v here.
fn image_rows_from_the_top(mesh: &mut MeshDesc) {
    for uv in &mut mesh.uvs {
        uv.y = 1.0 - uv.y;
    }
}

/// The shape's `to_world`, which must be invertible.
fn checked_transform(doc: &Doc, node: XNode) -> Result<Mat4, LoadError> {
    let m = to_world(doc, node)?;
    let det = m.determinant();
    if !(det.is_finite() && det.abs() > 1e-12) {
        return Err(doc.err(node, ErrorKind::BadValue, "to_world is not invertible"));
    }
    Ok(m)
}

/// A sphere's centre and radius after `m`, with `m`'s rotation (its
/// columns normalised), or `None` if `m` does not scale uniformly (within
/// 0.1 %).
fn place_sphere(m: Mat4, center: Vec3, radius: f32) -> Option<(Vec3, f32, Mat3)> {
    let scales = [m.x_axis, m.y_axis, m.z_axis].map(|c| c.truncate().length());
    let mean = (scales[0] + scales[1] + scales[2]) / 3.0;
    let uniform = scales.iter().all(|s| (s - mean).abs() <= 1e-3 * mean)
        && m.x_axis.truncate().dot(m.y_axis.truncate()).abs() <= 1e-3 * mean * mean;
    let rotation = Mat3::from_cols(
        m.x_axis.truncate() / scales[0],
        m.y_axis.truncate() / scales[1],
        m.z_axis.truncate() / scales[2],
    );
    uniform.then(|| (m.transform_point3(center), radius * mean, rotation))
}

/// Mitsuba's `cylinder`: the unit one of [`tessellate::cylinder`] placed
/// from `p0` to `p1` with `radius`, as Mitsuba places it (its axis frame
/// from the branchless orthonormal basis of Duff et al. 2017, which fixes
/// where u = 0 lies). The placement is baked into the mesh, so `to_world`
/// stays the instance's transform.
fn cylinder(
    doc: &Doc,
    node: XNode,
    name: String,
    loc: crate::desc::SourceLoc,
) -> Result<MeshDesc, LoadError> {
    let p0 = point(doc, node, "p0")?.unwrap_or(Vec3::ZERO);
    let p1 = point(doc, node, "p1")?.unwrap_or(Vec3::Z);
    let radius = float(doc, node, "radius", 1.0)?;
    let axis = p1 - p0;
    let length = axis.length();
    if !(radius > 0.0 && radius.is_finite() && length > 0.0 && length.is_finite()) {
        return Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("cylinder: radius {radius} and length {length} must be positive"),
        ));
    }
    let d = axis / length;
    let (s, t) = d.any_orthonormal_pair();
    let mut mesh = tessellate::cylinder(name, loc);
    for p in &mut mesh.positions {
        *p = p0 + radius * (p.x * s + p.y * t) + length * p.z * d;
    }
    for n in &mut mesh.normals {
        *n = n.x * s + n.y * t;
    }
    Ok(mesh)
}

/// A mesh file's normals as Mitsuba shades them: none with `face_normals`
/// (flat triangles), else the file's, else smooth angle-weighted ones, which
/// Mitsuba computes for `obj`, `ply` and `serialized` meshes without normals.
fn smooth_or_faceted(mesh: &mut MeshDesc, face_normals: bool) {
    if face_normals {
        mesh.normals.clear();
        mesh.normal_indices.clear();
    } else {
        mesh.set_angle_weighted_normals();
    }
}
