//! glTF metallic-roughness materials, read as what they are:
//! [`BsdfDesc::MetallicRoughness`] (the renderer's glTF BSDF: Lambert base,
//! GGX specular with Schlick Fresnel, mixed by metalness), with
//! `KHR_materials_transmission` (`transmissionFactor`),
//! `KHR_materials_ior` (1.5 by default) and `KHR_materials_specular`
//! (`specularFactor`, `specularColorFactor`; its two textures are reported
//! and not read), and every texture in its slot.
//!
//! A factor that multiplies a texture becomes the texture's scale; the
//! slot's scale is one number, so a non-grey colour factor is averaged (and
//! reported). Alpha: `MASK` puts the base colour's alpha in the opacity
//! slot with `alphaCutoff` (0.5 by default) as the slot's cutoff; `BLEND`
//! puts it there as a coverage fraction (stochastic opacity: a point of
//! alpha a is kept with probability a, which averages to the blended look
//! without ordering transparent surfaces). Without a base colour texture
//! the factor's alpha is a constant opacity (`opacity_constant`), read the
//! same way. Occlusion textures are not read:
//! a path tracer computes occlusion itself. Every material shades both
//! sides ([`Sides::Both`]): `doubleSided: false` lets a rasteriser cull
//! back faces, which a path tracer has no use for.

use super::accessors::Buffers;
use super::textures::texture_ref;
use super::Ctx;
use crate::desc::{BsdfDesc, ColorSpace, MaterialDesc, Sides, TextureSlot};
use crate::error::LoadError;
use glam::Vec3;
use gltf::material::AlphaMode;

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
    let transmission = m.transmission();
    if transmission
        .as_ref()
        .is_some_and(|t| t.transmission_texture().is_some())
    {
        ctx.warn(
            "transmissionTexture",
            "the transmission texture is not read; its factor is used",
        )?;
    }
    let specular = m.specular();
    if specular
        .as_ref()
        .is_some_and(|s| s.specular_texture().is_some() || s.specular_color_texture().is_some())
    {
        ctx.warn(
            "specularTexture",
            "the KHR_materials_specular textures are not read; their factors are used",
        )?;
    }
    let bsdf = BsdfDesc::MetallicRoughness {
        base_color: base,
        metallic: metal,
        roughness: rough,
        transmission: transmission.map_or(0.0, |t| t.transmission_factor()),
        ior: m.ior().unwrap_or(1.5),
        specular: specular.as_ref().map_or(1.0, |s| s.specular_factor()),
        specular_color: specular.map_or(Vec3::ONE, |s| Vec3::from(s.specular_color_factor())),
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
        // glTF's doubleSided asks rasterisers to cull back faces; a path
        // tracer shades both sides either way.
        sides: Sides::Both,
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
            if base_tex.is_some() {
                slot(
                    TextureSlot::Opacity,
                    base_tex,
                    ColorSpace::Linear,
                    alpha,
                    Some(3),
                )?;
            } else if alpha < 1.0 {
                desc.textures.opacity_constant = Some(alpha.clamp(0.0, 1.0));
            }
            if mode == AlphaMode::Mask {
                desc.textures.opacity_cutoff = Some(m.alpha_cutoff().unwrap_or(0.5));
            }
        }
    }
    Ok(desc)
}

/// A texture reference's texture and UV set.
fn info(i: Option<gltf::texture::Info<'_>>) -> Option<(gltf::Texture<'_>, u32)> {
    i.map(|i| (i.texture(), i.tex_coord()))
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
