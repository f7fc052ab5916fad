//! `<texture>` elements.
//!
//! | Mitsuba | Candela description |
//! |---|---|
//! | `bitmap` | an image [`TextureRef`]: `raw` (linear) or the file's colour space, `filter_type` (`bilinear`, `nearest`), `wrap_mode` ([`WrapMode`]: `repeat`, `mirror`, `clamp`), `to_uv` |
//! | `checkerboard` | [`TextureSource::Checkerboard`] of `color0`/`color1` (constants; textures in them are reported), `to_uv` |
//! | `mesh_attribute` | `name` `vertex_color`: [`TextureSource::VertexColor`] (a PLY's `red green blue`, a `serialized` mesh's colours; white on a mesh without them), `scale`; other attributes are reported, grey 0.5 |
//! | `volume` | reported, grey 0.5 |
//!
//! `to_uv` is a `<transform>` read as Mitsuba reads it: the 4×4 matrix of
//! its steps (later steps apply after earlier ones), of which the rows and
//! columns of x, y and the translation form the 2D affine map (so a z
//! translation or a 9-number `<matrix>`'s third column does nothing).
//! Mitsuba's v runs from the image's top; Candela's from its bottom (see
//! `shapes.rs`), so the map becomes F·M·F with F(u, v) = (u, 1 − v).
//!
//! Mitsuba's checkerboard is `color0` where u − ⌊u⌋ > ½ and v − ⌊v⌋ > ½
//! agree, when read as a colour; read as one value (`eval_1`: roughness,
//! metalness, opacity, height, blend weight) it swaps the two. In Candela's v, whose
//! cells are the mirror image of Mitsuba's, the colour reading is
//! therefore the description's checkerboard with the colours swapped, and
//! the one-value reading is it with them in order ([`for_slot`]).

use super::doc::{Doc, XNode};
use super::transform::transform;
use super::values::{boolean, float, string};
use super::Builder;
use crate::desc::{
    ColorSpace, TextureFilter, TextureRef, TextureSlot, TextureSource, TextureWrap, UvTransform,
    WrapMode,
};
use crate::error::{ErrorKind, LoadError};
use glam::{Affine2, Mat4, Vec2, Vec3};

/// A texture as this loader keeps it: one the description can vary over
/// a surface, or a constant that stands for one Candela lacks.
#[derive(Clone, Debug)]
pub(super) enum Texture {
    Varying(TextureRef),
    Constant(Vec3),
}

impl Builder {
    /// A `<texture>` element.
    pub(super) fn texture(&mut self, doc: &Doc, node: XNode) -> Result<Texture, LoadError> {
        let uv = uv_transform(doc, node)?;
        let mut t = match doc.plugin_type(node)?.as_str() {
            "bitmap" => {
                let path = self.existing_file(doc, node)?;
                let raw = boolean(doc, node, "raw", false)?;
                let color_space = if raw {
                    ColorSpace::Linear
                } else {
                    ColorSpace::of_image_file(&path)
                };
                let mut t = TextureRef::new(path, color_space);
                t.filter = filter(doc, node)?;
                t.wrap = TextureWrap::both(wrap_mode(doc, node)?);
                t
            }
            "checkerboard" => {
                let color0 = self.constant(doc, node, "color0", Vec3::splat(0.4))?;
                let color1 = self.constant(doc, node, "color1", Vec3::splat(0.2))?;
                // Swapped: see the module docs (colour reading, v flipped).
                TextureRef::checkerboard(color1, color0)
            }
            "mesh_attribute" => return self.mesh_attribute(doc, node),
            "volume" => {
                self.warn(doc, node, "texture type rendered as grey 0.5")?;
                return Ok(Texture::Constant(Vec3::splat(0.5)));
            }
            other => {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("unknown texture type \"{other}\""),
                ))
            }
        };
        t.uv = uv;
        Ok(Texture::Varying(t))
    }
}

impl Builder {
    /// A `mesh_attribute` texture: the vertex colours, the one attribute
    /// meshes carry here.
    fn mesh_attribute(&mut self, doc: &Doc, node: XNode) -> Result<Texture, LoadError> {
        let name = string(doc, node, "name")?.ok_or_else(|| {
            doc.err(
                node,
                ErrorKind::MissingElement,
                "mesh_attribute needs a name",
            )
        })?;
        if name != "vertex_color" {
            self.warn(
                doc,
                node,
                format!(
                    "mesh attribute \"{name}\" is not read (only vertex_color is); rendered as grey 0.5"
                ),
            )?;
            return Ok(Texture::Constant(Vec3::splat(0.5)));
        }
        let mut t = TextureRef::vertex_color();
        t.scale = float(doc, node, "scale", 1.0)?;
        Ok(Texture::Varying(t))
    }
}

/// `texture` as Mitsuba reads it into `slot`: a checkerboard read as one
/// value has its colours swapped back (see the module docs), and for a
/// blend weight made grey.
pub(super) fn for_slot(slot: TextureSlot, mut texture: TextureRef) -> TextureRef {
    let one_value = matches!(
        slot,
        TextureSlot::Roughness
            | TextureSlot::Metalness
            | TextureSlot::Opacity
            | TextureSlot::Bump
            | TextureSlot::Weight
            | TextureSlot::Clearcoat
            | TextureSlot::ClearcoatRoughness
            | TextureSlot::Transmission
            | TextureSlot::Specular
            | TextureSlot::SheenRoughness
    );
    if let (true, TextureSource::Checkerboard { color0, color1 }) = (one_value, &mut texture.source)
    {
        std::mem::swap(color0, color1);
        if slot == TextureSlot::Weight {
            // Mitsuba reads a checkerboard's colour as one value by its
            // channels' mean (an image's by its luminance, which the
            // renderer takes): grey cells make the two agree.
            *color0 = Vec3::splat(color0.element_sum() / 3.0);
            *color1 = Vec3::splat(color1.element_sum() / 3.0);
        }
    }
    texture
}

/// `wrap_mode`: repeat (the default), mirror or clamp, along both axes.
/// Mitsuba's v runs down the image and Candela's up; each mode folds texel
/// indices symmetrically under that flip, so it carries over as it is.
fn wrap_mode(doc: &Doc, node: XNode) -> Result<WrapMode, LoadError> {
    match string(doc, node, "wrap_mode")?.as_deref() {
        None | Some("repeat") => Ok(WrapMode::Repeat),
        Some("mirror") => Ok(WrapMode::Mirror),
        Some("clamp") => Ok(WrapMode::Clamp),
        Some(other) => Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("unknown wrap_mode \"{other}\" (expected repeat, mirror or clamp)"),
        )),
    }
}

/// `filter_type`: bilinear (the default) or nearest.
fn filter(doc: &Doc, node: XNode) -> Result<TextureFilter, LoadError> {
    match string(doc, node, "filter_type")?.as_deref() {
        None | Some("bilinear") => Ok(TextureFilter::Bilinear),
        Some("nearest") => Ok(TextureFilter::Nearest),
        Some(other) => Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("unknown filter_type \"{other}\" (expected bilinear or nearest)"),
        )),
    }
}

/// The texture's `to_uv` in Candela's uv (identity when it has none).
fn uv_transform(doc: &Doc, node: XNode) -> Result<UvTransform, LoadError> {
    let Some(p) = doc.prop(node, "to_uv")? else {
        return Ok(UvTransform::IDENTITY);
    };
    if p.tag_name().name() != "transform" {
        return Err(doc.err(p, ErrorKind::BadValue, "to_uv must be a <transform>"));
    }
    let mitsuba = UvTransform(planar(transform(doc, p)?));
    // F·M·F: into Mitsuba's v, its map, back into Candela's v.
    let flip_v = UvTransform(Affine2::from_cols(Vec2::X, -Vec2::Y, Vec2::Y));
    Ok(flip_v.then(mitsuba).then(flip_v))
}

/// The 2D affine map in `m`'s x and y rows and columns and its translation
/// column, as Mitsuba takes a texture's 3×3 from a 4×4 transform.
fn planar(m: Mat4) -> Affine2 {
    Affine2::from_cols(
        m.x_axis.truncate().truncate(),
        m.y_axis.truncate().truncate(),
        m.w_axis.truncate().truncate(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_v_flipped_map_reads_where_mitsuba_reads() {
        // Mitsuba's to_uv: u' = 2u + 0.5, v' = 3v + 0.25, in its own v
        // (v_m = 1 − v). The Candela map must land on 1 − v'.
        let m = Mat4::from_translation(glam::Vec3::new(0.5, 0.25, 7.0))
            * Mat4::from_scale(glam::Vec3::new(2.0, 3.0, 5.0));
        let mitsuba = UvTransform(planar(m));
        let flip = UvTransform(Affine2::from_cols(Vec2::X, -Vec2::Y, Vec2::Y));
        let candela = flip.then(mitsuba).then(flip);
        for uv in [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.9)] {
            let um = Vec2::new(uv.x, 1.0 - uv.y);
            let expected = Vec2::new(2.0 * um.x + 0.5, 1.0 - (3.0 * um.y + 0.25));
            let got = candela.apply(uv);
            assert!(
                (got - expected).abs().max_element() < 1e-6,
                "{got} vs {expected}"
            );
        }
    }
}
