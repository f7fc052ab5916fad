//! `<instance_geometry>`: material bindings, meshes (one [`crate::MeshDesc`]
//! per primitive element) and CGL spheres.

use super::builder::Builder;
use super::lenient::cgl_technique;
use super::numbers::float;
use super::sources::SourceCache;
use super::xml::{child, children, elements, require, Ctx, XNode};
use super::{mesh, primitives};
use crate::desc::SphereDesc;
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4, Vec3};
use std::collections::HashMap;

type Bindings<'a, 'i> = Vec<(&'a str, XNode<'a, 'i>)>;

/// Reads one geometry instance under the world-from-node transform `m`.
pub(crate) fn instance(ctx: &Ctx, b: &mut Builder, inst: XNode, m: Mat4) -> Result<(), LoadError> {
    let Some(geom) = ctx.resolve(inst, "url", &["geometry"])? else {
        return Ok(());
    };
    let bindings = bindings(ctx, inst)?;
    let name = geom
        .attribute("name")
        .or(geom.attribute("id"))
        .unwrap_or("geometry")
        .to_string();
    if let Some(mesh_node) = child(geom, "mesh") {
        return read_mesh(ctx, b, mesh_node, &bindings, m, &name);
    }
    if let Some(sphere) = cgl_technique(ctx, geom)?.and_then(|t| child(t, "sphere")) {
        let material = match bindings.first() {
            Some(&(_, mat)) => b.material(ctx, mat)?,
            None => b.default_material(),
        };
        let s = read_sphere(ctx, sphere, m, name, material)?;
        b.scene.spheres.push(SphereDesc {
            loc: ctx.loc(inst),
            ..s
        });
        return Ok(());
    }
    ctx.warn(
        geom,
        "geometry without <mesh> or CGL <sphere> not supported; ignored",
    )
}

/// `bind_material/technique_common/instance_material`: symbol -> `<material>`.
fn bindings<'a, 'i>(ctx: &Ctx<'a, 'i>, inst: XNode<'a, 'i>) -> Result<Bindings<'a, 'i>, LoadError> {
    let mut out = Vec::new();
    let Some(tc) = child(inst, "bind_material").and_then(|bm| child(bm, "technique_common")) else {
        return Ok(out);
    };
    for im in children(tc, "instance_material") {
        let symbol = im
            .attribute("symbol")
            .ok_or_else(|| ctx.err(im, ErrorKind::MissingElement, "missing attribute symbol"))?;
        if let Some(mat) = ctx.resolve(im, "target", &["material"])? {
            out.push((symbol, mat));
        }
    }
    Ok(out)
}

fn read_mesh(
    ctx: &Ctx,
    b: &mut Builder,
    mesh_node: XNode,
    bindings: &Bindings,
    m: Mat4,
    name: &str,
) -> Result<(), LoadError> {
    let by_symbol: HashMap<&str, XNode> = bindings.iter().copied().collect();
    let mut sources = SourceCache::default();
    for el in elements(mesh_node) {
        match el.tag_name().name() {
            "polylist" | "triangles" | "polygons" => {}
            "source" | "vertices" | "extra" => continue,
            other => {
                ctx.warn(el, format!("<{other}> primitives not supported; ignored"))?;
                continue;
            }
        }
        let prim = primitives::read(ctx, el)?;
        if prim.vcounts.is_empty() {
            continue;
        }
        let material = match el.attribute("material") {
            Some(sym) => match by_symbol.get(sym) {
                Some(&mat) => b.material(ctx, mat)?,
                // No bindings at all: the geometry simply has no material.
                None if bindings.is_empty() => b.default_material(),
                None => {
                    ctx.warn(
                        el,
                        format!("material symbol \"{sym}\" is not bound; default grey used"),
                    )?;
                    b.default_material()
                }
            },
            None if bindings.len() == 1 => b.material(ctx, bindings[0].1)?,
            None => b.default_material(),
        };
        let mesh = mesh::build(ctx, &mut sources, &prim, m, name.to_string(), material)?;
        b.add_world_mesh(mesh);
    }
    Ok(())
}

/// A CGL sphere: centre at the node origin, radius times the node's scale.
fn read_sphere(
    ctx: &Ctx,
    sphere: XNode,
    m: Mat4,
    name: String,
    material: usize,
) -> Result<SphereDesc, LoadError> {
    let r_node = require(ctx, sphere, "radius")?;
    let r = float(ctx, r_node)?;
    if r <= 0.0 {
        return Err(ctx.err(
            r_node,
            ErrorKind::BadValue,
            format!("radius {r} is not positive"),
        ));
    }
    let linear = Mat3::from_mat4(m);
    let scales = Vec3::new(
        linear.x_axis.length(),
        linear.y_axis.length(),
        linear.z_axis.length(),
    );
    if scales.min_element() <= 1e-12 {
        return Err(ctx.err(
            sphere,
            ErrorKind::BadValue,
            "sphere under a singular transform",
        ));
    }
    if scales.max_element() > scales.min_element() * (1.0 + 1e-4) {
        ctx.warn(sphere, "non-uniform scale on a sphere; mean scale used")?;
    }
    let scale = (scales.x + scales.y + scales.z) / 3.0;
    Ok(SphereDesc {
        name,
        center: m.transform_point3(Vec3::ZERO),
        radius: r * scale,
        material,
        axes: SphereDesc::Y_POLE,
        inward: false,
        loc: ctx.loc(sphere),
    })
}
