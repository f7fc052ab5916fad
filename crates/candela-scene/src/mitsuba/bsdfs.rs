//! BSDFs and textures.
//!
//! | Mitsuba | Candela description |
//! |---|---|
//! | `diffuse` | `Diffuse` (a `reflectance` texture fills the colour slot) |
//! | `twosided` | its inner BSDF (Candela shades both sides anyway) |
//! | `dielectric` | `Glass`, ior = int_ior / ext_ior (numbers or names) |
//! | `thindielectric` | `ThinDielectric` |
//! | `roughdielectric` | `RoughDielectric` (alpha, beckmann or ggx) |
//! | `conductor`, `roughconductor` | `Conductor` (alpha 0 when smooth), `material` presets (the measured metals of [`crate::metals`]) or eta/k; a smooth `none` with `specular_reflectance` is a `Mirror` of that reflectance |
//! | `plastic`, `roughplastic` | `Plastic` (alpha 0 when smooth), with `nonlinear` |
//! | `bumpmap`, `normalmap` | the inner BSDF, its texture in the bump (height) or normal-map slot |
//! | `mask` | the inner BSDF, its opacity texture in the opacity slot |
//! | `principled` | `Principled` (`principled.rs`: every parameter; textures on base_color, roughness, metallic) |
//!
//! Mitsuba BSDFs Candela lacks (`principledthin`, `blendbsdf`, `null`, ...) are
//! replaced by the closest one and reported once.

use super::doc::{elements, Doc, XNode};
use super::values::{boolean, constant_color, float_of, string};
use super::{tables, Builder};
use crate::desc::{
    BsdfDesc, ColorSpace, MaterialDesc, MicrofacetModel, TextureRef, TextureSlot, TextureSlots,
};
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

/// A texture as this loader keeps it: an image, or a constant that stands
/// for a procedural texture Candela lacks.
#[derive(Clone, Debug)]
pub(super) enum Texture {
    Image(TextureRef),
    Constant(Vec3),
}

/// A parameter that is a constant, maybe replaced by an image.
type Param = (Vec3, Option<TextureRef>);

impl Builder {
    /// A `<bsdf>` element as a material without emission.
    pub(super) fn bsdf(&mut self, doc: &Doc, node: XNode) -> Result<MaterialDesc, LoadError> {
        let kind = doc.plugin_type(node)?;
        let name = doc.attr(node, "id")?.unwrap_or_else(|| kind.clone());
        let mut textures = TextureSlots::default();
        let bsdf = match kind.as_str() {
            "diffuse" => {
                let (albedo, tex) = self.color(doc, node, "reflectance", Vec3::splat(0.5))?;
                set(&mut textures, TextureSlot::Color, tex);
                BsdfDesc::Diffuse { albedo }
            }
            "twosided" | "bumpmap" | "normalmap" | "mask" | "blendbsdf" => {
                return self.wrapper(doc, node, &kind, name)
            }
            "dielectric" => BsdfDesc::Glass {
                reflectance: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                transmittance: self.constant(doc, node, "specular_transmittance", Vec3::ONE)?,
                roughness: 0.0,
                ior: relative_ior(doc, node, tables::named_ior("bk7").unwrap_or(1.5))?,
            },
            "thindielectric" => BsdfDesc::ThinDielectric {
                reflectance: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                transmittance: self.constant(doc, node, "specular_transmittance", Vec3::ONE)?,
                ior: relative_ior(doc, node, tables::named_ior("bk7").unwrap_or(1.5))?,
            },
            "roughdielectric" => BsdfDesc::RoughDielectric {
                distribution: distribution(doc, node)?,
                alpha: self.alpha(doc, node, &mut textures)?,
                reflectance: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                transmittance: self.constant(doc, node, "specular_transmittance", Vec3::ONE)?,
                ior: relative_ior(doc, node, tables::named_ior("bk7").unwrap_or(1.5))?,
            },
            "conductor" | "roughconductor" => {
                let (eta, k) = conductor_ior(self, doc, node)?;
                let rough = kind == "roughconductor";
                let scale = self.constant(doc, node, "specular_reflectance", Vec3::ONE)?;
                // Fresnel is 1 at every angle for "none", so the BSDF is
                // exactly a mirror of reflectance `scale`; Candela's
                // conductor has no such factor otherwise.
                let smooth_none = !rough && (eta, k) == (Vec3::ZERO, Vec3::ONE);
                if scale != Vec3::ONE && smooth_none {
                    return Ok(MaterialDesc {
                        name,
                        bsdf: BsdfDesc::Mirror { reflectance: scale },
                        emission: None,
                        textures,
                        loc: doc.loc(node),
                    });
                }
                if scale != Vec3::ONE {
                    let p = doc.prop(node, "specular_reflectance")?.unwrap_or(node);
                    self.warn(
                        doc,
                        p,
                        "specular_reflectance is applied only to a smooth conductor of material \"none\" (ignored)",
                    )?;
                }
                BsdfDesc::Conductor {
                    distribution: if rough {
                        distribution(doc, node)?
                    } else {
                        MicrofacetModel::Beckmann
                    },
                    alpha: if rough {
                        self.alpha(doc, node, &mut textures)?
                    } else {
                        0.0
                    },
                    eta,
                    k,
                }
            }
            "plastic" | "roughplastic" | "pplastic" => {
                if kind == "pplastic" {
                    self.warn(doc, node, "polarized plastic rendered as roughplastic")?;
                }
                let (diffuse, tex) =
                    self.color(doc, node, "diffuse_reflectance", Vec3::splat(0.5))?;
                set(&mut textures, TextureSlot::Color, tex);
                let rough = kind != "plastic";
                let int = ior(
                    doc,
                    node,
                    "int_ior",
                    tables::named_ior("polypropylene").unwrap_or(1.49),
                )?;
                let ext = ior(
                    doc,
                    node,
                    "ext_ior",
                    tables::named_ior("air").unwrap_or(1.0),
                )?;
                BsdfDesc::Plastic {
                    diffuse,
                    specular: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                    ior: int / ext,
                    alpha: if rough {
                        self.alpha(doc, node, &mut textures)?
                    } else {
                        0.0
                    },
                    distribution: if rough {
                        distribution(doc, node)?
                    } else {
                        MicrofacetModel::Beckmann
                    },
                    nonlinear: boolean(doc, node, "nonlinear", false)?,
                }
            }
            "principled" => self.principled(doc, node, &mut textures)?,
            "principledthin" => {
                self.warn(
                    doc,
                    node,
                    format!("BSDF \"{kind}\" rendered as diffuse (its base_color)"),
                )?;
                let (albedo, tex) = self.color(doc, node, "base_color", Vec3::splat(0.5))?;
                set(&mut textures, TextureSlot::Color, tex);
                BsdfDesc::Diffuse { albedo }
            }
            "null" => {
                self.warn(
                    doc,
                    node,
                    "BSDF \"null\" (invisible surface) rendered as black",
                )?;
                BsdfDesc::Black
            }
            "measured" | "hair" | "polarizer" | "retarder" | "circular" => {
                self.warn(
                    doc,
                    node,
                    format!("BSDF \"{kind}\" rendered as grey diffuse"),
                )?;
                BsdfDesc::Diffuse {
                    albedo: Vec3::splat(0.5),
                }
            }
            other => {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("unknown BSDF type \"{other}\""),
                ))
            }
        };
        Ok(MaterialDesc {
            name,
            bsdf,
            emission: None,
            textures,
            loc: doc.loc(node),
        })
    }

    /// BSDFs that wrap another one (`twosided`, `bumpmap`, ...).
    fn wrapper(
        &mut self,
        doc: &Doc,
        node: XNode,
        kind: &str,
        name: String,
    ) -> Result<MaterialDesc, LoadError> {
        let mut inner: Option<MaterialDesc> = None;
        let mut extra = 0;
        for c in elements(node) {
            let m = match c.tag_name().name() {
                "bsdf" => self.bsdf(doc, c)?,
                "ref" => {
                    let id = doc.required(c, "id")?;
                    if self.textures.contains_key(&id) {
                        continue; // a bump or normal map given by reference
                    }
                    self.named_bsdf(doc, c, &id)?
                }
                _ => continue,
            };
            if inner.is_none() {
                inner = Some(m);
            } else {
                extra += 1;
            }
        }
        let Some(mut m) = inner else {
            return Err(doc.err(
                node,
                ErrorKind::MissingElement,
                format!("\"{kind}\" has no inner <bsdf>"),
            ));
        };
        if extra > 0 && kind != "twosided" {
            self.warn(
                doc,
                node,
                format!("\"{kind}\": only the first inner BSDF is used"),
            )?;
        } else if extra > 0 {
            self.warn(
                doc,
                node,
                "twosided with two BSDFs: the front one is used on both sides",
            )?;
        }
        match kind {
            "bumpmap" | "normalmap" => {
                if let Some(tex) = self.map_texture(doc, node)? {
                    let slot = if kind == "bumpmap" {
                        TextureSlot::Bump
                    } else {
                        TextureSlot::Normal
                    };
                    m.textures.set(slot, tex);
                }
            }
            "mask" => {
                let (opacity, tex) = self.color(doc, node, "opacity", Vec3::ONE)?;
                set(&mut m.textures, TextureSlot::Opacity, tex);
                if opacity.min_element() < 1.0 {
                    self.warn(
                        doc,
                        node,
                        "constant partial opacity is not supported (opaque)",
                    )?;
                }
            }
            "blendbsdf" => self.warn(doc, node, "blendbsdf rendered as its first BSDF")?,
            _ => {}
        }
        m.name = name;
        m.loc = doc.loc(node);
        Ok(m)
    }

    /// The image of a bump or normal map (a `<texture>` or `<ref>` child).
    fn map_texture(&mut self, doc: &Doc, node: XNode) -> Result<Option<TextureRef>, LoadError> {
        for c in elements(node) {
            let t = match c.tag_name().name() {
                "texture" => self.texture(doc, c)?,
                "ref" => match self.textures.get(&doc.required(c, "id")?) {
                    Some(t) => t.clone(),
                    None => continue,
                },
                _ => continue,
            };
            if let Texture::Image(mut t) = t {
                t.color_space = ColorSpace::Linear;
                return Ok(Some(t));
            }
        }
        Ok(None)
    }

    /// The material of the BSDF named `id`.
    pub(super) fn named_bsdf(
        &self,
        doc: &Doc,
        node: XNode,
        id: &str,
    ) -> Result<MaterialDesc, LoadError> {
        self.bsdfs.get(id).cloned().ok_or_else(|| {
            doc.err(
                node,
                ErrorKind::MissingReference,
                format!("no <bsdf> with id \"{id}\""),
            )
        })
    }

    /// A `<texture>` element.
    pub(super) fn texture(&mut self, doc: &Doc, node: XNode) -> Result<Texture, LoadError> {
        if let Some(t) = doc.prop(node, "to_uv")? {
            self.warn(
                doc,
                t,
                "a texture's to_uv is not supported (read at the surface's own uv)",
            )?;
        }
        match doc.plugin_type(node)?.as_str() {
            "bitmap" => {
                let path = self.existing_file(doc, node)?;
                let raw = boolean(doc, node, "raw", false)?;
                let color_space = if raw {
                    ColorSpace::Linear
                } else {
                    ColorSpace::of_image_file(&path)
                };
                Ok(Texture::Image(TextureRef::new(path, color_space)))
            }
            "checkerboard" => {
                self.warn(
                    doc,
                    node,
                    "checkerboard texture rendered as the mean of its colours",
                )?;
                let a = self.constant(doc, node, "color0", Vec3::splat(0.4))?;
                let b = self.constant(doc, node, "color1", Vec3::splat(0.2))?;
                Ok(Texture::Constant(0.5 * (a + b)))
            }
            "mesh_attribute" | "volume" => {
                self.warn(doc, node, "texture type rendered as grey 0.5")?;
                Ok(Texture::Constant(Vec3::splat(0.5)))
            }
            other => Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("unknown texture type \"{other}\""),
            )),
        }
    }

    /// Colour property `name`: a constant, or an image (its constant
    /// `default`).
    pub(super) fn color(
        &mut self,
        doc: &Doc,
        node: XNode,
        name: &str,
        default: Vec3,
    ) -> Result<Param, LoadError> {
        let Some(p) = doc.prop(node, name)? else {
            return Ok((default, None));
        };
        let texture = match p.tag_name().name() {
            "texture" => self.texture(doc, p)?,
            "ref" => {
                let id = doc.required(p, "id")?;
                self.textures.get(&id).cloned().ok_or_else(|| {
                    doc.err(
                        p,
                        ErrorKind::MissingReference,
                        format!("no <texture> with id \"{id}\""),
                    )
                })?
            }
            _ => {
                return match constant_color(doc, p)? {
                    Some(c) => Ok((c, None)),
                    None => Err(doc.err(
                        p,
                        ErrorKind::BadValue,
                        "expected a colour (<rgb>, <spectrum>, <float>) or a texture",
                    )),
                }
            }
        };
        Ok(match texture {
            Texture::Image(t) => (default, Some(t)),
            Texture::Constant(c) => (c, None),
        })
    }

    /// A colour property that Candela cannot texture: an image is reported
    /// and replaced by `default`.
    pub(super) fn constant(
        &mut self,
        doc: &Doc,
        node: XNode,
        name: &str,
        default: Vec3,
    ) -> Result<Vec3, LoadError> {
        let (c, tex) = self.color(doc, node, name, default)?;
        if tex.is_some() {
            let p = doc.prop(node, name)?.unwrap_or(node);
            self.warn(
                doc,
                p,
                format!("a texture for \"{name}\" is not supported (constant used)"),
            )?;
        }
        Ok(c)
    }

    /// Roughness `alpha` (default 0.1); a texture goes to the roughness slot.
    fn alpha(
        &mut self,
        doc: &Doc,
        node: XNode,
        textures: &mut TextureSlots,
    ) -> Result<f32, LoadError> {
        if doc.prop(node, "alpha_u")?.is_some() {
            let u = self.color(doc, node, "alpha_u", Vec3::splat(0.1))?.0.x;
            let v = self.color(doc, node, "alpha_v", Vec3::splat(0.1))?.0.x;
            self.warn(
                doc,
                node,
                "anisotropic roughness rendered isotropic (the mean alpha)",
            )?;
            return check_alpha(doc, node, 0.5 * (u + v));
        }
        let (a, tex) = self.color(doc, node, "alpha", Vec3::splat(0.1))?;
        set(textures, TextureSlot::Roughness, tex);
        check_alpha(doc, node, a.x)
    }
}

fn check_alpha(doc: &Doc, node: XNode, alpha: f32) -> Result<f32, LoadError> {
    if alpha > 0.0 {
        Ok(alpha)
    } else {
        Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("roughness alpha {alpha} is not positive"),
        ))
    }
}

fn set(textures: &mut TextureSlots, slot: TextureSlot, texture: Option<TextureRef>) {
    if let Some(t) = texture {
        textures.set(slot, t);
    }
}

/// `distribution`: beckmann (the default) or ggx.
fn distribution(doc: &Doc, node: XNode) -> Result<MicrofacetModel, LoadError> {
    match string(doc, node, "distribution")?.as_deref() {
        None | Some("beckmann") => Ok(MicrofacetModel::Beckmann),
        Some("ggx") => Ok(MicrofacetModel::Ggx),
        Some(other) => Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("unknown microfacet distribution \"{other}\" (expected beckmann or ggx)"),
        )),
    }
}

/// int_ior / ext_ior, with `int_default` inside and air outside.
fn relative_ior(doc: &Doc, node: XNode, int_default: f32) -> Result<f32, LoadError> {
    let int = ior(doc, node, "int_ior", int_default)?;
    let ext = ior(
        doc,
        node,
        "ext_ior",
        tables::named_ior("air").unwrap_or(1.0),
    )?;
    Ok(int / ext)
}

/// An IOR property: a number or a name from Mitsuba's table.
fn ior(doc: &Doc, node: XNode, name: &str, default: f32) -> Result<f32, LoadError> {
    let Some(p) = doc.prop(node, name)? else {
        return Ok(default);
    };
    let v = if p.tag_name().name() == "string" {
        let n = doc.required(p, "value")?;
        tables::named_ior(&n).ok_or_else(|| {
            doc.err(
                p,
                ErrorKind::BadValue,
                format!("unknown IOR name \"{n}\" (known: {})", tables::ior_names()),
            )
        })?
    } else {
        float_of(doc, p)?
    };
    if v > 0.0 {
        Ok(v)
    } else {
        Err(doc.err(p, ErrorKind::BadValue, format!("IOR {v} is not positive")))
    }
}

/// A conductor's (eta, k): explicit `eta`/`k`, or the `material` preset
/// (default "none", a perfect mirror, as in Mitsuba 3).
fn conductor_ior(b: &mut Builder, doc: &Doc, node: XNode) -> Result<(Vec3, Vec3), LoadError> {
    if doc.prop(node, "eta")?.is_some() || doc.prop(node, "k")?.is_some() {
        let eta = b.constant(doc, node, "eta", Vec3::ZERO)?;
        let k = b.constant(doc, node, "k", Vec3::ONE)?;
        return Ok((eta, k));
    }
    let name = string(doc, node, "material")?.unwrap_or_else(|| "none".into());
    tables::conductor(&name).ok_or_else(|| {
        let p = doc.prop(node, "material").ok().flatten().unwrap_or(node);
        doc.err(
            p,
            ErrorKind::BadValue,
            format!(
                "unknown conductor \"{name}\" (known: {})",
                tables::conductor_names()
            ),
        )
    })
}
