//! Materials and effects: the CGL technique names the BSDF; otherwise the
//! `profile_COMMON` diffuse colour (or texture) makes a Lambertian material.
//!
//! Defaults for CGL parameters the file leaves out: reflectance and
//! transmittance 1, roughness 0, ior 1.5, alpha 0.5. A conductor's `eta` and
//! `k`, and an emitter's `radiance`, have no sensible default and are required.
//! Every material shades both sides of its surfaces, as path tracers
//! reading COLLADA do (`Sides::Both`, the default grey's).

use super::lenient::{self, color_or, float_or, is_cgl, Color};
use super::numbers::vec3;
use super::xml::{child, children, elements, require, text, Ctx, XNode};
use crate::desc::{BsdfDesc, ColorSpace, MaterialDesc, TextureRef, TextureSlot};
use crate::error::LoadError;
use glam::Vec3;
use std::path::PathBuf;

/// Reads a `<material>` through its `<instance_effect>`.
pub(crate) fn read_material(ctx: &Ctx, material: XNode) -> Result<MaterialDesc, LoadError> {
    let name = material
        .attribute("id")
        .or(material.attribute("name"))
        .unwrap_or("material");
    let mut desc = MaterialDesc {
        name: name.to_string(),
        loc: ctx.loc(material),
        ..MaterialDesc::default_grey()
    };
    let inst = require(ctx, material, "instance_effect")?;
    let Some(effect) = ctx.resolve(inst, "url", &["effect"])? else {
        return Ok(desc);
    };
    let techniques = || effect.descendants().filter(|n| n.has_tag_name("technique"));
    let mut cgl = techniques().find(|t| t.attribute("profile") == Some("CGL"));
    if cgl.is_none() {
        for t in techniques() {
            if is_cgl(ctx, t)? {
                cgl = Some(t);
                break;
            }
        }
    }
    let cgl = cgl.and_then(|t| elements(t).next());
    if let Some(model) = cgl {
        if let Some((bsdf, emission)) = cgl_bsdf(ctx, model)? {
            desc.bsdf = bsdf;
            desc.emission = emission;
            return Ok(desc);
        }
    }
    common_profile(ctx, effect, &mut desc)?;
    Ok(desc)
}

/// The BSDF named by a CGL technique's first child, or `None` (after a
/// warning) for a model the loader does not know.
fn cgl_bsdf(ctx: &Ctx, model: XNode) -> Result<Option<(BsdfDesc, Option<Vec3>)>, LoadError> {
    let color = |name: &str, default: Vec3| -> Result<Vec3, LoadError> {
        color_or(ctx, child(model, name), Color::Reflectance, default)
    };
    let scalar = |name: &str, default: f32| -> Result<f32, LoadError> {
        float_or(ctx, child(model, name), default)
    };
    let bsdf = match model.tag_name().name() {
        "emission" => {
            let radiance = lenient::color(ctx, require(ctx, model, "radiance")?, Color::Emitted)?;
            return Ok(Some((BsdfDesc::Black, Some(radiance))));
        }
        "mirror" => BsdfDesc::Mirror {
            reflectance: color("reflectance", Vec3::ONE)?,
        },
        "glass" => BsdfDesc::Glass {
            reflectance: color("reflectance", Vec3::ONE)?,
            transmittance: color("transmittance", Vec3::ONE)?,
            roughness: scalar("roughness", 0.0)?,
            ior: scalar("ior", 1.5)?,
        },
        "refraction" => BsdfDesc::Refraction {
            transmittance: color("transmittance", Vec3::ONE)?,
            roughness: scalar("roughness", 0.0)?,
            ior: scalar("ior", 1.5)?,
        },
        "microfacet" => BsdfDesc::Microfacet {
            alpha: scalar("alpha", 0.5)?,
            eta: vec3(ctx, require(ctx, model, "eta")?)?,
            k: vec3(ctx, require(ctx, model, "k")?)?,
        },
        other => {
            ctx.warn(
                model,
                format!("CGL material <{other}> not supported; common profile used"),
            )?;
            return Ok(None);
        }
    };
    Ok(Some((bsdf, None)))
}

/// `profile_COMMON/technique/(phong|lambert|blinn|constant)/diffuse`.
fn common_profile(ctx: &Ctx, effect: XNode, desc: &mut MaterialDesc) -> Result<(), LoadError> {
    let Some(profile) = child(effect, "profile_COMMON") else {
        return Ok(());
    };
    let shader = child(profile, "technique")
        .into_iter()
        .flat_map(elements)
        .find(|s| {
            matches!(
                s.tag_name().name(),
                "phong" | "lambert" | "blinn" | "constant"
            )
        });
    let Some(diffuse) = shader.and_then(|s| child(s, "diffuse")) else {
        return Ok(());
    };
    if let Some(c) = child(diffuse, "color") {
        desc.bsdf = BsdfDesc::Diffuse {
            albedo: lenient::color(ctx, c, Color::Reflectance)?,
        };
    } else if let Some(t) = child(diffuse, "texture") {
        // The albedo stays 0.5 grey: it is what a renderer uses if the image
        // cannot be read.
        match texture_path(ctx, profile, t) {
            // COLLADA names no colour space: the image format's own.
            Some(path) => {
                let space = ColorSpace::of_image_file(&path);
                desc.textures
                    .set(TextureSlot::Color, TextureRef::new(path, space));
            }
            None => ctx.warn(t, "texture reference could not be resolved; ignored")?,
        }
    }
    Ok(())
}

/// Follows `texture` -> sampler2D newparam -> surface newparam -> `<image>` ->
/// `init_from`, and resolves the file relative to the scene file.
fn texture_path(ctx: &Ctx, profile: XNode, tex: XNode) -> Option<PathBuf> {
    let newparam =
        |sid: &str| children(profile, "newparam").find(|p| p.attribute("sid") == Some(sid));
    let mut image_id = tex.attribute("texture")?.to_string();
    if let Some(sampler) = newparam(&image_id).and_then(|p| child(p, "sampler2D")) {
        let surface_sid = text(child(sampler, "source")?).trim().to_string();
        let surface = newparam(&surface_sid).and_then(|p| child(p, "surface"))?;
        image_id = text(child(surface, "init_from")?).trim().to_string();
    }
    let image = ctx.by_id(&image_id).filter(|n| n.has_tag_name("image"))?;
    let init = child(image, "init_from")?;
    let raw = child(init, "ref").map_or_else(|| text(init), text).trim();
    let raw = raw.strip_prefix("file://").unwrap_or(raw);
    if raw.is_empty() {
        return None;
    }
    let base = ctx.file.parent().unwrap_or(std::path::Path::new(""));
    Some(base.join(raw))
}
