//! glTF metallic-roughness materials onto Candela's BSDF models, with every
//! texture in its slot (the renderer names the slots it cannot use yet).
//!
//! - `KHR_materials_transmission` > 0: [`BsdfDesc::Glass`] (base colour as
//!   transmittance, `KHR_materials_ior`, default 1.5).
//! - metallic ≥ 0.5: a conductor whose normal-incidence reflectance is the
//!   base colour: [`BsdfDesc::Microfacet`] with η = 1 and
//!   k = 2 √(F0 / (1 − F0)) (then F0 = k² / (4 + k²) exactly), α =
//!   roughness² (glTF's GGX α, used as the Beckmann α), or
//!   [`BsdfDesc::Mirror`] when α is below [`MIRROR_ALPHA`].
//! - otherwise [`BsdfDesc::Diffuse`] with the base colour (the 4 % dielectric
//!   specular layer of glTF is dropped; a principled BSDF is its own issue).
//!
//! A factor that multiplies a texture becomes the texture's scale; the
//! slot's scale is one number, so a non-grey colour factor is averaged (and
//! reported). Occlusion textures are not read: a path tracer computes
//! occlusion itself.

use super::accessors::Buffers;
use super::textures::texture_ref;
use super::Ctx;
use crate::desc::{BsdfDesc, ColorSpace, MaterialDesc, TextureSlot};
use crate::error::LoadError;
use glam::Vec3;
use gltf::material::AlphaMode;

/// Below this α a metal is a perfect mirror (the microfacet model clamps
/// smaller roughness anyway).
pub(super) const MIRROR_ALPHA: f32 = 1e-3;

/// Reads material `m` with its textures.
pub(super) fn read_material(
    ctx: &Ctx,
    buffers: &Buffers,
    m: &gltf::Material,
) -> Result<MaterialDesc, LoadError> {
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, alpha] = pbr.base_color_factor();
    let base = Vec3::new(r, g, b);
    let metal = pbr.metallic_factor();
    let rough = pbr.roughness_factor();
    let bsdf = if let Some(t) = m.transmission().filter(|t| t.transmission_factor() > 0.0) {
        if t.transmission_factor() < 1.0 || t.transmission_texture().is_some() {
            ctx.warn(
                "KHR_materials_transmission",
                "partial transmission is drawn as fully transmissive glass",
            )?;
        }
        BsdfDesc::Glass {
            reflectance: Vec3::ONE,
            transmittance: base,
            roughness: rough,
            ior: m.ior().unwrap_or(1.5),
        }
    } else {
        if metal > 0.0 && metal < 1.0 && pbr.metallic_roughness_texture().is_none() {
            ctx.warn(
                "metallicFactor",
                "a factor between 0 and 1 is rounded to a pure dielectric or metal",
            )?;
        }
        if metal >= 0.5 {
            conductor(base, rough)
        } else {
            BsdfDesc::Diffuse { albedo: base }
        }
    };
    let strength = m.emissive_strength().unwrap_or(1.0);
    let emissive = Vec3::from(m.emissive_factor()) * strength;
    let mut desc = MaterialDesc {
        name: m.name().map_or_else(
            || format!("material {}", m.index().unwrap_or(0)),
            str::to_string,
        ),
        bsdf,
        emission: (emissive.max_element() > 0.0).then_some(emissive),
        textures: Default::default(),
        loc: Default::default(),
    };
    let mut slot = |slot: TextureSlot,
                    info: Option<(gltf::Texture, u32)>,
                    space: ColorSpace,
                    scale: f32,
                    channel: Option<u8>|
     -> Result<(), LoadError> {
        let Some((tex, coord)) = info else {
            return Ok(());
        };
        if let Some(mut t) = texture_ref(ctx, buffers, &tex, coord, space)? {
            t.scale = scale;
            t.channel = channel;
            desc.textures.set(slot, t);
        }
        Ok(())
    };
    let base_tex = info(pbr.base_color_texture());
    let color_scale = match base_tex {
        Some(_) => grey(ctx, "baseColorFactor", base)?,
        None => 1.0,
    };
    slot(
        TextureSlot::Color,
        base_tex.clone(),
        ColorSpace::Srgb,
        color_scale,
        None,
    )?;
    let mr = info(pbr.metallic_roughness_texture());
    slot(
        TextureSlot::Roughness,
        mr.clone(),
        ColorSpace::Linear,
        rough,
        Some(1),
    )?;
    slot(
        TextureSlot::Metalness,
        mr,
        ColorSpace::Linear,
        metal,
        Some(2),
    )?;
    let normal = m.normal_texture();
    let scale = normal.as_ref().map_or(1.0, |n| n.scale());
    let normal = normal.map(|n| (n.texture(), n.tex_coord()));
    slot(TextureSlot::Normal, normal, ColorSpace::Linear, scale, None)?;
    let emissive_tex = info(m.emissive_texture());
    if emissive_tex.is_some() {
        let scale = grey(ctx, "emissiveFactor", Vec3::from(m.emissive_factor()))? * strength;
        slot(
            TextureSlot::Emission,
            emissive_tex,
            ColorSpace::Srgb,
            scale,
            None,
        )?;
    }
    match m.alpha_mode() {
        AlphaMode::Opaque => {}
        mode => {
            if mode == AlphaMode::Mask {
                ctx.warn(
                    "alphaCutoff",
                    "the opacity slot holds alpha as a coverage fraction; the cutoff is not applied",
                )?;
            }
            if base_tex.is_some() {
                slot(
                    TextureSlot::Opacity,
                    base_tex,
                    ColorSpace::Linear,
                    alpha,
                    Some(3),
                )?;
            } else if alpha < 1.0 {
                ctx.warn(
                    "alphaMode",
                    "a constant alpha without a texture is drawn opaque",
                )?;
            }
        }
    }
    Ok(desc)
}

/// A texture reference's texture and UV set.
fn info(i: Option<gltf::texture::Info<'_>>) -> Option<(gltf::Texture<'_>, u32)> {
    i.map(|i| (i.texture(), i.tex_coord()))
}

/// A conductor reflecting `f0` at normal incidence, with glTF roughness `rough`.
pub(super) fn conductor(f0: Vec3, rough: f32) -> BsdfDesc {
    let alpha = rough * rough;
    if alpha < MIRROR_ALPHA {
        return BsdfDesc::Mirror { reflectance: f0 };
    }
    let f0 = f0.clamp(Vec3::ZERO, Vec3::splat(0.999));
    BsdfDesc::Microfacet {
        alpha,
        eta: Vec3::ONE,
        k: (f0 / (Vec3::ONE - f0)).map(f32::sqrt) * 2.0,
    }
}

/// The one number a texture slot's scale can hold for a colour factor: the
/// factor itself when grey, else its mean (reported).
fn grey(ctx: &Ctx, name: &str, factor: Vec3) -> Result<f32, LoadError> {
    if factor.max_element() - factor.min_element() > 1e-6 {
        ctx.warn(
            name,
            "a coloured factor on a texture is applied as its mean (texture scales are one number)",
        )?;
    }
    Ok(factor.element_sum() / 3.0)
}
