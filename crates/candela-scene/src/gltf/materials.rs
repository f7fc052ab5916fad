//! glTF metallic-roughness materials, read as what they are:
//! [`BsdfDesc::MetallicRoughness`] (the renderer's glTF BSDF: Lambert base,
//! GGX specular with Schlick Fresnel, mixed by metalness), with
//! `KHR_materials_transmission` (`transmissionFactor`, `transmissionTexture`
//! in red), `KHR_materials_ior` (1.5 by default) and
//! `KHR_materials_specular` (`specularFactor` with `specularTexture` in
//! alpha, `specularColorFactor` with the sRGB `specularColorTexture`),
//! `KHR_materials_sheen` (`sheen.rs`: a sheen colour and roughness, the
//! colour texture's RGB in sRGB tinted by the factor, the roughness
//! texture's alpha), `KHR_materials_clearcoat` (`clearcoat.rs`), and every
//! texture in its slot.
//!
//! `KHR_materials_volume` fills the inside of a mesh whose `thicknessFactor`
//! is above 0 with an absorbing medium ([`volume_medium`]).
//!
//! A primitive with vertex colours (`COLOR_0`) multiplies its base colour
//! by them ([`times_vertex_colors`]).
//!
//! A factor multiplies its texture as glTF says, factor × texel ([`Factor`]):
//! a colour factor (`baseColorFactor`, `emissiveFactor` ×
//! `emissive_strength`, `specularColorFactor`) per channel, as the
//! texture's tint, a one-value factor as its scale on the channel holding
//! the value. Alpha: `MASK` puts the base colour's alpha in the opacity
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
use super::clearcoat::read_clearcoat;
use super::sheen::read_sheen;
use super::textures::texture_ref;
use super::Ctx;
use crate::desc::{
    BsdfDesc, ColorSpace, MaterialDesc, MediumDesc, Sides, TextureRef, TextureSlot, UvTransform,
};
use crate::error::LoadError;
use glam::{Affine2, Vec2, Vec3};
use gltf::material::AlphaMode;

/// The medium `KHR_materials_volume` puts inside the meshes of material
/// `m`: light is absorbed so that white turns `attenuationColor` after
/// `attenuationDistance` (σ_t = −ln(colour)/distance per channel, nothing
/// scattered). None for a thin-walled material (`thicknessFactor` 0, the
/// extension's default) or an infinite distance (no absorption). The
/// thickness itself (factor and texture) is what a rasteriser assumes the
/// volume to be; a path tracer meets the mesh's real back faces instead, as
/// the extension allows.
pub(super) fn volume_medium(m: &gltf::Material) -> Option<MediumDesc> {
    let volume = m.volume()?;
    let distance = volume.attenuation_distance();
    if !(volume.thickness_factor() > 0.0 && distance.is_finite() && distance > 0.0) {
        return None;
    }
    // A channel turned fully black is absorbed within a millionth of the
    // distance instead of at once.
    let colour = Vec3::from(volume.attenuation_color()).clamp(Vec3::splat(1e-6), Vec3::ONE);
    let sigma_t = Vec3::new(-colour.x.ln(), -colour.y.ln(), -colour.z.ln()) / distance;
    Some(MediumDesc {
        name: m.name().map_or_else(
            || format!("material {} volume", m.index().unwrap_or(0)),
            |n| format!("{n} volume"),
        ),
        sigma_t,
        albedo: Vec3::ZERO,
        phase_g: 0.0,
        loc: Default::default(),
    })
}

/// Reads material `m` with its textures.
pub(super) fn read_material(
    ctx: &Ctx,
    doc: &gltf::Document,
    buffers: &Buffers,
    m: &gltf::Material,
) -> Result<MaterialDesc, LoadError> {
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, alpha] = pbr.base_color_factor();
    let base = Vec3::new(r, g, b);
    let metal = pbr.metallic_factor();
    let rough = pbr.roughness_factor();
    let transmission = m.transmission();
    let specular = m.specular();
    let coat = read_clearcoat(ctx, doc, m)?;
    let transmission_factor = transmission
        .as_ref()
        .map_or(0.0, |t| t.transmission_factor());
    let specular_factor = specular.as_ref().map_or(1.0, |s| s.specular_factor());
    let specular_color = specular
        .as_ref()
        .map_or(Vec3::ONE, |s| Vec3::from(s.specular_color_factor()));
    let sheen = read_sheen(ctx, doc, m)?;
    let bsdf = BsdfDesc::MetallicRoughness {
        base_color: base,
        metallic: metal,
        roughness: rough,
        transmission: transmission_factor,
        ior: m.ior().unwrap_or(1.5),
        specular: specular_factor,
        specular_color,
        clearcoat: coat.as_ref().map_or(0.0, |c| c.factor),
        clearcoat_roughness: coat.as_ref().map_or(0.0, |c| c.roughness),
        sheen_color: sheen.as_ref().map_or(Vec3::ZERO, |s| s.color),
        sheen_roughness: sheen.as_ref().map_or(0.0, |s| s.roughness),
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
                    info: Option<TexInfo>,
                    space: ColorSpace,
                    factor: Factor|
     -> Result<(), LoadError> {
        let Some((tex, coord, uv)) = info else {
            return Ok(());
        };
        if let Some(mut t) = texture_ref(ctx, buffers, &tex, coord, space)? {
            factor.apply_to(&mut t);
            t.uv = uv;
            desc.textures.set(slot, t);
        }
        Ok(())
    };
    let base_tex = info(pbr.base_color_texture());
    slot(
        TextureSlot::Color,
        base_tex.clone(),
        ColorSpace::Srgb,
        Factor::Color(base),
    )?;
    let mr = info(pbr.metallic_roughness_texture());
    slot(
        TextureSlot::Roughness,
        mr.clone(),
        ColorSpace::Linear,
        Factor::Channel(rough, 1),
    )?;
    slot(
        TextureSlot::Metalness,
        mr,
        ColorSpace::Linear,
        Factor::Channel(metal, 2),
    )?;
    if let Some(t) = &transmission {
        slot(
            TextureSlot::Transmission,
            info(t.transmission_texture()),
            ColorSpace::Linear,
            Factor::Channel(transmission_factor, 0),
        )?;
    }
    if let Some(s) = &specular {
        slot(
            TextureSlot::Specular,
            info(s.specular_texture()),
            ColorSpace::Linear,
            Factor::Channel(specular_factor, 3),
        )?;
        slot(
            TextureSlot::SpecularColor,
            info(s.specular_color_texture()),
            ColorSpace::Srgb,
            Factor::Color(specular_color),
        )?;
    }
    if let Some(c) = coat {
        slot(
            TextureSlot::Clearcoat,
            c.texture,
            ColorSpace::Linear,
            Factor::Channel(c.factor, 0),
        )?;
        slot(
            TextureSlot::ClearcoatRoughness,
            c.roughness_texture,
            ColorSpace::Linear,
            Factor::Channel(c.roughness, 1),
        )?;
    }
    if let Some(s) = sheen {
        slot(
            TextureSlot::SheenColor,
            s.color_texture,
            ColorSpace::Srgb,
            Factor::Color(s.color),
        )?;
        slot(
            TextureSlot::SheenRoughness,
            s.roughness_texture,
            ColorSpace::Linear,
            Factor::Channel(s.roughness, 3),
        )?;
    }
    let normal = m.normal_texture();
    let scale = normal.as_ref().map_or(1.0, |n| n.scale());
    let normal = match normal {
        Some(n) => {
            let (coord, uv) = normal_transform(ctx, &n)?;
            Some((n.texture(), coord, uv))
        }
        None => None,
    };
    slot(
        TextureSlot::Normal,
        normal,
        ColorSpace::Linear,
        Factor::Strength(scale),
    )?;
    slot(
        TextureSlot::Emission,
        info(m.emissive_texture()),
        ColorSpace::Srgb,
        Factor::ColorTimes(Vec3::from(m.emissive_factor()), strength),
    )?;
    match m.alpha_mode() {
        AlphaMode::Opaque => {}
        mode => {
            if base_tex.is_some() {
                slot(
                    TextureSlot::Opacity,
                    base_tex,
                    ColorSpace::Linear,
                    Factor::Channel(alpha, 3),
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

/// How a glTF factor multiplies the texture it goes with (glTF: factor ×
/// texel, per channel for colours).
#[derive(Clone, Copy)]
enum Factor {
    /// A colour factor: the texture's tint (`baseColorFactor`,
    /// `specularColorFactor`).
    Color(Vec3),
    /// A colour factor times a number: `emissiveFactor` ×
    /// `emissive_strength`, tint and scale.
    ColorTimes(Vec3, f32),
    /// A one-value factor and the channel holding the value.
    Channel(f32, u8),
    /// A normal map's `scale` (its strength; the map reads RGB).
    Strength(f32),
}

impl Factor {
    fn apply_to(self, t: &mut TextureRef) {
        match self {
            Factor::Color(tint) => t.tint = tint,
            Factor::ColorTimes(tint, scale) => (t.tint, t.scale) = (tint, scale),
            Factor::Channel(scale, channel) => (t.scale, t.channel) = (scale, Some(channel)),
            Factor::Strength(scale) => t.scale = scale,
        }
    }
}

/// A texture reference's texture, UV set and uv transform.
pub(super) type TexInfo<'a> = (gltf::Texture<'a>, u32, UvTransform);

/// A texture reference's texture, its UV set (`KHR_texture_transform`'s
/// `texCoord` overrides the reference's) and its uv transform.
fn info(i: Option<gltf::texture::Info<'_>>) -> Option<TexInfo<'_>> {
    i.map(|i| {
        let t = i.texture_transform();
        let coord = t
            .as_ref()
            .and_then(|t| t.tex_coord())
            .unwrap_or(i.tex_coord());
        let uv = t.map_or(UvTransform::IDENTITY, |t| {
            khr_texture_transform(t.offset(), t.rotation(), t.scale())
        });
        (i.texture(), coord, uv)
    })
}

/// A normal texture's UV set and uv transform. The parser types
/// `KHR_texture_transform` only on plain texture references, so a normal
/// texture's extension object is read here through the parser's own type
/// (its defaults included); a malformed one is reported and not applied.
fn normal_transform(
    ctx: &Ctx,
    n: &gltf::material::NormalTexture<'_>,
) -> Result<(u32, UvTransform), LoadError> {
    let coord = n.tex_coord();
    let Some(value) = n.extensions().and_then(|e| e.get("KHR_texture_transform")) else {
        return Ok((coord, UvTransform::IDENTITY));
    };
    type Transform = gltf::json::extensions::texture::TextureTransform;
    match gltf::json::deserialize::from_value::<Transform>(value.clone()) {
        Ok(t) => Ok((
            t.tex_coord.unwrap_or(coord),
            khr_texture_transform(t.offset.0, t.rotation.0, t.scale.0),
        )),
        Err(e) => {
            ctx.warn(
                "KHR_texture_transform",
                &format!("a normal texture's transform is malformed ({e}); not applied"),
            )?;
            Ok((coord, UvTransform::IDENTITY))
        }
    }
}

/// `KHR_texture_transform` in Candela's uv. The extension reads the texture
/// at T(offset)·R(rotation)·S(scale)·uv, with R = [[cos, sin], [−sin, cos]]
/// (rows), in glTF's uv, whose v runs down the image; Candela's v runs up
/// (v = 1 − v_glTF, `meshes.rs`), so the map is F·M·F with F(u, v) = (u, 1 − v).
pub(super) fn khr_texture_transform(
    offset: [f32; 2],
    rotation: f32,
    scale: [f32; 2],
) -> UvTransform {
    let (s, c) = rotation.sin_cos();
    let gltf = Affine2::from_cols(
        Vec2::new(c, -s) * scale[0],
        Vec2::new(s, c) * scale[1],
        Vec2::from(offset),
    );
    let flip = Affine2::from_cols(Vec2::X, -Vec2::Y, Vec2::Y);
    UvTransform(flip * gltf * flip)
}

/// Makes `desc`'s base colour the product glTF defines for a primitive
/// with `COLOR_0`: factor × texture × vertex colour, per channel. A base
/// colour texture is multiplied by the vertex colour
/// ([`TextureRef::times_vertex_color`]), keeping its tint; without one the
/// vertex colour becomes the texture, tinted by the factor.
pub(super) fn times_vertex_colors(desc: &mut MaterialDesc) {
    if let Some(t) = &mut desc.textures.color {
        t.times_vertex_color = true;
        return;
    }
    let base = match desc.bsdf {
        BsdfDesc::MetallicRoughness { base_color, .. } => base_color,
        BsdfDesc::Diffuse { albedo } => albedo,
        _ => Vec3::ONE,
    };
    let mut t = TextureRef::vertex_color();
    t.tint = base;
    desc.textures.set(TextureSlot::Color, t);
}
